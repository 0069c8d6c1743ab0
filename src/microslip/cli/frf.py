"""``microslip frf``: frequency-response curves of a mode with a joint, several force levels."""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

import numpy as np

from ..dynamics.modal import epmc
from ..dynamics.response import DEFAULT_STEP, FrequencyResponse, frequency_response
from ..dynamics.structure import Structure
from ..errors import ParameterError
from ..progress import progress
from .common import number
from .modal import (
    add_balance_options,
    add_structure_options,
    balance_from_args,
    describe_structure,
    structure_from_args,
)

__all__ = ["add_parser", "default_range", "run"]

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
    g = p.add_argument_group("excitation and output")
    g.add_argument("--force", type=number, action="append", required=True, metavar="N",
                   help="excitation amplitude, N (repeat for several curves)")
    g.add_argument("--frequency-range", nargs=2, type=number, metavar=("MIN", "MAX"),
                   help=f"excitation frequencies, Hz (default {RANGE_MARGIN:g} x the "
                        f"joint-removed to {1 / RANGE_MARGIN:g} x the stuck frequency)")
    g.add_argument("--step", type=number, default=DEFAULT_STEP, metavar="S",
                   help="largest continuation step, relative to the frequency range and "
                        f"the peak amplitude (default {DEFAULT_STEP:g})")
    g.add_argument("--json", action="store_true", help="print one JSON object")
    g.add_argument("--csv", metavar="FILE.csv", help="write every curve's points as CSV")
    g.add_argument("--plot", metavar="FILE.png",
                   help="write the curves with the backbone (extended periodic motion "
                        "concept) over them")
    p.set_defaults(func=run)


def default_range(structure: Structure) -> tuple[float, float]:
    """(MIN, MAX) Hz around the resonance of the lowest mode, joint removed to stuck."""
    free = float(structure.linear_frequencies(stuck=False)[0])
    stuck = float(structure.linear_frequencies(stuck=True)[0])
    return RANGE_MARGIN * free, stuck / RANGE_MARGIN


def run(args: argparse.Namespace) -> int:
    from ..io import check_writable, write_csv
    from .common import check_plot, print_json

    check_plot(args.plot)
    if args.csv:
        check_writable(args.csv)
    structure = structure_from_args(args)
    harmonics, samples = balance_from_args(args)
    for f in args.force:
        if not (math.isfinite(f) and f > 0.0):
            raise ParameterError(f"--force must be finite and > 0 N, got {f!r}")
    if not (math.isfinite(args.step) and 0.0 < args.step <= 1.0):
        raise ParameterError(f"--step must be in (0, 1], got {args.step!r}")
    frange = _range(args, structure)
    shape = np.ones(structure.dofs)
    curves = [frequency_response(structure, f, shape, frange, harmonics, samples, args.step)
              for f in progress(args.force, desc="frf", total=len(args.force))]
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
        _plot(structure, curves, args.plot)
    if args.json:
        print_json({"structure": describe_structure(structure), "harmonics": harmonics,
                    "samples": samples, "frequency_range_Hz": list(frange),
                    "curves": [_curve_json(c) for c in curves]})
        return 0
    d = describe_structure(structure)
    print(f"mode {d['frequency_Hz']:.6g} Hz with the joint removed, "
          f"{d['stuck_frequency_Hz']:.6g} Hz stuck; {harmonics} harmonic(s), {samples} "
          f"samples, {frange[0]:.6g} to {frange[1]:.6g} Hz")
    print(f"{'force (N)':>12} {'peak a (mm)':>14} {'peak f (Hz)':>14} {'points':>7}")
    for c in curves:
        print(f"{c.force:12.6g} {c.peak_amplitude:14.7g} {c.peak_frequency:14.8g} "
              f"{c.frequency.size:7d}")
    return 0


def _curve_json(c: FrequencyResponse) -> dict[str, Any]:
    return {"force_N": c.force, "frequency_Hz": c.frequency, "amplitude_mm": c.amplitude,
            "peak_amplitude_mm": c.peak_amplitude, "peak_frequency_Hz": c.peak_frequency,
            "points": int(c.frequency.size), "success": c.success, "message": c.message}


def _range(args: argparse.Namespace, structure: Structure) -> tuple[float, float]:
    if args.frequency_range is None:
        return default_range(structure)
    lo, hi = args.frequency_range
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise ParameterError(f"--frequency-range must satisfy 0 < MIN < MAX (Hz), got "
                             f"{lo:g} {hi:g}")
    return float(lo), float(hi)


def _plot(structure: Structure, curves: list[FrequencyResponse], path: str) -> None:
    from ..plot import COLOURS, new_figure, save_figure

    top = max(float(c.amplitude.max()) for c in curves)
    backbone = epmc(structure, np.geomspace(top * 1e-3, top * 1.05, 80),
                    curves[0].harmonics, curves[0].samples)
    fig, axes = new_figure(width_mm=120.0)
    ax = axes[0][0]
    for c, colour in zip(curves, COLOURS * len(curves), strict=False):
        ax.plot(c.frequency, c.amplitude, color=colour, label=f"F = {c.force:g} N")
        ax.plot([c.peak_frequency], [c.peak_amplitude], "o", color=colour, markersize=3)
    ax.plot(backbone.frequency, backbone.amplitude, color="k", linestyle="--",
            label="backbone (EPMC)")
    ax.set_xlabel("excitation frequency f (Hz)")
    ax.set_ylabel("first-harmonic amplitude a (mm)")
    ax.legend()
    save_figure(fig, path)
