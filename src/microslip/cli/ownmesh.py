"""``microslip fe --mesh FILE``: the built-in frictional FE (or CalculiX) on the user's own mesh.

Parses and prints; the run is :func:`microslip.fe.ownmesh.run_own_mesh`. The box's options
(``--model``, the clamped zone's geometry, ``--pressure-law``, ...) are refused with a mesh
file, and the mesh file's options (``--contact-set``, ``--load``, ...) without one.
"""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

from ..case.assembly import ASSEMBLY_DESTS, MissingInput, build_assembly
from ..case.runflags import EXIT_UNSETTLED
from ..case.table import MODE_BOX, MODE_MESH, add_option, mode_options
from ..errors import ParameterError
from ..fe.constants import DEFAULT_NORMAL_SLOPE
from .common import check_output_dir, check_plot, print_json

if TYPE_CHECKING:
    from ..fe.assembly import Assembly

__all__ = ["EXIT_UNSETTLED", "add_assembly_options", "add_own_mesh_options",
           "check_mesh_input", "given", "is_mesh_file", "mesh_case",
           "mesh_clamp", "refuse_mesh_options", "run_own_mesh", "unsettled_status", "verb"]


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
        add_option(g, "normal_contact", mode=MODE_MESH,
                   note="default fixed: CalculiX has no fixed contact, so both solvers run a "
                        "hard penalty contact and the case's fixed W and d are given beside it")
        add_option(g, "normal_slope", note=f"default {DEFAULT_NORMAL_SLOPE:g}; with fixed "
                   "contact the hard contact's slope is a multiple of it", mode=MODE_MESH)
        add_option(g, "substeps", help="substeps over 1.25 cycles, a multiple of 5",
                   mode=MODE_MESH)
    add_option(g, "contact_set", mode=MODE_MESH)
    add_option(g, "clamp_set", mode=MODE_MESH)
    add_assembly_options(g)
    add_option(g, "load", mode=MODE_MESH)
    add_option(g, "history", choices=list(HISTORIES), mode=MODE_MESH,
               help="; ".join(f"{k}: {v}" for k, v in HISTORIES.items()),
               note="default settle")
    add_option(g, "settle_tol", note="default 1e-3", mode=MODE_MESH)
    add_option(g, "max_cycles", note="default 10", mode=MODE_MESH)
    add_option(g, "accept_unsettled", mode=MODE_MESH)
    if not validate:
        add_option(g, "cycles", help="calculix: cycles to run",
                   note="default 3; compare cycle_work_Nmm", mode=MODE_MESH)
        add_option(g, "plot", help="draw each load's loop over the settled cycle",
                   mode=MODE_MESH)
        from .convergence import add_convergence_options

        add_convergence_options(g)


def add_assembly_options(g: Any) -> None:
    """``--contact``, ``--preload``, ``--fixed`` and ``--material`` (each repeatable; with
    ``--mesh FILE`` only): the assembly of the mesh, beside the clamp's shorthand
    (``--contact-set``, ``--clamp-set``, ``--normal-force``, ``--modulus``,
    ``--poisson-ratio``)."""
    for dest in ASSEMBLY_DESTS:
        add_option(g, dest, mode=MODE_MESH)


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


def _flag(dest: str) -> str:
    return "--" + dest.replace("_", "-")


def mesh_clamp(args: argparse.Namespace, normal_contact: str | None = None,
               needs: tuple[str, ...] = ()) -> Assembly:
    """The assembly the options describe (the one place a namespace becomes an
    :class:`~microslip.fe.assembly.Assembly`, for ``fe --mesh``, ``validate --mesh`` and the
    structure commands alike; :func:`microslip.case.assembly.build_assembly`): the clamp's
    shorthand and ``--contact``, ``--preload``, ``--fixed``, ``--material``.
    ``normal_contact`` overrides ``--normal-contact``; what is not given takes the defaults.
    Values left out, with ``needs`` (the command's own: ``--load``, ``--density``), are one
    usage line (exit 2); a bad value is one line naming its option."""
    from .main import UsageError  # a required option left out: a usage mistake

    values = {d: getattr(args, d, None) for d in (
        "contact_set", "clamp_set", "normal_force", "modulus", "poisson_ratio", "density",
        "friction", "stick_slope", "normal_contact", "normal_slope", *ASSEMBLY_DESTS)}
    try:
        assembly = build_assembly(values, _flag, normal_contact)
    except MissingInput as exc:
        raise UsageError(f"--mesh {args.mesh} needs {', '.join([*exc.missing, *needs])}"
                         ) from None
    if needs:
        raise UsageError(f"--mesh {args.mesh} needs {', '.join(needs)}")
    return assembly


