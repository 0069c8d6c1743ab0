"""The whole-joint model: the interface as one rigid body with one joint (issue 23, item 4).

What an engineer can afford on a large structure: instead of a contact law at every contact
node (:mod:`.reduce`), the contact surface moves as a rigid body in its plane and carries one
joint. Three steps.

**Reduction to the interface's rigid-body motion** (a spider, RBE2). In the contact plane's
frame (e1, e2 in the plane, e3 the normal; :attr:`~.meshmodel.MeshModel.rotation`) the
contact node i at (x_i, y_i) from the area-weighted centroid of the contact moves as

    u_1,i = r1 - c y_i / R,    u_2,i = r2 + c x_i / R,

r1, r2 the translations (mm) and c = R theta the in-plane rotation theta about the normal
through the centroid, scaled by the interface's radius of gyration
R = sqrt(sum A_i rho_i^2 / sum A_i) (rho_i = |(x_i, y_i)|) so that c is a length (mm) and its
generalised force M / R (M the moment about the normal, N mm) a force (N). With ``penalty``
normal contact also the normal translation w and the two tilts (t1, t2, scaled the same way):
u_3,i = w + t1 y_i / R - t2 x_i / R, held by the summed linear penalty springs (no lift-off).
With the Craig-Bampton ROM of :func:`~.reduce.build_rom` (boundary: every contact node's
dofs), u_b = G p and the fixed-interface modes kept: ``T = [[G, 0], [0, I]]``,
``M_j = T^T M_r T``, ``K_j = T^T K_r T`` (:func:`reduce_to_interface`). A rigid motion of the
whole body is still exact (the constraint modes carry it); what is lost is the interface's own
deformation, which stiffens the structure (:attr:`WholeJoint.stuck_frequencies`).

**The joint is the FE's own first loading of that interface** (:func:`first_loading`): the
full frictional FE after the clamping step is loaded monotonically by the studied mode's
inertial pattern q M phi, from 0 to near gross sliding, and at each increment the interface's
generalised forces and displacements are recorded: the resultant of the nodes' friction
forces change sum tau_i (N; statically the applied in-plane resultant) against the
area-weighted mean displacement d = sum A_i u_i / sum A_i (mm), both along the interface's
direction of motion e in the stuck mode; and the moment change about the normal over R (N)
against the least-squares rotation c (mm). Each pair's concave majorant
(:func:`~.backbone.concave_majorant`) is the virgin curve of a parallel-Jenkins (Iwan)
operator (:func:`~microslip.dynamics.distributions.from_backbone`), extended with its last
slope to the interface's macroslip: mu F_N for the translation, mu sum N_i rho_i / R for the
rotation. Through this averaging the stuck FE has exactly the stiffness sum lambda A_i in
r1, r2 and c (no coupling: the centroid is area-weighted and lambda uniform), so the joint's
initial slope is the FE's stuck interface stiffness. The translation joint is made
two-directional by :func:`~microslip.dynamics.operators2d.circular`: **isotropic in the
plane**, the same backbone along any in-plane line (assumed; the contact's slip along and
across a long clamp differs, :func:`~microslip.dynamics.operators2d.anisotropic` would take
a second loading). The rotation carries (:data:`TORSION`) its own Iwan joint from the same
loading (``iwan``, default), or the linear stuck spring sum lambda A_i rho_i^2 (``stuck``,
the classical whole-joint's torsion). The default is ``iwan`` because in a bending mode in
the contact plane the clamp carries the bending moment as a torque about the normal: on the
24x6x2 cantilever M / R reaches 900 N near gross sliding against a resultant of 150 N, and
its secant has fallen to 1/37 of the stuck stiffness there, so a linear torsion spring
misses most of the mode's softening and damping (measured, benchmarks/joint_vs_fe.py: with
it the damping ratio is 78-100 % low, with ``iwan`` 16-88 %).

A mode whose interface resultant does not follow its mean displacement (out-of-plane bending
of a bar held on its face: the bending strain stretches the contact with a self-equilibrated
shear, the resultant even opposes the mean motion) gives no joint law; the translation
backbone is then the interface's pull test instead (:data:`PULL`): equal forces on the
response set's nodes along e, the FE's own joint for a resultant load. The rigid interface
cannot represent that mode's damping at all: it comes from the distortion the reduction
removes (:attr:`JointBackbone.source` says which loading made the joint).

Instead of the FE's loading the translation's curve may be the paper's 1-D clamp model
(:data:`BACKBONES` ``tip``, ``centre``; :func:`clamp_backbone`) on the contact patch seen
along e (its length along e, its width across, the body's thickness along the normal) behind
the contact layer sum lambda A_i, with the rotation's stuck spring: no FE run at all, what
the joint of a large structure is built from when the FE cannot be run.

A calibrated variant (:func:`work_backbone`, ``work``) stretches the first loading's
displacements so that the joint does the interface's whole work, the distortion's included:
on the 24x6x2 cantilever's in-plane bending (benchmarks/joint_vs_fe.py) the stuck
frequency comes within 1.1 % of the full FE's (4.7 % kinematic), the frequency within 8 %
and the damping ratio 19-42 % low over the microslip range (kinematic: 15 %, and 16-88 % low),
at the price of a joint softer than the stuck interface seen through the averaging.

EPMC on the whole-joint :class:`~microslip.dynamics.structure.Structure`
(:func:`whole_joint_epmc`) uses the odd harmonics (both joints are odd; the penalty springs are
linear here). Units: N, mm, t (ROM), kg and N/m (Structure, SI), Hz.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import MacroslipError, ParameterError
from ..errors import NonConvergenceError
from ..result import STICK
from .backbone import concave_majorant
from .meshmodel import MeshModel
from .meshrun import VectorLoad, _Run
from .modes import Mode, response_nodes
from .reduce import SI_FACTOR, Rom

__all__ = ["BACKBONES", "PULL", "TORSION", "FirstLoading", "Interface", "JointBackbone",
           "WholeJoint", "build_whole_joint", "clamp_backbone", "first_loading", "interface",
           "joint_backbone", "patch", "reduce_to_interface", "whole_joint_epmc",
           "work_backbone"]

FloatArray = NDArray[np.float64]

#: Factor between the modal forces of the first loading's increments (from first slip on).
STEP = 1.05
#: The first increment is this fraction of the first-slip force (a stuck point: the joint's
#: initial slope).
FIRST = 1e-3
#: The first loading stops when less than this share of the contact area sticks.
GROSS_STICK = 0.1
#: Tolerance of the backbone's concave majorant (share of its last force): the FE's nodes
#: slip one increment apart, and the clamping step's stick forces make the first slips early.
HULL_TOLERANCE = 0.05
#: The load pattern of the pull test (:func:`first_loading` ``pattern="pull"``): the
#: translation backbone when the mode's own gives no joint law.
PULL = "pull"


@dataclass(frozen=True, eq=False)
class Interface:
    """The rigid-body kinematics of the contact (:func:`interface`).

    Attributes
    ----------
    centroid : ndarray, shape (2,)
        Area-weighted centroid of the contact nodes in the contact plane (e1, e2), mm.
    radius : float
        R, the area-weighted radius of gyration about the centroid, mm.
    points : ndarray, shape (n_c, 2)
        Contact nodes from the centroid (e1, e2), mm.
    area : ndarray, shape (n_c,)
        A_i, mm^2.
    rigid : ndarray, shape (n_c * per_node, k)
        G: the ROM's boundary dofs (node-major e1, e2 [, e3]) per unit interface coordinate
        (r1, r2, c [, w, t1, t2]; mm, or mm per mm for the scaled rotations).
    per_node : int
        2 (``fixed`` normal contact) or 3 (``penalty``).
    """

    centroid: FloatArray = field(repr=False)
    radius: float
    points: FloatArray = field(repr=False)
    area: FloatArray = field(repr=False)
    rigid: FloatArray = field(repr=False)
    per_node: int

    @property
    def coordinates(self) -> tuple[str, ...]:
        """Names of the interface coordinates."""
        return ("r1", "r2", "c") + (("w", "t1", "t2") if self.per_node == 3 else ())

    def mean(self, g: FloatArray) -> tuple[FloatArray, float]:
        """The interface's mean motion from its nodes' tangential displacements g (n_c, 2;
        mm): the area-weighted mean (2,) and the least-squares rotation c = R theta (mm)."""
        a, x = self.area, self.points
        d = a @ g / a.sum()
        c = float(a @ (x[:, 0] * g[:, 1] - x[:, 1] * g[:, 0]) / (self.radius * a.sum()))
        return d, c

    def resultant(self, tau: FloatArray) -> tuple[FloatArray, float]:
        """The resultant (2,; N) and the moment over R (N) of nodal forces tau (n_c, 2; N)."""
        x = self.points
        return tau.sum(axis=0), float(np.sum(x[:, 0] * tau[:, 1] - x[:, 1] * tau[:, 0])
                                      / self.radius)


def interface(model: MeshModel) -> Interface:
    """The contact's rigid-body kinematics (:class:`Interface`) on the ROM's boundary layout
    (:func:`~.reduce.build_rom`: node-major e1, e2 and, with ``penalty``, e3)."""
    xy = (model.rotation @ np.asarray(model.mesh.nodes[model.contact_nodes], dtype=float).T
          ).T[:, :2]
    area = np.asarray(model.contact_area, dtype=float)
    centroid = area @ xy / area.sum()
    x = xy - centroid
    radius = math.sqrt(float(area @ np.sum(x**2, axis=1)) / float(area.sum()))
    per_node = 2 if model.normal is None else 3
    n = x.shape[0]
    g = np.zeros((n, per_node, 3 if per_node == 2 else 6))
    g[:, 0, 0] = 1.0
    g[:, 1, 1] = 1.0
    g[:, 0, 2] = -x[:, 1] / radius
    g[:, 1, 2] = x[:, 0] / radius
    if per_node == 3:
        g[:, 2, 3] = 1.0
        g[:, 2, 4] = x[:, 1] / radius
        g[:, 2, 5] = -x[:, 0] / radius
    return Interface(centroid=centroid, radius=radius, points=x, area=area,
                     rigid=g.reshape(n * per_node, -1), per_node=per_node)


def reduce_to_interface(rom: Rom, face: Interface) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(T, M_j, K_j)``: the ROM constrained to the interface's rigid motion.

    T (n_rom, k + n_m) maps (interface coordinates, fixed-interface modal coordinates) to
    the ROM's (boundary dofs, modal coordinates); M_j = T^T M_r T (t) and K_j = T^T K_r T
    (N/mm) of the body without its contact; with ``penalty`` the normal penalty springs
    k_n A_i summed onto (w, t1, t2), G_n^T diag(k_n A) G_n, are in K_j (linear: no lift-off).
    """
    if rom.per_node != face.per_node:
        raise ParameterError("the ROM and the interface disagree on the normal contact "
                             f"({rom.per_node} and {face.per_node} dofs per contact node)")
    nb, k = face.rigid.shape
    nm = rom.modes
    t = np.zeros((rom.dofs, k + nm))
    t[:nb, :k] = face.rigid
    t[nb:, k:] = np.eye(nm)
    m = t.T @ rom.mass @ t
    kk = t.T @ rom.stiffness @ t
    if rom.per_node == 3:
        gn = face.rigid.reshape(-1, 3, k)[:, 2, :]
        kk[:k, :k] += gn.T @ (rom.normal_stiffness[:, None] * gn)
    return t, 0.5 * (m + m.T), 0.5 * (kk + kk.T)


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


