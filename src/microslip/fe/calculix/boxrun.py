"""The paper's box on CalculiX through the mesh deck (issue 32, item 4).

The box of an :class:`~microslip.fe.calculix.case.FECase` is the 20-node bar
:func:`box20_mesh` (``box_hexmesh`` promoted by ``to_hex20``, with its mid-width plane as the
set ``sym``), the assembly :func:`~microslip.fe.builtin.box.box_assembly` with the symmetry
plane as a support (``Support("sym", "y")``: u_y = 0 there, as the box deck had it) and one
:class:`~microslip.fe.meshload.MeshLoad` on ``tip`` or ``centre``. It is written by
:func:`~microslip.fe.calculix.meshdeck.build_mesh_deck`, run by ccx and read by
:func:`~microslip.fe.calculix.meshrun.read_mesh_results`; :func:`run_case` converts that
:class:`~microslip.fe.calculix.meshrun.MeshCalculixResult` to the box's
:class:`~microslip.fe.result.FELoopResult` (the loop from the first force peak, the contact
pressure and shear at every state, the box's DOF count: 3 per node less the symmetry plane's
u_y, ``reuse`` by the deck's SHA-256).

``nlgeom``: the mesh deck has no geometrically nonlinear step; a case with ``nlgeom=True`` is
refused in one line (the rotations of the box are of order 1e-5 and the loop does not change,
docs/validation.md, so an option for it was not added).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...energy import DEFAULT_STRAIN_ENERGY
from ...errors import ParameterError
from ...io import write_json
from ...params import ClampParams
from ...results import HysteresisLoop
from ..assembly import Support
from ..hexmesh import HexMesh, face_load
from ..meshload import MeshLoad
from ..result import FELoopResult, loop_damping
from .assemblydeck import resolve_assembly
from .case import FECase
from .collect import CalculixDetails
from .mesh import MeshSpec
from .meshdeck import MESH_ELEMENTS, build_mesh_deck, load_plan
from .meshhistory import load_history
from .meshrun import (
    MeshCalculixResult,
    contact_values,
    read_mesh_results,
    run_mesh_calculix,
)
from .readers import read_frd
from .runner import (
    _RUN_RECORD,
    JOBNAME,
    _reusable,
    _sha256,
    ccx_version,
    default_timeout,
    find_ccx,
)

__all__ = ["box20_mesh", "box_calculix_setup", "box_dof", "box_fields", "read_results",
           "run_case", "to_loop_result"]

FloatArray = NDArray[np.float64]


def box20_mesh(params: ClampParams, spec: MeshSpec) -> HexMesh:
    """The box of ``params`` on the mesh ``spec`` as a 20-node :class:`HexMesh`:
    :func:`~microslip.fe.examples.box_hexmesh` promoted by
    :func:`~microslip.fe.examples.to_hex20`, with the set ``sym`` (the mid-width plane
    y = w/2).

    >>> from microslip import preset
    >>> m = box20_mesh(preset("table1"), MeshSpec(2, 2, 1))
    >>> m.elements.shape, len(m.nodes), len(m.node_sets["sym"])
    ((4, 20), 51, 13)
    """
    from ..examples import box_hexmesh, to_hex20

    level: Any = spec.label() if spec.graded else (spec.nx, spec.ny, spec.nz)
    m = to_hex20(box_hexmesh(params, level))
    sym = np.flatnonzero(np.isclose(m.nodes[:, 1], 0.5 * params.width, rtol=0.0,
                                    atol=1e-9 * params.width))
    return HexMesh(m.nodes, m.elements, {**m.node_sets, "sym": sym}, dict(m.surfaces),
                   source=m.source)


def box_calculix_setup(case: FECase) -> tuple[HexMesh, Any, list[MeshLoad], dict[str, Any]]:
    """(mesh, assembly, loads, deck options) of the box of ``case`` for the mesh deck."""
    from ..builtin.box import box_assembly

    if case.nlgeom:
        raise ParameterError("nlgeom is not available for CalculiX on the box: the mesh deck "
                             "has no geometrically nonlinear step (rotations ~1e-5)")
    mesh = box20_mesh(case.params, case.spec)
    a = box_assembly(case.params, stick_slope=case.stick_slope, normal_contact="penalty",
                     normal_slope=case.normal_slope)
    a = replace(a, supports=(Support("sym", "y"),))
    loads = [MeshLoad(case.model, (1.0, 0.0, 0.0), case.amplitude)]
    per_cycle = case.substeps * 4 // 5
    opts = {"increments_per_cycle": per_cycle, "cycles": 1,
            "max_iterations": case.max_iterations, "startup": "quarter"}
    return mesh, a, loads, opts


def to_loop_result(case: FECase, r: MeshCalculixResult, mesh: HexMesh, *,
                   pressure: FloatArray, shear: FloatArray,
                   strain_energy_kind: str = DEFAULT_STRAIN_ENERGY) -> FELoopResult:
    """The box's :class:`FELoopResult` of a mesh-deck run of ``case``."""
    if r.contact is None:
        raise ParameterError("the CalculiX result holds no contact history")
    force = r.force[:, 0].copy()
    displacement = r.displacement[:, 0].copy()
    q = case.quarter
    times = case.times.copy()
    loop = HysteresisLoop(
        force=force[q:].copy(), displacement=displacement[q:].copy(), source="calculix",
        meta={"model": case.model, "amplitude_N": case.amplitude, "mesh": case.spec.label(),
              "stick_slope": case.stick_slope, "dof": box_dof(mesh), "time_s": times[q:].copy()})
    details = CalculixDetails(case, float(r.clamp_displacement[0]), pressure, shear)
    damping, _ = loop_damping(loop, r.contact, strain_energy_kind)
    message = r.message if r.converged else "cut back"
    return FELoopResult(
        solver="calculix", load_case=case.model, params=case.params, amplitude=case.amplitude,
        time=times, force=force, displacement=displacement, loop=loop, damping=damping,
        contact=r.contact, dof=box_dof(mesh), iterations=r.iterations.copy(),
        wall_s=float(r.wall_s), converged=r.converged, message=message, details=details,
        job_dir=r.job_dir)


