"""Runs of the built-in solver: the paper's 1-D loops, planar cyclic paths, and the
coupled-versus-decoupled study.

* :func:`~microslip.fe.builtin.uniaxial.solve_uniaxial` (its own module) — one 1-D loading as
  in the paper's FE (Section 4).
* :func:`solve_load_path` — a planar cyclic path, repeated until the energy dissipated per
  cycle W = closed integral (F_tip d delta_tip + F_centre d delta_centre) settles.
* :func:`coupling_study` — the coupled path against its two uni-axial parts:
  coupling ratio W_coupled / (W_tip-only + W_centre-only).
* :func:`coupling_sweep` — that ratio over force ratios R and phases.

Units: N, mm, N·mm, degrees, seconds.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import conventions
from ...conventions import check_whole
from ...energy import loop_work
from ...errors import MacroslipError, ParameterError
from ...loading import LoadPath
from ...models.interface import PressureLaw
from ...params import ClampParams, check_amplitude, check_positive
from ...results import HysteresisLoop
from ..constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from ..result import OPEN, ContactHistory
from .box import BoxHistory, BoxLoading, box_describe, box_model
from .details import (
    CouplingResult,
    CycleWork,
    LoadPathResult,
    SolverStats,
)
from .meshmodel import MeshModel
from .model import CENTRE_DIRECTIONS, NewtonOptions

__all__ = [
    "DEFAULT_MESH",
    "CouplingSweep",
    "amplitudes_for_ratio",
    "check_body",
    "contact_history",
    "coupling_study",
    "coupling_sweep",
    "model_for",
    "solve_load_path",
    "solver_stats",
]

FloatArray = NDArray[np.float64]

#: Mesh used when none is given: mesh-converged for the Table 1 loops (docs/solver.md).
DEFAULT_MESH = conventions.DEFAULT_MESH

def model_for(params: ClampParams, mesh: Any, stick_slope: float, element: str,
              linear_solver: str, newton: NewtonOptions | None, *,
              pressure_law: PressureLaw | None = None, normal_contact: str = "fixed",
              normal_slope: float = DEFAULT_NORMAL_SLOPE) -> MeshModel:
    """The box model of ``params`` on ``mesh`` (:func:`~.box.box_model`; a model given as
    ``mesh`` is checked and returned)."""
    return box_model(params, mesh, stick_slope=stick_slope, element=element,
                     linear_solver=linear_solver, newton=newton, pressure_law=pressure_law,
                     normal_contact=normal_contact, normal_slope=normal_slope)


def solver_stats(model: MeshModel, hist: Sequence[BoxHistory], setup_s: float
                 ) -> SolverStats:
    its = np.concatenate([h.iterations for h in hist]) if hist else np.zeros(0, dtype=int)
    return SolverStats(
        dof=model.dof, total_dof=int(model.index.size),
        half_bandwidth=getattr(model.backend, "half_bandwidth", None),
        mesh=box_describe(model.mesh), element=model.element,
        linear_solver=model.backend.name, stick_slope=model.stick_slope,
        increments=int(its.size), iterations=int(its.sum()),
        factorisations=int(sum(h.factorisations for h in hist)),
        max_iterations=int(its.max()) if its.size else 0,
        setup_s=setup_s, wall_s=setup_s + float(sum(h.wall_s for h in hist)),
    )


def contact_history(params: ClampParams, model: MeshModel, time: FloatArray,
                    status: NDArray[np.int8], slip: FloatArray | None = None,
                    normal_force: FloatArray | None = None) -> ContactHistory:
    """The :class:`~microslip.fe.result.ContactHistory` of a run: stick or slip after every
    increment, or open where a penalty normal force is 0 (``normal_force``; the fixed normal
    contact stays closed), each node standing for its tributary area over the width in slip
    lengths."""
    nodes = model.contact_nodes
    status = np.asarray(status, dtype=np.int8).copy()
    if normal_force is not None:
        status[normal_force <= 0.0] = OPEN
    return ContactHistory(nodes, model.mesh.nodes[nodes].copy(), time, status,
                          model.contact_area / params.width, slip)


def check_body(params: Any, centre_direction: str) -> None:
    """One clear error for a wrong parameter object or centre direction."""
    if not isinstance(params, ClampParams):
        raise ParameterError(f"params must be a ClampParams, got {type(params).__name__}")
    if centre_direction not in CENTRE_DIRECTIONS:
        raise ParameterError(f"unknown centre direction {centre_direction!r}; choose one of "
                             f"{', '.join(CENTRE_DIRECTIONS)}")


def _cycle_works(path: LoadPath, ft: FloatArray, fc: FloatArray, dt: FloatArray,
                 dc: FloatArray, fw: FloatArray, cycles: int
                 ) -> tuple[FloatArray, FloatArray, FloatArray]:
    k0, n = path.cycle_start, path.samples_per_cycle
    tip, cen, fri = np.zeros(cycles), np.zeros(cycles), np.zeros(cycles)
    for c in range(cycles):  # a handful of cycles: vectorised within each
        s = slice(k0 + c * n, k0 + (c + 1) * n + 1)
        tip[c] = loop_work(ft[s], dt[s])
        cen[c] = loop_work(fc[s], dc[s])
        fri[c] = float(np.sum(fw[s][1:]))
    return tip, cen, fri


def as_load_path(path: Any, f_tip: ArrayLike | None = None,
                 f_centre: ArrayLike | None = None) -> LoadPath:
    """The path to solve: a :class:`~microslip.loading.LoadPath`, reached from rest
    (:meth:`~microslip.loading.LoadPath.from_rest`), or the times of one cycle with the
    forces at them (:meth:`~microslip.loading.LoadPath.from_cycle`)."""
    if isinstance(path, LoadPath) and f_tip is None and f_centre is None:
        out = path.from_rest()
    elif f_tip is None or f_centre is None:
        raise ParameterError("give a LoadPath, or times with f_tip and f_centre arrays")
    else:
        out = LoadPath.from_cycle(path, f_tip, f_centre)
    if not out.peak_resultant > 0.0:
        raise ParameterError("a load path needs a non-zero force")
    return out


def _check_cycles(cycles: Any, min_cycles: Any, cycle_tol: Any) -> tuple[int, int, float]:
    n = check_whole("cycles", cycles, 1, 1000)
    least = check_whole("min_cycles", min_cycles, 2, 1000)
    return n, least, check_positive("cycle_tol", cycle_tol, upper=1.0)


def _run_path(params: ClampParams, fem: MeshModel, path: LoadPath, *, cycles: int,
              min_cycles: int, cycle_tol: float, centre_direction: str, setup_s: float
              ) -> LoadPathResult:
    if path.peak_resultant >= params.macroslip_force:
        raise MacroslipError(
            f"the resultant load reaches {path.peak_resultant:g} N >= mu F_N = "
            f"{params.macroslip_force:g} N (macroslip)")
    sim = BoxLoading(params, fem, centre_direction)
    k0, n = path.cycle_start, path.samples_per_cycle
    theta_all, ft_all, fc_all = path.repeated(cycles)
    hists: list[BoxHistory] = []
    done_cycles = 0
    message = ""
    converged = True
    works: list[float] = []
    # Start-up and the first cycle, then one cycle at a time until W settles.
    end = k0 + n + 1
    pos = 0
    while True:
        h = sim.advance(ft_all[pos:end], fc_all[pos:end])
        hists.append(h)
        if not h.converged:
            converged, message = False, h.message
            break
        done_cycles += 1
        pos = end
        ft = np.concatenate([x.f_tip for x in hists])
        fc = np.concatenate([x.f_centre for x in hists])
        dt = np.concatenate([x.tip_displacement for x in hists])
        dc = np.concatenate([x.centre_displacement for x in hists])
        s = slice(k0 + (done_cycles - 1) * n, k0 + done_cycles * n + 1)
        works.append(loop_work(ft[s], dt[s]) + loop_work(fc[s], dc[s]))
        if done_cycles >= cycles:
            break
        if done_cycles >= min_cycles:
            w1, w0 = works[-1], works[-2]
            if abs(w1 - w0) <= cycle_tol * max(abs(w1), 1e-300):
                break
        end = pos + n
    ft = np.concatenate([x.f_tip for x in hists])
    fc = np.concatenate([x.f_centre for x in hists])
    dt = np.concatenate([x.tip_displacement for x in hists])
    dc = np.concatenate([x.centre_displacement for x in hists])
    fw = np.concatenate([x.friction_work for x in hists])
    status = np.concatenate([x.status for x in hists])
    normal = (None if fem.normal is None else
              np.concatenate([x.normal_force for x in hists if x.normal_force is not None]))
    theta = theta_all[:ft.size]
    ncyc = done_cycles
    tip, cen, fri = _cycle_works(path, ft, fc, dt, dc, fw, ncyc)
    cw = CycleWork(work=tip + cen, tip=tip, centre=cen, friction=fri, tolerance=cycle_tol)
    if ncyc:
        s = slice(k0 + (ncyc - 1) * n, k0 + ncyc * n + 1)
        loops = {
            "tip": HysteresisLoop(ft[s].copy(), dt[s].copy(), "builtin",
                                  {"component": "tip", "direction": "x (along the bar)"}),
            "centre": HysteresisLoop(fc[s].copy(), dc[s].copy(), "builtin",
                                     {"component": "centre", "direction": centre_direction}),
        }
    else:
        loops = {}
    settled = cw.settled
    if converged:
        message = (f"W per cycle settled to {cw.reached:.2e} (tolerance {cycle_tol:.1e}) after "
                   f"{ncyc} cycles" if settled else
                   f"W per cycle did not settle to {cycle_tol:.1e} in {ncyc} cycles "
                   f"(last change {cw.reached:.2e})")
    return LoadPathResult(
        theta=theta, f_tip=ft, f_centre=fc, tip_displacement=dt, centre_displacement=dc,
        cycle_start=k0,
        samples_per_cycle=n, centre_direction=centre_direction, cycle_work=cw, loops=loops,
        contact=contact_history(params, fem, theta, status, None, normal),
        stats=solver_stats(fem, hists, setup_s),
        converged=converged, success=converged and settled, message=message,
        meta=dict(path.meta))


def solve_load_path(params: ClampParams, times: Any, f_tip: ArrayLike | None = None,
                    f_centre: ArrayLike | None = None, *, mesh: Any = DEFAULT_MESH,
                    cycles: int = 6, min_cycles: int = 2, cycle_tol: float = 1e-3,
                    stick_slope: float = DEFAULT_STICK_SLOPE, element: str = "C3D8I",
                    centre_direction: str = "transverse", linear_solver: str = "banded",
                    newton: NewtonOptions | None = None) -> LoadPathResult:
    """A planar cyclic load path, repeated until the energy per cycle settles.

    Parameters
    ----------
    params : ClampParams
    times : array_like or LoadPath
        The samples of one cycle (any increasing times or angles) with ``f_tip`` and
        ``f_centre``; or a :class:`~microslip.loading.LoadPath` (see :func:`as_load_path`).
        Arrays: the cycle is closed if needed and reached from zero load by a straight ramp.
    f_tip, f_centre : array_like, optional
        Tip force (along the bar, end face) and centre force (mid-length section) at the
        samples, N.
    mesh : see :func:`solve_uniaxial`
    cycles : int
        Most cycles to run.
    min_cycles : int
        Fewest cycles before the settling test (>= 2: the first cycle starts from the virgin
        state).
    cycle_tol : float
        Stop when |W_k - W_(k-1)| <= cycle_tol |W_k|.
    centre_direction : {"transverse", "axial"}
        Direction of the centre force: across the bar (default, the planar study) or along it.

    Returns
    -------
    LoadPathResult
        Per-cycle W and its tip and centre terms, friction dissipation per cycle, the loops
        of the last cycle, contact status per increment, and whether W settled.

    Examples
    --------
    >>> from microslip import preset
    >>> from microslip.loading import LoadPath
    >>> r = solve_load_path(preset("table1"), LoadPath.ramped(150.0, 150.0, 90.0, 16),
    ...                     mesh=(8, 2, 1), cycles=4)
    >>> r.converged, r.dissipated_energy > 0
    (True, True)
    """
    check_body(params, centre_direction)
    cycles, min_cycles, tol = _check_cycles(cycles, min_cycles, cycle_tol)
    path = as_load_path(times, f_tip, f_centre)
    fem = model_for(params, mesh, stick_slope, element, linear_solver, newton)
    setup = fem.setup_s if not isinstance(mesh, MeshModel) else 0.0
    return _run_path(params, fem, path, cycles=cycles, min_cycles=min(min_cycles, cycles),
                     cycle_tol=tol, centre_direction=centre_direction, setup_s=setup)


def coupling_study(params: ClampParams, tip_amplitude: float, centre_amplitude: float,
                   phase_deg: float = 90.0, *, cycles: int = 6, increments_per_cycle: int = 256,
                   mesh: Any = DEFAULT_MESH, cycle_tol: float = 1e-3,
                   stick_slope: float = DEFAULT_STICK_SLOPE, element: str = "C3D8I",
                   centre_direction: str = "transverse", linear_solver: str = "banded",
                   path: Any = None, newton: NewtonOptions | None = None) -> CouplingResult:
    """Coupled planar loading against the paper's decoupling into two 1-D loadings.

    Three runs on the same clamped model, each until W per cycle settles: both forces
    together (F_tip = A_t sin theta, F_centre = A_c sin(theta + phase)), the tip force alone,
    and the centre force alone. The coupling ratio is W_coupled / (W_tip-only +
    W_centre-only); the paper's decoupling (two independent 1-D models) assumes it is 1.

    Parameters
    ----------
    params : ClampParams
    tip_amplitude, centre_amplitude : float
        A_t (along the bar, end face) and A_c (across the bar, mid-length section), N.
    phase_deg : float
        Phase of the centre force ahead of the tip force, degrees (0: straight-line path,
        90: ellipse).
    cycles : int
        Most cycles per run.
    increments_per_cycle : int
        Samples per cycle. The return map is first order in time when the friction force
        turns: at 256 the 90-degree ratios are about 1 % low, at 64 about 3 % (docs/solver.md).
    mesh, cycle_tol, stick_slope, element, centre_direction, linear_solver, newton
        As :func:`solve_load_path`.
    path : LoadPath, optional
        Use this path (e.g. the planar model's ``LoadPath.harmonic``) instead of
        ``LoadPath.ramped``; the amplitudes and phase are then only recorded.

    Returns
    -------
    CouplingResult

    Examples
    --------
    >>> from microslip import preset
    >>> r = coupling_study(preset("table1"), 150.0, 150.0, 90.0, cycles=4,
    ...                    increments_per_cycle=16, mesh=(8, 2, 1))
    >>> r.converged, 0.5 < r.coupling_ratio < 2.0
    (True, True)
    """
    check_body(params, centre_direction)
    cycles, _, tol = _check_cycles(cycles, 2, cycle_tol)
    if path is None:
        at = check_amplitude(tip_amplitude)
        ac = check_amplitude(centre_amplitude)
        cyc = LoadPath.ramped(at, ac, phase_deg, increments_per_cycle)
    else:
        cyc = as_load_path(path)
        at, ac = cyc.tip_amplitude, cyc.centre_amplitude
        if not (at > 0.0 and ac > 0.0):
            raise ParameterError("a coupling study needs both a tip and a centre force")
    phase = float(cyc.meta.get("phase_deg", phase_deg))
    fem = model_for(params, mesh, stick_slope, element, linear_solver, newton)
    setup = fem.setup_s if not isinstance(mesh, MeshModel) else 0.0
    kw: dict[str, Any] = {"cycles": cycles, "min_cycles": min(2, cycles), "cycle_tol": tol,
                          "centre_direction": centre_direction}
    coupled = _run_path(params, fem, cyc, setup_s=setup, **kw)
    tip_only = _run_path(params, fem, cyc.only("tip"), setup_s=0.0, **kw)
    centre_only = _run_path(params, fem, cyc.only("centre"), setup_s=0.0, **kw)
    return CouplingResult(tip_amplitude=at, centre_amplitude=ac, phase_deg=phase,
                          coupled=coupled, tip_only=tip_only, centre_only=centre_only)


@dataclass(frozen=True, eq=False)
class CouplingSweep:
    """Coupling ratio over force ratios R and phases (one :class:`CouplingResult` each).

    Attributes
    ----------
    ratios : ndarray, shape (n_R,)
        R = A_t / A_c.
    phases_deg : ndarray, shape (n_phi,)
    peak_force : float
        Largest resultant |(F_tip, F_centre)| of every path, N (the normalisation).
    results : tuple of tuple of CouplingResult
        ``results[i][j]`` for ``phases_deg[i]``, ``ratios[j]``.
    wall_s : float
    """

    ratios: FloatArray
    phases_deg: FloatArray
    peak_force: float
    results: tuple[tuple[CouplingResult, ...], ...]
    wall_s: float

    @property
    def coupling_ratio(self) -> FloatArray:
        """Shape (n_phi, n_R), dimensionless."""
        return np.array([[r.coupling_ratio for r in row] for row in self.results])

    def summary(self) -> dict[str, Any]:
        return {"force_ratios": self.ratios.tolist(), "phases_deg": self.phases_deg.tolist(),
                "peak_resultant_force_N": self.peak_force,
                "coupling_ratio": self.coupling_ratio.tolist(),
                "dissipated_energy_Nmm": [[r.dissipated_energy for r in row]
                                          for row in self.results],
                "decoupled_dissipated_energy_Nmm": [[r.decoupled_dissipated_energy for r in row]
                                                    for row in self.results],
                "tip_share": [[r.tip_share for r in row] for row in self.results],
                "success": all(r.success for row in self.results for r in row),
                "wall_s": self.wall_s}


def amplitudes_for_ratio(ratio: float, phase_deg: float, peak_force: float
                         ) -> tuple[float, float]:
    """A_t, A_c with A_t / A_c = R whose path F = (A_t sin theta, A_c sin(theta + phi)) has
    the largest resultant |F| = ``peak_force`` (N).

    The largest |F|^2 over theta of an ellipse with these components is
    (A_t^2 + A_c^2)/2 + sqrt(((A_t^2 - A_c^2)/2)^2 + (A_t A_c cos phi)^2).

    >>> [round(a, 6) for a in amplitudes_for_ratio(1.0, 90.0, 267.0)]
    [267.0, 267.0]
    >>> [round(a, 3) for a in amplitudes_for_ratio(1.0, 0.0, 267.0)]
    [188.798, 188.798]
    """
    r = check_positive("force ratio R", ratio)
    f = check_positive("peak force", peak_force, "N")
    c = math.cos(math.radians(phase_deg))
    # unit centre amplitude: a_t = R, a_c = 1
    a2, b2 = r * r, 1.0
    peak2 = 0.5 * (a2 + b2) + math.sqrt(0.25 * (a2 - b2) ** 2 + (r * c) ** 2)
    s = f / math.sqrt(peak2)
    return r * s, s


def coupling_sweep(params: ClampParams, ratios: Sequence[float] = (0.25, 1 / 3, 0.5, 1.0, 2.0,
                                                                   3.0, 4.0),
                   phases_deg: Sequence[float] = (0.0, 90.0), *, peak_force: float | None = None,
                   mesh: Any = DEFAULT_MESH, cycles: int = 6, increments_per_cycle: int = 256,
                   cycle_tol: float = 1e-3, **kw: Any) -> CouplingSweep:
    """:func:`coupling_study` over force ratios R = A_t / A_c and phases.

    Every path is scaled so that its largest resultant force is ``peak_force`` (default 0.75
    mu F_N: the Table 1 amplitude 267 N), i.e. each loads the interface to the same fraction
    of its macroslip force. The model is assembled and clamped once.
    """
    f = 0.75 * params.macroslip_force if peak_force is None else peak_force
    f = check_positive("peak force", f, "N", upper=params.macroslip_force)
    t0 = time.perf_counter()
    fem = model_for(params, mesh, kw.pop("stick_slope", DEFAULT_STICK_SLOPE),
                 kw.pop("element", "C3D8I"), kw.pop("linear_solver", "banded"),
                 kw.pop("newton", None))
    rows = []
    for phi in phases_deg:
        row = []
        for r in ratios:
            at, ac = amplitudes_for_ratio(r, phi, f)
            row.append(coupling_study(params, at, ac, phi, cycles=cycles,
                                      increments_per_cycle=increments_per_cycle, mesh=fem,
                                      cycle_tol=cycle_tol, **kw))
        rows.append(tuple(row))
    return CouplingSweep(np.asarray(ratios, dtype=float), np.asarray(phases_deg, dtype=float),
                         f, tuple(rows), time.perf_counter() - t0)
