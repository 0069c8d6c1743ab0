"""The contact interface as a rigid body in its plane: the whole-joint model's reduction
(:mod:`.wholejoint`, step 1).

A spider (RBE2). In the contact plane's frame (e1, e2 in the plane, e3 the normal;
:attr:`~.meshmodel.MeshModel.rotation`) the contact node i at (x_i, y_i) from the
area-weighted centroid of the contact moves as

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
deformation, which stiffens the structure
(:attr:`~.wholejoint.WholeJoint.stuck_frequencies`). Units: N, mm, t.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..fe.builtin.meshmodel import MeshModel
from .reduce import Rom

__all__ = ["Interface", "interface", "reduce_to_interface"]

FloatArray = NDArray[np.float64]


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
