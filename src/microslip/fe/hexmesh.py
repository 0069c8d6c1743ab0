"""A hexahedral mesh with named sets: the user's own clamp geometry, whatever file it came from.

:class:`HexMesh` is what the built-in solver and the CalculiX deck writer read; the readers
(``.inp``, and the formats meshio reads: :mod:`~microslip.fe.meshfile`) produce it, and
:func:`microslip.fe.examples.box_hexmesh` writes the built-in box as one. Node and element
numbers are 0-based rows; element connectivity is in
the CalculiX/Abaqus order (C3D8: corners 1-4 on one face, 5-8 opposite; C3D20: the corners,
then the 12 edge mid-points). Units: mm.

Element faces are numbered as CalculiX's surfaces S1..S6 (0-based here, 0..5), by the corner
nodes (1-based in the CalculiX manual): S1 1-2-3-4, S2 5-8-7-6, S3 1-5-6-2, S4 2-6-7-3,
S5 3-7-8-4, S6 4-8-5-1; in this order the right-hand-rule normal of each points into the
element (the outward normal is its negative).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError

__all__ = ["HEX_FACES", "HexMesh"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Corner nodes (0-based positions in a C3D8/C3D20 connectivity row) of faces S1..S6.
HEX_FACES: tuple[tuple[int, int, int, int], ...] = (
    (0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0))


def _frozen(a: Any, dtype: type) -> NDArray[Any]:
    out: NDArray[Any] = np.array(a, dtype=dtype)
    out.flags.writeable = False
    return out


@dataclass(frozen=True, eq=False)
class HexMesh:
    """Hexahedra (8 or 20 nodes) with named node sets and element-face surfaces.

    Attributes
    ----------
    nodes : ndarray, shape (n, 3)
        Node coordinates, mm.
    elements : ndarray of int, shape (e, 8) or (e, 20)
        Connectivity, 0-based node rows, CalculiX order.
    node_sets : mapping of str to ndarray of int
        Named node sets (sorted, unique 0-based rows).
    surfaces : mapping of str to ndarray of int, shape (k, 2)
        Named element-face surfaces: rows (element, face 0..5 as S1..S6).
    source : str
        Where the mesh came from (a file name, or ``"box"``), for messages.
    node_ids, element_ids : ndarray of int, or None
        The node and element numbers of the file (one per row), for messages and for writing
        the mesh back; None: the row + 1.
    set_dims : mapping of str to int
        The dimension (0 point, 1 curve, 2 surface, 3 volume) of the file's group a set came
        from, where the file says (gmsh physical groups, meshio cell sets); for messages.
    element_sets : mapping of str to ndarray of int
        Named sets of hexahedra (sorted, unique 0-based element rows): the file's ``*ELSET``
        and gmsh volume groups; the bodies' materials name them.
    """

    nodes: FloatArray
    elements: IntArray
    node_sets: Mapping[str, IntArray] = field(default_factory=dict)
    surfaces: Mapping[str, IntArray] = field(default_factory=dict)
    source: str = "mesh"
    node_ids: IntArray | None = None
    element_ids: IntArray | None = None
    set_dims: Mapping[str, int] = field(default_factory=dict)
    element_sets: Mapping[str, IntArray] = field(default_factory=dict)

    def __post_init__(self) -> None:
        nodes = _frozen(self.nodes, np.float64)
        elements = _frozen(self.elements, np.int64)
        if nodes.ndim != 2 or nodes.shape[1] != 3:
            raise ParameterError(f"{self.source}: nodes must have shape (n, 3), got {nodes.shape}")
        if elements.ndim != 2 or elements.shape[1] not in (8, 20) or len(elements) == 0:
            raise ParameterError(
                f"{self.source}: no hexahedra (8- or 20-node elements) in the mesh")
        if elements.min() < 0 or elements.max() >= len(nodes):
            raise ParameterError(f"{self.source}: an element refers to a node that does not exist")
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "elements", elements)
        object.__setattr__(self, "node_sets", MappingProxyType(
            {k: _frozen(np.unique(v), np.int64) for k, v in self.node_sets.items()}))
        object.__setattr__(self, "surfaces", MappingProxyType(
            {k: _frozen(np.asarray(v).reshape(-1, 2), np.int64)
             for k, v in self.surfaces.items()}))
        esets = {str(k): _frozen(np.unique(v), np.int64) for k, v in self.element_sets.items()}
        for k, v in esets.items():
            if len(v) and (v[0] < 0 or v[-1] >= len(elements)):
                raise ParameterError(f"{self.source}: element set {k!r} refers to an element "
                                     "that does not exist")
        object.__setattr__(self, "element_sets", MappingProxyType(esets))
        object.__setattr__(self, "set_dims", MappingProxyType(
            {str(k): int(v) for k, v in self.set_dims.items()}))
        for name, rows in (("node_ids", len(nodes)), ("element_ids", len(elements))):
            ids = getattr(self, name)
            if ids is None:
                continue
            ids = _frozen(ids, np.int64)
            if ids.shape != (rows,) or len(np.unique(ids)) != rows:
                raise ParameterError(f"{self.source}: {name} must be {rows} distinct numbers")
            object.__setattr__(self, name, ids)

    @property
    def nodes_per_element(self) -> int:
        return int(self.elements.shape[1])

    def node_label(self, row: int) -> int:
        """The file's number of node ``row`` (row + 1 when the mesh has no file numbers)."""
        return int(row) + 1 if self.node_ids is None else int(self.node_ids[row])

    def element_label(self, row: int) -> int:
        """The file's number of element ``row`` (row + 1 when the mesh has no file numbers)."""
        return int(row) + 1 if self.element_ids is None else int(self.element_ids[row])

    def set_names(self) -> tuple[str, ...]:
        """Every node-set and surface name, sorted."""
        return tuple(sorted(set(self.node_sets) | set(self.surfaces)))

    def faces(self, name: str) -> IntArray:
        """The element faces of a named set, shape (k, 2): (element, face 0..5).

        A surface gives its faces; a node set gives every element face whose corner nodes
        are all in the set (a face shared by two elements counts for both; a set on the
        boundary has each face once).
        """
        if name in self.surfaces:
            return self.surfaces[name]
        if name not in self.node_sets:
            raise ParameterError(
                f"{self.source}: no set named {name!r}; the mesh has "
                f"{', '.join(self.set_names()) or 'no named sets'}")
        inset = np.zeros(len(self.nodes), dtype=bool)
        inset[self.node_sets[name]] = True
        corners = self.elements[:, :8]
        rows = []
        for f, idx in enumerate(HEX_FACES):
            hit = np.flatnonzero(inset[corners[:, list(idx)]].all(axis=1))
            rows.append(np.stack([hit, np.full_like(hit, f)], axis=1))
        return np.concatenate(rows).astype(np.int64)

    def face_corners(self, faces: IntArray) -> IntArray:
        """Corner nodes, shape (k, 4), of faces (element, face), ordered as :data:`HEX_FACES`."""
        table = np.asarray(HEX_FACES, dtype=np.int64)
        return self.elements[faces[:, 0][:, None], table[faces[:, 1]]]


