"""``microslip fe``: one finite-element run of the tip or centre load case (paper, Section 4).

The solver is chosen from :data:`SOLVERS` (``--solver``): the built-in frictional solver
(default; validated against CalculiX, ``docs/solver.md``) or CalculiX. Each entry takes the
parsed arguments and a job directory and returns the JSON summary (the keys of
``microslip loop --json`` plus ``dof``, ``wall_s``, ``converged``) and the files it wrote.
"""

from __future__ import annotations

import argparse
import math
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..case.options import add_case_option
from ..errors import ParameterError
from ..fe.case import (
    DEFAULT_NORMAL_SLOPE,
    DEFAULT_STICK_SLOPE,
    ELEMENT_TYPES,
    LOAD_CASES,
    FECase,
)
from ..fe.mesh import MESHES
from ..solver.element import ELEMENTS as _BUILTIN_ELEMENTS
from ..solver.mesh import MESHES as BUILTIN_MESHES
from .common import add_params, add_strain_energy, number, params_from_args, print_json

__all__ = ["SOLVERS", "add_parser", "case_from_args", "run"]

BUILTIN_ELEMENTS = tuple(_BUILTIN_ELEMENTS)


#: Default element of each solver.
DEFAULT_ELEMENT = {"builtin": "C3D8I", "calculix": "C3D20R"}


def _run_calculix(args: argparse.Namespace, job_dir: Path | None
                  ) -> tuple[dict[str, Any], list[Path]]:
    from ..fe.runner import find_ccx, run_case

    case = case_from_args(args)
    if not args.reuse:
        find_ccx()  # one line saying how to install it, before anything is written
    if job_dir is None:
        with tempfile.TemporaryDirectory(prefix="microslip-fe-") as tmp:
            result = run_case(case, Path(tmp), timeout=args.timeout, threads=args.threads,
                              reuse=False, strain_energy_kind=args.strain_energy)
        return result.summary() | {"job_dir": None}, []
    result = run_case(case, job_dir, timeout=args.timeout, threads=args.threads,
                      reuse=args.reuse, strain_energy_kind=args.strain_energy)
    files: list[Path] = []
    if not args.no_vtu:
        from ..fe.vtu import export_vtu

        files = export_vtu(result, job_dir)
    return result.summary(), files


def _run_builtin(args: argparse.Namespace, job_dir: Path | None
                 ) -> tuple[dict[str, Any], list[Path]]:
    from ..io import write_json
    from ..solver import solve_uniaxial
    from ..solver.report import uniaxial_summary

    params, amplitude = params_from_args(args)
    result = solve_uniaxial(params, args.model, amplitude, mesh=args.mesh,
                            stick_slope=args.stick_slope, increments=args.substeps,
                            element=args.element)
    out = uniaxial_summary(result, params, args.strain_energy)
    files: list[Path] = []
    if job_dir is not None:
        out["job_dir"] = str(job_dir)
        write_json(job_dir / "result.json", out)
        files.append(job_dir / "result.json")
    return out, files


