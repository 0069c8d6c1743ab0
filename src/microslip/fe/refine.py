"""Uniform refinement of a hexahedral mesh: every 8-node hexahedron into N^3, sets carried.

:func:`refine_mesh` subdivides each element of a :class:`~microslip.fe.hexmesh.HexMesh` N
times along each of its natural axes by the element's own trilinear map, so that the refined
mesh fills exactly the same volume (every child is the parent's map restricted to a
sub-cube). A new node is named by its trilinear weights on the parent's corner nodes, as
exact integers over N^3: a node on a face (an edge, a corner) has weights on that face's
corners only, and they do not depend on which of the elements sharing the face produced it,
so nodes on shared faces and edges are found once, and their coordinates, computed from the
same weights, are bitwise equal. The parent's corner nodes keep their coordinates.

The sets are carried:

* a **surface** (element, face) becomes the N^2 child faces on it (same face number, the
  children keep the parent's corner order);
* a **node set** gets every new node whose weights lie on nodes of the set only: a set of
  face nodes gains the nodes inside its faces and edges, a set of an element's eight corners
  (a volume group) the element's interior nodes too.

:class:`Refinement` also carries the prolongation matrix P (new nodes x old nodes, the
weights): a field u given at the old nodes, interpolated as the elements do, is ``P @ u``.
Only 8-node hexahedra are refined (the built-in solver's element). Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import ParameterError
from .hexmesh import HexMesh

__all__ = ["MAX_REFINE", "Refinement", "refine", "refine_mesh"]

IntArray = NDArray[np.int64]

#: Largest subdivision per direction (N^3 = 512 children per element).
MAX_REFINE = 8

#: Natural coordinates (-1 or +1) of the corners of a C3D8 element, CalculiX order.
_CORNER_SIGN = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                         (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], dtype=np.int64)
#: The corners of a child cell as lattice offsets (0 or 1 per axis), CalculiX order.
_CORNER_OFFSET = (_CORNER_SIGN + 1) // 2


@dataclass(frozen=True, eq=False)
class Refinement:
    """A refined mesh and how its nodes come from the parent's.

    Attributes
    ----------
    mesh : HexMesh
        The refined mesh: N^3 children per parent element, parent ``e``'s children at rows
        ``e N^3 .. (e + 1) N^3 - 1``.
    factor : int
        N, the subdivisions per direction.
    prolongation : scipy.sparse.csr_matrix, shape (new nodes, old nodes)
        The trilinear weights of every new node on the parent's nodes (rows sum to 1).
    """

    mesh: HexMesh
    factor: int
    prolongation: sp.csr_matrix


def _check_factor(factor: int) -> int:
    if isinstance(factor, bool) or not isinstance(factor, (int, np.integer)) or not (
            1 <= factor <= MAX_REFINE):
        raise ParameterError(f"--refine must be a whole number in [1, {MAX_REFINE}], got "
                             f"{factor!r}")
    return int(factor)


def _lattice(n: int) -> tuple[IntArray, IntArray]:
    """The (n+1)^3 lattice points (i, j, k) and their integer corner weights, shape (p, 8):
    weight of corner c = prod over axes of (index if the corner's sign is +1 else n - index),
    summing to n^3."""
    idx = np.stack(np.meshgrid(*[np.arange(n + 1)] * 3, indexing="ij"), -1).reshape(-1, 3)
    plus = (_CORNER_SIGN > 0)[None, :, :]  # (1, 8, 3)
    per_axis = np.where(plus, idx[:, None, :], n - idx[:, None, :])  # (p, 8, 3)
    return idx.astype(np.int64), per_axis.prod(axis=2).astype(np.int64)


def refine(mesh: HexMesh, factor: int) -> Refinement:
    """``mesh`` with every element subdivided ``factor`` times in each direction.

    Raises :class:`~microslip.errors.ParameterError` for a factor outside [1,
    :data:`MAX_REFINE`] or a mesh of 20-node elements.
    """
    n = _check_factor(factor)
    if mesh.nodes_per_element != 8:
        raise ParameterError(f"{mesh.source}: --refine subdivides 8-node hexahedra only; the "
                             f"mesh has {mesh.nodes_per_element}-node elements")
    elements = mesh.elements
    n_el, n_old = len(elements), len(mesh.nodes)
    idx, weight = _lattice(n)
    p = len(idx)
    # every (element, lattice point): its corner nodes and weights, sorted by node with the
    # zero weights first (node -1), as an intrinsic key of the point
    nodes = np.broadcast_to(elements[:, None, :], (n_el, p, 8))
    w = np.broadcast_to(weight[None, :, :], (n_el, p, 8))
    nodes = np.where(w > 0, nodes, -1).reshape(-1, 8)
    w = w.reshape(-1, 8)
    order = np.argsort(nodes, axis=1, kind="stable")
    nodes = np.take_along_axis(nodes, order, 1)
    w = np.take_along_axis(w, order, 1)
    keys, inverse = np.unique(np.concatenate([nodes, w], axis=1), axis=0,
                              return_inverse=True)
    inverse = inverse.ravel()
    key_nodes, key_w = keys[:, :8], keys[:, 8:]
    # the parent's corner nodes first, in their old order, then the others in key order
    single = key_w[:, 7] == n ** 3
    rank = np.empty(len(keys), dtype=np.int64)
    rank[single] = key_nodes[single, 7]
    rank[~single] = n_old + np.arange(int((~single).sum()))
    unused = np.setdiff1d(np.arange(n_old), key_nodes[single, 7])  # kept where they are
    used = key_w > 0
    rows = np.concatenate([np.repeat(rank, used.sum(axis=1)), unused])
    cols = np.concatenate([key_nodes[used], unused])
    vals = np.concatenate([key_w[used] / float(n ** 3), np.ones(len(unused))])
    total = len(keys) + len(unused)
    prolong = sp.csr_matrix((vals, (rows, cols)), shape=(total, n_old))
    coords = np.zeros((total, 3))
    coords[rank] = np.einsum("kc,kcd->kd", np.where(used, key_w, 0) / float(n ** 3),
                             mesh.nodes[np.where(used, key_nodes, 0)])
    coords[:n_old] = mesh.nodes  # the old nodes exactly where they were
    point = rank[inverse].reshape(n_el, p)  # (element, lattice point) -> new node
    # children: cell (a, b, c) of each element, corners at lattice offsets
    cells = np.stack(np.meshgrid(*[np.arange(n)] * 3, indexing="ij"), -1).reshape(-1, 3)
    corner_idx = cells[:, None, :] + _CORNER_OFFSET[None, :, :]  # (n^3, 8, 3)
    flat = (corner_idx[..., 0] * (n + 1) + corner_idx[..., 1]) * (n + 1) + corner_idx[..., 2]
    children = point[:, flat].reshape(-1, 8)
    return Refinement(
        HexMesh(coords, children, _node_sets(mesh, prolong), _surfaces(mesh, cells, n),
                source=f"{mesh.source} (refined x{n})", set_dims=dict(mesh.set_dims),
                element_sets={k: (v[:, None] * n ** 3 + np.arange(n ** 3)).ravel()
                              for k, v in mesh.element_sets.items()}),
        n, prolong)


def refine_mesh(mesh: HexMesh, factor: int) -> HexMesh:
    """The refined mesh of :func:`refine` (``factor`` 1 gives ``mesh`` itself). A 20-node
    mesh with straight edges is refined as its corner mesh, then promoted again
    (:mod:`.promote`)."""
    if _check_factor(factor) == 1:
        return mesh
    if mesh.nodes_per_element == 20:
        from .promote import demote_mesh, promote_mesh

        return promote_mesh(refine(demote_mesh(mesh), factor).mesh)
    return refine(mesh, factor).mesh


def _node_sets(mesh: HexMesh, prolong: sp.csr_matrix) -> dict[str, IntArray]:
    """Each node set with the new nodes whose weights lie on its nodes only."""
    out = {}
    support = prolong.copy()
    support.data = np.ones_like(support.data)
    count = np.asarray(support.sum(axis=1)).ravel()
    for name, rows in mesh.node_sets.items():
        inset = np.zeros(len(mesh.nodes))
        inset[rows] = 1.0
        out[name] = np.flatnonzero(support @ inset == count).astype(np.int64)
    return out


#: For each face S1..S6: (axis, lattice cell index on it: 0 the low side, -1 the high side).
_FACE_SIDE = ((2, 0), (2, -1), (1, 0), (0, -1), (1, -1), (0, 0))


def _surfaces(mesh: HexMesh, cells: IntArray, n: int) -> dict[str, IntArray]:
    """Each surface as the child faces on its parent faces."""
    on_face = [np.flatnonzero(cells[:, axis] == (0 if side == 0 else n - 1))
               for axis, side in _FACE_SIDE]
    out = {}
    for name, faces in mesh.surfaces.items():
        parts = [np.stack([e * n ** 3 + on_face[f], np.full(n * n, f)], axis=1)
                 for e, f in faces.tolist()]
        out[name] = (np.concatenate(parts).astype(np.int64) if parts
                     else np.zeros((0, 2), np.int64))
    return out