#: Mid-side nodes (0-based positions in a C3D20 row) of faces S1..S6, in the order of the
#: face's edges (corner k to corner k+1).
HEX20_FACE_MIDSIDES: tuple[tuple[int, int, int, int], ...] = (
    (8, 9, 10, 11), (15, 14, 13, 12), (16, 12, 17, 8), (17, 13, 18, 9), (18, 14, 19, 10),
    (19, 15, 16, 11))


def _quad_shapes(xi: float, eta: float, serendipity: bool) -> tuple[FloatArray, FloatArray]:
    """Shape functions and their (xi, eta) derivatives of a 4- or 8-node quadrilateral."""
    c = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], dtype=float)
    if not serendipity:
        n = 0.25 * (1 + c[:, 0] * xi) * (1 + c[:, 1] * eta)
        d = 0.25 * np.stack([c[:, 0] * (1 + c[:, 1] * eta), c[:, 1] * (1 + c[:, 0] * xi)])
        return n, d
    m = np.array([(0, -1), (1, 0), (0, 1), (-1, 0)], dtype=float)
    a, b = c[:, 0], c[:, 1]
    nc = 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1)
    dc = 0.25 * np.stack([a * (1 + b * eta) * (2 * a * xi + b * eta),
                          b * (1 + a * xi) * (a * xi + 2 * b * eta)])
    p, q = m[:, 0], m[:, 1]
    nm = np.where(p == 0, 0.5 * (1 - xi**2) * (1 + q * eta), 0.5 * (1 + p * xi) * (1 - eta**2))
    dm = np.stack([np.where(p == 0, -xi * (1 + q * eta), 0.5 * p * (1 - eta**2)),
                   np.where(p == 0, 0.5 * q * (1 - xi**2), -eta * (1 + p * xi))])
    return np.concatenate([nc, nm]), np.concatenate([dc, dm], axis=1)


