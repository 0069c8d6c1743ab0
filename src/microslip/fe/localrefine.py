"""Local refinement of a hexahedral mesh: marked elements split in two along some or all of
their natural axes, hanging nodes constrained, sets carried.

:func:`refine_local` splits each marked 8-node hexahedron at the middle of each chosen
natural axis (all three: 2 x 2 x 2 children; one: 2; two: 4) by its own trilinear map, as
:func:`~microslip.fe.refine.refine` does with N = 2, so the children fill the parent exactly.
Splitting across a line (the edge of a contact, a slip front) but not along it refines where
the solution changes and keeps the element count of a line feature proportional to the number
of levels, not to 2^levels. New nodes at the same place (within 1e-9 of the mesh size) on the
same body are one node; coincident nodes of two bodies stay two.

**2:1 rule.** An element marked whose corner hangs on a coarser neighbour's edge (face) has
that neighbour split along the edge (the face's two axes) too, repeated until nothing
changes; so every hanging node lies at the middle of a neighbour's edge or face.

**Hanging nodes.** A node at the middle of some element's edge (face) that is not a node of
that element hangs: it is constrained to the element's interpolation, u = (u_a + u_b) / 2
(the mean of the face's four corners) (:mod:`.hanging`).

The sets are carried as :func:`~microslip.fe.refine.refine` carries them: a surface's face
of a split element becomes its children's faces on it, an element set its elements'
children, a node set gains every new node whose element corners (those with a non-zero
weight there) are all in it. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from .hanging import ConstrainedMesh, HangingNodes
from .hexmesh import HEX_FACES, HexMesh

__all__ = ["AXIS_EDGES", "AXIS_FACES", "EDGES", "LocalRefinement", "axis_directions",
           "balance", "check_conforming", "refine_local", "start"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

#: Natural coordinates (-1 or +1) of the corners of a C3D8 element, CalculiX order.
SIGN = np.array([(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                 (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], dtype=np.int64)
#: The 12 edges of a hexahedron as corner pairs, four along each natural axis xi, eta, zeta.
AXIS_EDGES = (((0, 1), (3, 2), (4, 5), (7, 6)), ((0, 3), (1, 2), (4, 7), (5, 6)),
              ((0, 4), (1, 5), (2, 6), (3, 7)))
EDGES = tuple(e for axis in AXIS_EDGES for e in axis)
#: The natural axes along each face S1..S6 (the two the face spans).
AXIS_FACES = ((0, 1), (0, 1), (0, 2), (1, 2), (0, 2), (1, 2))
#: The axis normal to each face and its side (-1, +1).
_FACE_NORMAL = ((2, -1), (2, 1), (1, -1), (0, 1), (1, 1), (0, -1))
#: Same-place tolerance, relative to the mesh size.
SAME = 1e-9


@dataclass(frozen=True, eq=False)
class LocalRefinement:
    """A locally refined mesh and what the next split needs.

    Attributes
    ----------
    mesh : ConstrainedMesh
        The elements (8-node), their sets and the hanging-node constraints.
    levels : ndarray of int, shape (e, 3)
        How often each element was split along each of its natural axes.
    body : ndarray of int, shape (n,)
        Each node's body (connected part of the given mesh).
    parent : ndarray of int, shape (e,)
        The element of the given mesh each element lies in.
    size : float
        The given mesh's largest extent, mm.
    """

    mesh: ConstrainedMesh
    levels: IntArray
    body: IntArray = field(repr=False)
    parent: IntArray = field(repr=False)
    size: float = 1.0

    @property
    def hanging(self) -> HangingNodes:
        assert self.mesh.hanging is not None
        return self.mesh.hanging

    @property
    def level(self) -> IntArray:
        """Each element's largest number of splits along an axis."""
        return np.asarray(self.levels.max(axis=1))


def _shape(xi: FloatArray) -> FloatArray:
    """Trilinear shape functions (p, 8) at natural points (p, 3)."""
    return np.prod(1.0 + xi[:, None, :] * SIGN[None, :, :], axis=2) / 8.0