def box_dof(mesh: HexMesh) -> int:
    """3 per node of the bar, less u_y of the symmetry plane."""
    return 3 * len(mesh.nodes) - int(np.asarray(mesh.node_sets["sym"]).size)


def read_results(case: FECase, job_dir: str | Path, *, wall_s: float = math.nan,
                 strain_energy_kind: str = DEFAULT_STRAIN_ENERGY) -> FELoopResult:
    """The :class:`FELoopResult` of a finished run of the box of ``case`` in ``job_dir``.

    Raises
    ------
    ResultsError
        A file is missing or truncated, or it does not hold the clamped state and every
        substep of the load step (a partial loop is never returned).
    """
    job_dir = Path(job_dir)
    mesh, a, loads, opts = box_calculix_setup(case)
    faces = resolve_assembly(mesh, a).contact_faces
    history = load_history(loads, opts["increments_per_cycle"], 1, "quarter")
    r = read_mesh_results(load_plan(mesh, loads), history, job_dir, JOBNAME,
                          element=MESH_ELEMENTS[20], dof=box_dof(mesh), wall_s=wall_s,
                          contact=(mesh, faces, a.friction, a.stick_slope))
    return _converted(case, r, mesh, faces, strain_energy_kind)


def _converted(case: FECase, r: MeshCalculixResult, mesh: HexMesh, faces: Any,
               strain_energy_kind: str) -> FELoopResult:
    assert r.job_dir is not None
    nodes = face_load(mesh, faces)[0]
    values = contact_values(r.job_dir / f"{JOBNAME}.frd", nodes, case.substeps)
    pressure, shear = values[:, :, 3].copy(), values[:, :, 4:6].copy()
    return to_loop_result(case, r, mesh, pressure=pressure, shear=shear,
                          strain_energy_kind=strain_energy_kind)


