"""The whole joint's virgin curves (:mod:`.wholejoint`, step 3): from the FE's first loading
(:mod:`.firstloading`; ``fe``), the same with work-equivalent displacements (``work``), or
the paper's 1-D clamp models on the contact patch (``tip``, ``centre``): :data:`BACKBONES`.
The notes of :mod:`.wholejoint` say why and what each costs. Units: N, mm.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..fe.builtin.backbone import concave_majorant
from ..fe.builtin.meshmodel import MeshModel
from .firstloading import PULL, FirstLoading, first_loading
from .interface import Interface, interface
from .modes import Mode

__all__ = ["BACKBONES", "HULL_TOLERANCE", "NEGLIGIBLE", "JointBackbone", "clamp_backbone",
           "joint_backbone", "patch", "shaken_down", "work_backbone"]

FloatArray = NDArray[np.float64]

#: Tolerance of the backbone's concave majorant (share of its last force): the FE's nodes
#: slip one increment apart, and the clamping step's stick forces make the first slips early.
HULL_TOLERANCE = 0.05


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
        from ..dynamics.distributions import from_backbone
        from ..dynamics.operators2d import circular

        return circular(from_backbone("whole-joint", self.displacement, self.force,
                                      macroslip_force=self.macroslip_force))

    def torsion(self) -> Any:
        """The rotation's Iwan operator (force M / R in N against c in mm), or None when
        the mode does not turn the interface (no curve: the rotation keeps its stuck
        stiffness)."""
        from ..dynamics.distributions import from_backbone

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

    Rows 0, 1, 2 of :func:`~.firstloading.first_loading` are the clamped state, a stuck
    point (:data:`~.firstloading.FIRST` of the first-slip force) and the first-slip force.
    Nodes the clamping step left at their friction limit slip once on the way to the
    first-slip force (on the 12x3x1 cantilever the secant there is 9 % below the stuck
    slope); under cyclic loading they shake down (:mod:`.qsma`), so a Masing joint built on
    that slip would dissipate at any amplitude. The displacements from row 2 on are shifted
    back by it, d_i - (d_2 - f_2 / k_0), k_0 = f_1 / d_1 the stuck slope: the joint sticks
    up to the first-slip force, as the FE does in its settled cycles."""
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
    pattern (see the notes of :mod:`.wholejoint`); the translation's from the pull test if
    the mode's resultant does not follow its mean displacement."""
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
    from ..params import ClampParams

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
    from ..conventions import CLAMP_MODELS
    from ..dynamics.distributions import clamp_joint

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
    through the interface's rigid motion (:attr:`~.firstloading.FirstLoading.rigid_work`),
    so that the joint's forces do the interface's whole work (stored and, by Masing's rule,
    dissipated), the distortion's included. The joint is then softer than the stuck
    interface seen through the averaging (by the rigid share of the stuck contact's energy,
    1/8 on the cantilever's in-plane bending), which in part makes up for the stiffening of
    the rigid interface. A calibration, not a kinematic reduction; when the mode's own
    loading gives no translation curve (the pull test) there is nothing to stretch and the
    curves are :func:`joint_backbone`'s.
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