def check_mesh_input(path: str, assembly: Assembly, loads: Any = (),
                     sets: tuple[tuple[str, str], ...] = (), warn: bool = False) -> None:
    """Before anything is built: the assembly's sets, materials and bodies, and its values
    against the mesh's scale (:func:`microslip.case.meshroles.check_on_mesh`). The first
    error is raised (one line: a unit mistake such as a mesh in metres is never run);
    with ``warn`` the borderline values are warned about (the own-mesh run warns of them
    itself)."""
    from ..case.meshroles import check_on_mesh
    from ..case.options import warn as say
    from ..fe.meshfile import read_mesh

    found = check_on_mesh(read_mesh(path), assembly, loads, sets)
    found.raise_first()
    if warn:
        for line in found.warnings:
            say(line)


def unsettled_status(args: argparse.Namespace, settled: bool) -> int:
    """:data:`EXIT_UNSETTLED` for a result that did not settle, unless
    ``--accept-unsettled``; else 0."""
    if settled or getattr(args, "accept_unsettled", False):
        return 0
    return EXIT_UNSETTLED


def mesh_case(args: argparse.Namespace, default_normal: str | None = None) -> Any:
    """The :class:`~microslip.fe.ownmesh.OwnMeshCase` of the options (``default_normal``:
    the normal contact when none is given; else ``penalty`` for ``--solver calculix`` and
    ``fixed`` for the built-in solver)."""
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
    normal = args.normal_contact or default_normal or (
        "penalty" if args.solver == "calculix" else "fixed")
    assembly = mesh_clamp(args, normal, () if args.load else
                          ("--load SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG]",))
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
    if normal == "fixed" and given(args, "normal_slope") and default_normal is None:
        raise ParameterError("--normal-slope needs --normal-contact penalty (the fixed normal "
                             "contact has no normal stiffness)")
    extra: dict[str, Any] = {}
    if args.solver == "calculix":
        extra = {"options": {k: v for k, v in (("timeout", args.timeout),
                                               ("threads", args.threads)) if v is not None}}
    elif getattr(args, "command", "fe") == "fe" and (given(args, "timeout")
                                                     or given(args, "threads")):
        raise ParameterError("--timeout and --threads apply to --solver calculix")
    loads = tuple(MeshLoad.parse(s) for s in args.load)
    check_mesh_input(args.mesh, assembly, loads)
    return OwnMeshCase(
        args.mesh, assembly, loads,
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
    tol = work_tolerance(out, args.solver)
    if tol is not None:
        out["work_tolerance_Nmm"] = tol
    out["assembly"] = case_assembly(case)
    for warning in out.get("warnings", []):
        print(f"warning: {warning}", file=sys.stderr)
    if not out.get("solver_converged", out.get("converged", True)):
        status = 1
    else:
        status = unsettled_status(args, bool(out.get("settled", True)))
    if args.json:
        print_json(out)
        return status
    _print_text(args, out)
    if table:
        print("\n".join(table))
    if status == EXIT_UNSETTLED:
        print(f"  exit status {EXIT_UNSETTLED}: W per cycle did not settle (raise "
              "--max-cycles, or --accept-unsettled to take the figures as they are)")
    return status


def case_assembly(case: Any) -> dict[str, Any]:
    """The JSON of the assembly a run used."""
    from ..fe.assembly import as_assembly

    return as_assembly(case.clamp).describe()


def work_tolerance(out: dict[str, Any], solver: str) -> float | None:
    """The W (N·mm) below which the built-in solver's W is rounding: the run's
    ``work_tolerance_Nmm`` if it gives one, else the settle floor of the W per cycle
    (:data:`~microslip.fe.builtin.meshrun.SETTLE_FLOOR` times the loads' work scale
    sum_j A_j d_j); None for CalculiX."""
    if "work_tolerance_Nmm" in out:
        return float(out["work_tolerance_Nmm"])
    if solver != "builtin" or not out.get("loads"):
        return None
    from ..fe.builtin.meshrun import SETTLE_FLOOR

    scale = sum(abs(ld["amplitude_N"]) * abs(ld["peak_displacement_mm"])
                for ld in out["loads"])
    return SETTLE_FLOOR * scale if scale > 0 else None


def work_text(w: float, tol: float | None, width: int = 0) -> str:
    """``w`` in N·mm, or ``0 N·mm (below the solver's tolerance of X N·mm)`` when its size
    is below ``tol``."""
    if tol is not None and abs(w) < tol:
        return f"{0:{width}d} N·mm  (below the solver's tolerance of {tol:.2g} N·mm)"
    return f"{w:{width}.6g} N·mm"


def _print_text(args: argparse.Namespace, out: dict[str, Any]) -> None:
    o = out["options"]
    tol = out.get("work_tolerance_Nmm")
    refined = f" refined x{out['refine']}" if "refine" in out else ""
    print(f"mesh {out['mesh']}{refined} ({out['nodes']} nodes, {out['elements']} elements, "
          f"{out['dof']} DOF), {args.solver} solver ({out['element']}), {o['normal_contact']} "
          f"normal contact, stick slope {o['stick_slope_N_per_mm3']:g} N/mm^3")
    if "model" in out:
        print_model(out["model"])
    for k, ld in enumerate(out["loads"], 1):
        d = ", ".join(f"{x:g}" for x in ld["direction"])
        work = work_text(ld["work_Nmm"], tol).replace("  (", " (")
        print(f"  load {k} on {ld['set']:<10s} A {ld['amplitude_N']:g} N along ({d}), phase "
              f"{ld['phase_deg']:g} deg: work {work}, peak displacement "
              f"{ld['peak_displacement_mm']:.6g} mm")
    text = work_text(out["dissipated_energy_Nmm"], tol, 12)
    cycle = "settled" if out.get("settled", True) else "last"
    note = "" if "(below" in text else f"  (work of all loads over the {cycle} cycle; the " \
        "whole clamp)"
    print(f"  dissipated energy W    {text}{note}")
    print(f"  peak displacement      {out['peak_displacement_mm']:12.6g} mm  (load 1, half "
          "peak-to-peak)")
    print(f"  cycles                 {out['cycles']:12d}")
    print(f"  wall time              {out['wall_s']:12.3g} s")
    print(f"  {out['message']}")
    for f in out.get("files", []):
        if str(f).endswith((".pvd", ".json", ".png", ".pdf", ".svg")):
            print(f"  file                   {f}")


def print_model(m: dict[str, Any]) -> None:
    """The model the solver built, in lines a user can check against the part (issue 34):
    each role set's faces, area and pressure, the contact state after the preload step."""
    print(f"  model: {m['bodies']} bod{'y' if m['bodies'] == 1 else 'ies'}, "
          f"{m['contact_nodes']} contact nodes ({m['closed_after_preload']} closed, "
          f"{m['open_after_preload']} open after the preload), contact force "
          f"{m['contact_force_N']:.6g} N")
    for name, s in m["sets"].items():
        area = f"{s['faces']} faces, {s['area_mm2']:.6g} mm^2" if "area_mm2" in s else "node set"
        extra = (f", {s['force_N']:g} N = {s['pressure_MPa']:.4g} MPa" if "force_N" in s
                 else f", holds {s['directions']}" if "directions" in s else "")
        print(f"    {s['role']:12s} {name:16s} {area}{extra}")