@dataclass(frozen=True, eq=False)
class JointBackbone:
    """The whole joint's virgin curves (:func:`joint_backbone`).

    Attributes
    ----------
    direction : ndarray, shape (2,)
        e, the interface's in-plane direction of motion in the stuck mode (e1, e2; unit).
    displacement, force : ndarray, shape (n,)
        Translation: mean displacement along e (mm) and resultant along e (N), from (0, 0),
        increasing (the concave majorant's nodes).
    rotation, moment : ndarray, shape (m,)
        Rotation c = R theta (mm) and M / R (N), from (0, 0) (the concave majorant's nodes);
        empty when the mode does not turn the interface with its moment.
    macroslip_force, macroslip_moment : float
        mu F_N (N) and mu sum N_i rho_i / R (N): where each joint slides as a whole.
    stuck_stiffness : float
        sum lambda A_i, N/mm: the FE's stuck interface stiffness in r1, r2 and c.
    source : str
        Where the translation's curve comes from: the FE's ``mode`` or ``pull`` loading,
        ``work`` (the mode's, stretched to work-equivalent displacements), or a clamp model
        of :data:`~microslip.conventions.CLAMP_MODELS` (``tip``, ``centre``).
    loading : FirstLoading or None
        The mode's first loading on the FE (the rotation's curve); None for a clamp model.
    """

    direction: FloatArray = field(repr=False)
    displacement: FloatArray = field(repr=False)
    force: FloatArray = field(repr=False)
    rotation: FloatArray = field(repr=False)
    moment: FloatArray = field(repr=False)
    macroslip_force: float
    macroslip_moment: float
    stuck_stiffness: float
    source: str
    loading: FirstLoading | None = field(repr=False)

    def translation(self) -> Any:
        """The two-directional translation joint: :func:`circular` of the Iwan operator of
        the translation's curve (isotropic in the plane)."""
        from ...dynamics.distributions import from_backbone
        from ...dynamics.operators2d import circular

        return circular(from_backbone("whole-joint", self.displacement, self.force,
                                      macroslip_force=self.macroslip_force))

    def torsion(self) -> Any:
        """The rotation's Iwan operator (force M / R in N against c in mm), or None when
        the mode does not turn the interface (no curve: the rotation keeps its stuck
        stiffness)."""
        from ...dynamics.distributions import from_backbone

        if self.rotation.size == 0:
            return None

        return from_backbone("whole-joint torsion", self.rotation, self.moment,
                             macroslip_force=self.macroslip_moment)

    def summary(self) -> dict[str, Any]:
        """JSON figures with units."""
        return {"source": self.source, "direction": [float(v) for v in self.direction],
                "force_N": self.force.tolist(), "displacement_mm": self.displacement.tolist(),
                "torsion_force_N": self.moment.tolist(),
                "torsion_displacement_mm": self.rotation.tolist(),
                "macroslip_force_N": self.macroslip_force,
                "macroslip_torsion_force_N": self.macroslip_moment,
                "stuck_stiffness_N_per_mm": self.stuck_stiffness,
                "first_loading": None if self.loading is None else self.loading.message}


