"""Quasi-static modal analysis of the full frictional FE (Lacayo and Allen 2019; issue 23).

After the clamping step, the stuck mode's inertial load pattern M phi (phi mass-normalised,
:func:`~microslip.meshdynamics.modes.linear_modes`) scaled by the modal force q is applied
cyclically, f(t) = q sin(2 pi t) M phi, on the full frictional FE (:func:`~microslip.fe.
builtin.meshrun.solve_mesh` with a :class:`~microslip.fe.builtin.meshrun.VectorLoad`) until
the work per cycle settles. The load's work-conjugate displacement is the modal coordinate
eta = phi^T M (u - u_clamped); from the settled loop (q sin 2 pi t, eta(t)):

* the modal amplitude a = |eta_1|, the first harmonic of eta (:func:`first_harmonic`);
* ``frequency_Hz``: omega^2 = Re(q_1 conj(eta_1)) / |eta_1|^2, the first-harmonic modal force
  in phase with the first-harmonic displacement over its amplitude (the definition of the
  extended periodic motion concept, EPMC) (:func:`loop_stiffness`);
* ``secant_frequency_Hz``: omega_s^2 = (force half peak-to-peak) / (eta half peak-to-peak),
  Lacayo and Allen's;
* the damping ratio zeta = W / (2 pi a^2 omega^2), W the work of the load over the settled
  cycle (unit modal mass: a linear viscous mode dissipates W = 2 pi zeta omega^2 a^2);
* ``amplitude_mm``: the first-harmonic amplitude of the response set's mean displacement
  along the mode's direction (:attr:`~microslip.meshdynamics.modes.Mode.direction`).

Units: phi in 1/sqrt(t), eta and a in sqrt(t)·mm, q in sqrt(t)·mm/s^2 (q M phi in N), omega^2
in 1/s^2, W in N·mm, frequencies in Hz. Each amplitude is an independent run: local processes
(:class:`concurrent.futures.ProcessPoolExecutor`) or a Dask cluster
(:func:`microslip.cluster.map_on_cluster`).
"""

from __future__ import annotations

import math
import time
import uuid
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import MacroslipError, ParameterError
from ..fe.assembly import Assembly
from ..fe.builtin.meshmodel import MESH_LINEAR_SOLVERS, MeshModel, build_mesh_model
from ..fe.builtin.meshrun import SineCycles, VectorLoad, _plane_resultant, _Run, solve_mesh
from ..fe.errors import NonConvergenceError
from ..fe.hexmesh import HexMesh
from ..fe.result import OPEN, SLIP, STICK
from .modes import Mode, modal_stiffness, response_nodes, shift_inverse

__all__ = [
    "GROSS_STICK",
    "QSMACurve",
    "QSMAPoint",
    "cyclic_ok",
    "first_closing_force",
    "first_harmonic",
    "first_slip_force",
    "loop_stiffness",
    "qsma",
    "qsma_amplitudes",
    "qsma_point",
]

FloatArray = NDArray[np.float64]
#: Near gross sliding: the stuck share of the contact area on the first loading drops below
#: this.
GROSS_STICK = 0.1
#: W below this times q a (the loop's energy scale) is rounding: W = 0.
W_FLOOR = 1e-9
#: The grid starts this factor above the first-slip force.
FIRST_SLIP_MARGIN = 1.05
#: The grid's first level as a fraction of the first closing force of a node the clamping
#: left open, where that comes before first slip (the level stays linear).
FIRST_CLOSING_MARGIN = 0.95
Progress = Callable[[int, int, float], None]


def first_harmonic(t: FloatArray, x: FloatArray) -> complex:
    """X_1 of x(t) over one period, t in cycles sampled uniformly with the last sample one
    period after the first (dropped): x ~ Re(X_1 exp(2 pi i t)) + ...

    >>> t = np.linspace(0.0, 1.0, 41)
    >>> round(abs(first_harmonic(t, 3 * np.sin(2 * np.pi * t))), 12)
    3.0
    """
    tt, xx = np.asarray(t, dtype=float)[:-1], np.asarray(x, dtype=float)[:-1]
    return complex(2.0 / tt.size * np.sum(xx * np.exp(-2j * np.pi * tt)))


