"""``microslip fe --mesh FILE``: the built-in frictional FE (or CalculiX) on the user's own mesh.

Parses and prints; the run is :func:`microslip.fe.ownmesh.run_own_mesh`. The box's options
(``--model``, the clamped zone's geometry, ``--pressure-law``, ...) are refused with a mesh
file, and the mesh file's options (``--contact-set``, ``--load``, ...) without one.
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

from ..case.table import MODE_BOX, MODE_MESH, add_option, mode_options
from ..errors import ParameterError
from ..fe.constants import DEFAULT_NORMAL_SLOPE

if TYPE_CHECKING:
    from ..fe.clamp import MeshClamp
from .common import check_output_dir, check_plot, flagged, print_json

__all__ = ["REQUIRED", "add_own_mesh_options", "given", "is_mesh_file", "mesh_case", "mesh_clamp",
           "refuse_mesh_options", "run_own_mesh", "verb"]

#: Clamp values a mesh run needs (the mesh gives the geometry): destination -> flag.
REQUIRED = {"normal_force": "--normal-force N", "friction": "--friction X",
            "modulus": "--modulus MPA", "poisson_ratio": "--poisson-ratio X"}


def is_mesh_file(mesh: str) -> bool:
    """Whether ``--mesh`` names a file (not a level or NXxNYxNZ)."""
    from ..meshlevels import is_mesh_spec

    return not is_mesh_spec(mesh)


def add_own_mesh_options(p: argparse.ArgumentParser, validate: bool = False) -> None:
    """The options of a mesh file; ``validate``: those ``validate --mesh FILE`` takes too (the
    clamp, the contact law and the substeps, which ``fe`` has of its own)."""
    from ..fe.ownmesh import HISTORIES

    g = p.add_argument_group("your own mesh (--mesh FILE; docs/ownmesh.md)")
    if validate:
        add_option(g, "normal_contact", choices=["penalty"], mode=MODE_MESH,
                   note="CalculiX takes penalty normal contact only (the default)")
        add_option(g, "normal_slope", note=f"default {DEFAULT_NORMAL_SLOPE:g}", mode=MODE_MESH)
        add_option(g, "substeps", help="substeps over 1.25 cycles, a multiple of 5",
                   mode=MODE_MESH)
    add_option(g, "contact_set", mode=MODE_MESH)
    add_option(g, "clamp_set", mode=MODE_MESH)
    add_option(g, "load", mode=MODE_MESH)
    add_option(g, "history", choices=list(HISTORIES), mode=MODE_MESH,
               help="; ".join(f"{k}: {v}" for k, v in HISTORIES.items()),
               note="default settle")
    add_option(g, "settle_tol", note="default 1e-3", mode=MODE_MESH)
    add_option(g, "max_cycles", note="default 10", mode=MODE_MESH)
    if not validate:
        add_option(g, "cycles", help="calculix: cycles to run",
                   note="default 3; compare cycle_work_Nmm", mode=MODE_MESH)
        add_option(g, "plot", help="draw each load's loop over the settled cycle",
                   mode=MODE_MESH)
        from .convergence import add_convergence_options

        add_convergence_options(g)


def verb(flags: list[str]) -> str:
    """'applies' after one flag, 'apply' after several."""
    return "apply" if len(flags) > 1 else "applies"


def given(args: argparse.Namespace, dest: str) -> bool:
    """Whether the option ``dest`` was given on the command line (not by a case file)."""
    given: frozenset[str] = getattr(args, "given_options", frozenset())
    return dest in given


def refuse_mesh_options(args: argparse.Namespace) -> None:
    """The box's run: a mesh file's option given on the command line is refused."""
    bad = [f"--{d.replace('_', '-')}" for d in mode_options(args, MODE_MESH) if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to --mesh FILE only (a mesh of your "
                             f"own), not to the box --mesh {args.mesh}; remove them")


def mesh_clamp(args: argparse.Namespace, normal_contact: str | None = None) -> MeshClamp:
    """The clamp the options describe (the one place a namespace becomes a
    :class:`~microslip.fe.clamp.MeshClamp`, for ``fe --mesh`` and the structure commands
    alike): ``normal_contact`` overrides ``--normal-contact``; what is not given takes the
    clamp's defaults; a bad value is one line naming its option."""
    from ..fe.clamp import MeshClamp

    optional: dict[str, Any] = {k: v for k, v in (
        ("stick_slope", args.stick_slope),
        ("normal_contact", normal_contact or args.normal_contact),
        ("normal_slope", args.normal_slope)) if v is not None}
    with flagged():
        return MeshClamp(args.contact_set, args.clamp_set,
                         normal_force=float(args.normal_force), modulus=float(args.modulus),
                         poisson_ratio=float(args.poisson_ratio),
                         friction=float(args.friction), **optional)