#: Solvers of ``--solver``: name -> callable(args, job_dir or None) -> (summary, files).
SOLVERS: dict[str, Callable[[argparse.Namespace, Path | None],
                            tuple[dict[str, Any], list[Path]]]] = {
    "builtin": _run_builtin,
    "calculix": _run_calculix,
}


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "fe", help="finite-element run (built-in solver or CalculiX) of the tip or centre case",
        description="Build the paper's FE model (Section 4: bar on a rigid base, Coulomb "
        "friction, clamping pressure, then F_T = F0 sin(2 pi t) over 1.25 s in equal "
        "substeps), run it, and report the loop, W_d, U and eta. The built-in solver "
        "(default) needs nothing else; --solver calculix needs CalculiX (ccx): "
        "bash scripts/setup.sh or apt-get install calculix-ccx.")
    p.add_argument("--model", choices=list(LOAD_CASES), required=True,
                   help="tip: traction on the end face; centre: on the mid-length section")
    add_params(p, default_preset="table1")
    g = p.add_argument_group("finite-element model (docs/validation.md)")
    g.add_argument("--mesh", choices=sorted(set(MESHES) | set(BUILTIN_MESHES)),
                   default="coarse",
                   help="mesh level; calculix: " + ", ".join(
                       f"{k} {v.label()} ({v.dof} DOF)" for k, v in MESHES.items())
                   + "; builtin: " + ", ".join(
                       f"{k} {'x'.join(map(str, v))}" for k, v in BUILTIN_MESHES.items())
                   + " elements (default coarse)")
    g.add_argument("--stick-slope", type=number, default=DEFAULT_STICK_SLOPE, metavar="N/MM3",
                   help=f"stick slope lambda of the friction law, N/mm^3 "
                   f"(default {DEFAULT_STICK_SLOPE:g})")
    g.add_argument("--normal-slope", type=number, default=DEFAULT_NORMAL_SLOPE,
                   metavar="N/MM3", help="slope of the linear pressure-overclosure law, "
                   f"N/mm^3 (default {DEFAULT_NORMAL_SLOPE:g})")
    g.add_argument("--element", choices=[*ELEMENT_TYPES, *BUILTIN_ELEMENTS], default=None,
                   help="calculix: 20-node brick, reduced (C3D20R, default) or full "
                        "integration (C3D20); builtin: 8-node brick with incompatible modes "
                        "(C3D8I, default) or plain (C3D8)")
    g.add_argument("--substeps", type=int, default=50, metavar="N",
                   help="equal substeps over t = 0..1.25 s, a multiple of 5 (default 50)")
    s = p.add_argument_group("solver")
    s.add_argument("--solver", choices=list(SOLVERS), default="builtin",
                   help="finite-element solver: builtin (default, docs/solver.md) or calculix "
                        "(docs/validation.md)")
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
    add_case_option(p)
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


def _check_solver_choices(args: argparse.Namespace) -> None:
    meshes = BUILTIN_MESHES if args.solver == "builtin" else MESHES
    if args.mesh not in meshes:
        raise ParameterError(f"--mesh {args.mesh} is not a mesh of the {args.solver} solver; "
                             f"choose one of {', '.join(meshes)}")
    elements = BUILTIN_ELEMENTS if args.solver == "builtin" else ELEMENT_TYPES
    if args.element is None:
        args.element = DEFAULT_ELEMENT[args.solver]
    elif args.element not in elements:
        raise ParameterError(f"--element {args.element} is not an element of the {args.solver} "
                             f"solver; choose one of {', '.join(elements)}")
    if args.solver == "builtin" and (args.reuse or args.no_vtu or args.normal_slope
                                     != DEFAULT_NORMAL_SLOPE):
        raise ParameterError("--reuse, --no-vtu and --normal-slope apply to --solver calculix "
                             "only (the built-in solver holds the contact closed)")


def run(args: argparse.Namespace) -> int:
    _check_run_options(args)
    _check_solver_choices(args)
    job_dir = Path(args.out) if args.out else None
    out, files = SOLVERS[args.solver](args, job_dir)
    out["files"] = [str(f) for f in files]
    if args.json:
        print_json(out)
        return 0 if out["converged"] else 1
    opts = out["options"]
    print(f"{args.model} load, {args.solver} solver, mesh {args.mesh} ({opts['element']}, "
          f"{out['dof']} DOF), stick slope {opts['stick_slope']:g} N/mm^3, "
          f"{out['increments']} substeps")
    print(f"  amplitude F0           {out['amplitude_N']:12.6g} N  (macroslip at "
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
            if f.suffix in (".pvd", ".json"):
                print(f"  {'ParaView' if f.suffix == '.pvd' else 'result':<22s} {f}")
    return 0 if out["converged"] else 1
