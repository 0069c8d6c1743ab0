"""``microslip sweep --solver fe``: an amplitude sweep of finite-element runs, resumable.

The options of the FE sweep (added to ``sweep``'s parser by :func:`add_options`) and its run;
the computation and the resumable file are :mod:`microslip.sweep.fe`.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..case.table import add_option, add_solver
from ..conventions import CLAMP_MODELS, DEFAULT_MESH
from ..errors import ParameterError
from .common import params_from_args

__all__ = ["RUNNERS", "add_options", "run"]

#: Flags of ``sweep`` that an FE sweep does not take, with their argparse destinations.
NOT_FE = (("--grid", "grid"), ("--sample", "sample"), ("--ratio-range", "ratio_range"),
          ("--scheduler", "scheduler"), ("--seed", "seed"), ("--amplitude", "amplitude"),
          ("--displacement-amplitude", "displacement_amplitude"), ("--plot", "plot"),
          ("--pressure-law", "pressure_law"), ("--no-shear-lag", "no_shear_lag"))


def add_options(parser: argparse.ArgumentParser) -> None:
    from ..fe import SOLVERS

    g = parser.add_argument_group("--solver fe: finite-element amplitude sweep (docs/report.md)")
    add_solver(g, "sweep")
    add_option(g, "fe_solver", choices=list(SOLVERS),
               note="with --solver fe")
    add_option(g, "mesh", default=DEFAULT_MESH, note="--solver fe")
    add_option(g, "substeps", note="of each FE run")


def _check(args: argparse.Namespace) -> None:
    from ..fe import SOLVERS

    given = [flag for flag, dest in NOT_FE if getattr(args, dest, None) not in (None, [], False)]
    if given:
        raise ParameterError(f"{given[0]} does not apply to --solver fe (it sweeps "
                             "--amplitude-range A B over --cases N)")
    if args.model not in CLAMP_MODELS:
        raise ParameterError(f"--solver fe sweeps --model tip or centre, not {args.model}")
    if args.amplitude_range is None:
        raise ParameterError("--solver fe needs --amplitude-range A B (N)")
    meshes = SOLVERS[args.fe_solver].meshes
    if args.mesh not in meshes:
        raise ParameterError(f"--mesh {args.mesh} is not a mesh of the {args.fe_solver} solver; "
                             f"choose one of {', '.join(meshes)}")
    if args.substeps < 5 or args.substeps % 5:
        raise ParameterError(f"--substeps must be a positive multiple of 5, got {args.substeps}")
    if not args.out or not args.out.lower().endswith(".csv"):
        raise ParameterError("--solver fe needs --out FILE.csv (finished points are saved there "
                             f"as they complete), got {args.out!r}")


def run(args: argparse.Namespace) -> int:
    from ..sweep.fe import FESweepSpec, amplitudes, run_fe_sweep

    _check(args)
    if args.preset is None and args.length is None:
        args.preset = "table1"
    params, _ = params_from_args(args, fallback_amplitude=1.0)
    a, b = args.amplitude_range
    values = amplitudes(a, b, 20 if args.cases is None else int(args.cases))
    if max(values) >= params.macroslip_force:
        raise ParameterError(f"--amplitude-range reaches {max(values):g} N; the FE runs need "
                             f"0 < amplitude < {params.macroslip_force:g} N (mu F_N, macroslip)")
    spec = FESweepSpec(load=args.model, params=params, amplitudes=values, solver=args.fe_solver,
                       mesh=args.mesh, substeps=args.substeps, strain_energy=args.strain_energy,
                       **({} if args.stick_slope is None else {"stick_slope": args.stick_slope}))
    print(f"FE sweep: {args.model} load, {args.fe_solver} solver, mesh {args.mesh}, "
          f"{args.substeps} substeps, {len(values)} amplitudes from {a:g} to {b:g} N -> "
          f"{args.out}", flush=True)
    try:
        result = run_fe_sweep(spec, args.out, progress=not args.no_progress,
                              say=lambda line: print(f"  {line}", flush=True),
                              on_point=None if sys.stderr.isatty() else _point_line(len(values)))
    except KeyboardInterrupt:
        print(f"interrupted: the finished points are in {args.out}; run the same command "
              "again to resume", file=sys.stderr)
        return 130
    _summary(result, args.out)
    return 0


def _point_line(total: int) -> Any:
    """Progress as one line per finished point, where no progress bar is drawn (no terminal)."""
    def say(done: int, row: tuple[float, ...]) -> None:
        print(f"  point {done}/{total}: F0 = {row[0]:.6g} N, eta = {row[4]:.6g} "
              f"(dimensionless), {row[-1]:.3g} s", flush=True)

    return say


def _summary(result: Any, out: str) -> None:
    eta = result.column("loss_factor")
    failed = int(result.table.shape[0] - result.column("converged").sum())
    print(f"  points                 {result.table.shape[0]} ({result.computed} computed now, "
          f"{result.table.shape[0] - result.computed} read from {out})")
    print(f"  loss factor eta        {eta.min():.6g} .. {eta.max():.6g} (dimensionless)")
    print(f"  wall time of the runs  {result.column('wall_s').sum():.3g} s")
    if failed:
        print(f"  not converged          {failed} point(s) (column converged = 0)")
    print(f"  wrote                  {out}")


#: Sweep runners other than the batch engine, by --solver.
RUNNERS = {"fe": run}