#: A first loading's generalised force below this share of mu F_N at its top does not load
#: that coordinate (rounding): no curve.
NEGLIGIBLE = 1e-6


def shaken_down(d: FloatArray, f: FloatArray) -> FloatArray:
    """The first loading's displacements without the clamping step's one-off slip.

    Rows 0, 1, 2 of :func:`first_loading` are the clamped state, a stuck point (:data:`FIRST`
    of the first-slip force) and the first-slip force. Nodes the clamping step left at their
    friction limit slip once on the way to the first-slip force (on the 12x3x1 cantilever
    the secant there is 9 % below the stuck slope); under cyclic loading they shake down
    (:mod:`.qsma`), so a Masing joint built on that slip would dissipate at any amplitude.
    The displacements from row 2 on are shifted back by it, d_i - (d_2 - f_2 / k_0), k_0 =
    f_1 / d_1 the stuck slope: the joint sticks up to the first-slip force, as the FE does
    in its settled cycles."""
    d = np.array(d, dtype=float)
    if d.size < 3 or not (d[1] > 0 and f[1] > 0):
        return d
    offset = d[2] - f[2] * d[1] / f[1]
    if offset > 0:
        d[2:] -= offset
    return d


def _curve(d: FloatArray, f: FloatArray, scale: float) -> tuple[FloatArray, FloatArray] | None:
    """The concave majorant's nodes of (d, f) from (0, 0) (:func:`shaken_down`), or None if
    (d, f) is no joint law (not both increasing from the origin, or the force at most
    :data:`NEGLIGIBLE` of ``scale`` N)."""
    if d.size < 3 or not (np.all(np.diff(d) > 0) and np.all(np.diff(f) > 0)):
        return None
    d = shaken_down(d, f)
    if not f[-1] > NEGLIGIBLE * scale:
        return None
    try:
        keep = concave_majorant(d, f, HULL_TOLERANCE)
    except ParameterError:
        return None
    return d[keep], f[keep]


