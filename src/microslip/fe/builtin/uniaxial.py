"""The paper's 1-D FE loading (Section 4) with the built-in solver, as an FELoopResult."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...energy import DEFAULT_STRAIN_ENERGY
from ...errors import MacroslipError
from ...loading import PaperSine, load_case
from ...models.interface import PressureLaw
from ...params import ClampParams
from ...results import HysteresisLoop
from ..constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from ..result import FELoopResult, gross_sliding_message, join_message, loop_damping
from .box import BoxLoading, box_describe, box_pressure_law
from .clamping import clamping_pressure
from .details import BuiltinDetails
from .meshmodel import MeshModel
from .model import NewtonOptions
from .study import DEFAULT_MESH, check_body, contact_history, model_for, solver_stats

__all__ = ["solve_uniaxial"]


def solve_uniaxial(params: ClampParams, model: str, amplitude: float, *,
                   mesh: Any = DEFAULT_MESH, stick_slope: float = DEFAULT_STICK_SLOPE,
                   increments: int = 50, element: str = "C3D8I",
                   centre_direction: str = "axial", linear_solver: str = "banded",
                   newton: NewtonOptions | None = None,
                   strain_energy_kind: str = DEFAULT_STRAIN_ENERGY,
                   record: bool = False,
                   pressure_law: PressureLaw | None = None, normal_contact: str = "fixed",
                   normal_slope: float = DEFAULT_NORMAL_SLOPE) -> FELoopResult:
    """The paper's 1-D FE loading of the clamped zone with the built-in solver.

    F = F0 sin(2 pi t), t = 0 .. 1.25 s in ``increments`` equal steps
    (:class:`~microslip.loading.PaperSine`, the paper's 50 substeps by default); the first
    quarter period leads from the clamped state to the peak, the loop is t = 0.25 .. 1.25 s.

    Parameters
    ----------
    params : ClampParams
    model : str
        Load case, a name in :data:`microslip.loading.LOAD_CASES`.
    amplitude : float
        F0, N; below mu F_N.
    mesh : str, (nx, ny, nz), HexMesh or MeshModel
        Mesh level (:mod:`microslip.meshlevels`), element counts, a box mesh
        (:func:`~microslip.fe.examples.box_hexmesh`), or a model already built
        (:func:`~microslip.fe.builtin.box.box_model`; then ``stick_slope``, ``element``,
        ``linear_solver`` are its own).
    stick_slope : float
        lambda, N/mm^3.
    increments : int
        Increments over t = 0 .. 1.25 s, a multiple of 5.
    element : {"C3D8", "C3D8I"}
    centre_direction : {"axial", "transverse"}
        Direction of the centre force (``axial``: the paper's 1-D centre model).
    linear_solver : {"banded", "splu", "cholmod"}
    newton : NewtonOptions, optional
    strain_energy_kind : str
        Definition of U in ``damping``.
    record : bool
        Keep the displacement and slip fields of every increment (``details.fields``) for
        a VTU export.
    pressure_law : PressureLaw, optional
        Shape of the clamping traction along the length (default uniform, the paper's).
    normal_contact : {"fixed", "penalty"}
        Normal forces fixed after clamping (the paper's reading) or a unilateral penalty
        of slope ``normal_slope`` (N/mm^3) that follows the load
        (:mod:`~microslip.fe.builtin.normal`).

    Returns
    -------
    FELoopResult
        ``solver="builtin"``; ``details`` is a
        :class:`~microslip.fe.builtin.details.BuiltinDetails`.

    Examples
    --------
    >>> from microslip import preset, closedform
    >>> p = preset("table1")
    >>> r = solve_uniaxial(p, "tip", 267.0, mesh=(8, 2, 1))
    >>> d0 = closedform.tip_displacement(267.0, p.axial_stiffness, p.friction_per_length)
    >>> r.converged, bool(abs(r.peak_displacement / d0 - 1) < 0.01)
    (True, True)
    """
    case = load_case(model)
    check_body(params, centre_direction)
    load = PaperSine.sampled(amplitude, increments)
    if load.amplitude >= params.macroslip_force:
        raise MacroslipError(f"amplitude {load.amplitude:g} N reaches the macroslip force "
                             f"mu F_N = {params.macroslip_force:g} N")
    fem = model_for(params, mesh, stick_slope, element, linear_solver, newton,
                    pressure_law=pressure_law, normal_contact=normal_contact,
                    normal_slope=normal_slope)
    sim = BoxLoading(params, fem, centre_direction)
    forces = {"tip": np.zeros_like(load.force), "centre": np.zeros_like(load.force)}
    forces[case.name] = load.force
    hist = sim.advance(forces["tip"], forces["centre"], record=record)
    d = hist.displacement(case.name)
    done = hist.completed
    loop_sl = slice(load.quarter, done)
    loop = HysteresisLoop(
        force=load.force[loop_sl].copy(), displacement=d[loop_sl].copy(), source="builtin",
        meta={"model": case.name, "amplitude_N": load.amplitude, "solver": "builtin",
              "centre_direction": centre_direction, "mesh": box_describe(fem.mesh),
              "element": fem.element, "dof": fem.dof, "stick_slope_N_per_mm3": fem.stick_slope,
              "increments": load.increments,
              "displacement": "force-weighted mean of the loaded section along the load, "
                              "relative to the clamped state"})
    setup = fem.setup_s if not isinstance(mesh, MeshModel) else 0.0
    stats = solver_stats(fem, [hist], setup)
    law = box_pressure_law(fem)
    details = BuiltinDetails(
        stats, centre_direction, float(np.sum(hist.friction_work[load.quarter + 1:])),
        None if hist.u is None else fem, hist.u, "uniform" if law is None else law.name,
        clamping_pressure(fem, params.width), fem.normal_contact,
        None if fem.normal is None else fem.normal.slope, hist.normal_force)
    time = load.time[:done]
    contact = contact_history(params, fem, time, hist.status, hist.slip, hist.normal_force)
    damping, idle = loop_damping(loop, contact, strain_energy_kind)
    message = (join_message(hist.message, idle, gross_sliding_message(contact))
               if hist.converged else f"{hist.message}; the loop is incomplete")
    return FELoopResult(
        solver="builtin", load_case=case.name, params=params, amplitude=load.amplitude,
        time=time, force=load.force[:done], displacement=d, loop=loop,
        damping=damping, contact=contact, dof=fem.dof, iterations=hist.iterations,
        wall_s=stats.wall_s, converged=hist.converged, message=message, details=details)
