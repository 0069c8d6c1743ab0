"""``microslip frf --mesh FILE``: the forced response of the structure of the user's own mesh
with its clamp, at the force levels the user gives (issue 23, item 5).

The study is the library's (:mod:`microslip.meshdynamics.frfstudy`: the solvers of
:data:`~microslip.meshdynamics.frfstudy.FRF_MESH_SOLVERS` on one
:class:`~microslip.meshdynamics.case.StructureCase`, the contact-node ROM built once with the
response set's and the load set's rows); this module checks the options, builds the case
(:func:`.meshstructure.structure_case`), calls, and prints. Units N, mm, Hz, kg/m^3.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Iterable
from typing import Any

import numpy as np

from ..case.table import MODE_MESH, add_option, add_solver, mode_options
from ..errors import ParameterError
from ..meshdynamics.frfstudy import (
    DEFAULT_MESH_HARMONICS,
    FRF_MESH_SOLVERS,
    MESH_RANGE,
    REFERENCE,
    ForcedModel,
    FrfSettings,
)
from .common import check_plot, flagged, print_json
from .meshstructure import (
    add_mesh_structure_options,
    add_reduced_model_options,
    check_mesh_structure,
    structure_case,
)
from .ownmesh import given, print_model, verb

__all__ = ["MESH_RANGE", "add_frf_mesh_options", "check_range", "refuse_frf_mesh_options",
           "run_frf_mesh"]

#: ``--solver`` that runs every solver of :data:`FRF_MESH_SOLVERS` on the same forces.
ALL = "all"


def add_frf_mesh_options(p: argparse.ArgumentParser) -> None:
    """The mesh structure's options (:mod:`.meshstructure`), the load and the solver."""
    g = p.add_argument_group("the structure of your own mesh (--mesh FILE; docs/ownmesh.md)")
    add_mesh_structure_options(g)
    add_option(g, "load_set", note="default: the response set", mode=MODE_MESH)
    add_option(g, "load_direction", note="default: the response set's motion in the mode",
               mode=MODE_MESH)
    add_solver(g, "frf", meaning={**{k: v.help for k, v in FRF_MESH_SOLVERS.items()},
                                  ALL: "both on the same forces and frequencies, the whole "
                                       "joint's peaks against the ROM's"}, mode=MODE_MESH,
               note=f"--mesh only, where --harmonics defaults to {DEFAULT_MESH_HARMONICS}")
    add_reduced_model_options(g)


def refuse_frf_mesh_options(args: argparse.Namespace) -> None:
    """Without --mesh, the mesh's options given on the command line are refused."""
    bad = [f"--{d.replace('_', '-')}" for d in mode_options(args, MODE_MESH) if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to frf --mesh FILE only; remove "
                             "them")


def check_range(lo: float, hi: float) -> tuple[float, float]:
    """A checked --frequency-range MIN MAX, Hz."""
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise ParameterError(f"--frequency-range must satisfy 0 < MIN < MAX (Hz), got "
                             f"{lo:g} {hi:g}")
    return float(lo), float(hi)


def _check(args: argparse.Namespace) -> None:
    check_mesh_structure(args)
    if args.response_set is None:
        from .main import UsageError  # a required option left out: a usage mistake

        raise UsageError(f"--mesh {args.mesh} needs --response-set NAME (the amplitude is its "
                         "mean displacement along the mode)")
    solver = args.solver or "rom"
    for dest in dict.fromkeys(o for s in FRF_MESH_SOLVERS.values() for o in s.options):
        if given(args, dest) and solver != ALL and dest not in FRF_MESH_SOLVERS[solver].options:
            owners = [n for n, s in FRF_MESH_SOLVERS.items() if dest in s.options]
            raise ParameterError(f"--{dest.replace('_', '-')} applies to --solver "
                                 f"{' or '.join(owners)} only")
    if solver == ALL and (args.plot or args.csv):
        raise ParameterError("--plot and --csv draw and write one solver's curves; give "
                             "--solver rom or joint with them (--solver all compares the "
                             "peaks)")
    if args.rom_modes is not None and args.rom_modes < 1:
        raise ParameterError(f"--rom-modes must be >= 1, got {args.rom_modes}")


def _load_direction(text: str | None) -> Any:
    """--load-direction DX,DY,DZ as numbers (the study checks them)."""
    if text is None:
        return None
    try:
        return [float(v) for v in str(text).split(",")]
    except ValueError:
        raise ParameterError(f"--load-direction must be three finite numbers DX,DY,DZ, not "
                             f"all 0, got {text!r}") from None