def _direction(mode: Mode, model: MeshModel, face: Interface) -> FloatArray:
    g = np.asarray(mode.vector, dtype=float)[model.contact_dofs]
    d, _ = face.mean(g)
    size = float(np.linalg.norm(d))
    if not size > 0:
        return np.array([1.0, 0.0])
    return d / size


def joint_backbone(model: MeshModel, mode: Mode, face: Interface | None = None
                   ) -> JointBackbone:
    """The whole joint's virgin curves from the FE's first loading by the mode's inertial
    pattern (see the module's notes); the translation's from the pull test if the mode's
    resultant does not follow its mean displacement."""
    face = interface(model) if face is None else face
    e = _direction(mode, model, face)
    own = first_loading(model, mode, face)
    sign = np.sign(own.rotation[-1] or 1.0)
    rot = _curve(own.rotation * sign, own.moment * sign, model.force_scale)
    if rot is None:  # the mode does not turn the interface: the rotation stays stuck
        rot = (np.zeros(0), np.zeros(0))
    trans = _curve(own.displacement @ e, own.force @ e, model.force_scale)
    source = "mode"
    if trans is None:
        pull = first_loading(model, mode, face, pattern=PULL, direction=e)
        trans = _curve(pull.displacement @ e, pull.force @ e, model.force_scale)
        source = PULL
        if trans is None:
            raise ParameterError("the interface's pull test gives no joint law (its "
                                 "resultant does not follow its mean displacement)")
    limit = np.asarray(model.friction_limit, dtype=float)
    rho = np.linalg.norm(face.points, axis=1)
    return JointBackbone(direction=e, displacement=trans[0], force=trans[1],
                         rotation=rot[0], moment=rot[1],
                         macroslip_force=float(max(limit.sum(), trans[1][-1])),
                         macroslip_moment=float(max(limit @ rho / face.radius,
                                                    rot[1][-1] if rot[1].size else 0.0)),
                         stuck_stiffness=float(model.contact_stiffness.sum()),
                         source=source, loading=own)