def axis_directions(mesh: HexMesh, elements: IntArray | None = None) -> tuple[FloatArray,
                                                                               FloatArray]:
    """Each element's natural axes as unit vectors (e, 3 axes, 3) and extents (e, 3), mm: the
    mean of its four edges along each axis."""
    e = mesh.elements if elements is None else mesh.elements[elements]
    x = mesh.nodes[e]
    vec = np.stack([np.mean([x[:, b] - x[:, a] for a, b in AXIS_EDGES[k]], axis=0)
                    for k in range(3)], axis=1)
    length = np.linalg.norm(vec, axis=2)
    return vec / np.maximum(length, 1e-300)[..., None], length


def start(mesh: HexMesh) -> LocalRefinement:
    """The given mesh as level 0 of a local refinement (8-node hexahedra only)."""
    from .builtin.bodies import body_labels

    if mesh.nodes_per_element != 8:
        raise ParameterError(f"{mesh.source}: local refinement takes 8-node hexahedra (refine "
                             "the corner mesh of a 20-node one)")
    if isinstance(mesh, ConstrainedMesh) and mesh.hanging is not None and len(mesh.hanging):
        raise ParameterError(f"{mesh.source}: the mesh already has hanging nodes; continue its "
                             "LocalRefinement instead")
    _, label = body_labels(mesh)
    out = _constrained(mesh, mesh.nodes, mesh.elements, dict(mesh.node_sets),
                       dict(mesh.surfaces), dict(mesh.element_sets), _no_hanging(),
                       np.zeros(len(mesh.elements), np.int64), mesh.source)
    return LocalRefinement(out, np.zeros((len(mesh.elements), 3), np.int64),
                           np.asarray(label, dtype=np.int64),
                           np.arange(len(mesh.elements), dtype=np.int64),
                           float(np.max(np.ptp(mesh.nodes, axis=0))))


def _no_hanging() -> HangingNodes:
    return HangingNodes(np.zeros(0, np.int64), np.zeros((0, 4), np.int64), np.zeros((0, 4)))


def _constrained(base: HexMesh, nodes: FloatArray, elements: IntArray,
                 node_sets: dict[str, Any], surfaces: dict[str, Any],
                 element_sets: dict[str, Any], hanging: HangingNodes, levels: IntArray,
                 source: str) -> ConstrainedMesh:
    return ConstrainedMesh(nodes, elements, node_sets, surfaces, source=source,
                           set_dims=dict(base.set_dims), element_sets=element_sets,
                           hanging=hanging, levels=levels)


def _owners(elements: IntArray, hanging: HangingNodes) -> tuple[dict[tuple[int, ...],
                                                                     list[tuple[int, int]]],
                                                                dict[int, tuple[int, ...]]]:
    """Each hanging node's edge (face) as sorted corners -> (element, edge axis or -1 - face)
    of the elements it is an edge (face) of; and the hanging node -> that key."""
    key_of = {}
    for h, par in zip(hanging.nodes.tolist(), hanging.parents.tolist(), strict=True):
        key_of[h] = tuple(sorted(p for p in par if p >= 0))
    wanted = set(key_of.values())
    out: dict[tuple[int, ...], list[tuple[int, int]]] = {}
    if not wanted:
        return out, key_of
    for axis, edges in enumerate(AXIS_EDGES):
        for a, b in edges:
            pair = np.sort(elements[:, [a, b]], axis=1)
            for el, row in enumerate(pair.tolist()):
                t = tuple(row)
                if t in wanted:
                    out.setdefault(t, []).append((el, axis))
    for f, corners in enumerate(HEX_FACES):
        quad = np.sort(elements[:, list(corners)], axis=1)
        for el, row in enumerate(quad.tolist()):
            t = tuple(row)
            if t in wanted:
                out.setdefault(t, []).append((el, -1 - f))
    return out, key_of


