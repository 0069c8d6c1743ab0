"""The whole joint's source: the full FE's first loading of its interface (:mod:`.wholejoint`,
step 2).

The full frictional FE after the clamping step is loaded monotonically, by the studied
mode's inertial pattern q M phi or by the interface's pull test (:data:`PULL`), from 0 to
near gross sliding, and at each increment the interface's generalised forces and
displacements are recorded (:class:`~.interface.Interface`'s mean motion and resultant):
the resultant of the nodes' friction forces change sum tau_i (N) against the area-weighted
mean displacement (mm), and the moment change about the normal over R (N) against the
least-squares rotation c (mm). :mod:`.jointbackbone` makes the joint's virgin curves of
them. Units: N, mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import MacroslipError, ParameterError
from ..fe.builtin.meshmodel import MeshModel
from ..fe.builtin.meshrun import VectorLoad, _Run
from ..fe.errors import NonConvergenceError
from ..fe.result import STICK
from .interface import Interface
from .modes import Mode, response_nodes
from .qsma import GROSS_STICK  # near gross sliding: where the QSMA's grid ends too

__all__ = ["FIRST", "GROSS_STICK", "PULL", "STEP", "FirstLoading", "first_loading"]

FloatArray = NDArray[np.float64]

#: Factor between the modal forces of the first loading's increments (from first slip on).
STEP = 1.05
#: The first increment is this fraction of the first-slip force (a stuck point: the joint's
#: initial slope).
FIRST = 1e-3
#: The load pattern of the pull test (:func:`first_loading` ``pattern="pull"``): the
#: translation backbone when the mode's own gives no joint law.
PULL = "pull"


@dataclass(frozen=True, eq=False)
class FirstLoading:
    """The interface's generalised forces and displacements along a monotonic loading of
    the full FE from the clamped state (:func:`first_loading`), changes from that state.

    Attributes
    ----------
    pattern : str
        ``mode`` (q M phi) or ``pull`` (equal forces on the response set along e).
    load : ndarray, shape (n,)
        The load factor at each increment (q, or the pull's total force in N).
    displacement : ndarray, shape (n, 2)
        Area-weighted mean tangential displacement of the contact nodes (e1, e2), mm.
    force : ndarray, shape (n, 2)
        Resultant of the nodes' friction forces (e1, e2), N.
    rotation : ndarray, shape (n,)
        c = R theta, mm.
    moment : ndarray, shape (n,)
        M / R, N.
    stuck_share : ndarray, shape (n,)
        Share of the contact area that sticks.
    work : ndarray, shape (n,)
        The friction forces' work on the contact nodes, integral sum_i (tau_i - tau_i0) .
        d u_i (trapezoidal, N mm): what the interface stores and dissipates.
    message : str
        Why the loading stopped.
    """

    pattern: str
    load: FloatArray = field(repr=False)
    displacement: FloatArray = field(repr=False)
    force: FloatArray = field(repr=False)
    rotation: FloatArray = field(repr=False)
    moment: FloatArray = field(repr=False)
    stuck_share: FloatArray = field(repr=False)
    work: FloatArray = field(repr=False)
    message: str

    @property
    def rigid_work(self) -> FloatArray:
        """The work through the interface's rigid motion, integral F . dd + (M / R) dc
        (trapezoidal, N mm); ``work`` minus it is the work of the interface's distortion,
        which the whole-joint model does not have."""
        def integral(f: FloatArray, d: FloatArray) -> FloatArray:
            step = 0.5 * (f[1:] + f[:-1]) * np.diff(d, axis=0)
            return np.concatenate([[0.0], np.cumsum(step.reshape(step.shape[0], -1).sum(1))])

        return (integral(self.force, self.displacement)
                + integral(self.moment, self.rotation))


def _pull_pattern(model: MeshModel, mode: Mode, e: FloatArray) -> FloatArray:
    """Nodal forces (free dofs, model frame) of 1 N in total along the in-plane direction e
    (model frame e1, e2), shared equally by the response set's nodes."""
    nodes = model.model_nodes(response_nodes(model, mode.response_set))
    p = np.zeros(model.dof)
    for c in range(2):
        pos = model.index[3 * nodes + c]
        p[pos[pos >= 0]] += e[c] / nodes.size
    return p


def first_loading(model: MeshModel, mode: Mode, face: Interface, *, pattern: str = "mode",
                  direction: FloatArray | None = None, step: float = STEP,
                  max_steps: int = 400) -> FirstLoading:
    """Load the full frictional FE monotonically and record the interface's resultant,
    mean displacement, moment and rotation (:class:`FirstLoading`).

    ``pattern`` ``mode``: the mode's inertial pattern q M phi, first at :data:`FIRST` of the
    first-slip force (:func:`~.qsma.first_slip_force`, a stuck point), then from that force
    up by factors ``step`` until less than :data:`GROSS_STICK` of the contact area sticks,
    an increment fails to converge (gross sliding) or the in-plane resultant would reach
    mu F_N. ``pull``: 1 N along ``direction`` (in-plane, model frame) shared by the
    response set's nodes, scaled the same way from its own first-slip force (N).
    """
    from .qsma import first_slip_force

    if pattern == "mode":
        p = np.asarray(mode.inertia, dtype=float)
        q1 = first_slip_force(model, mode)
    elif pattern == PULL:
        if direction is None:
            raise ParameterError("the pull test needs its in-plane direction")
        p = _pull_pattern(model, mode, np.asarray(direction, dtype=float))
        # the first-slip force of the pull's pattern under the stuck response
        q1 = first_slip_force(model, replace(mode, inertia=p))
    else:
        raise ParameterError(f"unknown first-loading pattern {pattern!r}; choose mode or "
                             f"{PULL}")
    load = VectorLoad(p, 1.0, set=f"{pattern} {mode.number}")
    run = _Run(model, [load], record=False)
    cd = run.stepper.cdofs
    k = np.asarray(model.contact_stiffness, dtype=float)
    g0 = run.u[cd].copy()
    tau0 = k[:, None] * (g0 - run.slip)
    d0, c0 = face.mean(g0)
    f0, m0 = face.resultant(tau0)
    full = np.zeros(model.index.size)
    full[model.free] = p
    plane = float(np.linalg.norm(full.reshape(-1, 3)[:, :2].sum(axis=0)))
    cap = 0.99 * model.force_scale / plane if plane > 0 else math.inf
    rows: list[tuple[float, ...]] = [(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)]
    g_old, dtau_old, work = g0, np.zeros_like(tau0), 0.0
    loads = [FIRST * q1] + [q1 * step**i for i in range(max_steps)]
    message = f"{max_steps} increments"
    area = face.area
    for i, q in enumerate(loads):
        if q >= cap:
            message = "the in-plane resultant reaches 0.99 mu F_N"
            break
        try:
            run.advance(np.array([[q]]), i)
        except (NonConvergenceError, MacroslipError, np.linalg.LinAlgError) as exc:
            message = f"gross sliding: {exc}"
            break
        g = run.u[cd]
        d, c = face.mean(g)
        tau = k[:, None] * (g - run.slip)
        f, m = face.resultant(tau)
        work += float(np.sum(0.5 * (tau - tau0 + dtau_old) * (g - g_old)))
        g_old, dtau_old = g.copy(), tau - tau0
        stuck = float(area[run.status[-1] == STICK].sum() / area.sum())
        rows.append((q, *(d - d0), *(f - f0), c - c0, m - m0, stuck, work))
        if stuck < GROSS_STICK:
            message = f"less than {GROSS_STICK:g} of the contact area sticks"
            break
    r = np.array(rows)
    return FirstLoading(pattern=pattern, load=r[:, 0], displacement=r[:, 1:3],
                        force=r[:, 3:5], rotation=r[:, 5], moment=r[:, 6],
                        stuck_share=r[:, 7], work=r[:, 8], message=message)