def loop_stiffness(t: FloatArray, force: FloatArray, disp: FloatArray) -> tuple[float, float]:
    """The first-harmonic (in-phase) and the secant stiffness of a closed loop over one
    period: Re(F_1 conj(D_1)) / |D_1|^2 and ptp(F) / ptp(D).

    A Jenkins element (stiffness k, slip displacement x_s) driven at 4 x_s: 0.196 k and 0.25 k
    (k/pi (beta - sin(2 beta)/2), cos beta = 1 - 2 x_s / A).
    """
    f1, d1 = first_harmonic(t, force), first_harmonic(t, disp)
    k1 = (f1 * d1.conjugate()).real / abs(d1) ** 2
    ks = float(np.ptp(force) / np.ptp(disp))
    return float(k1), ks


@dataclass(frozen=True)
class QSMAPoint:
    """One amplitude of the quasi-static modal analysis (see the module docstring).

    Attributes
    ----------
    force : float
        q, sqrt(t)·mm/s^2.
    modal_amplitude : float
        a = |eta_1|, sqrt(t)·mm.
    amplitude_mm : float
        First harmonic of the response set's mean displacement along the mode, mm.
    frequency_Hz, secant_frequency_Hz : float
    damping_ratio : float
    dissipated_energy_Nmm : float
    slip_fraction : float
        Share of the contact area in touch with the base (closed at some state of the settled
        cycle) that slips while closed at some state of it; a node that stays lifted off is
        not counted.
    settled : bool
    cycles : int
    wall_s : float
    message : str
    open_fraction : float
        Share of the contact area that is open (lifted off the base, N_i = 0) at some state
        of the settled cycle, reported apart from the slip.
    node_slipped : ndarray of bool, shape (n_c,)
        Per contact node (:attr:`~.meshmodel.MeshModel.contact_nodes` order): it slipped at
        some state of the settled cycle (the slip pattern; all False for a failed run). Not
        in :meth:`QSMACurve.summary`.
    node_open : ndarray of bool, shape (n_c,)
        Per contact node: it was open (lifted off, N_i = 0) at some state of the settled
        cycle. Not in :meth:`QSMACurve.summary`.
    """

    force: float
    modal_amplitude: float
    amplitude_mm: float
    frequency_Hz: float
    secant_frequency_Hz: float
    damping_ratio: float
    dissipated_energy_Nmm: float
    slip_fraction: float
    settled: bool
    cycles: int
    wall_s: float
    message: str
    open_fraction: float = 0.0
    node_slipped: NDArray[np.bool_] = field(repr=False, compare=False,
                                            default_factory=lambda: np.zeros(0, dtype=bool))
    node_open: NDArray[np.bool_] = field(repr=False, compare=False,
                                         default_factory=lambda: np.zeros(0, dtype=bool))


@dataclass(frozen=True, eq=False)
class QSMACurve:
    """Frequency and damping against amplitude of one mode (:func:`qsma`).

    Attributes
    ----------
    mode : int
        1-based.
    label : str
    linear_frequency_Hz : float
        The stuck mode's, Hz.
    force, modal_amplitude, amplitude_mm, frequency_Hz, secant_frequency_Hz, damping_ratio,
    dissipated_energy_Nmm, slip_fraction, open_fraction : ndarray
        Per amplitude, increasing force (:class:`QSMAPoint`).
    settled : ndarray of bool
    points : tuple of QSMAPoint
    wall_s : float
        Wall time of all runs, s.
    """

    mode: int
    label: str
    linear_frequency_Hz: float
    points: tuple[QSMAPoint, ...] = field(repr=False)
    wall_s: float = 0.0

    def _col(self, name: str) -> FloatArray:
        return np.array([getattr(p, name) for p in self.points], dtype=float)

    @property
    def force(self) -> FloatArray:
        return self._col("force")

    @property
    def modal_amplitude(self) -> FloatArray:
        return self._col("modal_amplitude")

    @property
    def amplitude_mm(self) -> FloatArray:
        return self._col("amplitude_mm")

    @property
    def frequency_Hz(self) -> FloatArray:
        return self._col("frequency_Hz")

    @property
    def secant_frequency_Hz(self) -> FloatArray:
        return self._col("secant_frequency_Hz")

    @property
    def damping_ratio(self) -> FloatArray:
        return self._col("damping_ratio")

    @property
    def dissipated_energy_Nmm(self) -> FloatArray:
        return self._col("dissipated_energy_Nmm")

    @property
    def slip_fraction(self) -> FloatArray:
        return self._col("slip_fraction")

    @property
    def open_fraction(self) -> FloatArray:
        return self._col("open_fraction")

    @property
    def settled(self) -> NDArray[np.bool_]:
        return np.array([p.settled for p in self.points], dtype=bool)

    @property
    def warnings(self) -> tuple[str, ...]:
        """One line per amplitude that did not settle or failed (its figures NaN)."""
        return tuple(f"amplitude {i + 1}: {p.message}" for i, p in enumerate(self.points)
                     if not p.settled)

    def summary(self) -> dict[str, Any]:
        """Plain figures for JSON."""
        out: dict[str, Any] = {"mode": self.mode, "label": self.label,
                               "linear_frequency_Hz": self.linear_frequency_Hz}
        for name in ("force", "modal_amplitude", "amplitude_mm", "frequency_Hz",
                     "secant_frequency_Hz", "damping_ratio", "dissipated_energy_Nmm",
                     "slip_fraction", "open_fraction"):
            out[name] = self._col(name).tolist()
        out["warnings"] = list(self.warnings)
        return out


