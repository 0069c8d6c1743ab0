"""``microslip planar``: one circular or elliptical load case, the paper's coupling and the work."""

from __future__ import annotations

import argparse
from typing import Any

from ..case.options import add_case_option
from ..case.run import (
    compute_planar,
    contact_from_options,
    model_options_from,
    planar_amplitudes,
    planar_inputs,
    planar_json,
    planar_zones_from,
    portion_text,
    with_portion,
)
from ..case.table import add_option, add_solver
from ..conventions import DEFAULT_MESH, check_whole
from ..energy import STRAIN_ENERGY
from ..errors import ParameterError
from ..params import PRESETS, preset
from ..planar import (
    LEVEL_SCHEMES,
    TIP_SYMMETRY,
    WORK_STRAIN_ENERGY,
)
from ..planar.loadpath import DEFAULT_WORK_STRAIN_ENERGY
from .common import (
    MODEL_OPTION_DESTS,
    add_clamp_flags,
    add_model_options,
    add_strain_energy,
    check_plot,
    clamp_overrides,
    increments_option,
    print_json,
    refuse_inapplicable,
)
from .contact import (
    add_contact_options,
    report_warnings,
)
from .displacement import PLANAR_HELP, add_displacement_option, planar_displacement_forces

__all__ = ["SOLVERS", "add_parser", "run"]

#: Solvers of the planar case: the paper's decoupled analytical models, or the built-in
#: frictional FE solver with one shared Coulomb circle per contact node (coupled 2-D friction).
SOLVERS = ("analytical", "fe")

#: Options that apply to one solver only (the others are refused, not silently ignored).
SOLVER_OPTIONS: dict[str, tuple[str, ...]] = {
    **{dest: ("analytical",) for dest in (
        "plot", "levels", "tip_preset", "centre_preset", "tip_symmetry",
        "strain_energy", "work_energy", "increments", "samples_per_cycle",
        *MODEL_OPTION_DESTS)},
    **{dest: ("fe",) for dest in (
        "preset", "mesh", "cycles", "increments_per_cycle", "cycle_tolerance")},
}


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "planar", help="circular/elliptical loading: paper's coupling and work-based damping",
        description="Run the tip and centre models at two amplitudes (or a force ratio R with "
        "the paper's levels), couple their loops as the paper does (Eqs 19-23) and compute the "
        "work of the load over a cycle with any phase between the components. "
        "Units: N, mm, N·mm. See docs/planar.md.")
    g = p.add_argument_group("load case (give both amplitudes, or --ratio)")
    add_option(g, "tip_amplitude")
    add_option(g, "centre_amplitude")
    add_option(g, "ratio", note="the amplitudes follow from the paper's levels (2000 N tip, "
               "4000 N centre per level)")
    add_displacement_option(g, PLANAR_HELP, nargs=2, metavar=("TIP_MM", "CENTRE_MM"))
    add_option(g, "levels", choices=list(LEVEL_SCHEMES),
               help="level pairs for --ratio: "
               + "; ".join(f"{k}: {v}" for k, v in LEVEL_SCHEMES.items()))
    add_option(g, "phase",
               note="0: the paper's loading; 90: the ellipse of Fig. 1")
    m = p.add_argument_group("clamped zones")
    add_option(m, "tip_preset", choices=sorted(PRESETS))
    add_option(m, "centre_preset", choices=sorted(PRESETS))
    add_option(m, "tip_symmetry", default=TIP_SYMMETRY)
    c = p.add_argument_group(
        "one's own clamp (overrides the zones' values; the tip zone is one of --tip-symmetry "
        "symmetric parts of the contact width, so it takes width w/K; with --solver fe, the "
        "--preset bar)")
    add_clamp_flags(c)
    add_model_options(p)
    add_contact_options(p)
    add_strain_energy(p)
    add_option(p, "work_energy", choices=list(WORK_STRAIN_ENERGY),
               default=DEFAULT_WORK_STRAIN_ENERGY,
               help="U of the combined motion in the work-based eta: "
               + "; ".join(f"{k}: {v[1]}" for k, v in WORK_STRAIN_ENERGY.items()))
    add_option(p, "increments")
    add_option(p, "samples_per_cycle")
    add_solver(p, "planar", SOLVERS)
    f = p.add_argument_group("--solver fe (docs/solver.md)")
    add_option(f, "preset", choices=sorted(PRESETS), default="table1",
               help="the clamped body", note="table1 is the paper's FE bar")
    add_option(f, "mesh", note=f"default {DEFAULT_MESH}")
    add_option(f, "cycles", default=6, help="most load cycles per run, until W per cycle "
                                             "settles")
    add_option(f, "increments_per_cycle")
    add_option(f, "cycle_tolerance")
    add_option(p, "json")
    add_option(p, "plot", help="write a figure of the loops and the load path")
    add_case_option(p)
    p.set_defaults(func=run)


def amplitudes(args: argparse.Namespace) -> tuple[float, float]:
    """(tip, centre) amplitudes in N from the amplitude flags or --ratio."""
    return planar_amplitudes(vars(args))


def run(args: argparse.Namespace) -> int:
    runners = {"analytical": run_analytical, "fe": run_fe}
    if args.solver not in runners:  # argparse checks choices; a registry guard
        raise ParameterError(f"unknown solver {args.solver!r}; choose one of {', '.join(SOLVERS)}")
    refuse_inapplicable(args, "solver", SOLVER_OPTIONS)
    return runners[args.solver](args)