def balance(ref: LocalRefinement, marked: Any, axes: Any = None) -> tuple[IntArray, BoolArray]:
    """The marked elements (with the axes to split, (k, 3) bool; default all) and what the 2:1
    rule adds: an element marked whose corner hangs on a neighbour's edge (face) has the
    neighbour split along that edge (face) too, repeated. Returns the elements and their
    axes."""
    e = ref.mesh.elements
    mask = np.zeros((len(e), 3), dtype=bool)
    marked = np.asarray(marked, dtype=np.int64).ravel()
    mask[marked] = True if axes is None else np.asarray(axes, dtype=bool).reshape(-1, 3)
    hanging = ref.hanging
    if len(hanging):
        owners, key_of = _owners(e, hanging)
        is_hanging = np.zeros(len(ref.mesh.nodes), dtype=bool)
        is_hanging[hanging.nodes] = True
        todo = np.flatnonzero(mask.any(axis=1))
        while todo.size:
            corners = np.unique(e[todo])
            new = set()
            for h in corners[is_hanging[corners]].tolist():
                for el, which in owners.get(key_of[h], []):
                    need = [which] if which >= 0 else list(AXIS_FACES[-1 - which])
                    if not mask[el, need].all():
                        mask[el, need] = True
                        new.add(el)
            todo = np.asarray(sorted(new), dtype=np.int64)
    rows = np.flatnonzero(mask.any(axis=1))
    return rows, mask[rows]


def _lattice(m: BoolArray) -> tuple[FloatArray, IntArray]:
    """The natural points of an element split along the axes ``m`` and its children as
    point indices (c, 8), CalculiX corner order."""
    values = [np.array([-1.0, 0.0, 1.0]) if s else np.array([-1.0, 1.0]) for s in m]
    grid = np.stack(np.meshgrid(*values, indexing="ij"), -1).reshape(-1, 3)
    dims = [len(v) for v in values]
    cells = np.stack(np.meshgrid(*[np.arange(d - 1) for d in dims], indexing="ij"),
                     -1).reshape(-1, 3)
    off = (SIGN + 1) // 2
    idx = cells[:, None, :] + off[None, :, :]  # (c, 8, 3)
    flat = (idx[..., 0] * dims[1] + idx[..., 1]) * dims[2] + idx[..., 2]
    return grid, flat.astype(np.int64)