def patch(model: MeshModel, face: Interface, direction: FloatArray) -> Any:
    """The contact patch as the paper's clamped zone (:class:`~microslip.params.ClampParams`):
    its length along the in-plane ``direction`` and its width across (the extents of the
    contact nodes, mm), the body's thickness along the contact normal (the extent of its
    nodes, mm), the model's modulus, Poisson's ratio, mu and F_N."""
    from ...params import ClampParams

    e = np.asarray(direction, dtype=float)
    across = np.array([-e[1], e[0]])
    normal = np.asarray(model.mesh.nodes, dtype=float)[model.order] @ model.rotation[2]
    return ClampParams(length=float(np.ptp(face.points @ e)),
                       width=float(np.ptp(face.points @ across)),
                       thickness=float(np.ptp(normal)), modulus=model.modulus,
                       poisson_ratio=model.poisson_ratio, friction=model.friction,
                       normal_force=model.clamp_force)


def clamp_backbone(model: MeshModel, mode: Mode, name: str, face: Interface | None = None
                   ) -> JointBackbone:
    """The whole joint's translation from the paper's 1-D clamp model ``name`` (``tip`` or
    ``centre``) on the contact patch (:func:`patch`, along the mode's direction of motion)
    behind the contact layer's stiffness sum lambda A_i
    (:func:`~microslip.dynamics.distributions.clamp_joint`: the bar on a rigid Coulomb
    foundation has no finite stiffness at zero load); so its initial slope is the FE's
    stuck interface stiffness, less the bar's compliance at the model's first force step
    (3.5 % on the cantilever). No FE loading: the rotation keeps its stuck stiffness (the
    1-D models have no torsion)."""
    from ...conventions import CLAMP_MODELS
    from ...dynamics.distributions import clamp_joint

    if name not in CLAMP_MODELS:
        raise ParameterError(f"unknown clamp model {name!r}; choose one of "
                             f"{', '.join(CLAMP_MODELS)}")
    face = interface(model) if face is None else face
    e = _direction(mode, model, face)
    k = float(model.contact_stiffness.sum())
    op = clamp_joint(name, patch(model, face, e), k)
    # the operator's virgin-curve nodes: F(a) at the elements' slip displacements
    d = np.concatenate([[0.0], np.sort(op.slip)])
    f = np.asarray(op.backbone_force(d), dtype=float)
    return JointBackbone(direction=e, displacement=d, force=f, rotation=np.zeros(0),
                         moment=np.zeros(0), macroslip_force=float(f[-1]),
                         macroslip_moment=0.0, stuck_stiffness=k, source=name, loading=None)