def run_fe(args: argparse.Namespace) -> int:
    """Coupled 2-D friction (built-in FE solver) against the sum of its uni-axial runs."""
    from ..fe.builtin import DEFAULT_MESH, coupling_study

    planar_displacement_forces(args, 0, None, (None, None))  # refused with --solver fe
    if args.ratio is not None:
        raise ParameterError("--ratio maps onto the paper's Table 2 levels; with --solver fe "
                             "give --tip-amplitude N and --centre-amplitude N")
    at, ac = amplitudes(args)
    for name, value in (("--cycles", args.cycles),
                        ("--increments-per-cycle", args.increments_per_cycle)):
        check_whole(name, value, 1, 100_000)
    params = preset(args.preset).replace(**clamp_overrides(args))
    if args.pressure_law is not None or args.no_shear_lag:
        raise ParameterError("--pressure-law and --no-shear-lag apply to the analytical "
                             "models; the FE body has its own shear field and uniform clamping")
    slope = {} if args.stick_slope is None else {"stick_slope": args.stick_slope}
    result = coupling_study(params, at, ac, args.phase, cycles=args.cycles,
                            increments_per_cycle=args.increments_per_cycle,
                            mesh=args.mesh or DEFAULT_MESH, cycle_tol=args.cycle_tolerance,
                            **slope)
    out = with_portion({"preset": args.preset, "mesh": args.mesh or DEFAULT_MESH,
                        "units": {"force": "N", "energy": "N·mm", "angle": "degrees",
                                  "time": "s"}, **result.summary()}, "whole")
    if args.json:
        print_json(out)
        return 0 if result.converged else 1
    print(f"coupled planar friction, built-in FE solver: {args.preset} bar, mesh "
          f"{out['mesh']} ({out['dof']} DOF), tip {at:g} N along the bar, centre {ac:g} N across "
          f"it, phase {args.phase:g} deg")
    print(f"  W per cycle, coupled                {out['dissipated_energy_Nmm']:12.6g} N·mm  "
          f"({portion_text(out['clamp_portion'])})")
    print(f"  W per cycle, tip alone              {out['tip_only_dissipated_energy_Nmm']:12.6g} "
          "N·mm")
    print(f"  W per cycle, centre alone           "
          f"{out['centre_only_dissipated_energy_Nmm']:12.6g} N·mm")
    print(f"  decoupled sum (the paper's model)   {out['decoupled_dissipated_energy_Nmm']:12.6g} "
          "N·mm")
    print(f"  coupling ratio W_coupled/W_decoupled {out['coupling_ratio']:11.6g} (dimensionless)")
    print(f"  share of coupled W: tip {out['tip_share']:.4f}, centre {out['centre_share']:.4f}")
    print(f"  {result_message(result)}; wall time {out['wall_s']:.3g} s")
    return 0 if result.converged else 1


def result_message(result: Any) -> str:
    return str(result.summary().get("message", "converged" if result.converged else
                                     "not converged"))


def run_analytical(args: argparse.Namespace) -> int:
    n = increments_option(args.increments, loops=2)
    check_plot(args.plot)
    opts = vars(args)
    zones = planar_zones_from(opts)
    forced = planar_displacement_forces(args, n, model_options_from(opts), zones,
                                        contact_from_options(opts, zones[0]))
    run = compute_planar(planar_inputs(opts, forced))
    result, at, ac, opt = (run.result, run.inputs.tip_amplitude, run.inputs.centre_amplitude,
                           run.inputs.options)
    if args.plot:
        from ..plot.paper import figure_planar

        figure_planar(result, args.plot)
    report_warnings(list(run.warnings))
    out = planar_json(run)
    if args.json:
        print_json(out)
        return 0
    w = result.work
    print(f"planar case R = {result.ratio:.6g} (eccentricity {result.eccentricity:.4f}), "
          f"tip {at:g} N ({args.tip_preset}, x{result.tip_symmetry} in parallel), "
          f"centre {ac:g} N ({args.centre_preset}), {n} increments, poisson={opt.poisson}, "
          f"length_update={opt.length_update}, centre reading={opt.centre}")
    if clamp_overrides(args):
        given = ", ".join(f"{k} {v:g}" for k, v in clamp_overrides(args).items())
        print(f"  own clamp: {given} (N, mm, MPa; tip zone width / {result.tip_symmetry})")
    print(f"  strain energy U: {args.strain_energy} ({STRAIN_ENERGY[args.strain_energy][1]})")
    print(f"  {'':31s}{'W_d (N·mm)':>14s}{'U (N·mm)':>14s}{'eta (-)':>12s}  W_d of")
    rows = (("tip model", result.tip, out["tip"]["clamp_portion"]),
            ("centre model", result.centre, out["centre"]["clamp_portion"]),
            ("paper's resultant (Eqs 19-23)", result.paper, out["paper_clamp_portion"]))
    for name, r, portion in rows:
        print(f"  {name:31s}{r.dissipated_energy:14.6g}{r.strain_energy:14.6g}"
              f"{r.loss_factor:12.6g}  {portion_text(portion)}")
    print(f"  {'work of the load':31s}{w.dissipated_energy:14.6g}{w.strain_energy:14.6g}"
          f"{w.loss_factor:12.6g}  {portion_text(out['clamp_portion'])} "
          f"(phase {result.phase_deg:g} deg, U {result.work_energy})")
    print(f"  share of W: tip {w.tip_dissipated_energy / w.dissipated_energy:.4f}, centre "
          f"{w.centre_dissipated_energy / w.dissipated_energy:.4f} (dimensionless); "
          f"paper's eta with secant U {result.paper_loss_factors['secant']:.6g}")
    if args.plot:
        print(f"  figure {args.plot}")
    return 0
