"""One run of the user's own clamp mesh: read, check, solve (built-in or CalculiX), write.

The library side of ``microslip fe --mesh FILE``: :class:`OwnMeshCase` holds what a case
file or the command line gives (the mesh, its role sets, the clamp, the contact law, the
loads), :func:`run_own_mesh` reads the mesh (:func:`~microslip.fe.meshfile.read_mesh`),
checks the roles (:func:`~microslip.fe.meshcheck.check_roles`) and runs a solver of
:data:`OWN_MESH_SOLVERS` on it; with ``out`` it writes ``result.json``, one loop CSV per load
and (built-in solver) a VTU series with the contact status, slip and pressure on the user's
mesh. Units: N, mm, MPa, N·mm.

Both solvers run the same load history: a ramp from rest where a phase makes a load non-zero
at t = 0, then whole cycles of F_j = A_j sin(2 pi t + phi_j). The built-in solver runs cycles
until the work per cycle settles to ``tol``; CalculiX runs ``cycles`` cycles (its
``cycle_work_Nmm`` shows whether they settled).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..io import atomic_write, write_loop_csv
from .assembly import Assembly, as_assembly
from .clamp import MeshClamp
from .hexmesh import HexMesh
from .meshload import MeshLoad

__all__ = ["HISTORIES", "OWN_MESH_SOLVERS", "OwnMeshCase", "OwnMeshRun", "run_fe", "run_own_mesh"]

#: Load histories of an own-mesh run (see :class:`OwnMeshCase`).
HISTORIES = {"settle": "cycles until the work per cycle settles to the tolerance",
             "paper": "the paper's load step: a quarter-cycle rise, then one cycle"}


@dataclass(frozen=True)
class OwnMeshCase:
    """A clamp described by its mesh: the file, the clamp (:class:`~.clamp.MeshClamp`: the
    role sets, the clamping force, the material and the contact law) and the loads.

    The clamp's ``normal_contact`` is ``fixed`` (normal forces of the clamping step) or
    ``penalty`` (``normal_slope`` N/mm^3, lift-off allowed); CalculiX takes ``penalty`` only.
    ``substeps`` as the box's ``fe --substeps``: equal substeps over 1.25 cycles (a multiple of
    5; 50 gives 40 increments per cycle). ``history`` is one of :data:`HISTORIES`: ``settle``
    runs cycles until the work of a cycle is within ``tol`` (relative) of the last, at most
    ``max_cycles`` (CalculiX runs ``cycles``); ``paper`` is the paper's load step of the box
    (a quarter-cycle rise, then one cycle; W over that cycle), loads at phase 0 only.
    ``refine`` N > 1 runs the mesh with every element subdivided N times in each direction
    (:func:`~microslip.fe.refine.refine_mesh`, its sets carried). ``element`` ``hex20`` runs
    an 8-node mesh as 20-node hexahedra (:func:`~microslip.fe.promote.promote_mesh`, after the
    refinement), ``hex8`` refuses a 20-node mesh; None: as the file.
    """

    mesh_file: str | Path | HexMesh
    clamp: Assembly | MeshClamp
    loads: tuple[MeshLoad, ...]
    substeps: int = 50
    history: str = "settle"
    tol: float = 1e-3
    max_cycles: int = 10
    cycles: int = 3
    options: dict[str, Any] = field(default_factory=dict)
    refine: int = 1
    element: str | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "clamp", as_assembly(self.clamp))
        if not self.loads:
            raise ParameterError("give at least one --load SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG]")
        if self.history not in HISTORIES:
            raise ParameterError(f"history must be one of {', '.join(HISTORIES)}, got "
                                 f"{self.history!r}")
        if isinstance(self.substeps, bool) or not isinstance(self.substeps, int) or not (
                self.substeps >= 10 and self.substeps % 5 == 0):
            raise ParameterError(f"--substeps must be a multiple of 5, at least 10, got "
                                 f"{self.substeps!r}")
        from .refine import MAX_REFINE

        if isinstance(self.refine, bool) or not isinstance(self.refine, int) or not (
                1 <= self.refine <= MAX_REFINE):
            raise ParameterError(f"--refine must be a whole number in [1, {MAX_REFINE}], got "
                                 f"{self.refine!r}")
        from .promote import ELEMENT_ORDERS

        if self.element is not None and self.element not in ELEMENT_ORDERS:
            raise ParameterError(f"--element must be one of {', '.join(ELEMENT_ORDERS)}, got "
                                 f"{self.element!r}")
        if self.history == "paper" and any(ld.phase_deg % 360 for ld in self.loads):
            raise ParameterError("the paper's load step starts every load from rest at phase "
                                 "0; with phases use the default history (settle)")

    @property
    def increments(self) -> int:
        """Increments per cycle: 4/5 of the substeps over 1.25 cycles."""
        return self.substeps * 4 // 5


@dataclass(frozen=True)
class OwnMeshRun:
    """What a run gives: the JSON summary, the files written, the solver's own result."""

    summary: dict[str, Any]
    files: tuple[Path, ...]
    result: Any