def _load(mode: Mode, force: float) -> VectorLoad:
    d = np.asarray(mode.direction, dtype=float)
    return VectorLoad(mode.inertia, force, set=f"mode {mode.number}",
                      direction=(float(d[0]), float(d[1]), float(d[2])))


def qsma_point(model: MeshModel, mode: Mode, force: float,
               history: SineCycles | None = None) -> QSMAPoint:
    """One amplitude: the cyclic modal load q sin(2 pi t) M phi until W per cycle settles."""
    q = float(force)
    if not (math.isfinite(q) and q > 0):
        raise ParameterError(f"the modal force must be > 0, got {force!r}")
    history = SineCycles() if history is None else history
    r = solve_mesh(model, [_load(mode, q)], history, record=True)
    loop = r.loads[0].loop
    k0 = r.cycle_start
    t = r.time[k0:]
    k1, ks = loop_stiffness(t, loop.force, loop.displacement)
    a = abs(first_harmonic(t, loop.displacement))
    assert r.displacement is not None
    nodes = response_nodes(model, mode.response_set)
    along = r.displacement[k0:, nodes].mean(axis=1) @ np.asarray(mode.direction, dtype=float)
    amp = abs(first_harmonic(t, along))
    w = r.dissipated_energy
    settled = bool(r.settled)
    if w <= W_FLOOR * q * a:  # shakedown: slip of the first cycles only, W at rounding
        w, settled = 0.0, True
    # a node slipped in the cycle if its slip moved by more than 1e-6 of its slip
    # displacement mu N_i / k_i (a node left at its limit by the clamping step is flagged
    # ``slip`` without moving)
    scale = model.friction_limit / model.contact_stiffness
    slipped = (np.max(np.ptp(r.contact.slip[k0:], axis=0), axis=1) > 1e-6 * scale
               if r.contact.slip is not None else np.zeros(scale.size, dtype=bool))
    # an open node's slider follows it at no force: it slips only if it slid while closed
    status = r.contact.status[k0:]
    opened = np.any(status == OPEN, axis=0)
    touching = np.any(status != OPEN, axis=0)
    slipped &= np.any(status == SLIP, axis=0)
    if w == 0.0:
        slipped[:] = False
    area = model.contact_area
    in_touch = float(area[touching].sum())
    zeta = w / (2 * math.pi * a**2 * k1) if k1 > 0 and a > 0 else math.nan
    return QSMAPoint(force=q, modal_amplitude=a, amplitude_mm=float(amp),
                     frequency_Hz=math.sqrt(max(k1, 0.0)) / (2 * math.pi),
                     secant_frequency_Hz=math.sqrt(max(ks, 0.0)) / (2 * math.pi),
                     damping_ratio=float(zeta), dissipated_energy_Nmm=float(w),
                     slip_fraction=float(area[slipped].sum() / in_touch) if in_touch else 0.0,
                     settled=settled, cycles=r.cycles, wall_s=r.wall_s,
                     message=r.message, open_fraction=float(area[opened].sum() / area.sum()),
                     node_slipped=np.asarray(slipped, dtype=bool),
                     node_open=np.asarray(opened, dtype=bool))


