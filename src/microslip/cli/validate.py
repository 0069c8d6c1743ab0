"""``microslip validate``: FE validation of the analytical models (paper, Figs 8 and 9)."""

from __future__ import annotations

import argparse
import math
from typing import Any

from ..case.options import add_case_option
from ..case.runflags import EXIT_STATUS
from ..case.table import MODE_BOX, add_option, mesh_or_file
from ..conventions import DEFAULT_MESH
from ..errors import ParameterError
from ..fe.calculix.case import DEFAULT_STICK_SLOPE, LOAD_CASES
from .common import add_params, check_output_dir, params_from_args, print_json
from .ownmesh import (
    add_own_mesh_options,
    is_mesh_file,
    mesh_case,
    refuse_mesh_options,
    unsettled_status,
)

__all__ = ["add_parser", "run"]



def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "validate", help="run the FE validation (CalculiX) and write Figs 8 and 9",
        description="Run the tip and centre load cases of Table 1 (or of one's own clamp: "
        "--length ... or --case) in CalculiX, compare them "
        "with the analytical models and the closed forms, and write fig08_contact_status.png, "
        "fig09_fe_vs_model.png and validation.csv into DIR. Needs CalculiX (ccx): "
        "bash scripts/setup.sh or apt-get install calculix-ccx.",
        epilog=EXIT_STATUS)
    add_option(p, "out", metavar="DIR", required=True, help="output directory")
    add_params(p, mode=MODE_BOX)
    add_option(p, "mesh", action="append", type=mesh_or_file, metavar="LEVEL|FILE",
               note="repeat for several; or one mesh file of your own clamp (.inp, .msh, "
               ".vtu, ...) with --contact-set, --clamp-set and --load: the built-in solver "
               "against CalculiX on it (docs/ownmesh.md)")
    add_own_mesh_options(p, validate=True)
    add_option(p, "contact_formulation", default=None,
               note="validate --mesh FILE only; default node-to-surface")
    add_option(p, "model", choices=list(LOAD_CASES), action="append", mode=MODE_BOX,
               note="repeat for several (default: tip and centre)")
    add_option(p, "stick_slope", default=DEFAULT_STICK_SLOPE)
    add_option(p, "timeout", note="of each solver run (default 120 s + 0.15 s per DOF; on a "
               "mesh file per 50 increments)")
    add_option(p, "threads", help="OpenMP threads of each solver run")
    add_option(p, "scheduler", note="default: locally")
    add_option(p, "reuse", mode=MODE_BOX)
    add_option(p, "no_progress")
    add_option(p, "json", help="print the table rows and the files as JSON")
    add_case_option(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..validate import run_validation

    if any(is_mesh_file(m) for m in args.mesh or []):
        return _run_mesh(args)
    refuse_mesh_options(args)
    if args.contact_formulation is not None:
        raise ParameterError("--contact-formulation applies to --mesh FILE (a mesh of your "
                             "own), not to the box's validation")
    if args.timeout is not None and not (math.isfinite(args.timeout) and args.timeout > 0):
        raise ParameterError(f"--timeout must be > 0 s, got {args.timeout!r}")
    if not 1 <= args.threads <= 256:
        raise ParameterError(f"--threads must be in [1, 256], got {args.threads}")
    params, amplitude = params_from_args(args)
    check_output_dir(args.out)
    meshes = tuple(dict.fromkeys(args.mesh or [DEFAULT_MESH]))
    models = tuple(dict.fromkeys(args.model or list(LOAD_CASES)))
    report = run_validation(args.out, meshes, models, progress=not args.no_progress,
                            timeout=args.timeout, scheduler=args.scheduler,
                            stick_slope=args.stick_slope, threads=args.threads,
                            reuse=args.reuse, params=params, amplitude=amplitude)
    if args.json:
        print_json({"passed": report.passed, "files": [str(f) for f in report.files],
                    "rows": list(report.rows)})
    else:
        print(report.summary_markdown, end="")
        for f in report.files:
            print(f"wrote {f}")
    return 0 if report.passed else 1


def _run_mesh(args: argparse.Namespace) -> int:
    """``validate --mesh FILE``: the built-in solver against CalculiX on the user's mesh, like
    with like (:func:`~microslip.fe.calculix.compare.compare_on_mesh`)."""
    from ..fe.calculix.compare import DEFAULT_FORMULATION, compare_on_mesh

    if len(args.mesh) != 1:
        raise ParameterError("give one --mesh FILE (a mesh of your own) to validate, not "
                             f"{len(args.mesh)} meshes")
    if "model" in getattr(args, "given_options", ()):
        raise ParameterError("--model applies to the box (--mesh LEVEL); with --mesh FILE "
                             "--load gives the loads")
    args.mesh = args.mesh[0]
    args.solver = "calculix"
    case = mesh_case(args, default_normal="fixed")  # fixed: compared as a hard contact
    check_output_dir(args.out)
    result = compare_on_mesh(case, args.out,
                             formulation=args.contact_formulation or DEFAULT_FORMULATION,
                             progress=not args.no_progress)
    model = _case_model(result)
    if model is not None:
        result = {"mesh": result["mesh"], "model": model,
                  **{k: v for k, v in result.items() if k not in ("mesh", "model")}}
    if args.json:
        print_json(result)
    else:
        _print_mesh(result, args.out)
    return mesh_status(args, result)


def _case_model(result: dict[str, Any]) -> dict[str, Any] | None:
    """What the built-in solver built for the case as given (issue 34 item 5): its run of
    the case's own normal contact (``fixed``: the run beside the hard contact), else the
    compared run's."""
    normal = result.get("normal_contact") or {}
    for run in (normal.get("fixed_builtin"), result.get("builtin")):
        if isinstance(run, dict) and "model" in run:
            return dict(run["model"])
    return None


def mesh_status(args: argparse.Namespace, result: dict[str, Any]) -> int:
    """0 passed; :data:`~.ownmesh.EXIT_UNSETTLED` when a side's W per cycle did not settle
    (unless --accept-unsettled: then 0 or 1 by the tolerances alone); 1 otherwise."""
    if result["passed"]:
        return 0
    if not all(result["settled"].values()):
        status = unsettled_status(args, False)
        if status:
            return status
    within = all(abs(result["relative_difference"][k]) <= tol
                 for k, tol in result["tolerance"].items())
    return 0 if within and getattr(args, "accept_unsettled", False) else 1


def _print_mesh(result: dict[str, Any], out: str) -> None:
    b, c, d = result["builtin"], result["calculix"], result["relative_difference"]
    tol, ok = result["tolerance"], result["settled"]
    print(f"mesh {result['mesh']}: built-in against CalculiX, {b['cycles']} cycles of "
          f"{result['increments_per_cycle']} increments, normal slope "
          f"{result['normal_slope_N_per_mm3']:g} N/mm^3, stick slope "
          f"{result['stick_slope_N_per_mm3']:g} N/mm^3 on both")
    if "model" in result:
        from .ownmesh import print_model

        print_model(result["model"])
    normal = result.get("normal_contact") or {}
    if normal.get("reason"):
        print(f"  normal contact: the case's {normal['case']}; {normal['reason']}")
    fixed, off = normal.get("fixed_builtin"), normal.get("fixed_against_hard")
    if fixed and off:
        print(f"  the case's fixed contact, built-in: W {fixed['dissipated_energy_Nmm']:.6g} "
              f"N·mm ({off['dissipated_energy_Nmm']:+.2%} from the hard contact), d "
              f"{fixed['peak_displacement_mm']:.6g} mm ({off['peak_displacement_mm']:+.2%})")
    print(f"  contact built-in: {b['contact']}")
    print(f"  contact CalculiX: {c['contact']}")
    print(f"  W  built-in {b['dissipated_energy_Nmm']:.6g} N·mm, CalculiX "
          f"{c['dissipated_energy_Nmm']:.6g} N·mm: {d['dissipated_energy_Nmm']:+.3%} "
          f"(tolerance {tol['dissipated_energy_Nmm']:.1%})")
    print(f"  d  built-in {b['peak_displacement_mm']:.6g} mm, CalculiX "
          f"{c['peak_displacement_mm']:.6g} mm: {d['peak_displacement_mm']:+.4%} "
          f"(tolerance {tol['peak_displacement_mm']:.1%})")
    for side in ("builtin", "calculix"):
        works = ", ".join(f"{w:.5g}" for w in result["cycle_work_Nmm"][side])
        print(f"  W per cycle {side:<8s} {works} N·mm: "
              f"{'settled' if ok[side] else 'NOT settled'}")
    s = result.get("normal_slope_sensitivity")
    if s:
        print(f"  normal slope x10 ({s['normal_slope_N_per_mm3']:g} N/mm^3, built-in): W "
              f"{s['dissipated_energy_Nmm']:.6g} N·mm ({s['relative_change']:+.2%}), "
              f"dW/dlog10(slope) {s['dW_dlog10_slope_Nmm']:+.4g} N·mm")
    print(f"  {'passed' if result['passed'] else 'NOT passed'}; wrote "
          f"{out}/validation_mesh.json")
