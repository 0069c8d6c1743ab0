"""``microslip fe``: one finite-element run of the tip or centre load case (paper, Section 4).

The solver is chosen from :data:`SOLVERS` (``--solver``); each entry takes the validated
:class:`~microslip.fe.case.FECase`, the job directory and the parsed arguments, and returns an
:class:`~microslip.fe.results.FEResult`-like object with ``summary()``.
"""

from __future__ import annotations

import argparse
import math
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..errors import ParameterError
from ..fe.case import (
    DEFAULT_NORMAL_SLOPE,
    DEFAULT_STICK_SLOPE,
    ELEMENT_TYPES,
    LOAD_CASES,
    FECase,
)
from ..fe.mesh import MESHES
from .common import add_params, add_strain_energy, number, params_from_args, print_json

__all__ = ["SOLVERS", "add_parser", "case_from_args", "run"]


def _run_calculix(case: FECase, job_dir: Path, args: argparse.Namespace) -> Any:
    from ..fe.runner import run_case

    return run_case(case, job_dir, timeout=args.timeout, threads=args.threads,
                    reuse=args.reuse, strain_energy_kind=args.strain_energy)


#: Solvers of ``--solver``: name -> callable(case, job_dir, args) -> result with summary().
SOLVERS: dict[str, Callable[[FECase, Path, argparse.Namespace], Any]] = {
    "calculix": _run_calculix,
}


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "fe", help="finite-element run (CalculiX) of the tip or centre load case",
        description="Build the paper's FE model (Section 4: bar on a rigid base, Coulomb "
        "friction, clamping pressure, then F_T = F0 sin(2 pi t) over 1.25 s in equal "
        "substeps), run it, and report the loop, W_d, U and eta. Needs CalculiX (ccx): "
        "bash scripts/setup.sh or apt-get install calculix-ccx.")
    p.add_argument("--model", choices=list(LOAD_CASES), required=True,
                   help="tip: traction on the end face; centre: on the mid-length section")
    add_params(p, default_preset="table1")
    g = p.add_argument_group("finite-element model (docs/validation.md)")
    g.add_argument("--mesh", choices=list(MESHES), default="coarse",
                   help="mesh level: " + ", ".join(
                       f"{k} {v.label()} ({v.dof} DOF)" for k, v in MESHES.items())
                   + " (default coarse)")
    g.add_argument("--stick-slope", type=number, default=DEFAULT_STICK_SLOPE, metavar="N/MM3",
                   help=f"stick slope lambda of the friction law, N/mm^3 "
                   f"(default {DEFAULT_STICK_SLOPE:g})")
    g.add_argument("--normal-slope", type=number, default=DEFAULT_NORMAL_SLOPE,
                   metavar="N/MM3", help="slope of the linear pressure-overclosure law, "
                   f"N/mm^3 (default {DEFAULT_NORMAL_SLOPE:g})")
    g.add_argument("--element", choices=list(ELEMENT_TYPES), default="C3D20R",
                   help="20-node brick, reduced (C3D20R, default) or full integration")
    g.add_argument("--substeps", type=int, default=50, metavar="N",
                   help="equal substeps over t = 0..1.25 s, a multiple of 5 (default 50)")
    s = p.add_argument_group("solver")
    s.add_argument("--solver", choices=list(SOLVERS), default="calculix",
                   help="finite-element solver (default calculix)")
    s.add_argument("--timeout", type=number, metavar="S",
                   help="stop the solver after S seconds (default 120 s + 0.15 s per DOF)")
    s.add_argument("--threads", type=int, default=1, metavar="N",
                   help="OpenMP threads of the solver (default 1)")
    s.add_argument("--out", metavar="DIR",
                   help="keep the job directory (deck, solver files, log) and the VTU "
                        "export in DIR (default: a temporary directory, removed)")
    s.add_argument("--reuse", action="store_true",
                   help="if DIR already holds a successful run of the identical deck, read it")
    s.add_argument("--no-vtu", action="store_true", help="do not write the VTU files")
    add_strain_energy(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def case_from_args(args: argparse.Namespace) -> FECase:
    """The validated load case of the command line."""
    params, amplitude = params_from_args(args)
    return FECase(args.model, params, amplitude, mesh=args.mesh, stick_slope=args.stick_slope,
                  normal_slope=args.normal_slope, substeps=args.substeps,
                  element=args.element)


def _check_run_options(args: argparse.Namespace) -> None:
    if args.timeout is not None and not (math.isfinite(args.timeout) and args.timeout > 0):
        raise ParameterError(f"--timeout must be > 0 s, got {args.timeout!r}")
    if not 1 <= args.threads <= 256:
        raise ParameterError(f"--threads must be in [1, 256], got {args.threads}")


def run(args: argparse.Namespace) -> int:
    case = case_from_args(args)
    _check_run_options(args)
    solve = SOLVERS[args.solver]
    if args.solver == "calculix" and not args.reuse:
        from ..fe.runner import find_ccx

        find_ccx()  # one line saying how to install it, before anything is written
    files: list[Path] = []
    if args.out:
        job_dir = Path(args.out)
        result = solve(case, job_dir, args)
        if not args.no_vtu and hasattr(result, "contact"):
            from ..fe.vtu import export_vtu

            files = export_vtu(result, job_dir)
    else:
        with tempfile.TemporaryDirectory(prefix="microslip-fe-") as tmp:
            result = solve(case, Path(tmp), args)
    out = result.summary()
    if not args.out:
        out["job_dir"] = None
    out["files"] = [str(f) for f in files]
    if args.json:
        print_json(out)
        return 0
    c = case
    print(f"{c.model} load, {args.solver}, mesh {args.mesh} ({c.spec.label()} {c.element}, "
          f"{out['dof']} DOF), stick slope {c.stick_slope:g} N/mm^3, {c.substeps} substeps")
    print(f"  amplitude F0           {c.amplitude:12.6g} N  (macroslip at "
          f"{out['macroslip_force_N']:.6g} N)")
    print(f"  peak displacement d0   {out['peak_displacement_mm']:12.6g} mm  "
          "(half peak-to-peak of the loop t = 0.25..1.25 s)")
    for name, a in out["slip_length_by_domain_mm"].items():
        label = f"slip length, {name}"
        print(f"  {label:<22s} {a:12.6g} mm  (contact status at t = 0.25 s)")
    print(f"  dissipated energy W_d  {out['dissipated_energy_Nmm']:12.6g} N·mm")
    print(f"  strain energy U        {out['strain_energy_Nmm']:12.6g} N·mm  "
          f"({out['strain_energy_definition']})")
    print(f"  loss factor eta        {out['loss_factor']:12.6g} (dimensionless)")
    print(f"  loop closure           {out['loop_closure']:12.3g} (relative)")
    print(f"  iterations             {out['iterations']:12d}")
    print(f"  wall time              {out['wall_s']:12.3g} s  "
          f"(converged: {'yes' if out['converged'] else 'no'})")
    if args.out:
        print(f"  job directory          {args.out}")
        for f in files:
            if f.suffix == ".pvd":
                print(f"  ParaView               {f}")
    return 0