def _failed(force: float, why: str, contact_nodes: int) -> QSMAPoint:
    nan = math.nan
    return QSMAPoint(force=force, modal_amplitude=nan, amplitude_mm=nan, frequency_Hz=nan,
                     secant_frequency_Hz=nan, damping_ratio=nan, dissipated_energy_Nmm=nan,
                     slip_fraction=nan, settled=False, cycles=0, wall_s=0.0,
                     message=f"failed: {why}", open_fraction=nan,
                     node_slipped=np.zeros(contact_nodes, dtype=bool),
                     node_open=np.zeros(contact_nodes, dtype=bool))


def _point(model: MeshModel, mode: Mode, force: float,
           history: SineCycles | None) -> QSMAPoint:
    """:func:`qsma_point`, a run that fails (gross sliding) as a point of NaNs with the
    reason, so that one amplitude does not lose the others."""
    try:
        return qsma_point(model, mode, force, history)
    except (NonConvergenceError, MacroslipError, np.linalg.LinAlgError) as exc:
        return _failed(force, str(exc), int(model.contact_nodes.size))


def _held_stiffness(model: MeshModel) -> sp.csr_matrix:
    """The stuck stiffness, with a free-free assembly's determinate soft support kept: the
    inertial load M phi is self-equilibrated, so the contact's response to it is the same
    and the factor is not singular."""
    k = modal_stiffness(model, "stuck")
    return k if model.ground is None else sp.csr_matrix(k + model.ground)


def first_slip_force(model: MeshModel, mode: Mode) -> float:
    """The modal force q from which some contact node slips in every cycle under the stuck
    (linear) response u = q K^-1 M phi about the clamped state: the smallest
    mu N0_i / (|a_i| + mu |b_i|) (a_i, b_i the tangential and normal force change per unit q;
    b = 0 with ``fixed`` normal contact): the force range 2 q |a_i| of a cycle reaches the
    width 2 mu N_i of the friction limit. The stick forces the clamping step leaves (some
    nodes at their limit) only shake down below it."""
    k = _held_stiffness(model)
    du = shift_inverse(k).matvec(mode.inertia)  # not spsolve: its COLAMD LU is 1.5 GB at 50k DOF
    c = model.contact_dofs
    kc = model.contact_stiffness[:, None]
    a = kc * du[c]
    n0 = model.normal_force
    if model.normal is None:
        b = np.zeros_like(n0)
    else:
        b = model.normal.tangent(model.u0) * -du[model.normal.dofs]
    mu = model.friction
    rate = np.linalg.norm(a, axis=1) + mu * np.abs(b)
    ok = (rate > 1e-12 * float(rate.max(initial=0.0))) & (n0 > 0)
    if not np.any(ok) or not float(rate.max(initial=0.0)) > 0:
        raise ParameterError(f"mode {mode.number} does not load the contact: no node "
                             "ever slips under its inertial load")
    return float(np.min(mu * n0[ok] / rate[ok]))


def first_closing_force(model: MeshModel, mode: Mode) -> float:
    """The modal force q at which a contact node that the clamping step left open first
    touches the base under the stuck (linear) response u = q K^-1 M phi: the smallest
    g_i / |du_n,i| (g_i = -N0_i / (k_n A_i) its gap, du_n its normal motion per unit q);
    inf with ``fixed`` normal contact or no open node. Below it and the first-slip force the
    response is linear (every open node stays open, every closed one sticks)."""
    normal = model.normal
    open_ = ~model.closed
    if normal is None or not np.any(open_):
        return math.inf
    du = shift_inverse(_held_stiffness(model)).matvec(mode.inertia)
    gap = -model.preload[open_] / normal.stiffness[open_]
    motion = np.abs(du[normal.dofs[open_]])
    moves = motion > 0.0
    return float(np.min(gap[moves] / motion[moves])) if np.any(moves) else math.inf


