"""``microslip frf``: frequency-response curves of a mode with a joint, several force levels;
with ``--mesh FILE`` the structure of the user's own mesh with its clamp (:mod:`.frfmesh`)."""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

import numpy as np

from ..case.table import add_option
from ..dynamics.assemble import joint_orbits, mode_load
from ..dynamics.files import read_structure
from ..dynamics.harmonics import adaptive_response, cap_warning
from ..dynamics.modal import epmc
from ..dynamics.response import DEFAULT_STEP, FrequencyResponse, frequency_response
from ..dynamics.structure import Structure
from ..errors import ParameterError
from ..progress import progress
from .contact import report_warnings
from .frfmesh import (
    MESH_RANGE,
    add_frf_mesh_options,
    check_range,
    refuse_frf_mesh_options,
    run_frf_mesh,
)
from .structure import (
    NOT_MESH,
    across_warnings,
    add_balance_options,
    add_structure_options,
    balance_from_args,
    connectivity_from_args,
    describe_structure,
    harmonic_control,
    headline,
    mode_from_args,
    structure_from_args,
)

__all__ = ["add_parser", "default_range", "excitation_from_args", "run"]

#: Default frequency range: this fraction of the joint-removed frequency up to the
#: reciprocal fraction of the stuck frequency.
RANGE_MARGIN = 0.8


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "frf", help="forced response: frequency-response curves through the resonance",
        description="Steady-state response of a mode with a joint to F cos(2 pi f t) by "
        "harmonic balance (alternating frequency-time scheme) and arclength continuation "
        "through the resonance, one curve per --force; amplitudes are first-harmonic "
        "amplitudes of the modal coordinate.")
    add_structure_options(p)
    add_balance_options(p)
    add_frf_mesh_options(p)
    g = p.add_argument_group("excitation and output")
    add_option(g, "force", required=True, note="with --mesh the total force on --load-set")
    add_option(g, "excitation", note="default: the modal force of --mode", mode=NOT_MESH)
    add_option(g, "frequency_range", note=f"default {RANGE_MARGIN:g} x the joint-removed to "
               f"{1 / RANGE_MARGIN:g} x the stuck frequency; with --mesh {MESH_RANGE[0]:g} to "
               f"{MESH_RANGE[1]:g} x the mode's stuck frequency")
    add_option(g, "step", default=DEFAULT_STEP)
    add_option(g, "json")
    add_option(g, "csv", help="write every curve's points as CSV")
    add_option(g, "plot", help="write the curves with the backbone (extended periodic motion "
                               "concept) over them")
    p.set_defaults(func=run)


def default_range(structure: Structure, mode: int = 0) -> tuple[float, float]:
    """(MIN, MAX) Hz around the resonance of ``mode`` (0-based), joints removed to stuck
    (from half the stuck frequency if the joint-free structure has a rigid-body mode)."""
    free = float(structure.linear_frequencies(stuck=False)[mode])
    stuck = float(structure.linear_frequencies(stuck=True)[mode])
    low = min(free, stuck) if free > 0.0 else stuck / (2.0 * RANGE_MARGIN)
    return RANGE_MARGIN * low, stuck / RANGE_MARGIN


def excitation_from_args(args: argparse.Namespace, structure: Structure) -> np.ndarray:
    """Force per unit --force on each DOF, N: the modal force of --mode, or the
    --excitation DOFs (one mode: 1)."""
    if structure.dofs == 1 and args.structure is None:
        return np.ones(1)
    if args.excitation is None:
        return mode_load(structure, mode_from_args(args))
    dofs = np.array(args.excitation)
    if np.any(dofs < 0) or np.any(dofs >= structure.dofs) or len(set(dofs)) != dofs.size:
        raise ParameterError(f"--excitation must name distinct DOFs in [0, "
                             f"{structure.dofs - 1}], got {args.excitation}")
    shape = np.zeros(structure.dofs)
    shape[dofs] = 1.0
    return shape


