"""Structured hexahedral mesh of a rectangular body, numbered slice by slice along the bar.

The body occupies ``0 <= x <= L`` (bar axis, the tip load acts on the end face ``x = L``),
``0 <= y <= w`` (across the bar, in the plane of the interface) and ``0 <= z <= t``
(thickness; ``z = 0`` is the interface with the rigid base, ``z = t`` carries the clamping
pressure). Units: mm.

Node ``(i, j, k)`` (``i`` along x, ``j`` along y, ``k`` along z) has the number
``(i (ny + 1) + j) (nz + 1) + k``: all nodes of one cross-section (a *slice*) come before
the next slice, so an element couples nodes at most ``(ny + 1)(nz + 1) + (nz + 1) + 1`` numbers
apart and the stiffness matrix is a band matrix whose half-bandwidth does not grow with the
number of elements along the bar (Section 3 of ``docs/solver.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..params import ClampParams

__all__ = [
    "MAX_NODES",
    "MESHES",
    "MESH_LEVELS",
    "BoxMesh",
    "MeshLevel",
    "box_mesh",
    "level_counts",
    "mesh_from_spec",
]

IntArray = NDArray[np.int64]
FloatArray = NDArray[np.float64]

#: Upper bound on the number of nodes of one mesh (memory guard: ~1e6 DOF).
MAX_NODES = 350_000

#: Named element counts ``(nx, ny, nz)`` along the length, width and thickness on the Table 1
#: bar (element lengths 10.6, 5.3, 2.6 and 1.6 mm). ``coarse`` (625 DOF) is mesh-converged for
#: the Table 1 tip loop to 0.2 %; ``medium`` (1 225 DOF) also for the centre loads to about
#: 1 %; ``paper`` (9 016 DOF) is the size of the paper's ANSYS model (~10 500 DOF) and of the
#: CalculiX ``paper`` mesh (9 090 DOF); see docs/solver.md. ``tiny`` and ``paper`` are these
#: counts on any body; the accuracy levels ``coarse``, ``medium`` and ``fine`` take their
#: counts from the geometry (:data:`MESH_LEVELS`, :func:`level_counts`), which gives these.
MESHES: dict[str, tuple[int, int, int]] = {
    "tiny": (8, 2, 1),
    "coarse": (24, 4, 1),
    "medium": (48, 4, 1),
    "fine": (96, 8, 2),
    "paper": (160, 6, 2),
}


@dataclass(frozen=True)
class MeshLevel:
    """An accuracy level: element sizes from the geometry of the clamped zone.

    ``across`` elements over the width set the size h = w / across; the thickness gets
    ceil(t / h) layers (at least one, at most ``max_layers``: the banded factorisation costs
    the square of the layers), the length ceil(L / (aspect h)) elements (at least
    ``min_along``, the Table 1 count, made even for the mid-length section). On the Table 1
    bar this gives the counts of :data:`MESHES`; a thick block gets layers through its
    thickness, and no body gets fewer elements than before the levels took the geometry.
    """

    across: int
    aspect: float
    min_along: int
    max_layers: int

    def counts(self, length: float, width: float, thickness: float) -> tuple[int, int, int]:
        h = width / self.across
        nz = min(self.max_layers, max(1, math.ceil(thickness / h - 1e-9)))
        nx = max(self.min_along, math.ceil(length / (self.aspect * h) - 1e-9))
        return nx + nx % 2, self.across, nz


#: Accuracy levels of the built-in solver (element aspect dx / dy as on the Table 1 bar).
MESH_LEVELS: dict[str, MeshLevel] = {
    "coarse": MeshLevel(4, 5.0 / 3.0, 24, 4),
    "medium": MeshLevel(4, 5.0 / 6.0, 48, 6),
    "fine": MeshLevel(8, 5.0 / 6.0, 96, 8),
}


def level_counts(params: ClampParams, level: str) -> tuple[int, int, int]:
    """Element counts (nx, ny, nz) of a mesh name for this clamped zone: an accuracy level of
    :data:`MESH_LEVELS` from the geometry, or the fixed counts of ``tiny`` and ``paper``.

    >>> from microslip import preset
    >>> level_counts(preset("table1"), "fine"), level_counts(preset("table2-tip"), "coarse")
    ((96, 8, 2), (24, 4, 2))
    """
    if level in MESH_LEVELS:
        return MESH_LEVELS[level].counts(params.length, params.width, params.thickness)
    try:
        return MESHES[level]
    except KeyError:
        raise ParameterError(
            f"unknown mesh {level!r}; choose one of {', '.join(MESHES)} or give (nx, ny, nz)"
        ) from None


def _count(name: str, value: Any, lower: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ParameterError(f"{name} must be an integer >= {lower}, got {value!r}")
    if value < lower:
        raise ParameterError(f"{name} must be an integer >= {lower}, got {value!r}")
    return int(value)


@dataclass(frozen=True, eq=False)
class BoxMesh:
    """Uniform structured mesh of 8-node hexahedra on a box ``L x w x t`` (mm).

    Attributes
    ----------
    length, width, thickness : float
        Box size along x, y, z, mm.
    nx, ny, nz : int
        Elements along x, y, z.
    nodes : ndarray, shape (n_nodes, 3)
        Node coordinates, mm, slice-by-slice numbering (see the module docstring).
    elements : ndarray, shape (n_elements, 8)
        Node numbers of each element: the four nodes of its face ``z = z_k``
        counter-clockwise seen from +z, then the four of ``z = z_(k+1)``.
    """

    length: float
    width: float
    thickness: float
    nx: int
    ny: int
    nz: int
    nodes: FloatArray = field(repr=False)
    elements: IntArray = field(repr=False)

    @property
    def n_nodes(self) -> int:
        return int(self.nodes.shape[0])

    @property
    def n_elements(self) -> int:
        return int(self.elements.shape[0])

    @property
    def slice_size(self) -> int:
        """Nodes per cross-section, (ny + 1)(nz + 1)."""
        return (self.ny + 1) * (self.nz + 1)

    @property
    def spacing(self) -> tuple[float, float, float]:
        """Element size (dx, dy, dz), mm."""
        return self.length / self.nx, self.width / self.ny, self.thickness / self.nz

    def node_id(self, i: Any, j: Any, k: Any) -> IntArray:
        """Node numbers of grid indices ``(i, j, k)`` (broadcast)."""
        return np.asarray((np.asarray(i) * (self.ny + 1) + np.asarray(j)) * (self.nz + 1)
                          + np.asarray(k), dtype=np.int64)

    def face_nodes(self, face: str) -> IntArray:
        """Node numbers of a face (see :data:`FACES`), in increasing order."""
        i, j, k = _face_grid(self, face)
        gi, gj, gk = np.meshgrid(i, j, k, indexing="ij")
        return self.node_id(gi, gj, gk).ravel()

    def face_weights(self, face: str) -> FloatArray:
        """Tributary areas (mm^2) of the nodes of a face, in the order of :meth:`face_nodes`.

        The consistent nodal forces of a uniform traction on bilinear faces: each node gets a
        quarter of the area of every face element it belongs to, so corners get A/4, edges A/2
        and interior nodes A of one face element. The weights add up to the face's area.
        """
        i, j, k = _face_grid(self, face)
        dx, dy, dz = self.spacing
        wi = _trib(self.nx, dx) if i.size > 1 else np.ones(1)
        wj = _trib(self.ny, dy) if j.size > 1 else np.ones(1)
        wk = _trib(self.nz, dz) if k.size > 1 else np.ones(1)
        return np.asarray((wi[:, None, None] * wj[None, :, None] * wk[None, None, :]).ravel(),
                          dtype=float)

    def half_bandwidth(self) -> int:
        """Largest difference of two node numbers in one element."""
        e = self.elements
        return int(np.max(e.max(axis=1) - e.min(axis=1)))

    def describe(self) -> dict[str, Any]:
        """Plain summary for reports (sizes in mm)."""
        return {"nx": self.nx, "ny": self.ny, "nz": self.nz, "nodes": self.n_nodes,
                "elements": self.n_elements, "length_mm": self.length,
                "width_mm": self.width, "thickness_mm": self.thickness}


#: Named faces: bottom (z = 0, the interface), top (z = t, the clamping pressure),
#: end (x = L, the tip load), mid (x = L/2, the centre load; needs an even nx).
FACES = ("bottom", "top", "end", "mid", "start")


def _face_grid(mesh: BoxMesh, face: str) -> tuple[IntArray, IntArray, IntArray]:
    """Grid index ranges (i, j, k) of a face; node numbers increase along them (i slowest)."""
    ii, jj, kk = np.arange(mesh.nx + 1), np.arange(mesh.ny + 1), np.arange(mesh.nz + 1)
    if face == "bottom":
        return ii, jj, kk[:1]
    if face == "top":
        return ii, jj, kk[-1:]
    if face == "end":
        return ii[-1:], jj, kk
    if face == "start":
        return ii[:1], jj, kk
    if face == "mid":
        if mesh.nx % 2:
            raise ParameterError(f"the mid-length section needs an even nx, got nx = {mesh.nx}")
        return ii[mesh.nx // 2: mesh.nx // 2 + 1], jj, kk
    raise ParameterError(f"unknown face {face!r}; choose one of {', '.join(FACES)}")


def _trib(n: int, h: float) -> FloatArray:
    w = np.full(n + 1, h)
    w[0] = w[-1] = 0.5 * h
    return w


def box_mesh(length: float, width: float, thickness: float, nx: int, ny: int, nz: int
             ) -> BoxMesh:
    """Build a :class:`BoxMesh`.

    Examples
    --------
    >>> m = box_mesh(254.0, 25.4, 3.18, 4, 2, 1)
    >>> m.n_nodes, m.n_elements, m.half_bandwidth()
    (30, 8, 9)
    >>> abs(float(m.face_weights("bottom").sum()) - 254.0 * 25.4) < 1e-9
    True
    """
    nx = _count("nx", nx, 1)
    ny = _count("ny", ny, 1)
    nz = _count("nz", nz, 1)
    n_nodes = (nx + 1) * (ny + 1) * (nz + 1)
    if n_nodes > MAX_NODES:
        raise ParameterError(f"mesh {nx}x{ny}x{nz} has {n_nodes} nodes; at most {MAX_NODES}")
    x = np.linspace(0.0, length, nx + 1)
    y = np.linspace(0.0, width, ny + 1)
    z = np.linspace(0.0, thickness, nz + 1)
    gx, gy, gz = np.meshgrid(x, y, z, indexing="ij")
    nodes = np.stack([gx.ravel(), gy.ravel(), gz.ravel()], axis=1)
    gi, gj, gk = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    i, j, k = gi.ravel(), gj.ravel(), gk.ravel()
    sj, si = nz + 1, (ny + 1) * (nz + 1)
    n0 = (i * (ny + 1) + j) * (nz + 1) + k
    base = np.stack([n0, n0 + si, n0 + si + sj, n0 + sj], axis=1)
    elements = np.concatenate([base, base + 1], axis=1).astype(np.int64)
    return BoxMesh(float(length), float(width), float(thickness), nx, ny, nz, nodes, elements)


def mesh_from_spec(params: ClampParams, spec: Any) -> BoxMesh:
    """A mesh of the clamped zone from a name in :data:`MESHES` (:func:`level_counts`),
    ``(nx, ny, nz)`` or a mesh.

    A given :class:`BoxMesh` must have the size of the clamped zone (L, w, t of ``params``).

    >>> from microslip import preset
    >>> mesh_from_spec(preset("table1"), "coarse").describe()["nodes"]
    250
    """
    if isinstance(spec, BoxMesh):
        dims = (params.length, params.width, params.thickness)
        if not all(math.isclose(a, b, rel_tol=1e-12) for a, b in
                   zip((spec.length, spec.width, spec.thickness), dims, strict=True)):
            raise ParameterError(
                f"mesh size {spec.length:g} x {spec.width:g} x {spec.thickness:g} mm does not "
                f"match the clamped zone {dims[0]:g} x {dims[1]:g} x {dims[2]:g} mm")
        return spec
    if isinstance(spec, str):
        counts = level_counts(params, spec)
    else:
        try:
            counts = tuple(spec)
        except TypeError:
            raise ParameterError(
                f"mesh must be a name ({', '.join(MESHES)}) or (nx, ny, nz), got {spec!r}"
            ) from None
        if len(counts) != 3:
            raise ParameterError(f"mesh must be (nx, ny, nz), got {spec!r}")
    return box_mesh(params.length, params.width, params.thickness, *counts)