def _mesh_of(case: OwnMeshCase) -> HexMesh:
    from .meshcheck import check_assembly
    from .meshfile import read_mesh
    from .promote import as_element
    from .refine import refine_mesh

    mesh = case.mesh_file if isinstance(case.mesh_file, HexMesh) else read_mesh(case.mesh_file)
    check_assembly(mesh, as_assembly(case.clamp), case.loads)
    return as_element(refine_mesh(mesh, case.refine), case.element)


def _builtin(mesh: HexMesh, case: OwnMeshCase, record: bool) -> tuple[dict[str, Any], Any]:
    from .builtin.meshrun import LoadFactors, SineCycles, solve_mesh
    from .clamp import clamped_model

    model = clamped_model(mesh, case.clamp)
    history: SineCycles | LoadFactors
    if case.history == "paper":
        time = np.arange(case.substeps + 1) / case.increments
        history = LoadFactors(np.repeat(np.sin(2 * np.pi * time)[:, None], len(case.loads), 1),
                              case.increments // 4, time)
    else:
        history = SineCycles(increments=case.increments, tol=case.tol,
                             max_cycles=case.max_cycles)
    result = solve_mesh(model, case.loads, history, record=record)
    return {"solver": "builtin", "element": model.element, **result.summary(),
            "converged": result.converged, "model": model.describe()}, result


def _calculix(mesh: HexMesh, case: OwnMeshCase, record: bool) -> tuple[dict[str, Any], Any]:
    from .assembly import as_assembly
    from .calculix.meshrun import run_mesh_calculix

    result = run_mesh_calculix(
        mesh, as_assembly(case.clamp), loads=case.loads,
        increments_per_cycle=case.increments,
        cycles=1 if case.history == "paper" else case.cycles,
        startup="quarter" if case.history == "paper" else "ramp", **case.options)
    return result.summary(), result


#: Solvers of an own-mesh run: name -> function (mesh, case, record) -> (summary, result).
OWN_MESH_SOLVERS: dict[str, Callable[[HexMesh, OwnMeshCase, bool],
                                     tuple[dict[str, Any], Any]]] = {
    "builtin": _builtin, "calculix": _calculix}


def _loops(result: Any) -> list[tuple[str, Any, Any]]:
    """(set, force, displacement) of every load over the settled (last) cycle."""
    out = []
    if hasattr(result, "cycle_start"):  # built-in
        for ld in result.loads:
            out.append((ld.load.set, ld.loop.force, ld.loop.displacement))
    else:
        n = result.increments_per_cycle
        for j, ld in enumerate(result.loads):
            out.append((ld.set, result.force[-n - 1:, j], result.displacement[-n - 1:, j]))
    return out


def _vtu(mesh: HexMesh, result: Any, out: Path) -> list[Path]:
    """The VTU series of a built-in run on the user's mesh: displacement, contact status
    (-1 not a contact node, 0 open, 1 stick, 2 slip as :data:`~microslip.fe.result.STATUS`),
    slip (global components, mm) and contact pressure (MPa) at every state."""
    from .vtu import FieldSeries, write_vtu_series

    n = len(mesh.nodes)
    nodes = result.contact.nodes
    pressure = np.zeros((result.time.size, n))
    pressure[:, nodes] = result.pressure
    slip = np.zeros((result.time.size, n, 3))
    if result.contact.slip is not None:
        slip[:, nodes] = result.contact.slip @ result.tangent_axes
    cell = "hexahedron" if mesh.nodes_per_element == 8 else "hexahedron20"
    fields = FieldSeries(mesh.nodes, [(cell, mesh.elements)], result.displacement,
                         point_data={"contact_pressure": pressure, "contact_slip": slip})
    return write_vtu_series(result, fields, out, basename="fe_mesh")


def run_own_mesh(case: OwnMeshCase, solver: str = "builtin", *, out: str | Path | None = None,
                 vtu: bool = True) -> OwnMeshRun:
    """Read, check and solve the mesh of ``case``; with ``out`` write its files there.

    Raises
    ------
    ParameterError
        A bad mesh, set or value (one line naming it).
    NonConvergenceError, MacroslipError
        From the solver.
    """
    if solver not in OWN_MESH_SOLVERS:
        raise ParameterError(f"unknown solver {solver!r}; choose one of "
                             f"{', '.join(OWN_MESH_SOLVERS)}")
    mesh = _mesh_of(case)
    record = out is not None and vtu and solver == "builtin"
    summary, result = OWN_MESH_SOLVERS[solver](mesh, case, record)
    from .meshcheck import scale_warnings

    units = scale_warnings(mesh, case.clamp.clamp_set, case.clamp.normal_force, case.clamp.modulus)
    if units:
        summary["warnings"] = [*units, *summary.get("warnings", [])]
    summary = {"mesh": mesh.source if isinstance(case.mesh_file, HexMesh)
               else str(case.mesh_file), "nodes": len(mesh.nodes),
               "elements": len(mesh.elements), **summary}
    if case.refine > 1:
        summary["refine"] = case.refine
    files: list[Path] = []
    if out is not None:
        d = Path(out)
        for k, (name, force, disp) in enumerate(_loops(result)):
            files.append(write_loop_csv(d / f"loop_{k + 1}_{name}.csv", force, disp))
        if record:
            files.extend(_vtu(mesh, result, d))
        listed = [f for f in files if f.suffix != ".vtu"]  # the .pvd lists the VTU files
        summary["files"] = [str(f) for f in listed] + [str(d / "result.json")]
        with atomic_write(d / "result.json") as fh:
            json.dump(summary, fh, indent=2, default=float)
        files.append(d / "result.json")
    return OwnMeshRun(summary, tuple(files), result)


def loops_of(run: OwnMeshRun) -> Sequence[tuple[str, Any, Any]]:
    """(set, force N, work-conjugate displacement mm) of every load over the settled cycle."""
    return _loops(run.result)


#: Agreement of the built-in solver with CalculiX that ``validate --mesh`` requires
#: (issue 22): relative difference of W and of the first load's displacement.
VALIDATION_TOLERANCE = {"dissipated_energy_Nmm": 0.03, "peak_displacement_mm": 0.01}


def compare_solvers(case: OwnMeshCase, out: str | Path | None = None) -> dict[str, Any]:
    """The built-in solver and CalculiX on the same mesh, sets, loads and history: the
    built-in runs until W settles, CalculiX then runs as many cycles from the same ramp.
    Returns both summaries and the relative differences, with ``passed`` against
    :data:`VALIDATION_TOLERANCE`; with ``out`` writes ``validation_mesh.json`` there."""
    builtin = run_own_mesh(case, "builtin").summary
    from dataclasses import replace

    ccx = run_own_mesh(replace(case, cycles=int(builtin["cycles"])), "calculix").summary
    diff = {k: ccx[k] / builtin[k] - 1.0 if builtin[k] else float("nan")
            for k in VALIDATION_TOLERANCE}
    passed = all(abs(diff[k]) <= tol for k, tol in VALIDATION_TOLERANCE.items())
    result = {"mesh": str(case.mesh_file), "builtin": builtin, "calculix": ccx,
              "relative_difference": diff, "tolerance": dict(VALIDATION_TOLERANCE),
              "passed": passed}
    if out is not None:
        with atomic_write(Path(out) / "validation_mesh.json") as fh:
            json.dump(result, fh, indent=2, default=float)
    return result


def run_fe(mesh: str | Path | HexMesh, assembly: Assembly | MeshClamp,
           loads: Sequence[MeshLoad], *, solver: str = "builtin",
           out: str | Path | None = None, **options: Any) -> OwnMeshRun:
    """The frictional FE of ``mesh`` (a file or a :class:`~.hexmesh.HexMesh`) under
    ``assembly`` (:class:`~.assembly.Assembly`, or a clamp on the rigid base) and ``loads``
    (:class:`~.meshload.MeshLoad`, N): one call, one named result (``summary`` as the
    command line's JSON, ``result`` the solver's own, ``files`` with ``out``). ``options``
    are :class:`OwnMeshCase`'s (``substeps``, ``tol``, ``max_cycles``, ``refine``,
    ``element``, ...).

    >>> from microslip.fe.assembly import rigid_base
    >>> run = run_fe("examples/cantilever.inp", rigid_base(
    ...     contact_set="contact", clamp_set="clamp", normal_force=2000.0, modulus=70000.0,
    ...     poisson_ratio=0.33, friction=0.5, stick_slope=1e4),
    ...     [MeshLoad("tip", (1.0, 0.0, 0.0), 300.0)])  # doctest: +SKIP
    >>> run.summary["dissipated_energy_Nmm"]  # doctest: +SKIP
    """
    return run_own_mesh(OwnMeshCase(mesh, assembly, tuple(loads), **options), solver,
                        out=out)