def run(args: argparse.Namespace) -> int:
    from ..io import check_writable, write_csv
    from .common import check_plot, print_json

    if args.mesh is not None:
        _check_levels(args)
        return run_frf_mesh(args, [float(f) for f in args.force])
    refuse_frf_mesh_options(args)
    check_plot(args.plot)
    if args.csv:
        check_writable(args.csv)
    structure = structure_from_args(args)
    warnings = across_warnings(args)
    report_warnings(warnings)
    control = harmonic_control(args)
    if control is None:
        harmonics, samples = balance_from_args(args)
    _check_levels(args)
    mode = mode_from_args(args)
    frange = _range(args, structure, mode)
    shape = excitation_from_args(args, structure)
    levels = progress(args.force, desc="frf", total=len(args.force))
    if control is not None:
        chosen = [adaptive_response(structure, f, shape, frange, control, args.step)
                  for f in levels]
        curves = [c.response for c in chosen]
        estimates = [c.harmonic_error_estimate for c in chosen]
        capped = cap_warning(estimates, max(c.harmonics for c in curves), control,
                             "curve(s)")
        if capped:
            warnings.append(capped)
            report_warnings([capped])
    else:
        curves = [frequency_response(structure, f, shape, frange, harmonics, samples,
                                     args.step) for f in levels]
    for c in curves:
        if not c.success:
            print(f"warning: curve at {c.force:g} N stopped early: {c.message}",
                  file=sys.stderr)
    if args.csv:
        write_csv(args.csv, {
            "force_N": np.concatenate([np.full(c.frequency.size, c.force) for c in curves]),
            "frequency_Hz": np.concatenate([c.frequency for c in curves]),
            "amplitude_mm": np.concatenate([c.amplitude for c in curves])})
    if args.plot:
        _plot(structure, curves, args.plot, mode,
              [joint_orbits(c, _connectivity(args)) for c in curves])
    if args.json:
        balance: dict[str, Any] = (
            {"harmonics": harmonics, "samples": samples} if control is None else
            {"harmonics": [c.harmonics for c in curves],
             "samples": [c.samples for c in curves], "harmonic_error_estimate": estimates,
             "harmonic_tolerance": control.tolerance})
        print_json({"structure": describe_structure(structure, args), **balance,
                    "frequency_range_Hz": list(frange),
                    "curves": [_curve_json(c, _connectivity(args)) for c in curves],
                    "warnings": warnings})
        return 0
    if control is not None:
        used = sorted({c.harmonics for c in curves})
        text = (f"harmonics auto: {' or '.join(map(str, used))} harmonic(s), largest "
                f"error estimate {100 * max(estimates):.3g} %")
    else:
        text = f"{harmonics} harmonic(s), {samples} samples"
    print(f"{headline(structure, mode)}; {text}, {frange[0]:.6g} to {frange[1]:.6g} Hz")
    print(f"{'force (N)':>12} {'peak a (mm)':>14} {'peak f (Hz)':>14} {'points':>7}")
    for c in curves:
        print(f"{c.force:12.6g} {c.peak_amplitude:14.7g} {c.peak_frequency:14.8g} "
              f"{c.frequency.size:7d}")
    return 0


def _check_levels(args: argparse.Namespace) -> None:
    """Every --force finite and > 0 N, --step in (0, 1]."""
    for f in args.force:
        if not (math.isfinite(f) and f > 0.0):
            raise ParameterError(f"--force must be finite and > 0 N, got {f!r}")
    if not (math.isfinite(args.step) and 0.0 < args.step <= 1.0):
        raise ParameterError(f"--step must be in (0, 1], got {args.step!r}")


def _connectivity(args: argparse.Namespace) -> np.ndarray | list[np.ndarray]:
    if args.structure is None:
        return np.zeros((0, 1, 2), dtype=np.int64)
    return connectivity_from_args(args, read_structure(args.structure))


def _curve_json(c: FrequencyResponse, joints: np.ndarray | list[np.ndarray]
                ) -> dict[str, Any]:
    out = {"force_N": c.force, "frequency_Hz": c.frequency, "amplitude_mm": c.amplitude,
           "peak_amplitude_mm": c.peak_amplitude, "peak_frequency_Hz": c.peak_frequency,
           "points": int(c.frequency.size), "success": c.success, "message": c.message}
    orbits = joint_orbits(c, joints)
    if orbits:
        out["joint_orbits"] = orbits
    return out


def _range(args: argparse.Namespace, structure: Structure, mode: int
           ) -> tuple[float, float]:
    if args.frequency_range is None:
        return default_range(structure, mode)
    return check_range(*args.frequency_range)


def _plot(structure: Structure, curves: list[FrequencyResponse], path: str, mode: int,
          orbits: list[list[dict[str, Any]]]) -> None:
    """The curves with the backbone (EPMC, up to 1.05 times the highest peak) over them, and
    the joint orbits (:func:`microslip.plot.dynamics.plot_frequency_response`)."""
    from ..plot.dynamics import plot_frequency_response

    top = max(float(c.amplitude.max()) for c in curves)
    backbone = epmc(structure, np.geomspace(top * 1e-3, top * 1.05, 80),
                    curves[0].harmonics, curves[0].samples, mode)
    plot_frequency_response(curves, backbone, orbits, path)