def mesh_case(args: argparse.Namespace) -> Any:
    from ..fe.meshload import MeshLoad
    from ..fe.ownmesh import OwnMeshCase
    from ..fe.promote import ELEMENT_ORDERS

    # the box's options (added with mode=MODE_BOX): refused with a mesh file
    bad = [f"--{d.replace('_', '-')}" for d in mode_options(args, MODE_BOX) if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to the box (--mesh LEVEL) only; with "
                             f"--mesh {args.mesh} the mesh gives the geometry and --load the "
                             "loads")
    element = getattr(args, "element", None)
    if element is not None and element not in ELEMENT_ORDERS:
        raise ParameterError(f"--element {element} applies to the box (--mesh LEVEL) only; with "
                             f"--mesh {args.mesh} give --element {' or '.join(ELEMENT_ORDERS)}")
    missing = [flag for dest, flag in REQUIRED.items() if getattr(args, dest, None) is None]
    for dest in ("contact_set", "clamp_set"):
        if getattr(args, dest, None) is None:
            missing.insert(0, f"--{dest.replace('_', '-')} NAME")
    if not args.load:
        missing.append("--load SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG]")
    if missing:
        from .main import UsageError  # a required option left out: a usage mistake

        raise UsageError(f"--mesh {args.mesh} needs {', '.join(missing)}")
    for dest in ("cycles", "plot", "settle_tol", "max_cycles", "history"):
        if not hasattr(args, dest):
            setattr(args, dest, None)
    if args.solver == "builtin" and args.cycles is not None:
        raise ParameterError("--cycles applies to --solver calculix (the built-in solver runs "
                             "until W settles: --settle-tol, --max-cycles)")
    if args.solver == "calculix":
        for dest in ("settle_tol", "max_cycles"):
            if getattr(args, dest) is not None:
                raise ParameterError(f"--{dest.replace('_', '-')} applies to --solver builtin "
                                     "(CalculiX runs --cycles cycles)")
    normal = args.normal_contact or ("penalty" if args.solver == "calculix" else "fixed")
    if normal == "fixed" and given(args, "normal_slope"):
        raise ParameterError("--normal-slope needs --normal-contact penalty (the fixed normal "
                             "contact has no normal stiffness)")
    extra: dict[str, Any] = {}
    if args.solver == "calculix":
        extra = {"options": {k: v for k, v in (("timeout", args.timeout),
                                               ("threads", args.threads)) if v is not None}}
    elif getattr(args, "command", "fe") == "fe" and (given(args, "timeout")
                                                     or given(args, "threads")):
        raise ParameterError("--timeout and --threads apply to --solver calculix")
    return OwnMeshCase(
        args.mesh, mesh_clamp(args, normal), tuple(MeshLoad.parse(s) for s in args.load),
        substeps=args.substeps, history=args.history or "settle",
        tol=1e-3 if args.settle_tol is None else args.settle_tol,
        max_cycles=10 if args.max_cycles is None else args.max_cycles,
        cycles=3 if args.cycles is None else args.cycles,
        refine=1 if getattr(args, "refine", None) is None else args.refine, element=element,
        **extra)


def run_own_mesh(args: argparse.Namespace) -> int:
    from ..fe.ownmesh import loops_of
    from ..fe.ownmesh import run_own_mesh as run
    from .convergence import check_convergence, mesh_convergence

    case = mesh_case(args)
    check_convergence(args, ("out", "plot"))
    check_output_dir(args.out)
    check_plot(args.plot)
    table: list[str] = []
    if args.convergence:
        summary, table = mesh_convergence(args, case)
    else:
        done = run(case, args.solver, out=args.out, vtu=not args.no_vtu)
        summary = done.summary
    clamp = case.clamp
    out = {**summary, "clamp_portion": "whole",
           "options": {"normal_contact": clamp.normal_contact,
                       "stick_slope_N_per_mm3": clamp.stick_slope,
                       "normal_slope_N_per_mm3": clamp.normal_slope
                       if clamp.normal_contact == "penalty" else None,
                       "friction": clamp.friction, "normal_force_N": clamp.normal_force,
                       "modulus_MPa": clamp.modulus, "poisson_ratio": clamp.poisson_ratio,
                       "substeps": case.substeps, "increments_per_cycle": case.increments,
                       "history": case.history}}
    if args.plot:
        from ..plot.ownmesh import plot_mesh_loops

        works = [ld["work_Nmm"] for ld in out["loads"]]
        plot_mesh_loops(loops_of(done), works, args.plot, title=f"{args.mesh}, {args.solver}")
        out.setdefault("files", []).append(args.plot)
    for warning in out.get("warnings", []):
        print(f"warning: {warning}", file=sys.stderr)
    status = 0 if out.get("solver_converged", out.get("converged", True)) else 1
    if args.json:
        print_json(out)
        return status
    _print_text(args, out)
    if table:
        print("\n".join(table))
    return status


def _print_text(args: argparse.Namespace, out: dict[str, Any]) -> None:
    o = out["options"]
    refined = f" refined x{out['refine']}" if "refine" in out else ""
    print(f"mesh {out['mesh']}{refined} ({out['nodes']} nodes, {out['elements']} elements, "
          f"{out['dof']} DOF), {args.solver} solver ({out['element']}), {o['normal_contact']} "
          f"normal contact, stick slope {o['stick_slope_N_per_mm3']:g} N/mm^3")
    for k, ld in enumerate(out["loads"], 1):
        d = ", ".join(f"{x:g}" for x in ld["direction"])
        print(f"  load {k} on {ld['set']:<10s} A {ld['amplitude_N']:g} N along ({d}), phase "
              f"{ld['phase_deg']:g} deg: work {ld['work_Nmm']:.6g} N·mm, peak displacement "
              f"{ld['peak_displacement_mm']:.6g} mm")
    print(f"  dissipated energy W    {out['dissipated_energy_Nmm']:12.6g} N·mm  (work of all "
          "loads over the settled cycle; the whole clamp)")
    print(f"  peak displacement      {out['peak_displacement_mm']:12.6g} mm  (load 1, half "
          "peak-to-peak)")
    print(f"  cycles                 {out['cycles']:12d}")
    print(f"  wall time              {out['wall_s']:12.3g} s")
    print(f"  {out['message']}")
    for f in out.get("files", []):
        if str(f).endswith((".pvd", ".json", ".png", ".pdf", ".svg")):
            print(f"  file                   {f}")
