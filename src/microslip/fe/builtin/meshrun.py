"""Tangential loads on the user's own mesh: sinusoidal cycles until the work per cycle settles,
or an explicit history of load factors (issue 22).

Each load j (:class:`~microslip.fe.meshload.MeshLoad`) is a uniform traction over its set's
faces along its direction, of total force F_j(t); its unit load vector p_j (consistent nodal
shares, :meth:`~microslip.fe.builtin.meshmodel.MeshModel.unit_load`) is also the weight of its
work-conjugate displacement delta_j = p_j . (u - u_clamped), the force-weighted mean of the
set's nodal displacements along the direction, so that sum_j F_j d delta_j is the work of the
loads. Every increment solves r(u) = f_clamp + sum_j F_j p_j - K u - C^T tau(u) = 0 by the box's
semi-smooth Newton (:func:`~microslip.fe.builtin.stepper.load_increment`); the paper's box is
stepped by the same loading state (:class:`~microslip.fe.builtin.box.BoxLoading`).

The dissipated energy of a cycle is the work of all loads around it (Eq. 21 summed over the
loads), W = sum_j closed-integral F_j d delta_j, trapezoidal over the increments. Under sine
loads F_j = A_j sin(2 pi t + phi_j) (:class:`SineCycles`) cycles are run until W per cycle
changes by at most a relative tolerance from one cycle to the next: a rotating load ratchets
during the first cycles. :class:`LoadFactors` replays any history F_j = A_j g_j(k) (the paper's
load step of the box, for one). Units: N, mm, N·mm; time in cycles.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...blas import single_threaded_blas
from ...energy import loop_work
from ...errors import MacroslipError, ParameterError
from ...named import result
from ...params import check_positive
from ...results import HysteresisLoop
from ..errors import NonConvergenceError
from ..meshload import MeshLoad
from ..result import (
    OPEN,
    SLIP,
    STICK,
    ContactHistory,
    gross_sliding_message,
    gross_sliding_states,
    idle_loop_reason,
    join_message,
)
from .meshmodel import MeshModel
from .stepper import _Stepper, load_increment, runaway_reason

__all__ = ["LoadFactors", "MeshLoadResult", "MeshRunResult", "SineCycles", "VectorLoad",
           "solve_mesh"]

FloatArray = NDArray[np.float64]
#: W per cycle has settled when its change is within the tolerance times W, or within this
#: times the loads' work scale sum_j max |F_j| max |d_j| (W about 0: nothing slips, W is
#: rounding and its relative change means nothing).
SETTLE_FLOOR = 1e-9
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class VectorLoad:
    """A load given as a pattern of nodal forces on the model's free dofs (model frame):
    F(t) p with F(t) = A sin(2 pi t + phi), e.g. the inertial pattern M phi of a mode
    (:mod:`.qsma`). Its work-conjugate displacement is p . (u - u_clamped).

    Attributes
    ----------
    vector : ndarray, shape (dof,)
        p, nodal forces per unit of F.
    amplitude : float
        A (> 0).
    phase_deg : float
    set : str
        A name for reports.
    direction : tuple of float
        A unit direction for reports (the pattern's own has no single one).
    """

    vector: FloatArray
    amplitude: float
    phase_deg: float = 0.0
    set: str = "vector"
    direction: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        v = np.array(self.vector, dtype=float)
        if v.ndim != 1 or not np.all(np.isfinite(v)) or not np.any(v):
            raise ParameterError("a vector load needs a finite, non-zero force pattern")
        object.__setattr__(self, "vector", v)
        check_positive("amplitude", self.amplitude)

    def force(self, t: FloatArray | float) -> FloatArray:
        """A sin(2 pi t + phi) at times t (cycles)."""
        return self.amplitude * np.sin(2 * np.pi * np.asarray(t, dtype=float)
                                       + np.radians(self.phase_deg))


AnyLoad = MeshLoad | VectorLoad


def _unit(model: MeshModel, load: AnyLoad) -> FloatArray:
    if isinstance(load, VectorLoad):
        if load.vector.size != model.dof:
            raise ParameterError(f"a vector load must have {model.dof} entries (the model's "
                                 f"free dofs), got {load.vector.size}")
        return load.vector
    return model.unit_load(load)


def _whole(name: str, value: Any, lower: int, upper: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not (
            lower <= value <= upper):
        raise ParameterError(f"{name} must be a whole number in [{lower}, {upper}], "
                             f"got {value!r}")
    return int(value)


@dataclass(frozen=True)
class SineCycles:
    """Sine loads F_j = A_j sin(2 pi t + phi_j), repeated until W per cycle settles.

    Attributes
    ----------
    increments : int
        Increments per cycle (a multiple of 4, >= 8).
    tol : float
        Settled when |W_c - W_(c-1)| <= tol |W_c| (or no node slips in cycle c: W = 0).
    min_cycles, max_cycles : int
        Cycles run at least (>= 2) and at most.
    startup : int or None
        Increments of the straight ramp from rest to the loads at t = 0 when they are not all
        zero there (a phase); default a quarter cycle.
    """

    increments: int = 40
    tol: float = 1e-3
    min_cycles: int = 2
    max_cycles: int = 10
    startup: int | None = None

    def __post_init__(self) -> None:
        n = _whole("increments", self.increments, 8, 100_000)
        if n % 4:
            raise ParameterError(f"increments must be a multiple of 4, got {n}")
        check_positive("tol", self.tol, upper=1.0)
        lo = _whole("min_cycles", self.min_cycles, 2, 1000)
        _whole("max_cycles", self.max_cycles, lo, 1000)
        if self.startup is not None:
            _whole("startup", self.startup, 1, 100_000)

    def samples(self, loads: Sequence[AnyLoad], cycles: int) -> tuple[FloatArray, FloatArray,
                                                                         int]:
        """Times (cycles; the ramp before 0), forces (samples, loads; N) and the index of
        t = 0, for ``cycles`` cycles."""
        n = self.increments
        t = np.arange(cycles * n + 1) / n
        f = np.stack([ld.force(t) for ld in loads], axis=1)
        if float(np.max(np.abs(f[0]))) <= 1e-12 * max(ld.amplitude for ld in loads):
            f[0] = 0.0
            return t, f, 0
        m = self.startup if self.startup is not None else n // 4
        ramp = np.arange(m) / m
        t_ramp = (ramp - 1.0) / 4.0
        return (np.concatenate([t_ramp, t]),
                np.concatenate([ramp[:, None] * f[:1], f]), m)


@dataclass(frozen=True, eq=False)
class LoadFactors:
    """An explicit history: F_j at sample k is A_j factors[k, j] (the phase is not used).

    Sample 0 is applied from the clamped state, each next sample is one increment. The
    dissipated energy is the work of the loads over samples ``cycle_start`` to the end.

    Attributes
    ----------
    factors : ndarray, shape (n, n_loads)
    cycle_start : int
        First sample of the closed cycle.
    time : ndarray, shape (n,), optional
        Time of each sample (default k, in increments).
    """

    factors: FloatArray
    cycle_start: int = 0
    time: FloatArray | None = None

    def __post_init__(self) -> None:
        f = np.array(self.factors, dtype=float)
        if f.ndim == 1:
            f = f[:, None]
        if f.ndim != 2 or f.shape[0] < 2 or not np.all(np.isfinite(f)):
            raise ParameterError("load factors must be a finite (samples, loads) array with at "
                                 f"least 2 samples, got shape {np.shape(self.factors)}")
        _whole("cycle_start", self.cycle_start, 0, f.shape[0] - 2)
        object.__setattr__(self, "factors", f)
        t = np.arange(f.shape[0], dtype=float) if self.time is None else np.array(
            self.time, dtype=float)
        if t.shape != (f.shape[0],):
            raise ParameterError(f"time must have {f.shape[0]} samples, got {t.shape}")
        object.__setattr__(self, "time", t)


@result
class MeshLoadResult:
    """One load's response.

    Attributes
    ----------
    load : MeshLoad or VectorLoad
    force : ndarray, shape (n,)
        F_j at every state, N.
    displacement : ndarray, shape (n,)
        Its work-conjugate displacement from the clamped state, mm.
    loop : HysteresisLoop
        (force, displacement) over the settled cycle.
    work : float
        closed-integral F_j d delta_j over the settled cycle, N·mm.
    peak_displacement : float
        Half the peak-to-peak displacement over the settled cycle, mm.
    """

    load: MeshLoad | VectorLoad
    force: FloatArray
    displacement: FloatArray
    loop: HysteresisLoop
    work: float
    peak_displacement: float

    def summary(self) -> dict[str, Any]:
        return {"set": self.load.set, "direction": list(self.load.direction),
                "amplitude_N": self.load.amplitude, "phase_deg": self.load.phase_deg,
                "work_Nmm": self.work, "peak_displacement_mm": self.peak_displacement}


@result
class MeshRunResult:
    """The frictional response of a clamped mesh to its loads.

    Attributes
    ----------
    dissipated_energy : float
        W, the work of all loads over the settled cycle, N·mm (0 under stick or shakedown).
    loads : tuple of MeshLoadResult
    time : ndarray, shape (n,)
        Time of every state, cycles (the start-up ramp before 0).
    cycle_start : int
        First state of the settled cycle (the cycle is ``cycle_start`` .. the last state).
    contact : ContactHistory
        Status (open/stick/slip) and slip (n, n_c, 2; mm, along the contact plane's axes
        ``tangent_axes``) of every contact node at every state.
    normal_force : ndarray, shape (n, n_c)
        N_i at every state, N (constant under ``fixed`` normal contact).
    pressure : ndarray, shape (n, n_c)
        N_i / A_i, MPa.
    tangent_axes : ndarray, shape (2, 3)
        The contact plane's axes e1, e2 (global components) of ``contact.slip``.
    work_per_cycle : ndarray, shape (cycles,)
        W of every cycle run, N·mm.
    settled : bool
        W per cycle settled to the tolerance (an explicit history: True).
    reason : str or None
        Why W = 0 (stick throughout, shakedown), or None.
    gross_sliding : bool
        Some state has no stuck contact node (full slip).
    success : bool
        Settled and no gross sliding.
    message : str
    iterations : ndarray of int, shape (n,)
        Newton iterations of each increment.
    dof : int
    factorisations : int
    wall_s, setup_s : float
        Wall time of the loading and of the model's set-up, s.
    displacement : ndarray, shape (n, n_nodes, 3) or None
        Nodal displacements at every state (global frame, total: the clamping step's
        included), mm, with ``record=True``.
    """

    dissipated_energy: float
    loads: tuple[MeshLoadResult, ...]
    time: FloatArray
    cycle_start: int
    contact: ContactHistory
    normal_force: FloatArray
    pressure: FloatArray
    tangent_axes: FloatArray
    work_per_cycle: FloatArray
    settled: bool
    reason: str | None
    gross_sliding: bool
    success: bool
    message: str
    iterations: IntArray
    dof: int
    factorisations: int
    wall_s: float
    setup_s: float
    displacement: FloatArray | None = None

    @property
    def converged(self) -> bool:
        """Always True: every increment converged (a failed one raises
        :class:`~microslip.fe.errors.NonConvergenceError` instead of returning a partial
        result)."""
        return True

    @property
    def warnings(self) -> tuple[str, ...]:
        """What makes the figures doubtful: W per cycle not settled, gross sliding."""
        out = []
        if not self.settled:
            out.append(f"W per cycle did not settle in {self.cycles} cycles: "
                       f"{self.work_per_cycle.tolist()} N·mm")
        if self.gross_sliding:
            out.append(gross_sliding_message(self.contact) or "gross sliding")
        return tuple(out)

    @property
    def cycles(self) -> int:
        """Cycles run."""
        return int(self.work_per_cycle.size)

    @property
    def pressed(self) -> dict[str, Any]:
        """The contact patch at the first state (the clamped one when the loads start at 0):
        its pressing nodes (N_i > 0), their area (mm^2), the pressure's centre (mm, global)
        and the radius of the Hertz pressure p0 sqrt(1 - r^2/a^2) of the same second moment
        about that centre, a = sqrt(5/2 sum N_i r_i^2 / sum N_i) (mm; a patch's size, Hertz's
        contact radius where the contact is Hertz's: issue 33)."""
        n = np.asarray(self.normal_force[0], dtype=float)
        on = n > 0.0
        if not np.any(on):
            return {"nodes": 0, "area_mm2": 0.0, "centre_mm": None, "hertz_radius_mm": 0.0}
        x = self.contact.coords[on]
        w = n[on] / n[on].sum()
        centre = w @ x
        d = (x - centre) @ np.asarray(self.tangent_axes, dtype=float).T
        r2 = float(w @ np.sum(d * d, axis=1))
        area = float(np.sum(n[on] / self.pressure[0][on]))
        return {"nodes": int(on.sum()), "area_mm2": area, "centre_mm": centre.tolist(),
                "hertz_radius_mm": math.sqrt(2.5 * r2)}

    @property
    def peak_displacement(self) -> float:
        """The first load's half peak-to-peak work-conjugate displacement, mm."""
        return self.loads[0].peak_displacement

    def summary(self) -> dict[str, Any]:
        """The JSON figures of ``microslip fe --mesh``."""
        return {"dissipated_energy_Nmm": self.dissipated_energy,
                "peak_displacement_mm": self.peak_displacement,
                "loads": [ld.summary() for ld in self.loads],
                "cycles": self.cycles, "work_per_cycle_Nmm": self.work_per_cycle.tolist(),
                "settled": self.settled, "gross_sliding": self.gross_sliding,
                "dof": self.dof, "wall_s": self.wall_s, "warnings": list(self.warnings),
                "message": self.message, "pressed": self.pressed}


class _Run:
    """The loading state of a model: displacements, slips, forces, the Newton stepper; on the
    condensed body (``model.reduced``) when there is one."""

    def __init__(self, model: MeshModel, loads: Sequence[AnyLoad], record: bool) -> None:
        self.model, self.record = model, record
        full = [_unit(model, ld) for ld in loads]
        red = model.reduced
        m = len(full)
        #: d_j = a_j . u + sum_k B_jk F_k - base_j (B = 0 without condensation)
        self.coupling = np.zeros((m, m))
        if red is None:
            self.vectors, self.weights = full, full
            k, backend, cdofs, normal = (model.stiffness, model.backend, model.contact_dofs,
                                         model.normal)
            clamp, u0 = model.clamp_load, model.u0
        else:
            self.vectors, self.weights, self.interior = [], [], []
            for j, p in enumerate(full):
                reduced, a, b = red.load(p)
                self.vectors.append(reduced)
                self.weights.append(a)
                self.interior.append(p[red.interior])
                self.coupling[j] = [float(b @ q[red.interior]) for q in full]
            k, backend, cdofs, normal = red.stiffness, red.backend, red.contact_dofs, red.normal
            clamp, u0 = red.clamp_load, red.u0
        self.clamp = clamp
        #: contact nodes the stepper sees (None: all); the others are open (:mod:`.curved`)
        self.active = None if red is None else red.active
        kc, limit, slip0 = model.contact_stiffness, model.friction_limit, model.slip0
        if self.active is not None:
            kc, limit, slip0 = kc[self.active], limit[self.active], slip0[self.active]
        self.stepper = _Stepper(k, backend, cdofs, kc, limit, model.newton, model.force_scale,
                                normal, None if normal is None else model.friction)
        self.normal_springs = normal
        self.u, self.slip = u0.copy(), slip0.copy()
        self.base = [float(p @ self.u) for p in self.weights]
        self.last = tuple(0.0 for _ in full)
        self.d: list[FloatArray] = []
        self.status: list[NDArray[np.int8]] = []
        self.slips: list[FloatArray] = []
        self.normal: list[FloatArray] = []
        self.its: list[int] = []
        self.works: list[float] = []
        self.fields: list[FloatArray] = []
        self.wall = 0.0

    def full_field(self, u: FloatArray, forces: tuple[float, ...]) -> FloatArray:
        """Free-dof displacements of a state, mm."""
        red = self.model.reduced
        if red is None:
            return u.copy()
        f_i = red.clamp_interior.copy()
        for f, p in zip(forces, self.interior, strict=True):
            f_i = f_i + f * p
        return red.expand(u, f_i)

    def advance(self, forces: FloatArray, first: int, *, stop: bool = False) -> str | None:
        """Apply the samples ``forces`` (k, loads), one increment each; raise
        :class:`~microslip.fe.errors.NonConvergenceError` on a failed increment, or with
        ``stop`` return why it failed (the states before it kept; None: all solved)."""
        model = self.model
        t0 = time.perf_counter()
        with single_threaded_blas():
            for i, row in enumerate(forces):
                new = tuple(float(x) for x in row)
                step = load_increment(self.stepper, self.clamp, self.vectors, self.last,
                                      new, self.u, self.slip, model.newton.max_cuts)
                why = (runaway_reason(self.normal_springs, step.u, model.size)
                       if step.converged
                       else "has no static equilibrium: the tangent stiffness is singular "
                            "(the body tips over on its unilateral contact, or the friction "
                            "cannot hold the loads' moment)"
                       if self.stepper.singular
                       else f"did not converge in {model.newton.max_iterations} Newton "
                            f"iterations, even cut into {model.newton.max_cuts} sub-increments "
                            "(are the loads, or their moment, more than the friction holds?)")
                if why:
                    loads = ", ".join(f"{f:g}" for f in new)
                    message = (f"{model.mesh.source}: increment {first + i} (loads {loads} N) "
                               f"{why}")
                    if stop:
                        self.wall += time.perf_counter() - t0
                        return message
                    raise NonConvergenceError(message)
                self.u, self.slip, self.last = step.u, step.slip, new
                self.its.append(step.iterations)
                self.works.append(step.work)
                self.d.append(np.array([float(p @ self.u) - b
                                        for p, b in zip(self.weights, self.base, strict=True)])
                              + self.coupling @ np.array(new))
                status = np.where(step.response.slipping, SLIP, STICK).astype(np.int8)
                slip = self.slip
                if self.active is not None:  # the open nodes: no force, slip not followed
                    status = np.full(model.contact_nodes.size, OPEN, dtype=np.int8)
                    status[self.active] = np.where(step.response.slipping, SLIP, STICK)
                    slip = model.slip0.copy()
                    slip[self.active] = self.slip
                if self.normal_springs is not None:
                    n = self.normal_springs.forces(self.u)
                    status[n <= 0.0] = OPEN
                    self.normal.append(n)
                else:  # fixed: the nodes the clamping step released stay open
                    status[~model.closed] = OPEN
                self.status.append(status)
                self.slips.append(slip.copy())
                if self.record:
                    self.fields.append(self.full_field(self.u, new))
        self.wall += time.perf_counter() - t0
        return None

    def displacements(self) -> FloatArray:
        return np.array(self.d).reshape(len(self.d), len(self.vectors))

    def idle(self, first: int) -> bool:
        """No node slipped in the increments after state ``first``."""
        return not any(np.any(s == SLIP) for s in self.status[first + 1:])


def _plane_resultant(model: MeshModel, load: AnyLoad) -> FloatArray:
    """The in-plane (e1, e2) resultant of a load's unit pattern."""
    if isinstance(load, MeshLoad):
        return np.asarray(model.rotation[:2] @ np.asarray(load.direction, dtype=float))
    full = np.zeros(model.index.size)
    full[model.free] = load.vector
    return np.asarray(full.reshape(-1, 3)[:, :2].sum(axis=0))


def _check(model: MeshModel, loads: Sequence[AnyLoad], peak: FloatArray) -> None:
    """Refuse loads whose tangential resultant reaches mu F_N at some sample (macroslip)."""
    if model.assembly.supports or not model.assembly.rigid_base_only:
        return  # supports and pairs carry loads past mu F_N: no such bound
    dirs = np.array([_plane_resultant(model, ld) for ld in loads])  # (loads, 2)
    resultant = float(np.max(np.linalg.norm(peak @ dirs, axis=1)))
    if resultant >= model.force_scale:
        raise MacroslipError(
            f"the loads' resultant in the contact plane reaches {resultant:g} N >= mu F_N = "
            f"{model.force_scale:g} N (macroslip: no static equilibrium)")


def solve_mesh(model: MeshModel, loads: Sequence[MeshLoad | VectorLoad],
               history: SineCycles | LoadFactors | None = None, *,
               record: bool = False) -> MeshRunResult:
    """Load a clamped mesh and return its dissipated energy and loops.

    Parameters
    ----------
    model : MeshModel
        :func:`~microslip.fe.builtin.meshmodel.build_mesh_model`.
    loads : sequence of MeshLoad or VectorLoad
        At least one; each set must hold element faces (a :class:`VectorLoad` is a raw
        pattern of nodal forces).
    history : SineCycles or LoadFactors, optional
        Default :class:`SineCycles` ().
    record : bool
        Keep the nodal displacement field of every state (``displacement``, for VTU).

    Returns
    -------
    MeshRunResult

    Raises
    ------
    NonConvergenceError
        An increment did not converge (or a penalty contact tipped over).
    MacroslipError
        The loads' tangential resultant reaches mu F_N.
    """
    if not loads or not all(isinstance(ld, (MeshLoad, VectorLoad)) for ld in loads):
        raise ParameterError("give at least one MeshLoad")
    loads = tuple(loads)
    history = SineCycles() if history is None else history
    amps = np.array([ld.amplitude for ld in loads])
    run = _Run(model, loads, record)
    works: list[float] = []
    settled = True
    if isinstance(history, LoadFactors):
        if history.factors.shape[1] != len(loads):
            raise ParameterError(f"load factors have {history.factors.shape[1]} columns for "
                                 f"{len(loads)} loads")
        forces = amps[None, :] * history.factors
        _check(model, loads, forces)
        times = np.asarray(history.time)
        k0 = history.cycle_start
        run.advance(forces, 0)
        works.append(_work(forces, run.displacements(), k0, forces.shape[0]))
    elif isinstance(history, SineCycles):
        times, forces, k0 = history.samples(loads, history.max_cycles)
        _check(model, loads, forces)
        n = history.increments
        run.advance(forces[:k0 + n + 1], 0)
        while True:
            c = len(works)
            a, b = k0 + c * n, k0 + (c + 1) * n + 1
            works.append(0.0 if run.idle(a) else _work(forces, run.displacements(), a, b))
            if len(works) >= history.min_cycles and (
                    abs(works[-1] - works[-2]) <= max(
                        history.tol * abs(works[-1]),
                        SETTLE_FLOOR * _work_scale(forces, run, a, b))):
                break
            if len(works) >= history.max_cycles:
                settled = False
                break
            run.advance(forces[b:b + n], b)
        k0 = k0 + (len(works) - 1) * n
        end = k0 + n + 1
        times, forces = times[:end], forces[:end]
    else:
        raise ParameterError(f"history must be SineCycles or LoadFactors, got "
                             f"{type(history).__name__}")
    return _result(model, loads, run, times, forces, k0, np.array(works), settled, history)


def _work_scale(forces: FloatArray, run: _Run, a: int, b: int) -> float:
    """The loads' work scale over the samples a:b, sum_j max |F_j| max |d_j| (N·mm)."""
    d = run.displacements()[a:b]
    return float(np.sum(np.max(np.abs(forces[a:b]), axis=0) * np.max(np.abs(d), axis=0)))


def _work(forces: FloatArray, d: FloatArray, a: int, b: int) -> float:
    return float(sum(loop_work(forces[a:b, j], d[a:b, j]) for j in range(forces.shape[1])))


def _result(model: MeshModel, loads: tuple[AnyLoad, ...], run: _Run, times: FloatArray,
            forces: FloatArray, k0: int, works: FloatArray, settled: bool,
            history: SineCycles | LoadFactors) -> MeshRunResult:
    d = run.displacements()
    states = forces.shape[0]
    status = np.array(run.status[:states])
    slip = np.array(run.slips[:states])
    normal = (np.array(run.normal[:states]) if model.normal is not None
              else np.broadcast_to(model.normal_force, (states, model.contact_nodes.size)))
    e2 = model.rotation[1]
    across = model.mesh.nodes[model.contact_nodes] @ e2
    width = float(np.ptp(across)) or 1.0
    contact = ContactHistory(model.contact_nodes, model.mesh.nodes[model.contact_nodes].copy(),
                             np.asarray(times, dtype=float), status.astype(np.int8),
                             model.contact_area / width, slip)
    cyc = slice(k0, states)
    per_load = []
    for j, ld in enumerate(loads):
        loop = HysteresisLoop(forces[cyc, j].copy(), d[cyc, j].copy(), "builtin",
                              {"set": ld.set, "direction": list(ld.direction),
                               "displacement": "force-weighted mean of the set along the "
                                               "load, from the clamped state"})
        per_load.append(MeshLoadResult(ld, forces[:, j].copy(), d[:states, j].copy(), loop,
                                       loop_work(loop.force, loop.displacement),
                                       loop.peak_displacement))
    reason = idle_loop_reason(contact, states - k0)
    w = 0.0 if reason else float(sum(r.work for r in per_load))
    sliding = gross_sliding_states(contact).size > 0
    if isinstance(history, SineCycles):
        change = (abs(works[-1] - works[-2]) / abs(works[-1]) if works[-1] else 0.0)
        cyc_msg = (f"W per cycle settled to {change:.2e} (tolerance {history.tol:.1e}) after "
                   f"{works.size} cycles" if settled and change <= history.tol else
                   f"W per cycle settled at {works[-1]:.3g} N·mm, a change of "
                   f"{abs(works[-1] - works[-2]):.2e} N·mm within {SETTLE_FLOOR:g} times the "
                   f"loads' work scale (W about 0), after {works.size} cycles" if settled else
                   f"W per cycle did not settle to {history.tol:.1e} in {works.size} cycles "
                   f"(last change {change:.2e})")
    else:
        cyc_msg = f"explicit history of {states} samples"
    message = join_message(cyc_msg, reason, gross_sliding_message(contact))
    fields = (model.global_vectors(np.array(run.fields[:states])) if run.record else None)
    return MeshRunResult(
        dissipated_energy=w, loads=tuple(per_load), time=np.asarray(times, dtype=float),
        cycle_start=k0, contact=contact, normal_force=np.array(normal),
        pressure=np.array(normal) / model.contact_area[None, :],
        tangent_axes=model.rotation[:2].copy(), work_per_cycle=works, settled=settled,
        reason=reason, gross_sliding=sliding, success=settled and not sliding,
        message=message, iterations=np.array(run.its[:states], dtype=np.int64),
        dof=model.dof, factorisations=run.stepper.factorisations, wall_s=run.wall,
        setup_s=model.setup_s, displacement=fields)