def run_frf_mesh(args: argparse.Namespace, levels: list[float]) -> int:
    """``frf --mesh``: one curve per force level (N, checked by the caller)."""
    from ..io import check_writable, write_csv
    from ..meshdynamics.frfstudy import frf_output, prepare_frf, run_forced
    from ..progress import progress
    from .structure import balance_from_args, harmonic_control

    check_plot(args.plot)
    if args.csv:
        check_writable(args.csv)
    _check(args)
    case = structure_case(args)
    direction = _load_direction(args.load_direction)
    if args.harmonics == "auto":
        raise ParameterError("--harmonics auto is not available with frf --mesh (each level "
                             "a whole continuation on the ROM); give a number, default "
                             f"{DEFAULT_MESH_HARMONICS}")
    if args.harmonics is None:
        args.harmonics = DEFAULT_MESH_HARMONICS
    harmonic_control(args, auto=False)  # refuses --harmonic-tolerance with fixed harmonics
    harmonics, samples = balance_from_args(args)
    frange = None if args.frequency_range is None else check_range(*args.frequency_range)
    settings = FrfSettings(harmonics=harmonics, samples=samples, frequency_range=frange,
                           step=args.step, damping_ratio=args.damping_ratio or 0.0)
    with flagged():
        study = prepare_frf(case, args.load_set, direction)
    solver = args.solver or "rom"
    names = tuple(FRF_MESH_SOLVERS) if solver == ALL else (solver,)

    def each(name: str, forces: Iterable[float]) -> Iterable[float]:
        return progress(list(forces), desc="frf" if solver != ALL else f"frf {name}",
                        total=len(levels))

    runs = run_forced(study, levels, settings, names, each)
    out = frf_output(study, runs, settings, compare=solver == ALL)
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if solver == ALL:
        return _print_all(args, study, out)
    forced, curves = runs[solver]
    if args.csv:
        write_csv(args.csv, {
            "force_N": np.concatenate([np.full(c.frequency.size, c.force) for c in curves]),
            "frequency_Hz": np.concatenate([c.frequency for c in curves]),
            "amplitude_mm": np.concatenate([c.amplitude for c in curves])})
    if args.plot:
        _plot(forced, curves, args.plot)
    if args.json:
        print_json(out)
        return 0
    lo, hi = out["frequency_range_Hz"]
    stuck_hz = out["linear_frequencies_Hz"][study.number - 1]
    print(f"mesh {args.mesh}: mode {study.number} ({out['label']}), stuck {stuck_hz:.6g} Hz, "
          f"free {out['free_frequencies_Hz'][study.number - 1]:.6g} Hz; {forced.label}, "
          f"{harmonics} harmonic(s); load on {study.load_set!r}, "
          f"{lo:.6g} to {hi:.6g} Hz")
    print_model(out["model"])
    print(f"{'force (N)':>12} {'peak a (mm)':>14} {'peak f (Hz)':>14} {'zeta (-)':>12} "
          f"{'points':>7}")
    for c in out["curves"]:
        zeta = "n/a" if c["damping_ratio"] is None else f"{c['damping_ratio']:.5g}"
        print(f"{c['force_N']:12.6g} {c['peak_amplitude_mm']:14.7g} "
              f"{c['peak_frequency_Hz']:14.8g} {zeta:>12} {c['points']:7d}")
    return 0


def _print_all(args: argparse.Namespace, study: Any, out: dict[str, Any]) -> int:
    """``frf --mesh --solver all``: every solver's curves on the same forces and range, and
    each one's peaks against the ROM's."""
    if args.json:
        print_json(out)
        return 0
    lo, hi = out["frequency_range_Hz"]
    print(f"mesh {args.mesh}: mode {study.number} ({out['label']}); load on "
          f"{study.load_set!r}, {lo:.6g} to {hi:.6g} Hz, {out['harmonics']} harmonic(s)")
    print_model(out["model"])
    print(f"{'solver':>8} {'force (N)':>10} {'peak a (mm)':>13} {'peak f (Hz)':>13} "
          f"{'zeta (-)':>10}")
    for name, s in out["solvers"].items():
        for c in s["curves"]:
            zeta = "n/a" if c["damping_ratio"] is None else f"{c['damping_ratio']:.5g}"
            print(f"{name:>8} {c['force_N']:10.6g} {c['peak_amplitude_mm']:13.6g} "
                  f"{c['peak_frequency_Hz']:13.7g} {zeta:>10}")
    for name, rows in out["comparison"].items():
        for r in rows:
            parts = [f"{label} {100 * r[key]:+.2g} %" for key, label in (
                ("peak_amplitude_difference", "peak amplitude"),
                ("peak_frequency_difference", "peak frequency"),
                ("damping_ratio_difference", "damping ratio")) if r[key] is not None]
            print(f"  {name} against {REFERENCE} at {r['force_N']:g} N: {', '.join(parts)}")
    return 0


def _plot(forced: ForcedModel, curves: list[Any], path: str) -> None:
    """The curves with the structure's backbone (EPMC up to 1.05 times the highest peak)."""
    from ..dynamics.modal import epmc
    from ..dynamics.modal_odd import epmc_odd
    from ..plot.dynamics import plot_frequency_response

    top = max(float(c.amplitude.max()) for c in curves)
    method = epmc_odd if forced.odd else epmc
    backbone = method(forced.structure, np.geomspace(top * 1e-2, top * 1.05, 20),
                      curves[0].harmonics, curves[0].samples, forced.mode)
    plot_frequency_response(curves, backbone, [[] for _ in curves], path)