def qsma_amplitudes(model: MeshModel, mode: Mode, count: int, *, step: float = 1.25,
                    max_steps: int = 80, history: SineCycles | None = None) -> FloatArray:
    """Modal forces q from first slip to near gross sliding, log-uniform, ``count`` of them.

    The first is :data:`FIRST_SLIP_MARGIN` times :func:`first_slip_force`, or
    :data:`FIRST_CLOSING_MARGIN` times :func:`first_closing_force` where an open node closes
    before any node slips (a part that lifts off: the first level is then linear, its
    frequency the stuck one). The last is found
    in two passes: a first loading (q raised from the first-slip force by factors ``step`` on
    the full FE) gives the largest level that converges with at least :data:`GROSS_STICK`
    of the contact area still stuck, below 0.99 of the level whose in-plane resultant reaches
    mu F_N (macroslip); then, because a cycle reverses the load (a force range of 2 q, more
    slip than the first loading), that level is lowered until its cyclic run
    (:func:`qsma_point`, two cycles of ``history``) converges and keeps :data:`GROSS_STICK` of the
    area stuck over the settled cycle (:attr:`QSMAPoint.slip_fraction` at most
    1 - GROSS_STICK; :func:`_cyclic_top`). The grid's top is thus a level whose cyclic run
    converged, not one that only a first loading carries (past it the cycle fails: NaN)."""
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 1000:
        raise ParameterError(f"count must be a whole number in [1, 1000], got {count!r}")
    q1 = first_slip_force(model, mode)
    lo = min(FIRST_SLIP_MARGIN * q1, FIRST_CLOSING_MARGIN * first_closing_force(model, mode))
    top = max(_first_loading_top(model, mode, q1, step, max_steps), lo)
    if count == 1:
        return np.array([lo])
    top = _cyclic_top(model, mode, lo, top, step, history)
    return np.geomspace(lo, top, count)


def _first_loading_top(model: MeshModel, mode: Mode, q1: float, step: float,
                       max_steps: int) -> float:
    run = _Run(model, [_load(mode, 1.0)], record=False)
    area = model.contact_area
    top = q1
    for i in range(max_steps):
        q = q1 * step ** (i + 1)
        try:
            run.advance(np.array([[q]]), i)
        except (NonConvergenceError, MacroslipError, np.linalg.LinAlgError):
            break
        status = run.status[-1]  # the stuck share of the area in touch (open nodes apart)
        stuck = float(area[status == STICK].sum() / area[status != OPEN].sum())
        if stuck < GROSS_STICK:
            break
        top = q
    resultant = float(np.linalg.norm(_plane_resultant(model, _load(mode, 1.0))))
    if resultant > 0:  # solve_mesh refuses an in-plane resultant of mu F_N or more
        top = min(top, 0.99 * model.force_scale / resultant)
    return top


def cyclic_ok(point: QSMAPoint) -> bool:
    """The cyclic run converged (finite figures) and kept :data:`GROSS_STICK` of the contact
    area stuck over its settled cycle."""
    return bool(math.isfinite(point.damping_ratio)
                and point.slip_fraction <= 1.0 - GROSS_STICK)


def _cyclic_top(model: MeshModel, mode: Mode, lo: float, top: float, step: float,
                history: SineCycles | None) -> float:
    """The largest level in [lo, top] whose cyclic run (two cycles of ``history``) is
    :func:`cyclic_ok`, to within a factor ``step``: top itself, or a bisection in log q
    between lo (the grid's first, taken as good) and the first failing level."""
    h = SineCycles() if history is None else history
    # two cycles: a level the cycle cannot carry fails on the first reversal
    check = SineCycles(increments=h.increments, tol=h.tol, min_cycles=2, max_cycles=2,
                       startup=h.startup)
    if top <= lo or cyclic_ok(_point(model, mode, top, check)):
        return top
    good, bad = lo, top
    while bad / good > step:
        mid = math.sqrt(good * bad)
        if cyclic_ok(_point(model, mode, mid, check)):
            good = mid
        else:
            bad = mid
    return good


