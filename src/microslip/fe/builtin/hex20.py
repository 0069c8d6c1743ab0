"""Quadratic (20-node serendipity) hexahedra: stiffness, consistent mass, contact weights.

Two elements (:data:`HEX20_ELEMENTS`), as CalculiX's:

``C3D20R``
    20-node brick, 2 x 2 x 2 Gauss points (reduced integration). Its spurious zero-energy
    modes do not communicate between elements in a mesh of more than one element through
    each direction; it is the element CalculiX recommends and what the built-in's hex20 uses.
``C3D20``
    The same with 3 x 3 x 3 Gauss points (full integration).

The consistent mass is integrated with 3 x 3 x 3 points for both (exact for a
parallelepiped). Node order: CalculiX's (corners 1-8 as C3D8, then the mid-edge nodes of
edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8).

The contact of a quadratic face (:data:`CONTACT_WEIGHTS`): a uniform pressure on an 8-node
face has the consistent nodal shares -1/12 (corners) and 1/3 (mid-sides) of the face's area,
so the consistent "area" of a corner node is negative, which a node-to-rigid-base spring
cannot take (a negative stick spring, a friction limit in tension). The built-in follows
CalculiX's node-to-face contact, which replaces them by 1/100 and 24/100 (CalculiX manual,
"Node-to-face penalty contact"); ``hrz`` (Hinton-Rock-Zienkiewicz: the diagonal of the face's
consistent mass matrix scaled to the face's area) is the alternative from the literature,
kept to show how much W depends on the choice (docs/interpretation.md §18).

Units: coordinates mm, modulus MPa, stiffness N/mm, density t/mm^3, mass t.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...errors import ParameterError
from .element import SHAPE_TOL, _strain_operator, elasticity_matrix, physical_derivatives

__all__ = [
    "CONTACT_WEIGHTS",
    "DEFAULT_CONTACT_WEIGHTS",
    "HEX20_ELEMENTS",
    "NODE_XI20",
    "QuadContact",
    "RecoveredNormal",
    "assemble_hex20",
    "contact_areas",
    "element_stiffness20",
    "face_mass",
    "hex20_b_matrices",
    "mass_matrix20",
    "shape20",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Natural coordinates of the 20 nodes, CalculiX order.
NODE_XI20 = np.array(
    [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1],
     [0, -1, -1], [1, 0, -1], [0, 1, -1], [-1, 0, -1],
     [0, -1, 1], [1, 0, 1], [0, 1, 1], [-1, 0, 1],
     [-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=float)

#: The 12 edges as (corner, corner, mid-edge node), positions in a C3D20 row.
EDGES20: tuple[tuple[int, int, int], ...] = (
    (0, 1, 8), (1, 2, 9), (2, 3, 10), (3, 0, 11), (4, 5, 12), (5, 6, 13), (6, 7, 14),
    (7, 4, 15), (0, 4, 16), (1, 5, 17), (2, 6, 18), (3, 7, 19))


def _gauss(n: int) -> tuple[FloatArray, FloatArray]:
    """Tensor Gauss rule of n points per direction: points (n^3, 3), weights (n^3,)."""
    g, w = np.polynomial.legendre.leggauss(n)
    pts = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    wts = np.einsum("i,j,k->ijk", w, w, w).ravel()
    return pts, wts


def shape20(xi: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Shape functions (n_p, 20) and their derivatives dN_a/dxi_i (n_p, 3, 20) at ``xi``.

    >>> n, d = shape20(NODE_XI20)
    >>> bool(np.allclose(n, np.eye(20))), bool(np.allclose(d.sum(axis=2), 0.0))
    (True, True)
    """
    x = np.atleast_2d(np.asarray(xi, dtype=float))
    a = NODE_XI20[None, :, :]  # (1, 20, 3)
    s = 1.0 + x[:, None, :] * a  # (p, 20, 3); 1 on a mid-edge node's zero axis
    corner = np.all(NODE_XI20 != 0, axis=1)
    n = np.empty((x.shape[0], 20))
    d = np.empty((x.shape[0], 3, 20))
    # corners: 1/8 prod(1 + xi_i a_i) (sum xi_i a_i - 2)
    c = s[:, corner]
    lin = (x[:, None, :] * a[:, corner]).sum(axis=2) - 2.0
    prod = c.prod(axis=2)
    n[:, corner] = 0.125 * prod * lin
    for i in range(3):
        others = np.prod(np.delete(c, i, axis=2), axis=2)
        d[:, i, corner] = 0.125 * a[0, corner, i] * (others * lin + prod)
    # mid-edge nodes: 1/4 (1 - xi_k^2) prod_{i != k}(1 + xi_i a_i), k their zero axis
    for m in np.flatnonzero(~corner):
        k = int(np.flatnonzero(NODE_XI20[m] == 0)[0])
        bub = 1.0 - x[:, k] ** 2
        rest = [i for i in range(3) if i != k]
        f = [s[:, m, i] for i in rest]
        n[:, m] = 0.25 * bub * f[0] * f[1]
        d[:, k, m] = -0.5 * x[:, k] * f[0] * f[1]
        d[:, rest[0], m] = 0.25 * bub * NODE_XI20[m, rest[0]] * f[1]
        d[:, rest[1], m] = 0.25 * bub * NODE_XI20[m, rest[1]] * f[0]
    return n, d