def work_backbone(model: MeshModel, mode: Mode, face: Interface | None = None
                  ) -> JointBackbone:
    """:func:`joint_backbone` with work-equivalent displacements: along the mode's first
    loading each increment of the mean displacement and of the rotation is stretched by
    kappa = dW / dW_rigid, the friction forces' work on the contact nodes over the work
    through the interface's rigid motion (:attr:`FirstLoading.rigid_work`), so that the
    joint's forces do the interface's whole work (stored and, by Masing's rule, dissipated),
    the distortion's included. The joint is then softer than the stuck interface seen
    through the averaging (by the rigid share of the stuck contact's energy, 1/8 on the
    cantilever's in-plane bending), which in part makes up for the stiffening of the rigid
    interface. A calibration, not a kinematic reduction; when the mode's own loading gives
    no translation curve (the pull test) there is nothing to stretch and the curves are
    :func:`joint_backbone`'s.
    """
    face = interface(model) if face is None else face
    bb = joint_backbone(model, mode, face)
    loading = bb.loading
    if bb.source != "mode" or loading is None or bb.rotation.size == 0:
        return bb
    dw, dr = np.diff(loading.work), np.diff(loading.rigid_work)
    if not np.all(dr > 0):
        return bb
    kappa = dw / dr
    e = bb.direction

    def stretched(x: FloatArray) -> FloatArray:
        return np.concatenate([[0.0], np.cumsum(kappa * np.diff(x))])

    trans = _curve(stretched(loading.displacement @ e), loading.force @ e, model.force_scale)
    sign = np.sign(loading.rotation[-1] or 1.0)
    rot = _curve(stretched(loading.rotation * sign), loading.moment * sign,
                 model.force_scale)
    if trans is None or rot is None:
        return bb
    return replace(bb, displacement=trans[0], force=trans[1], rotation=rot[0],
                   moment=rot[1], source="work")


def _fe_backbone(model: MeshModel, mode: Mode, face: Interface) -> JointBackbone:
    return joint_backbone(model, mode, face)


def _tip(model: MeshModel, mode: Mode, face: Interface) -> JointBackbone:
    return clamp_backbone(model, mode, "tip", face)


def _centre(model: MeshModel, mode: Mode, face: Interface) -> JointBackbone:
    return clamp_backbone(model, mode, "centre", face)


#: Where the whole joint's backbone comes from: ``fe`` the FE's own first loading by the
#: mode (:func:`joint_backbone`), ``work`` the same with work-equivalent displacements
#: (:func:`work_backbone`), ``tip`` and ``centre`` the paper's 1-D clamp models on
#: the contact patch (:func:`clamp_backbone`).
BACKBONES: dict[str, Callable[[MeshModel, Mode, Interface], JointBackbone]] = {
    "fe": _fe_backbone, "work": work_backbone, "tip": _tip, "centre": _centre}


def _torsion_iwan(backbone: JointBackbone, face: Interface) -> Any:
    return backbone.torsion()


def _torsion_stuck(backbone: JointBackbone, face: Interface) -> Any:
    return None


#: How the interface's rotation c = R theta is held: name -> (backbone, interface) -> the
#: rotation's 1-D operator, or None for the linear stuck spring sum lambda A_i rho_i^2
#: (lambda sum A_i on c) added to K_j.
TORSION: dict[str, Callable[[JointBackbone, Interface], Any]] = {
    "iwan": _torsion_iwan,
    "stuck": _torsion_stuck,
}


@dataclass(frozen=True, eq=False)
class WholeJoint:
    """The whole-joint model (:func:`build_whole_joint`).

    Attributes
    ----------
    structure : Structure
        SI matrices over (interface coordinates, fixed-interface modes); the translation
        joint on (r1, r2) and, with ``iwan`` torsion, the rotation's joint on c.
    transform : ndarray, shape (n_rom, n)
        T of :func:`reduce_to_interface`.
    face : Interface
    backbone : JointBackbone
    torsion : str
        A key of :data:`TORSION`.
    """

    structure: Any = field(repr=False)
    transform: FloatArray = field(repr=False)
    face: Interface = field(repr=False)
    backbone: JointBackbone = field(repr=False)
    torsion: str

    def stuck_frequencies(self, count: int | None = None) -> FloatArray:
        """Linear natural frequencies with the joint stuck, Hz, ascending."""
        f = np.asarray(self.structure.linear_frequencies(stuck=True))
        return f if count is None else f[:count]

    def mode_index(self, frequency_Hz: float) -> int:
        """0-based index of the stuck mode nearest (in ratio) ``frequency_Hz``: the full FE's
        mode as the whole-joint model has it."""
        f = self.stuck_frequencies()
        return int(np.argmin(np.abs(np.log(np.maximum(f, 1e-30) / frequency_Hz))))