def refine_local(ref: LocalRefinement, marked: Any, axes: Any = None, *,
                 balanced: bool = True) -> LocalRefinement:
    """Split the ``marked`` elements (rows of ``ref.mesh``) along ``axes`` ((k, 3) bool, one
    row per marked element; default all three), with what the 2:1 rule adds
    (:func:`balance`). The unsplit elements keep their order; a split element's children
    take its place."""
    from scipy.spatial import cKDTree

    mesh = ref.mesh
    if balanced:
        split, masks = balance(ref, marked, axes)
    else:
        split = np.asarray(marked, dtype=np.int64).ravel()
        masks = (np.ones((split.size, 3), bool) if axes is None
                 else np.asarray(axes, bool).reshape(-1, 3))
        keep_rows = masks.any(axis=1)
        split, masks = split[keep_rows], masks[keep_rows]
    if not split.size:
        return ref
    e, x = mesh.elements, mesh.nodes
    elem_body = ref.body[e[:, 0]]
    tol = SAME * ref.size
    # every split element's points: corners (existing nodes) and new points
    pts_xyz, pts_body, pts_corners = [], [], []
    local_children, point_ref = [], []  # per split element
    count = 0
    for el, m in zip(split.tolist(), masks, strict=True):
        grid, children = _lattice(m)
        n = _shape(grid)
        corner_of = np.full(len(grid), -1, dtype=np.int64)
        at_corner = np.all(np.abs(grid) == 1.0, axis=1)
        for p in np.flatnonzero(at_corner):
            corner_of[p] = e[el][int(np.flatnonzero(np.all(SIGN == grid[p], axis=1))[0])]
        new = np.flatnonzero(~at_corner)
        ref_ids = corner_of.copy()
        ref_ids[new] = -1 - (count + np.arange(new.size))  # provisional new ids
        count += new.size
        pts_xyz.append(n[new] @ x[e[el]])
        pts_body.append(np.full(new.size, elem_body[el]))
        pts_corners.append([tuple(sorted(int(c) for c in e[el][n[p] > 0])) for p in new])
        local_children.append(children)
        point_ref.append(ref_ids)
    xyz = np.concatenate(pts_xyz)
    body = np.concatenate(pts_body)
    corners_of_new = [c for part in pts_corners for c in part]
    # same place, same body: an existing node, or one new node for all
    final = np.full(len(xyz), -1, dtype=np.int64)
    found, at = _same_place(cKDTree(x), ref.body, xyz, body, tol)
    final[at] = found
    rest = np.flatnonzero(final < 0)
    n_old = len(x)
    new_xyz: list[FloatArray] = []
    new_body: list[int] = []
    new_corners: list[tuple[int, ...]] = []
    if rest.size:
        groups = cKDTree(xyz[rest]).query_ball_point(xyz[rest], tol)
        rep = np.full(rest.size, -1, dtype=np.int64)
        for i, g in enumerate(groups):
            if rep[i] >= 0:
                continue
            same = [j for j in g if body[rest[j]] == body[rest[i]] and rep[j] < 0]
            row = n_old + len(new_xyz)
            new_xyz.append(xyz[rest[i]])
            new_body.append(body[rest[i]])
            new_corners.append(corners_of_new[rest[i]])
            for j in same:
                rep[j] = row
        final[rest] = rep
    coords = np.concatenate([x, np.array(new_xyz).reshape(-1, 3)])
    node_body = np.concatenate([ref.body, np.asarray(new_body, dtype=np.int64)])
    # the new elements: an unsplit element keeps its place, a split one gives its children
    n_children = np.array([len(c) for c in local_children], dtype=np.int64)
    count_el = np.ones(len(e), dtype=np.int64)
    count_el[split] = n_children
    first = np.concatenate([[0], np.cumsum(count_el)[:-1]])
    elements = np.empty((int(count_el.sum()), 8), dtype=np.int64)
    keep = np.ones(len(e), dtype=bool)
    keep[split] = False
    elements[first[keep]] = e[keep]
    levels = np.repeat(ref.levels, count_el, axis=0)
    for el, m, children, ids in zip(split.tolist(), masks, local_children, point_ref,
                                    strict=True):
        rows = ids.copy()
        neg = rows < 0
        rows[neg] = final[-1 - rows[neg]]
        at = first[el] + np.arange(len(children))
        elements[at] = rows[children]
        levels[at] += m.astype(np.int64)
    parent = np.repeat(ref.parent, count_el)
    # sets
    node_sets = {}
    for name, rows_ in mesh.node_sets.items():
        inset = np.zeros(len(coords), dtype=bool)
        inset[rows_] = True
        add = [n_old + k for k, c in enumerate(new_corners) if inset[list(c)].all()]
        node_sets[name] = np.union1d(rows_, np.asarray(add, dtype=np.int64))
    child_faces = {}
    for el, m, children in zip(split.tolist(), masks, local_children, strict=True):
        grid, _ = _lattice(m)
        cx = grid[children]  # (c, 8, 3) natural corner coordinates
        for f, (axis, side) in enumerate(_FACE_NORMAL):
            on = np.flatnonzero(np.any(cx[:, :, axis] == side, axis=1))
            child_faces[(el, f)] = first[el] + on
    surfaces = {}
    for name, faces in mesh.surfaces.items():
        parts = []
        for el, f in faces.tolist():
            if (el, f) in child_faces:
                rows_ = child_faces[(el, f)]
                parts.append(np.stack([rows_, np.full(rows_.size, f)], axis=1))
            else:
                parts.append(np.array([[first[el], f]]))
        surfaces[name] = (np.concatenate(parts).astype(np.int64) if parts
                          else np.zeros((0, 2), np.int64))
    is_split = np.zeros(len(e), dtype=bool)
    is_split[split] = True
    element_sets = {}
    for name, rows_ in mesh.element_sets.items():
        parts = [first[rows_[~is_split[rows_]]]]
        parts += [first[el] + np.arange(count_el[el]) for el in rows_[is_split[rows_]]]
        element_sets[name] = np.concatenate(parts).astype(np.int64)
    hanging = find_hanging(coords, elements, node_body, tol)
    src = mesh.source.split(" (adapted")[0]
    out = _constrained(mesh, coords, elements, node_sets, surfaces, element_sets, hanging,
                       levels.max(axis=1), f"{src} (adapted, level {int(levels.max())})")
    return LocalRefinement(out, levels, node_body, parent, ref.size)


def _edge_points(nodes: FloatArray, elements: IntArray, t: float) -> tuple[FloatArray,
                                                                          IntArray]:
    """Points at t along every element edge ((e 12, 3)) and the edges' corners (e 12, 2)."""
    ends = elements[:, np.asarray(EDGES)].reshape(-1, 2)
    return (1.0 - t) * nodes[ends[:, 0]] + t * nodes[ends[:, 1]], ends


