"""Hanging nodes: the constraints that keep a locally refined hexahedral mesh conforming.

After local refinement (:mod:`.adapt`) a refined element's corner can lie in the middle of an
unrefined neighbour's edge or face: a *hanging node*. The coarse element interpolates its
edge (face) linearly (bilinearly) between its corners, so the hanging node h must move as

    u_h = sum_k w_k u_k,

its parents k the corners of that edge (w = 1/2, 1/2) or face (w = 1/4 each): the trilinear
shape functions of the coarse element at h. A parent can hang itself (a corner of a once
refined element on the edge of a coarser one): :class:`HangingNodes` substitutes such
parents by their own until every row names free nodes only (:meth:`HangingNodes.resolved`).

The built-in solver enforces these rows with the assembly's machinery (:mod:`.builtin.bodies`):
the nodal displacements are u = T v, the hanging node's row of T holds its weights and its own
unknowns are held (removed, like a support's); K -> T^T K T and f -> T^T f. The contact
areas of a hanging node on a contact face go to its parents (the consistent shares T^T a),
so friction acts at the free nodes only. A mesh without hanging nodes is a plain
:class:`~.hexmesh.HexMesh`, and solved as before. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..errors import ParameterError
from .hexmesh import HexMesh

__all__ = ["ConstrainedMesh", "HangingNodes", "hanging_of", "plain"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class HangingNodes:
    """The constraint rows u_h = sum_k w_k u_k of a mesh's hanging nodes.

    Attributes
    ----------
    nodes : ndarray of int, shape (h,)
        Mesh rows of the hanging nodes (unique).
    parents : ndarray of int, shape (h, k)
        Mesh rows of each one's parents, -1 where a row has fewer than k.
    weights : ndarray, shape (h, k)
        Their weights (each row sums to 1; 0 where the parent is -1).
    """

    nodes: IntArray
    parents: IntArray
    weights: FloatArray

    def __post_init__(self) -> None:
        nodes = np.asarray(self.nodes, dtype=np.int64).ravel()
        parents = np.asarray(self.parents, dtype=np.int64)
        parents = parents.reshape(nodes.size, parents.shape[-1] if parents.ndim == 2 else -1)
        weights = np.asarray(self.weights, dtype=float).reshape(parents.shape)
        if np.unique(nodes).size != nodes.size:
            raise ParameterError("a hanging node is constrained twice")
        if nodes.size and not np.allclose(weights.sum(axis=1), 1.0, rtol=0, atol=1e-12):
            raise ParameterError("the weights of a hanging node must sum to 1")
        weights = np.where(parents >= 0, weights, 0.0)
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "parents", parents)
        object.__setattr__(self, "weights", weights)

    def __len__(self) -> int:
        return int(self.nodes.size)

    def matrix(self, n_nodes: int) -> sp.csr_matrix:
        """H (n_nodes square, CSR): u = H w, identity on the free nodes, each hanging node's
        row its weights on its parents (resolved: free parents only), its column zero."""
        r = self.resolved()
        keep = np.ones(n_nodes, dtype=bool)
        keep[r.nodes] = False
        free = np.flatnonzero(keep)
        used = r.parents >= 0
        rows = np.concatenate([free, np.repeat(r.nodes, used.sum(axis=1))])
        cols = np.concatenate([free, r.parents[used]])
        vals = np.concatenate([np.ones(free.size), r.weights[used]])
        return sp.csr_matrix((vals, (rows, cols)), shape=(n_nodes, n_nodes))

    def resolved(self) -> HangingNodes:
        """The same constraints with every hanging parent replaced by its own parents (so
        that each row names free nodes only)."""
        if not self.nodes.size:
            return self
        hang = np.zeros(int(max(self.nodes.max(), self.parents.max())) + 1, dtype=bool)
        hang[self.nodes] = True
        if not np.any(hang[self.parents[self.parents >= 0]]):
            return self
        row = {int(h): k for k, h in enumerate(self.nodes)}
        out_p, out_w = [], []
        for k in range(self.nodes.size):
            acc: dict[int, float] = {}
            stack = [(int(p), float(w)) for p, w in zip(self.parents[k], self.weights[k],
                                                           strict=True) if p >= 0]
            depth = 0
            while stack:
                depth += 1
                if depth > 10_000:
                    raise ParameterError("the hanging-node constraints form a cycle")
                p, w = stack.pop()
                if p in row:
                    j = row[p]
                    stack += [(int(q), w * float(v)) for q, v in
                              zip(self.parents[j], self.weights[j], strict=True) if q >= 0]
                else:
                    acc[p] = acc.get(p, 0.0) + w
            out_p.append(sorted(acc))
            out_w.append([acc[p] for p in sorted(acc)])
        width = max(len(p) for p in out_p)
        parents = np.full((self.nodes.size, width), -1, dtype=np.int64)
        weights = np.zeros((self.nodes.size, width))
        for k, (ps, ws) in enumerate(zip(out_p, out_w, strict=True)):
            parents[k, :len(ps)] = ps
            weights[k, :len(ws)] = ws
        return HangingNodes(self.nodes, parents, weights)

    def lump(self, nodes: IntArray, values: FloatArray) -> tuple[IntArray, FloatArray]:
        """Values at ``nodes`` (e.g. the contact nodes' areas) with those of the hanging nodes
        given to their parents by the weights (T^T a): the free nodes among ``nodes`` and the
        parents, sorted, and their values."""
        nodes = np.asarray(nodes, dtype=np.int64)
        values = np.asarray(values, dtype=float)
        at = np.isin(nodes, self.nodes)
        if not np.any(at):
            return nodes, values
        r = self.resolved()
        pos = np.searchsorted(r.nodes, nodes[at], sorter=np.argsort(r.nodes))
        rows = np.argsort(r.nodes)[pos]
        par, w = r.parents[rows], r.weights[rows] * values[at][:, None]
        used = par >= 0
        all_nodes = np.concatenate([nodes[~at], par[used]])
        all_vals = np.concatenate([values[~at], w[used]])
        out, inverse = np.unique(all_nodes, return_inverse=True)
        summed = np.bincount(inverse.ravel(), weights=all_vals, minlength=out.size)
        return out.astype(np.int64), np.asarray(summed, dtype=float)

    def numbering_rows(self, width: int) -> IntArray:
        """Rows (hanging node, its parents, repeated to ``width`` entries) that let a
        bandwidth-reducing numbering see the coupling the constraints add."""
        r = self.resolved()
        rows = np.concatenate([r.nodes[:, None], r.parents], axis=1)
        rows = np.where(rows >= 0, rows, rows[:, :1])
        reps = -(-width // rows.shape[1])
        return np.tile(rows, (1, reps))[:, :width].astype(np.int64)

    def dofs(self, inv: IntArray) -> IntArray:
        """The model dofs of the hanging nodes (``inv``: mesh row -> model node)."""
        return (3 * inv[self.nodes][:, None] + np.arange(3)).ravel().astype(np.int64)

    def in_numbering(self, inv: IntArray) -> HangingNodes:
        """The constraints in the model's node numbering (``inv``: mesh row -> model node),
        resolved."""
        r = self.resolved()
        return HangingNodes(inv[r.nodes], np.where(r.parents >= 0, inv[np.maximum(r.parents, 0)],
                                                   -1), r.weights)


@dataclass(frozen=True, eq=False)
class ConstrainedMesh(HexMesh):
    """A :class:`~.hexmesh.HexMesh` with hanging nodes (``hanging``), e.g. a locally refined
    one. ``levels`` (optional) the refinement level of every element."""

    hanging: HangingNodes | None = None
    levels: IntArray | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        h = self.hanging
        if h is not None:
            if not isinstance(h, HangingNodes):
                raise ParameterError("hanging must be HangingNodes")
            if h.nodes.size and (h.nodes.max() >= len(self.nodes)
                                 or h.parents.max() >= len(self.nodes)):
                raise ParameterError(f"{self.source}: a hanging-node constraint names a node "
                                     "that does not exist")


def hanging_of(mesh: Any) -> HangingNodes | None:
    """The hanging nodes of a mesh, or None (a plain mesh, or a constrained one with none)."""
    h = getattr(mesh, "hanging", None)
    return h if h is not None and len(h) else None


def plain(mesh: HexMesh) -> bool:
    """Whether the mesh has no hanging node."""
    return hanging_of(mesh) is None
