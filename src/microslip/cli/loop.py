"""``microslip loop``: one model, one amplitude: backbone, Masing loop, W_d, U, eta."""

from __future__ import annotations

import argparse
from typing import Any

from ..case.options import add_case_option
from ..case.run import compute_loop, loop_inputs, loop_json, portion_text
from ..case.table import add_option
from ..io import check_writable, write_loop_csv
from ..models import MODELS, Contact, get_model
from .common import (
    add_model_options,
    add_params,
    add_strain_energy,
    check_plot,
    increments_option,
    print_json,
)
from .contact import add_contact_options, report_warnings
from .displacement import add_displacement_option, displacement_force

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    p = sub.add_parser("loop", help="hysteresis loop and damping of the tip or centre model",
                       description="Run the tip (Eqs 2-10) or centre (Eqs 11-18) model to an "
                       "amplitude, complete the loop with Masing's rule, report W_d, U and eta.")
    add_option(p, "model", choices=list(MODELS), required=True)
    add_params(p)
    add_displacement_option(p)
    add_option(p, "increments")
    add_model_options(p)
    add_strain_energy(p)
    add_contact_options(p)
    add_option(p, "json")
    add_option(p, "plot", help="write a figure of loop and backbone")
    add_option(p, "csv", help="write the loop as CSV (force_N,displacement_mm: what fit reads)")
    add_case_option(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    inputs = loop_inputs(vars(args), 1.0 if args.displacement_amplitude else None)
    n = increments_option(inputs.increments)
    check_plot(args.plot)
    if args.csv is not None:
        check_writable(args.csv, (".csv",), "loop file")
    forced = displacement_force(args, inputs.model, inputs.params, n, inputs.options,
                                inputs.contact)
    loop = compute_loop(inputs, forced)
    result, amplitude, opt, contact = (loop.result, loop.inputs.amplitude, inputs.options,
                                       inputs.contact)
    out = loop_json(loop)
    report_warnings(list(loop.warnings))
    if args.displacement_amplitude is not None:
        out["displacement_amplitude_mm"] = args.displacement_amplitude
    if args.plot:
        from ..plot import plot_damping

        plot_damping(result, args.plot, title=f"{args.model} model, F0 = {amplitude:g} N")
    if args.csv is not None:
        write_loop_csv(args.csv, result.loop.force, result.loop.displacement)
    if args.json:
        print_json(out)
        return 0
    reading = get_model(args.model).reading(opt)
    print(f"{args.model} model ({MODELS[args.model].equations}), {n} increments, "
          f"poisson={opt.poisson}, length_update={opt.length_update}"
          + (f", centre reading={reading}" if reading else ""))
    print(f"  contact                {_contact_text(contact)}")
    print(f"  amplitude F0           {amplitude:12.6g} N  (macroslip at "
          f"{out['macroslip_force_N']:.6g} N)")
    print(f"  peak displacement d0   {result.peak_displacement:12.6g} mm")
    if args.displacement_amplitude is not None:
        print(f"  (F0 = {amplitude!r} N from --displacement-amplitude "
              f"{args.displacement_amplitude:g} mm)")
    for name, a in out["slip_length_by_domain_mm"].items():
        print(f"  slip length ({name})   {a:12.6g} mm")
    print(f"  dissipated energy W_d  {result.dissipated_energy:12.6g} N·mm  "
          f"({portion_text(out['clamp_portion'])})")
    print(f"  strain energy U        {result.strain_energy:12.6g} N·mm  ({args.strain_energy})")
    print(f"  loss factor eta        {result.loss_factor:12.6g} (dimensionless)")
    if args.plot:
        print(f"  figure                 {args.plot}")
    if args.csv is not None:
        print(f"  loop                   {args.csv}")
    return 0


def _contact_text(contact: Contact | None) -> str:
    if contact is None:
        return "rigid foundation, uniform pressure (the paper's)"
    layer = (f"stick slope {contact.stick_slope:g} N/mm^3" if contact.stick_slope < float("inf")
             else "rigid contact")
    lag = " + the body's shear lag" if contact.shear_lag else ""
    return f"{layer}{lag}, {contact.law_name} pressure"