def _face_points(nodes: FloatArray, elements: IntArray, xi: float, eta: float
                 ) -> tuple[FloatArray, IntArray]:
    """Bilinear points (xi, eta) of every element face ((e 6, 3)) and the faces' corners."""
    quad = elements[:, np.asarray(HEX_FACES)].reshape(-1, 4)
    w = 0.25 * np.array([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta),
                         (1 - xi) * (1 + eta)])
    return np.einsum("k,fkd->fd", w, nodes[quad]), quad


def _at(points: FloatArray, owner_body: IntArray, nodes: FloatArray, body: IntArray,
        tol: float) -> tuple[IntArray, IntArray]:
    """(node, point) pairs where a node of the same body lies at a point."""
    from scipy.spatial import cKDTree

    return _same_place(cKDTree(nodes), body, points, owner_body, tol)


def _same_place(tree: Any, body: IntArray, points: FloatArray, point_body: IntArray,
                tol: float) -> tuple[IntArray, IntArray]:
    """(node, point) pairs where a node of the tree of the point's body lies at the point
    (nodes of other bodies may lie there too: an interface)."""
    k = min(4, tree.n)
    dist, near = tree.query(points, k=k, distance_upper_bound=tol)
    dist, near = dist.reshape(len(points), k), near.reshape(len(points), k)
    ok = np.isfinite(dist)
    ok[ok] = body[near[ok]] == np.broadcast_to(point_body[:, None], ok.shape)[ok]
    first = np.argmax(ok, axis=1)
    hit = np.flatnonzero(ok.any(axis=1))
    return near[hit, first[hit]], hit


def find_hanging(nodes: FloatArray, elements: IntArray, body: IntArray, tol: float
                 ) -> HangingNodes:
    """The nodes at the middle of an element's edge (face) that are not its nodes, with the
    edge's (face's) corners as their parents."""
    eb = np.repeat(body[elements[:, 0]], 12)
    mid, ends = _edge_points(nodes, elements, 0.5)
    h_e, p_e = _at(mid, eb, nodes, body, tol)
    fb = np.repeat(body[elements[:, 0]], 6)
    centre, quad = _face_points(nodes, elements, 0.0, 0.0)
    h_f, p_f = _at(centre, fb, nodes, body, tol)
    rows: dict[int, tuple[list[int], list[float]]] = {}
    for h, p in zip(h_e.tolist(), p_e.tolist(), strict=True):
        rows.setdefault(h, ([*ends[p].tolist(), -1, -1], [0.5, 0.5, 0.0, 0.0]))
    for h, p in zip(h_f.tolist(), p_f.tolist(), strict=True):
        rows.setdefault(h, (quad[p].tolist(), [0.25] * 4))
    if not rows:
        return _no_hanging()
    hs = np.array(sorted(rows), dtype=np.int64)
    return HangingNodes(hs, np.array([rows[h][0] for h in hs.tolist()], dtype=np.int64),
                        np.array([rows[h][1] for h in hs.tolist()]))


def check_conforming(ref: LocalRefinement) -> None:
    """Raise if a node lies inside an element's edge or face other than at its middle (two
    levels between neighbours: the constraints would not hold it)."""
    mesh = ref.mesh
    tol = SAME * ref.size
    body = ref.body
    e = mesh.elements
    for t in (0.25, 0.75):
        pts, _ = _edge_points(mesh.nodes, e, t)
        h, _ = _at(pts, np.repeat(body[e[:, 0]], 12), mesh.nodes, body, tol)
        if h.size:
            raise ParameterError(f"{mesh.source}: node {int(h[0])} at a quarter of an element "
                                 "edge (two refinement levels between neighbours)")
    for xi, eta in ((0.5, 0.0), (-0.5, 0.0), (0.0, 0.5), (0.0, -0.5), (0.5, 0.5)):
        pts, _ = _face_points(mesh.nodes, e, xi, eta)
        h, _ = _at(pts, np.repeat(body[e[:, 0]], 6), mesh.nodes, body, tol)
        if h.size:
            raise ParameterError(f"{mesh.source}: node {int(h[0])} inside an element face off "
                                 "its middle (two refinement levels between neighbours)")
