"""``microslip modal``: natural frequency and damping ratio of a mode versus amplitude.

The options of the structure and of harmonic balance, shared with ``microslip frf``, are in
:mod:`.structure`.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np

from ..case.table import add_option
from ..dynamics.harmonics import adaptive_epmc, cap_warning
from ..dynamics.modal import METHODS, MODAL_COORDINATE, energy_method
from ..errors import ParameterError
from .contact import report_warnings
from .modalmesh import (
    ALL,
    add_modal_mesh_options,
    mesh_study,
    refuse_mesh_options,
    run_modal_mesh,
)
from .structure import (
    NOT_MESH,
    across_warnings,
    add_balance_options,
    add_structure_options,
    balance_from_args,
    balance_json,
    balance_text,
    describe_structure,
    harmonic_control,
    headline,
    mode_from_args,
    structure_from_args,
)

__all__ = ["add_parser", "amplitudes_from_args", "run"]


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "modal", help="nonlinear modal analysis: frequency and damping ratio vs amplitude",
        description="Natural frequency and damping ratio (linear damping included) of a "
        "mode with a joint versus its modal amplitude: by the extended periodic motion "
        "concept with harmonic balance (epmc) or by the energy method from the joint's "
        "describing function (energy).")
    add_structure_options(p)
    add_balance_options(p)
    add_modal_mesh_options(p)
    g = p.add_argument_group("amplitudes and output")
    add_option(g, "amplitude_range", help="modal amplitudes, mm (geometric spacing); required "
               "but with --mesh, where the default runs from first slip to near gross sliding")
    add_option(g, "amplitudes")
    add_option(g, "method", choices=list(METHODS), default="epmc", mode=NOT_MESH)
    add_option(g, "json")
    add_option(g, "csv", mode=NOT_MESH)
    add_option(g, "plot", help="write a figure of frequency and damping ratio vs amplitude")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..io import check_writable, write_csv
    from .common import check_plot, print_json

    if args.mesh is not None:
        if args.csv:
            raise ParameterError("--csv is not used with --mesh; use --json")
        if args.solver == ALL:
            from .modalcompare import run_modal_all

            return run_modal_all(mesh_study(args), args)
        return run_modal_mesh(args)
    refuse_mesh_options(args)
    if args.amplitude_range is None:
        raise ParameterError("give --amplitude-range MIN MAX (modal amplitudes, mm)")

    check_plot(args.plot)
    if args.csv:
        check_writable(args.csv)
    structure = structure_from_args(args)
    warnings = across_warnings(args)
    three_d = any(link.directions == 3 for link in structure.joints)
    if three_d and args.method == "epmc":  # the energy method refuses 3-D contact elements
        warnings.append("3-D contact joints: no energy-method curve (it takes 1-D and 2-D "
                        "joints); energy_method is null")
    report_warnings(warnings)
    if args.method == "energy" and args.harmonics is not None:
        raise ParameterError("--harmonics is not used by --method energy (a single-harmonic "
                             "balance); leave it out or use --method epmc")
    if args.method == "energy" and args.harmonic_tolerance is not None:
        raise ParameterError("--harmonic-tolerance is not used by --method energy (a "
                             "single-harmonic balance); leave it out or use --method epmc")
    control = harmonic_control(args) if args.method == "epmc" else None
    if control is None:
        harmonics, samples = balance_from_args(args)
    amps = amplitudes_from_args(args)
    mode = mode_from_args(args)
    failures: list[str] = []  # 3-D contact (a ROM's file): an amplitude missed is NaN
    if control is not None:
        curve = adaptive_epmc(structure, amps, control, mode)
        capped = cap_warning(curve.harmonic_error_estimate, curve.harmonics, control)
        if capped:
            warnings.append(capped)
            report_warnings([capped])
    elif args.method == "epmc" and three_d:
        from ..dynamics.modal import epmc

        curve = epmc(structure, amps, harmonics, samples, mode, failures=failures)
        report_warnings(failures)
        warnings += failures
    else:
        curve = METHODS[args.method](structure, amps, harmonics, samples, mode)
    energy = curve if args.method == "energy" or three_d else energy_method(structure, amps,
                                                                            mode=mode)
    if args.csv:
        write_csv(args.csv, {"amplitude_mm": curve.amplitude, "frequency_Hz": curve.frequency,
                             "damping_ratio": curve.damping_ratio})
    if args.plot:
        from ..plot.dynamics import plot_modal

        plot_modal(curve, energy, args.plot)
    if args.json:
        print_json({"structure": describe_structure(structure, args), "method": curve.method,
                    **balance_json(curve, control),
                    "amplitude_mm": curve.amplitude, "amplitude_coordinate": MODAL_COORDINATE,
                    "frequency_Hz": _nulls(curve.frequency),
                    "damping_ratio": _nulls(curve.damping_ratio),
                    "energy_method": None if three_d else {
                        "frequency_Hz": energy.frequency,
                        "damping_ratio": energy.damping_ratio},
                    "warnings": warnings})
        return 0
    print(f"{headline(structure, mode)}; {args.method}, {balance_text(curve)}")
    print(f"{'q (mm)':>12} {'f (Hz)':>12} {'zeta (-)':>12}")  # the modal coordinate
    for row in zip(curve.amplitude, curve.frequency, curve.damping_ratio, strict=True):
        print("{:12.5g} {:12.7g} {:12.5g}".format(*row))
    return 0


def _nulls(values: np.ndarray) -> list[float | None]:
    """A column for JSON: NaN (an amplitude the EPMC missed, its reason a warning) as
    null."""
    return [None if math.isnan(v) else float(v) for v in values]


def amplitudes_from_args(args: argparse.Namespace) -> np.ndarray:
    """Geometrically spaced modal amplitudes (mm) of --amplitude-range and --amplitudes."""
    n = args.amplitudes
    if not 1 <= n <= 100_000:
        raise ParameterError(f"--amplitudes must be in [1, 100000], got {n}")
    lo, hi = args.amplitude_range
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ParameterError(f"--amplitude-range must satisfy 0 < MIN <= MAX (mm), got "
                             f"{lo:g} {hi:g}")
    return np.geomspace(lo, hi, n) if n > 1 else np.array([lo])
