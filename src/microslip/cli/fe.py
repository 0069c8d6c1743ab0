"""``microslip fe``: one finite-element run of a load case (paper, Section 4).

The solver is chosen from :data:`microslip.fe.SOLVERS` (``--solver``): the built-in
frictional solver (default; validated against CalculiX, ``docs/solver.md``) or CalculiX.
The run itself is :func:`microslip.case.run.compute_fe` (:func:`microslip.fe.run_loop` on the
options, the path ``microslip report`` takes too); this module parses and prints.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..case.options import add_case_option
from ..case.run import compute_fe, fe_inputs, fe_json, portion_text
from ..case.runflags import EXIT_STATUS
from ..case.table import MODE_BOX, OPTIONS, add_option, add_solver, mesh_or_file
from ..conventions import DEFAULT_MESH
from ..errors import ParameterError
from ..fe import SOLVERS
from ..fe.builtin.normal import NORMAL_CONTACTS
from ..fe.constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from ..io import write_loop_csv
from ..loading import LOAD_CASES
from .common import (
    add_params,
    add_strain_energy,
    check_output_dir,
    print_json,
)
from .displacement import add_displacement_option, fe_displacement_force
from .ownmesh import add_own_mesh_options, is_mesh_file, refuse_mesh_options, run_own_mesh

__all__ = ["add_parser", "run"]




def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "fe", help="finite-element run (built-in solver or CalculiX) of the tip or centre case",
        description="Build the paper's FE model (Section 4: bar on a rigid base, Coulomb "
        "friction, clamping pressure, then F_T = F0 sin(2 pi t) over 1.25 s in equal "
        "substeps), run it, and report the loop, W_d, U and eta. The built-in solver "
        "(default) needs nothing else; --solver calculix needs CalculiX (ccx): "
        "bash scripts/setup.sh or apt-get install calculix-ccx.",
        epilog=EXIT_STATUS)
    add_option(p, "model", choices=list(LOAD_CASES), mode=MODE_BOX,
               help="the box's load case (required unless --mesh is a file): "
               + "; ".join(f"{k}: {v.description}" for k, v in LOAD_CASES.items()))
    add_params(p, mode=MODE_BOX)
    add_displacement_option(p, note="a root-find on the force, one run per step "
                            "(docs/report.md)", mode=MODE_BOX)
    g = p.add_argument_group("finite-element model (docs/validation.md)")
    add_option(g, "mesh", default=DEFAULT_MESH, type=mesh_or_file, metavar="LEVEL|FILE",
               note="or a mesh file of your own clamp (.inp, .msh, .vtu, ...; hexahedra with "
               "named sets): then give --contact-set, --clamp-set and --load (docs/ownmesh.md)")
    add_option(g, "stick_slope", default=DEFAULT_STICK_SLOPE)
    add_option(g, "normal_slope", default=DEFAULT_NORMAL_SLOPE,
               note="calculix, and builtin with --normal-contact penalty")
    add_option(g, "normal_contact",
               help="builtin: " + "; ".join(f"{k}: {v}" for k, v in NORMAL_CONTACTS.items()),
               note="default fixed; docs/solver.md")
    add_option(g, "pressure_law", mode=MODE_BOX, note="builtin: on the top face; "
               "power:N[:EDGE] or table:FILE.csv (columns x_mm,pressure) as the 1-D commands "
               "take it")
    add_option(g, "clamping_csv", mode=MODE_BOX, note="ready for --pressure-law table:FILE "
               "of loop, planar and sweep")
    # one --element for both modes, each value checked against the mode it belongs to
    add_option(g, "element", choices=[*(e for s in SOLVERS.values() for e in s.elements),
                                      *(OPTIONS["mesh_element"].choices or ())],
               help="the box: calculix: 20-node brick, reduced integration (C3D20R); "
                    "builtin: 8-node brick with incompatible modes (C3D8I, default) or plain "
                    "(C3D8). --mesh FILE: "
                    + OPTIONS["mesh_element"].help + " (default: as the file)")
    add_option(g, "substeps")
    add_own_mesh_options(p)
    s = p.add_argument_group("solver")
    add_solver(s, "fe", list(SOLVERS))
    add_option(s, "timeout", note="default 120 s + 0.15 s per DOF")
    add_option(s, "threads", help="OpenMP threads of the solver")
    add_option(s, "out", metavar="DIR",
               help="write result.json and the VTU series (displacement, contact status and "
                    "slip of every increment, fe_<model>.pvd for ParaView) into DIR; calculix "
                    "keeps its job files there too (default: nothing written)")
    add_option(s, "reuse", mode=MODE_BOX,
               help="if DIR already holds a successful run of the identical deck, read it")
    add_option(s, "no_vtu")
    add_strain_energy(p, mode=MODE_BOX)
    add_option(p, "json")
    add_case_option(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if is_mesh_file(args.mesh):
        return run_own_mesh(args)
    refuse_mesh_options(args)
    if args.element in (OPTIONS["mesh_element"].choices or ()):
        raise ParameterError(f"--element {args.element} applies to --mesh FILE (a mesh of your "
                             "own); the box takes C3D8I or C3D8 (builtin), C3D20R or C3D20 "
                             "(calculix)")
    if args.model is None:
        raise ParameterError("give --model tip|centre (the box's load case), or --mesh FILE "
                             "with its sets and loads")
    inputs = fe_inputs(vars(args), 1.0 if args.displacement_amplitude else None)
    check_output_dir(args.out)
    forced = fe_displacement_force(args, inputs.model, inputs.params,
                                   lambda f: compute_fe(inputs, f)[0])
    result, files = compute_fe(inputs, forced, out=args.out, vtu=not args.no_vtu)
    clamping = getattr(result.details, "clamping", None)
    if args.clamping_csv is not None and clamping is not None:
        files.append(clamping.write_csv(args.clamping_csv))
    if args.out is not None and result.converged and result.loop is not None:
        files.append(write_loop_csv(Path(args.out) / "loop.csv", result.loop.force,
                                    result.loop.displacement))
    out = fe_json(result)
    out["files"] = [str(f) for f in files]
    if forced is not None:
        out["displacement_amplitude_mm"] = args.displacement_amplitude
    status = 0 if result.converged else 1
    for warning in out["warnings"]:
        print(f"warning: {warning}", file=sys.stderr)
    if args.json:
        print_json(out)
        return status
    _print_text(args, out, files)
    return status


def _print_text(args: argparse.Namespace, out: dict[str, Any], files: list[Any]) -> None:
    """The text report; a run that did not converge prints why and no damping figure."""
    opts = out["options"]
    print(f"{args.model} load, {args.solver} solver, mesh {args.mesh} ({opts['element']}, "
          f"{out['dof']} DOF), stick slope {opts['stick_slope']:g} N/mm^3, "
          f"{out['increments']} substeps")
    if not out["converged"]:
        print(f"  not converged: {out['message']}; no damping figures")
        return
    print(f"  amplitude F0           {out['amplitude_N']:12.6g} N  (macroslip at "
          f"{out['macroslip_force_N']:.6g} N)")
    print(f"  peak displacement d0   {out['peak_displacement_mm']:12.6g} mm  "
          "(half peak-to-peak of the loop t = 0.25..1.25 s)")
    for name, a in out["slip_length_by_domain_mm"].items():
        label = f"slip length, {name}"
        print(f"  {label:<22s} {a:12.6g} mm  (contact status at t = 0.25 s)")
    print(f"  dissipated energy W_d  {out['dissipated_energy_Nmm']:12.6g} N·mm  "
          f"({portion_text(out['clamp_portion'])})")
    print(f"  strain energy U        {out['strain_energy_Nmm']:12.6g} N·mm  "
          f"({out['strain_energy_definition']})")
    print(f"  loss factor eta        {out['loss_factor']:12.6g} (dimensionless)")
    print(f"  loop closure           {out['loop_closure']:12.3g} (relative)")
    print(f"  iterations             {out['iterations']:12d}")
    print(f"  wall time              {out['wall_s']:12.3g} s  (converged: yes)")
    if out["message"] != "converged":
        print(f"  note                   {out['message']}")
    if args.out:
        print(f"  job directory          {args.out}")
        for f in files:
            if f.suffix in (".pvd", ".json"):
                print(f"  {'ParaView' if f.suffix == '.pvd' else 'result':<22s} {f}")