def face_load(mesh: HexMesh, faces: IntArray) -> tuple[IntArray, FloatArray, float]:
    """Consistent nodal forces of a uniform traction of total 1 N over element faces.

    Returns the nodes, their shares (summing to 1; the corner shares of 8-node faces are
    negative, as the consistent load of a serendipity face is) and the faces' area, mm^2.
    Integrated exactly for flat faces: 2 x 2 Gauss points on 4-node faces, 3 x 3 on 8-node.
    """
    quadratic = mesh.nodes_per_element == 20
    corners = np.asarray(HEX_FACES, dtype=np.int64)[faces[:, 1]]
    if quadratic:
        mids = np.asarray(HEX20_FACE_MIDSIDES, dtype=np.int64)[faces[:, 1]]
        corners = np.concatenate([corners, mids], axis=1)
    face_nodes = mesh.elements[faces[:, 0][:, None], corners]
    if quadratic:
        g, w = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5, 8, 5]) / 9.0
    else:
        g, w = np.array([-1.0, 1.0]) / np.sqrt(3.0), np.ones(2)
    x = mesh.nodes[face_nodes]  # (k, m, 3)
    share = np.zeros(face_nodes.shape)
    for i, xi in enumerate(g):
        for j, eta in enumerate(g):
            n, d = _quad_shapes(float(xi), float(eta), quadratic)
            t = np.einsum("am,kmc->kac", d, x)
            jac = np.linalg.norm(np.cross(t[:, 0], t[:, 1]), axis=1)
            share += w[i] * w[j] * jac[:, None] * n[None, :]
    area = float(share.sum())
    if not area > 0:
        raise ParameterError(f"{mesh.source}: the faces have no area")
    nodes, inverse = np.unique(face_nodes.ravel(), return_inverse=True)
    weights = np.bincount(inverse, weights=share.ravel(), minlength=len(nodes)) / area
    return nodes.astype(np.int64), weights, area


#: Gauss-Legendre points per direction on each face for :func:`law_face_load` (8: exact for a
#: law polynomial up to degree 14 along an axis-parallel face, as the box's 8 points along x).
LAW_POINTS = 8


def law_face_load(mesh: HexMesh, faces: IntArray, shape: Any, axis: int,
                  points: int = LAW_POINTS) -> tuple[IntArray, FloatArray]:
    """Consistent nodal forces of a traction p(xi) of total 1 N over element faces, with
    xi = (x_axis - lo) / (hi - lo) the position along the global ``axis`` (0 x, 1 y, 2 z)
    across the faces' extent [lo, hi] and ``shape`` the law p (a
    :attr:`~microslip.models.interface.PressureLaw.shape`, vectorised over xi).

    Each face is integrated by ``points`` x ``points`` Gauss-Legendre points (the shape
    functions times p times the surface Jacobian) and the shares are scaled to add up to 1
    (a law whose kinks fall inside faces is otherwise integrated to the quadrature error),
    as the box's clamping forces were. Returns the nodes and their shares.
    """
    quadratic = mesh.nodes_per_element == 20
    corners = np.asarray(HEX_FACES, dtype=np.int64)[faces[:, 1]]
    if quadratic:
        mids = np.asarray(HEX20_FACE_MIDSIDES, dtype=np.int64)[faces[:, 1]]
        corners = np.concatenate([corners, mids], axis=1)
    face_nodes = mesh.elements[faces[:, 0][:, None], corners]
    x = mesh.nodes[face_nodes]  # (k, m, 3)
    s = x[:, :, axis]
    lo, hi = float(np.min(s)), float(np.max(s))
    if not hi > lo:
        raise ParameterError(f"{mesh.source}: a pressure law along {'xyz'[axis]} needs faces "
                             f"that extend along {'xyz'[axis]}; these lie across it")
    g, w = np.polynomial.legendre.leggauss(points)
    share = np.zeros(face_nodes.shape)
    for i, xi in enumerate(g):
        for j, eta in enumerate(g):
            n, d = _quad_shapes(float(xi), float(eta), quadratic)
            t = np.einsum("am,kmc->kac", d, x)
            jac = np.linalg.norm(np.cross(t[:, 0], t[:, 1]), axis=1)
            p = np.asarray(shape((s @ n - lo) / (hi - lo)), dtype=float)
            share += (w[i] * w[j] * jac * p)[:, None] * n[None, :]
    nodes, inverse = np.unique(face_nodes.ravel(), return_inverse=True)
    weights = np.bincount(inverse, weights=share.ravel(), minlength=len(nodes))
    total = float(weights.sum())
    if not (np.isfinite(total) and total > 0):
        raise ParameterError(f"{mesh.source}: the pressure law gives no force on the faces")
    return nodes.astype(np.int64), weights / total