def build_whole_joint(rom: Rom, model: MeshModel, mode: Mode, output: FloatArray, *,
                      torsion: str = "iwan", backbone: JointBackbone | str = "fe"
                      ) -> WholeJoint:
    """The whole-joint :class:`~microslip.dynamics.structure.Structure` of ``mode``: the
    ROM reduced to the interface's rigid motion (:func:`reduce_to_interface`), the joint of
    ``backbone`` (a name of :data:`BACKBONES`, or a :class:`JointBackbone`) on it, the
    output ``output`` (n_rom,: the response set's mean displacement along the mode per ROM
    coordinate, as for :func:`~.reduce.rom_structure`) carried through T."""
    from ...dynamics.structure import JointLink, Structure

    if torsion not in TORSION:
        raise ParameterError(f"unknown torsion {torsion!r}; choose one of "
                             f"{', '.join(TORSION)}")
    if isinstance(backbone, str) and backbone not in BACKBONES:
        raise ParameterError(f"unknown backbone {backbone!r}; choose one of "
                             f"{', '.join(BACKBONES)}")
    face = interface(model)
    t, m, k = reduce_to_interface(rom, face)
    bb = (BACKBONES[backbone](model, mode, face) if isinstance(backbone, str)
          else backbone)
    n = m.shape[0]
    w = np.zeros((n, 2))
    w[0, 0] = w[1, 1] = 1.0
    links = [JointLink(bb.translation(), w)]
    rot = TORSION[torsion](bb, face)
    if rot is None:
        k = k.copy()
        k[2, 2] += bb.stuck_stiffness  # lambda sum A_i rho_i^2 / R^2 on c = R theta
    else:
        links.append(JointLink(rot, np.eye(n)[2]))
    out = np.asarray(output, dtype=float) @ t
    s = Structure(mass=m * SI_FACTOR, damping=np.zeros((n, n)), stiffness=k * SI_FACTOR,
                  joints=tuple(links), output=out)
    return WholeJoint(structure=s, transform=t, face=face, backbone=bb, torsion=torsion)


#: Amplitudes of the ladder from the first amplitude to one whose continuation failed.
LADDER = 8


def whole_joint_epmc(joint: WholeJoint, amplitudes: FloatArray, harmonics: int,
                     samples: int, frequency_Hz: float) -> tuple[Any, tuple[str, ...]]:
    """EPMC on the odd harmonics (:func:`~microslip.dynamics.modal_odd.epmc_odd`; both
    joints are odd) of the whole-joint mode nearest ``frequency_Hz`` (the full FE's stuck
    mode), at ``amplitudes`` (mm of the output).

    Returns the :class:`~microslip.dynamics.modal.ModalCurve` and warnings: if the
    continuation over the amplitudes fails, each amplitude is reached on its own by a
    ladder of :data:`LADDER` amplitudes from the first, and one that still fails (near the
    joint's macroslip) is NaN with its reason.
    """
    from ...dynamics.modal import ModalCurve
    from ...dynamics.modal_odd import epmc_odd

    a = np.asarray(amplitudes, dtype=float)
    index = joint.mode_index(frequency_Hz)
    try:
        return epmc_odd(joint.structure, a, harmonics, samples, index), ()
    except ParameterError:
        pass
    freq, zeta = np.full(a.size, np.nan), np.full(a.size, np.nan)
    warnings = []
    for i, ai in enumerate(a):
        ladder = np.geomspace(min(float(a.min()), ai), ai, LADDER if i else 1)
        try:
            c = epmc_odd(joint.structure, ladder, harmonics, samples, index)
        except ParameterError as exc:
            warnings.append(f"amplitude {i + 1} ({ai:.6g} mm): {exc}")
            continue
        freq[i], zeta[i] = c.frequency[-1], c.damping_ratio[-1]
    return ModalCurve(method="epmc", amplitude=a, frequency=freq, damping_ratio=zeta,
                      harmonics=harmonics, samples=samples), tuple(warnings)
