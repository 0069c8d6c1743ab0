"""A bolt's shank: an elastic beam between the mean motions of its head face and its nut
face (issue 32), so that the bolt's axial, bending, shear and torsional stiffness carry load
after the preload (shank-to-hole contact is not modelled).

Each face's mean motion is its least-squares rigid motion: with the face's nodal weights w_i
(the consistent shares of a uniform traction, summing to 1), positions r_i from their
weighted centroid and nodal displacements u_i,

    t = sum_i w_i u_i,    theta = J^-1 sum_i w_i r_i x u_i,
    J = sum_i w_i (|r_i|^2 I - r_i r_i^T)

(the translation and rotation minimising sum_i w_i |u_i - t - theta x r_i|^2). The shank is a
two-node Timoshenko beam (12 x 12: axial EA/L, torsion GJ/L, bending EI with the shear
parameter Phi = 12 EI / (kappa G A L^2), kappa = 6 (1 + nu) / (7 + 6 nu) of a circle) from the
head's centroid to the nut's, of a circular section of diameter d; its stiffness acts on the
faces' nodes as B^T K_b B, B the two faces' rigid-fit operators (6 x 3n each). A rigid motion
of the two faces together stores no energy in it.

The preload step presses the faces with the bolt's force and the shank carries nothing (as
CalculiX's pre-tension section in its first step); afterwards its length is locked: the
tangential loading adds B^T K_b B to the stiffness and its value at the preloaded state to the
constant load, so the shank's force is the preload plus K_b times the change of the faces'
relative motion. Units: N, mm, MPa.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...errors import ParameterError

__all__ = ["beam_stiffness", "rigid_fit", "shank_stiffness"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def _cross(r: FloatArray) -> FloatArray:
    """[r]x of each row of r (n, 3) -> (n, 3, 3): [r]x u = r x u."""
    z = np.zeros(len(r))
    return np.stack([np.stack([z, -r[:, 2], r[:, 1]], -1),
                     np.stack([r[:, 2], z, -r[:, 0]], -1),
                     np.stack([-r[:, 1], r[:, 0], z], -1)], axis=1)


def rigid_fit(x: FloatArray, w: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The face's centroid (3,) and the operator A (6, 3 n) taking its nodal displacements
    (n nodes x 3, flattened) to its least-squares rigid motion (t, theta).

    >>> x = np.array([[0.0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]]); w = np.full(4, 0.25)
    >>> c, a = rigid_fit(x, w)
    >>> u = np.cross([0.0, 0.0, 0.1], x - c) + [1.0, 0.0, 0.0]  # a rigid motion
    >>> np.round(a @ u.ravel(), 12).tolist()
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.1]
    """
    c = w @ x
    r = x - c
    j = np.einsum("i,i->", w, np.einsum("ij,ij->i", r, r)) * np.eye(3) - np.einsum(
        "i,ij,ik->jk", w, r, r)
    try:
        j_inv = np.linalg.inv(j)
    except np.linalg.LinAlgError:
        raise ParameterError("a bolt face's nodes lie on one line: its rotation is not "
                             "defined") from None
    a = np.zeros((6, 3 * len(x)))
    for k in range(3):
        a[k, k::3] = w
    a[3:] = np.einsum("jk,i,ikl->jil", j_inv, w, _cross(r)).reshape(3, -1)
    return c, a


def beam_stiffness(length: float, diameter: float, modulus: float, poisson_ratio: float,
                   axis: FloatArray) -> FloatArray:
    """12 x 12 stiffness (N/mm, N, N·mm/rad) of a circular Timoshenko beam along ``axis``
    (global components), dofs (t1, theta1, t2, theta2)."""
    e, nu, ell, d = modulus, poisson_ratio, length, diameter
    area, inertia = math.pi * d * d / 4.0, math.pi * d ** 4 / 64.0
    g = e / (2.0 * (1.0 + nu))
    kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)
    phi = 12.0 * e * inertia / (kappa * g * area * ell * ell)
    a = 12.0 * e * inertia / (ell ** 3 * (1.0 + phi))
    b = 6.0 * e * inertia / (ell ** 2 * (1.0 + phi))
    c = (4.0 + phi) * e * inertia / (ell * (1.0 + phi))
    dd = (2.0 - phi) * e * inertia / (ell * (1.0 + phi))
    k = np.zeros((12, 12))
    ea, gj = e * area / ell, g * 2.0 * inertia / ell
    for i, j, v in ((0, 0, ea), (0, 6, -ea), (6, 6, ea), (3, 3, gj), (3, 9, -gj), (9, 9, gj),
                    # bending in the local x-y plane: v, theta_z (1, 5, 7, 11)
                    (1, 1, a), (1, 5, b), (1, 7, -a), (1, 11, b), (5, 5, c), (5, 7, -b),
                    (5, 11, dd), (7, 7, a), (7, 11, -b), (11, 11, c),
                    # bending in the local x-z plane: w, theta_y (2, 4, 8, 10)
                    (2, 2, a), (2, 4, -b), (2, 8, -a), (2, 10, -b), (4, 4, c), (4, 8, b),
                    (4, 10, dd), (8, 8, a), (8, 10, b), (10, 10, c)):
        k[i, j] = k[j, i] = v
    e1 = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    ref = np.eye(3)[int(np.argmin(np.abs(e1)))]
    e2 = ref - (ref @ e1) * e1
    e2 /= np.linalg.norm(e2)
    lam = np.stack([e1, e2, np.cross(e1, e2)])  # rows: local axes
    t = np.kron(np.eye(4), lam)
    return np.asarray(t.T @ k @ t)


def shank_stiffness(nodes: FloatArray, head: tuple[IntArray, FloatArray],
                    nut: tuple[IntArray, FloatArray], diameter: float, modulus: float,
                    poisson_ratio: float, name: str = "bolt") -> sp.csr_matrix:
    """B^T K_b B on every node's dofs (3 len(nodes) square): ``head``, ``nut`` the faces'
    (node rows into ``nodes``, weights summing to 1), ``nodes`` positions (model frame)."""
    ch, ah = rigid_fit(nodes[head[0]], head[1])
    cn, an = rigid_fit(nodes[nut[0]], nut[1])
    length = float(np.linalg.norm(cn - ch))
    if not length > 0.0:
        raise ParameterError(f"{name}: the head and nut faces have the same centroid; a "
                             "shank needs a length")
    kb = beam_stiffness(length, diameter, modulus, poisson_ratio, cn - ch)
    dofs_h = (3 * head[0][:, None] + np.arange(3)).ravel()
    dofs_n = (3 * nut[0][:, None] + np.arange(3)).ravel()
    n = 3 * len(nodes)
    b = sp.lil_matrix((12, n))
    b[:6, dofs_h] = ah
    b[6:, dofs_n] = an
    bc = b.tocsr()
    return sp.csr_matrix(bc.T @ sp.csr_matrix(kb) @ bc)