def hex20_b_matrices(coords: FloatArray, points: int = 2
                     ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Strain operators of 20-node hexahedra at ``points``^3 Gauss points.

    Returns B (n_e, g, 6, 60), det J times the Gauss weight (n_e, g), and the shape
    functions at the points (g, 20). Raises :class:`~microslip.errors.ParameterError` for a
    non-positive Jacobian.
    """
    pts, wts = _gauss(points)
    n, dn = shape20(pts)
    dndx, detj, _ = physical_derivatives(dn, coords, "C3D20")
    return _strain_operator(dndx), detj * wts[None, :], n


def _stiffness(points: int) -> Callable[[FloatArray, FloatArray], FloatArray]:
    def k(coords: FloatArray, d: FloatArray) -> FloatArray:
        b, dv, _ = hex20_b_matrices(coords, points)
        return np.asarray(np.einsum("egki,kl,eglj,eg->eij", b, d, b, dv, optimize=True))
    return k


#: Quadratic element formulations: name -> (stiffness function, description).
HEX20_ELEMENTS: dict[str, tuple[Callable[[FloatArray, FloatArray], FloatArray], str]] = {
    "C3D20R": (_stiffness(2), "20-node hexahedron, 2x2x2 Gauss (CalculiX C3D20R)"),
    "C3D20": (_stiffness(3), "20-node hexahedron, 3x3x3 Gauss (CalculiX C3D20)"),
}


def element_stiffness20(coords: FloatArray, modulus: float, poisson_ratio: float,
                        kind: str = "C3D20R") -> FloatArray:
    """Stiffness matrices (n_e, 60, 60) of 20-node hexahedra (n_e, 20, 3), N/mm; dof order
    node-major (node 0 x, y, z, node 1 x, ...).

    A unit cube stretched uniformly (nu = 0) carries E on its face x = 1:

    >>> cube = NODE_XI20[None] * 0.5 + 0.5
    >>> k = element_stiffness20(cube, 1000.0, 0.0)[0]
    >>> u = np.zeros(60); u[0::3] = cube[0, :, 0] * 1e-3
    >>> round(float((k @ u)[0::3][cube[0, :, 0] == 1.0].sum()), 9)
    1.0
    """
    if kind not in HEX20_ELEMENTS:
        raise ParameterError(f"unknown element {kind!r}; choose one of "
                             f"{', '.join(HEX20_ELEMENTS)}")
    c = np.asarray(coords, dtype=float)
    if c.ndim != 3 or c.shape[1:] != (20, 3):
        raise ParameterError(f"element coordinates must have shape (n, 20, 3), got {c.shape}")
    return HEX20_ELEMENTS[kind][0](c, elasticity_matrix(modulus, poisson_ratio))


def _classes(x: FloatArray, e: IntArray) -> tuple[IntArray, IntArray]:
    """Translated copies share one element matrix (as :func:`.element.assemble_hex8`)."""
    rel = x[e] - x[e[:, :1]]
    size = float(np.max(np.ptp(x, axis=0))) if x.size else 1.0
    key = np.round(rel.reshape(e.shape[0], -1) / (SHAPE_TOL * max(size, 1e-300)))
    _, first, shape = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return shape.ravel().astype(np.int64), first.astype(np.int64)


def _scatter(blocks: FloatArray, shape: IntArray, e: IntArray, n_nodes: int) -> sp.csr_matrix:
    m = 3 * e.shape[1]
    edof = (3 * e[:, :, None] + np.arange(3)).reshape(e.shape[0], m)
    rows = np.repeat(edof, m, axis=1).ravel()
    cols = np.tile(edof, (1, m)).ravel()
    data = blocks.reshape(blocks.shape[0], -1)[shape].ravel()
    n = 3 * n_nodes
    k = sp.coo_matrix((data, (rows, cols)), shape=(n, n)).tocsr()
    k.sum_duplicates()
    return k


def _check(nodes: FloatArray, elements: IntArray) -> tuple[FloatArray, IntArray]:
    x = np.asarray(nodes, dtype=float)
    e = np.asarray(elements, dtype=np.int64)
    if e.ndim != 2 or e.shape[1] != 20:
        raise ParameterError(f"elements must have 20 nodes each, got shape {e.shape}")
    return x, e


def assemble_hex20(nodes: FloatArray, elements: IntArray, modulus: float,
                   poisson_ratio: float, kind: str = "C3D20R") -> sp.csr_matrix:
    """Global stiffness (3 n_nodes square, CSR, N/mm) of a 20-node hexahedral mesh; one
    element matrix per distinct element shape (translated copies share it)."""
    x, e = _check(nodes, elements)
    shape, first = _classes(x, e)
    return _scatter(element_stiffness20(x[e[first]], modulus, poisson_ratio, kind), shape, e,
                    len(x))


def mass_matrix20(nodes: FloatArray, elements: IntArray, density: float) -> sp.csr_matrix:
    """Consistent mass (3 n_nodes square, CSR, t) of a 20-node mesh, 3 x 3 x 3 points;
    ``density`` in t/mm^3.

    >>> x = NODE_XI20 * 0.5 + 0.5
    >>> m = mass_matrix20(x, np.arange(20)[None], 2.0)
    >>> round(float(m.sum()) / 3, 12)  # each direction carries the whole mass, rho V
    2.0
    """
    x, e = _check(nodes, elements)
    shape, first = _classes(x, e)
    _, dv, n = hex20_b_matrices(x[e[first]], 3)
    scalar = np.einsum("eg,ga,gb->eab", density * dv, n, n)
    block = np.einsum("eab,ij->eaibj", scalar, np.eye(3)).reshape(len(first), 60, 60)
    return _scatter(block, shape, e, len(x))


# --- contact on quadratic faces -------------------------------------------------------------

def _quad8(xi: float, eta: float) -> tuple[FloatArray, FloatArray]:
    from ..hexmesh import _quad_shapes

    return _quad_shapes(xi, eta, True)


def face_mass(x: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The consistent "mass" M_ab = integral of N_a N_b dA (k, 8, 8) of 8-node faces with
    node coordinates x (k, 8, 3; corners then mid-sides), 3 x 3 Gauss points, and their
    areas (k,), mm^2."""
    g, w = np.polynomial.legendre.leggauss(3)
    m = np.zeros((x.shape[0], 8, 8))
    for i, a in enumerate(g):
        for j, b in enumerate(g):
            n, d = _quad8(float(a), float(b))
            t = np.einsum("am,kmc->kac", d, x)
            jac = np.linalg.norm(np.cross(t[:, 0], t[:, 1]), axis=1)
            m += w[i] * w[j] * jac[:, None, None] * np.outer(n, n)[None]
    return m, m.sum(axis=(1, 2))


def _calculix(x: FloatArray) -> FloatArray:
    """CalculiX's node-to-face weights: 1/100 of the face's area at each corner, 24/100 at
    each mid-side."""
    _, area = face_mass(x)
    return area[:, None] * np.array([0.01] * 4 + [0.24] * 4)[None, :]


def _hrz(x: FloatArray) -> FloatArray:
    """HRZ lumping: the diagonal of the consistent face mass, scaled to the face's area."""
    m, area = face_mass(x)
    diag = np.einsum("kaa->ka", m)
    return diag * (area / diag.sum(axis=1))[:, None]


#: Nodal areas of an 8-node face (k, 8, 3) -> (k, 8) mm^2, all > 0, summing to the area.
CONTACT_WEIGHTS: dict[str, tuple[Callable[[FloatArray], FloatArray], str]] = {
    "calculix": (_calculix, "CalculiX node-to-face: corners 1/100, mid-sides 24/100 of the "
                 "face's area"),
    "hrz": (_hrz, "HRZ: the face's consistent mass diagonal scaled to its area (corners "
            "3/76, mid-sides 4/19 on a parallelogram)"),
}
#: The weighting the built-in uses.
DEFAULT_CONTACT_WEIGHTS = "calculix"


@dataclass(frozen=True, eq=False)
class QuadContact:
    """The contact nodes of 8-node faces: their positive areas and what recovers their normal
    forces from consistent reactions (:class:`RecoveredNormal`).

    Attributes
    ----------
    nodes : ndarray of int, shape (n_c,)
        The mesh nodes of the faces, sorted.
    area : ndarray, shape (n_c,)
        A_i, mm^2 (> 0; sum: the faces' area), from :data:`CONTACT_WEIGHTS`.
    mass : scipy.sparse.csr_matrix, shape (n_c, n_c)
        Consistent face mass, integral of N_a N_b dA, mm^2.
    face : ndarray of int, shape (k, 8)
        Each face's nodes as positions in ``nodes``.
    consistent, weight : ndarray, shape (k, 8)
        Each face's consistent shares (integral of N_a dA) and lumped areas, mm^2.
    """

    nodes: IntArray
    area: FloatArray
    mass: sp.csr_matrix
    face: IntArray
    consistent: FloatArray
    weight: FloatArray

    def permuted(self, order: IntArray) -> QuadContact:
        """The same with the nodes in the order ``nodes[order]``."""
        inv = np.empty_like(order)
        inv[order] = np.arange(order.size)
        return QuadContact(self.nodes[order], self.area[order],
                           self.mass[order][:, order].tocsr(), inv[self.face],
                           self.consistent, self.weight)


def contact_areas(face_x: FloatArray, face_nodes: IntArray,
                  weights: str = DEFAULT_CONTACT_WEIGHTS) -> QuadContact:
    """The contact of 8-node faces with coordinates ``face_x`` (k, 8, 3) and node numbers
    ``face_nodes`` (k, 8), nodal areas by ``weights`` (a name of :data:`CONTACT_WEIGHTS`)."""
    if weights not in CONTACT_WEIGHTS:
        raise ParameterError(f"unknown contact weights {weights!r}; choose one of "
                             f"{', '.join(CONTACT_WEIGHTS)}")
    share = CONTACT_WEIGHTS[weights][0](face_x)
    nodes, inv = np.unique(face_nodes.ravel(), return_inverse=True)
    inv = inv.reshape(face_nodes.shape)
    area = np.bincount(inv.ravel(), weights=share.ravel(), minlength=len(nodes)).astype(float)
    m, _ = face_mass(face_x)
    rows = np.repeat(inv, 8, axis=1).ravel()
    cols = np.tile(inv, (1, 8)).ravel()
    mass = sp.coo_matrix((m.ravel(), (rows, cols)), shape=(len(nodes), len(nodes))).tocsr()
    return QuadContact(nodes.astype(np.int64), area, mass, inv.astype(np.int64),
                       m.sum(axis=2), share)


def face_nodes20(elements: IntArray, faces: IntArray) -> IntArray:
    """The 8 nodes (k, 8) of faces (element, face 0..5) of a 20-node mesh: corners as
    :data:`~microslip.fe.hexmesh.HEX_FACES`, then the mid-sides."""
    from ..hexmesh import HEX20_FACE_MIDSIDES, HEX_FACES

    table = np.concatenate([np.asarray(HEX_FACES), np.asarray(HEX20_FACE_MIDSIDES)], axis=1)
    return np.asarray(elements[faces[:, 0][:, None], table[faces[:, 1]]], dtype=np.int64)


class RecoveredNormal:
    """The normal forces N_i of a quadratic contact face under ``fixed`` normal contact, from
    the consistent reactions R = ``k_rf @ u`` - ``clamp_fixed``.

    The consistent reactions are negative at the corners and cannot be friction limits. The
    nodal pressure is recovered as p = M^-1 R (M the consistent face mass: R_a = integral of
    N_a p dA for p = sum N_b p_b), and each face's normal force F_f = integral of p dA is
    shared among its nodes in proportion to A_a p_a (A_a the positive nodal areas of
    :data:`CONTACT_WEIGHTS`). A uniform pressure gives N_i = A_i p exactly, and the N_i add
    up to the reactions' total (F_N) whatever the pressure.

    ``self @ u`` is N, as :func:`~.solve.clamping_step` takes ``k_rf @ u``.
    """

    def __init__(self, k_rf: sp.csr_matrix, contact: QuadContact,
                 clamp_fixed: FloatArray | None = None) -> None:
        from scipy.sparse.linalg import splu

        self.k_rf, self.contact = k_rf, contact
        self.clamp_fixed = clamp_fixed
        self.lu = splu(sp.csc_matrix(contact.mass))

    def recover(self, reaction: FloatArray) -> FloatArray:
        """N_i (n_c,) from consistent nodal reactions R (n_c,), N."""
        c = self.contact
        p = self.lu.solve(np.asarray(reaction, dtype=float))[c.face]  # (k, 8)
        total = (c.consistent * p).sum(axis=1)
        q = c.weight * p
        norm = q.sum(axis=1)
        safe = np.where(norm != 0.0, norm, 1.0)
        share = np.where((norm != 0.0)[:, None], q / safe[:, None], c.weight
                         / c.weight.sum(axis=1)[:, None])
        return np.bincount(c.face.ravel(), weights=(share * total[:, None]).ravel(),
                           minlength=c.nodes.size).astype(float)

    def __matmul__(self, u: FloatArray) -> FloatArray:
        r = np.asarray(self.k_rf @ u)
        return self.recover(r if self.clamp_fixed is None else r - self.clamp_fixed)