# ---------------------------------------------------------------- independent runs
@dataclass(frozen=True)
class _Recipe:
    """What a worker needs to rebuild the model (HexMesh holds mapping proxies, which do not
    pickle): the mesh's arrays and the build's arguments."""

    nodes: FloatArray
    elements: NDArray[np.int64]
    node_sets: dict[str, NDArray[np.int64]]
    surfaces: dict[str, NDArray[np.int64]]
    source: str
    kwargs: dict[str, Any]
    token: str
    assembly: Assembly
    element_sets: dict[str, NDArray[np.int64]]

    @classmethod
    def of(cls, model: MeshModel) -> _Recipe:
        m = model.mesh
        linear = model.backend.name if model.backend.name in MESH_LINEAR_SOLVERS else "auto"
        kwargs: dict[str, Any] = dict(
            element=model.element, linear_solver=linear, newton=model.newton,
            condensed=model.reduced is not None)
        return cls(np.asarray(m.nodes), np.asarray(m.elements),
                   {k: np.asarray(v) for k, v in m.node_sets.items()},
                   {k: np.asarray(v) for k, v in m.surfaces.items()}, m.source, kwargs,
                   uuid.uuid4().hex, model.assembly,
                   {k: np.asarray(v) for k, v in m.element_sets.items()})

    def build(self) -> MeshModel:
        mesh = HexMesh(self.nodes, self.elements, self.node_sets, self.surfaces,
                       source=self.source, element_sets=self.element_sets)
        return build_mesh_model(mesh, self.assembly, **self.kwargs)


#: The model a worker process built last, by its recipe's token (one model per worker).
_MODELS: dict[str, MeshModel] = {}


def _remote_point(recipe: _Recipe, mode: Mode, force: float,
                  history: SineCycles | None) -> QSMAPoint:
    key = recipe.token
    if key not in _MODELS:
        _MODELS.clear()
        _MODELS[key] = recipe.build()
    return _point(_MODELS[key], mode, force, history)


def _local_point(recipe: _Recipe, mode: Mode, force: float,
                 history: SineCycles | None) -> QSMAPoint:
    return _remote_point(recipe, mode, force, history)


def qsma(model: MeshModel, mode: Mode, forces: Sequence[float] | None = None, *,
         count: int = 10, history: SineCycles | None = None, workers: int | None = 1,
         scheduler: str | None = None, progress: Progress | None = None) -> QSMACurve:
    """Quasi-static modal analysis of one mode over a grid of modal forces.

    Parameters
    ----------
    model : MeshModel
    mode : Mode
        :meth:`~microslip.meshdynamics.modes.Modes.select` of the stuck modes.
    forces : sequence of float, optional
        Modal forces q; default :func:`qsma_amplitudes` (``count`` of them).
    history : SineCycles, optional
    workers : int or None
        Local processes (1: in this process, the given model; None: one per CPU).
    scheduler : str, optional
        A Dask scheduler address: the runs go there instead (as ``microslip sweep`` does).
    progress : callable, optional
        ``progress(done, total, eta_s)`` after each amplitude.

    Returns
    -------
    QSMACurve
        An amplitude whose run fails (gross sliding: no convergence) is a point of NaNs with
        its reason in :attr:`QSMACurve.warnings`.
    """
    t0 = time.perf_counter()
    q = (qsma_amplitudes(model, mode, count, history=history) if forces is None
         else np.asarray(forces, dtype=float))
    if q.ndim != 1 or q.size == 0 or not np.all(np.isfinite(q) & (q > 0)):
        raise ParameterError("forces must be one or more modal forces > 0")
    total = int(q.size)
    points: list[QSMAPoint | None] = [None] * total
    done = 0

    def tick() -> None:
        nonlocal done
        done += 1
        if progress is not None:
            spent = time.perf_counter() - t0
            progress(done, total, spent / done * (total - done))

    if scheduler is not None:
        from ..cluster import map_on_cluster

        recipe = _Recipe.of(model)
        payloads = [(recipe, mode, float(f), history) for f in q]

        def on_result(i: int, r: Any) -> None:
            points[i] = r
            tick()

        map_on_cluster(_remote_point, payloads, scheduler, on_result=on_result,
                       key_prefix="microslip-qsma")
    elif workers == 1 or total == 1:
        for i, f in enumerate(q):
            points[i] = _point(model, mode, float(f), history)
            tick()
    else:
        recipe = _Recipe.of(model)
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futures = {pool.submit(_local_point, recipe, mode, float(f), history): i
                       for i, f in enumerate(q)}
            for fut in as_completed(futures):
                points[futures[fut]] = fut.result()
                tick()
    out = tuple(p for p in points if p is not None)
    return QSMACurve(mode=mode.number, label=mode.label,
                     linear_frequency_Hz=mode.frequency_Hz, points=out,
                     wall_s=time.perf_counter() - t0)