def run_case(case: FECase, job_dir: str | Path, *, timeout: float | None = None,
             threads: int = 1, executable: str | None = None, reuse: bool = False,
             strain_energy_kind: str = DEFAULT_STRAIN_ENERGY) -> FELoopResult:
    """Write the box of ``case`` with the mesh deck into ``job_dir``, run ccx and read the
    result.

    Parameters
    ----------
    case : FECase
    job_dir : path
        Created if needed; holds ``job.inp``, the solver's files, ``ccx.log`` and ``run.json``.
    timeout : float, optional
        Seconds (default :func:`~.runner.default_timeout`).
    threads : int
        ``OMP_NUM_THREADS`` of the solver.
    executable : str, optional
        Solver name or path (default ``ccx``).
    reuse : bool
        If ``job_dir`` already holds a successful run of the identical deck (same SHA-256),
        read its results instead of running the solver again.
    strain_energy_kind : str
        Definition of U for the loss factor (:data:`microslip.energy.STRAIN_ENERGY`).

    Raises
    ------
    ParameterError
        A bad case (``nlgeom``, an element other than C3D20R).
    SolverError
        Any failure (solver missing, time-out, killed, not converged, results missing or
        truncated); nothing partial is returned.
    """
    if not isinstance(case, FECase):
        raise ParameterError("run_case needs an FECase")
    mesh, a, loads, opts = box_calculix_setup(case)
    digest = _sha256(build_mesh_deck(mesh, a, loads=loads, **opts))
    job_dir = Path(job_dir)
    wall = _reusable(job_dir, JOBNAME, digest) if reuse else None
    if wall is not None:
        return read_results(case, job_dir, wall_s=wall, strain_energy_kind=strain_energy_kind)
    exe = find_ccx(executable)  # fail before touching the directory
    (job_dir / _RUN_RECORD).unlink(missing_ok=True)
    r = run_mesh_calculix(mesh, a, loads=loads, job_dir=job_dir,
                          timeout=timeout or default_timeout(case), threads=threads,
                          executable=exe, **opts)
    result = _converted(case, r, mesh, resolve_assembly(mesh, a).contact_faces,
                        strain_energy_kind)
    write_json(job_dir / _RUN_RECORD, {
        "deck_sha256": digest, "returncode": 0, "wall_s": r.wall_s, "threads": threads,
        "ccx_version": ccx_version(exe), "case": case.label(), "dof": result.dof,
        "iterations": result.total_iterations})
    return result


def box_fields(result: FELoopResult) -> Any:
    """The nodal fields of a box run for the VTU export (:class:`~microslip.fe.vtu.FieldSeries`):
    the bar's C3D20R and the base's C3D8 (``part`` 0 and 1), the displacement of every node
    from the ``.frd`` file, the contact pressure and shear at the contact nodes."""
    from ..vtu import FieldSeries
    from .meshdeck import base_slab

    d = result.details
    if not isinstance(d, CalculixDetails) or result.job_dir is None:
        raise ParameterError("the CalculiX result has no job directory to read fields from")
    mesh, a, _, _ = box_calculix_setup(d.case)
    slab = base_slab(mesh, resolve_assembly(mesh, a).contact_faces)
    nodes = np.vstack([mesh.nodes, slab.nodes])
    k = result.time.size
    blocks = read_frd(result.job_dir / f"{JOBNAME}.frd", names=("DISP",)).select("DISP")
    u = np.zeros((k, nodes.shape[0], 3))
    for i, b in enumerate(blocks[-k:]):
        u[i, b.nodes - 1] = b.values[:, :3]
    c = result.contact
    pressure = np.zeros((k, nodes.shape[0]))
    pressure[:, c.nodes] = d.pressure
    shear = np.zeros((k, nodes.shape[0], 3))
    shear[:, c.nodes, :2] = d.shear
    part = [np.zeros(mesh.elements.shape[0], dtype=np.int32),
            np.ones(slab.elements.shape[0], dtype=np.int32)]
    return FieldSeries(nodes, [("hexahedron20", mesh.elements),
                               ("hexahedron", slab.elements + mesh.nodes.shape[0])], u,
                       {"contact_pressure": pressure, "contact_shear": shear}, {"part": part})
