"""``microslip report --case FILE.toml --out report.html``: one self-contained HTML page."""

from __future__ import annotations

import argparse
import os
from typing import Any

from ..case.table import add_option
from ..conventions import DEFAULT_MESH
from ..errors import ParameterError

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    from ..fe import SOLVERS

    p = sub.add_parser(
        "report", help="HTML report of a case: loops, damping, FE comparison, validity",
        description="A case of your own mesh ([mesh] file): the part, its loads and what the "
        "solver built, its loops at the case's [[mesh.load]] tables (as fe --case), the "
        "checks, and the damping of its mode (as modal --mesh --solver all) when it gives a "
        "density; no [geometry] needed. A bar case (a preset or [geometry]): its loops, "
        "damping against amplitude, the 1-D model against finite elements with the validity "
        "warnings, and the planar coupling where the case gives a ratio. Written with every "
        "input and its unit into one HTML page that needs no network (docs/report.md). "
        "Units: N, mm, MPa, N·mm.")
    # the report's --case is its subject, read by the report itself (not the case defaults
    # of the parse, :func:`microslip.case.options.parse_args`): its own destination
    add_option(p, "case", dest="report_case", required=True,
               help="the case file (microslip case new FILE.toml writes a template; "
                    "microslip case new --mesh MESHFILE FILE.toml a case of your own part)")
    add_option(p, "out", metavar="FILE.html",
               help="the page to write (needed unless --json is given)")
    add_option(p, "json", help="print every number of the page as one JSON object (its one_d, "
               "fe and planar objects are those of loop, fe and planar --case --json)")
    add_option(p, "increments", note="of each 1-D first loading")
    g = p.add_argument_group("finite-element runs")
    add_option(g, "fe_solver", choices=list(SOLVERS))
    add_option(g, "mesh", default=DEFAULT_MESH, help="FE mesh of the bar (a level or "
               "NXxNYxNZ); a case of your own mesh runs its [mesh] file")
    add_option(g, "substeps", note="of each FE run")
    add_option(g, "no_fe")
    add_option(g, "bar")
    add_option(p, "no_progress")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..case.model import load_case
    from ..fe import SOLVERS
    from ..io import check_writable
    from ..models import check_increments
    from ..report import MeshReport, ReportSettings, compute_report, report_json, write_report
    from .common import print_json

    if args.out is None and not args.json:
        from .main import UsageError

        raise UsageError("give --out FILE.html, --json or both")
    if args.out is not None:
        if os.path.splitext(args.out)[1].lower() not in (".html", ".htm"):
            raise ParameterError(f"--out must end in .html, got {args.out!r}")
        check_writable(args.out, (".html", ".htm"), "report")  # before the work
    meshes = SOLVERS[args.fe_solver].meshes
    if args.mesh not in meshes:
        raise ParameterError(f"--mesh {args.mesh} is not a mesh of the {args.fe_solver} solver; "
                             f"choose one of {', '.join(meshes)}")
    if args.substeps < 5 or args.substeps % 5:
        raise ParameterError(f"--substeps must be a positive multiple of 5, got {args.substeps}")
    settings = ReportSettings(increments=check_increments(args.increments),
                              fe_solver=args.fe_solver, mesh=args.mesh, substeps=args.substeps,
                              fe_points=not args.no_fe, bar=args.bar)
    case = load_case(args.report_case)
    mesh_case = "mesh.file" in case.values
    if mesh_case and not args.bar and "mesh" in getattr(args, "given_options", ()):
        raise ParameterError(f"--mesh {args.mesh} is the bar's FE mesh; case "
                             f"{args.report_case} is a part of your own mesh "
                             f"({case.values['mesh.file']}): give --bar with it for the bar's "
                             "report, or leave it out")
    if args.out is not None:
        data = write_report(case, args.out, settings, progress=not args.no_progress)
    else:
        data = compute_report(case, settings, progress=not args.no_progress)
    if args.json:
        print_json(report_json(data) | {"case_file": args.report_case, "page": args.out})
        return 0
    if isinstance(data, MeshReport):
        return _print_mesh(args, data)
    print(f"report of case {args.report_case}: {data.model} model, F0 = {data.amplitude:.6g} N "
          f"(macroslip {data.macroslip:.6g} N), "
          f"{data.fe_curve.shape[0]} FE run(s), "
          f"{len(data.validity_rigid.warnings) + len(data.validity_layer.warnings)} validity "
          f"warning(s), planar coupling: {_planar_state(data)}")
    if data.structure is not None:
        for v in data.structure["verdicts"].values():
            print(f"  structure: {v['verdict']}")
    print(f"  wrote                  {args.out}")
    return 0


def _print_mesh(args: argparse.Namespace, data: Any) -> int:
    """The text summary of a mesh case's report: the part, what was built, W at the
    case's loads, the checks, the structure's verdicts."""
    from .ownmesh import print_model

    loads = "; ".join(f"{ld.amplitude:g} N on {ld.set}" for ld in data.case.mesh_loads)
    print(f"report of case {args.report_case}: mesh {data.mesh_file}, loads: "
          f"{loads or 'none'}")
    print_model(data.model)
    if data.fe is not None:
        print(f"  dissipated energy W at the case's loads {data.fe['dissipated_energy_Nmm']:.6g}"
              f" N·mm per cycle ({'settled' if data.fe.get('settled', True) else 'NOT settled'})")
    elif data.fe_error is not None:
        print(f"  the run at the case's loads stopped: {data.fe_error}")
    print(f"  checks                 {len(data.checks)} warning(s)")
    if data.structure is not None:
        for v in data.structure["verdicts"].values():
            print(f"  structure: {v['verdict']}")
    if data.bar is not None:
        print(f"  the bar (--bar): {data.bar.model} model, F0 = {data.bar.amplitude:.6g} N")
    if args.out is not None:
        print(f"  wrote                  {args.out}")
    return 0


def _planar_state(data: Any) -> str:
    if data.planar_error is not None:
        return f"not computed ({data.planar_error})"
    return "yes" if data.planar is not None else "no"
