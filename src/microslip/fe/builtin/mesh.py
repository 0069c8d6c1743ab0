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

from ...errors import ParameterError
from ...meshlevels import (
    LEVELS,
    MESH_LEVELS,
    MeshLevel,
    level_axes,
    level_counts,
    mesh_counts,
)
from ...params import ClampParams

__all__ = [
    "ELEMENT",
    "LEVELS",
    "MAX_NODES",
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
#: The built-in solver's default element (:data:`~microslip.fe.builtin.element.ELEMENTS`).
ELEMENT = "C3D8I"

def _count(name: str, value: Any, lower: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ParameterError(f"{name} must be an integer >= {lower}, got {value!r}")
    if value < lower:
        raise ParameterError(f"{name} must be an integer >= {lower}, got {value!r}")
    return int(value)


@dataclass(frozen=True, eq=False)
class BoxMesh:
    """Structured mesh of 8-node box-shaped hexahedra on a box ``L x w x t`` (mm): uniform, or
    graded (node planes at any increasing coordinates along each axis).

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
    axes : tuple of 3 ndarrays
        Node coordinates along x (nx + 1), y (ny + 1) and z (nz + 1), mm.
    graded : tuple of 3 bool
        Whether each axis is graded (False: equal elements, sizes exactly L / nx, ...).
    """

    length: float
    width: float
    thickness: float
    nx: int
    ny: int
    nz: int
    nodes: FloatArray = field(repr=False)
    elements: IntArray = field(repr=False)
    axes: tuple[FloatArray, FloatArray, FloatArray] = field(repr=False)
    graded: tuple[bool, bool, bool] = (False, False, False)

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
        """Smallest element size (dx, dy, dz), mm (the element size of a uniform mesh)."""
        return tuple(float(np.min(s)) for s in self.steps())  # type: ignore[return-value]

    def steps(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Element sizes along x, y and z, mm (equal on an axis that is not graded)."""
        sizes = []
        for a, n, size, g in zip(self.axes, (self.nx, self.ny, self.nz),
                                 (self.length, self.width, self.thickness), self.graded,
                                 strict=True):
            sizes.append(np.diff(a) if g else np.full(n, size / n))
        return sizes[0], sizes[1], sizes[2]

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
        dx, dy, dz = self.steps()
        wi = _trib(dx) if i.size > 1 else np.ones(1)
        wj = _trib(dy) if j.size > 1 else np.ones(1)
        wk = _trib(dz) if k.size > 1 else np.ones(1)
        return np.asarray((wi[:, None, None] * wj[None, :, None] * wk[None, None, :]).ravel(),
                          dtype=float)

    def half_bandwidth(self) -> int:
        """Largest difference of two node numbers in one element."""
        e = self.elements
        return int(np.max(e.max(axis=1) - e.min(axis=1)))

    def describe(self) -> dict[str, Any]:
        """Plain summary for reports (sizes in mm)."""
        return {"nx": self.nx, "ny": self.ny, "nz": self.nz, "graded": any(self.graded),
                "nodes": self.n_nodes,
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


def _trib(h: FloatArray) -> FloatArray:
    """Tributary lengths of the nodes of a line of elements of sizes ``h``."""
    w = np.zeros(h.size + 1)
    w[:-1] += 0.5 * h
    w[1:] += 0.5 * h
    return w


def box_mesh(length: float, width: float, thickness: float, nx: int, ny: int, nz: int,
             axes: tuple[Any, Any, Any] | None = None) -> BoxMesh:
    """Build a :class:`BoxMesh`, uniform or with the node coordinates ``axes`` = (x, y, z)
    (increasing, from 0 to the box size; None on an axis: uniform along it).

    Examples
    --------
    >>> m = box_mesh(254.0, 25.4, 3.18, 4, 2, 1)
    >>> m.n_nodes, m.n_elements, m.half_bandwidth()
    (30, 8, 9)
    >>> abs(float(m.face_weights("bottom").sum()) - 254.0 * 25.4) < 1e-9
    True
    >>> g = box_mesh(4.0, 1.0, 1.0, 2, 1, 1, axes=([0.0, 3.0, 4.0], None, None))
    >>> g.face_weights("bottom").tolist()
    [0.75, 0.75, 1.0, 1.0, 0.25, 0.25]
    """
    nx = _count("nx", nx, 1)
    ny = _count("ny", ny, 1)
    nz = _count("nz", nz, 1)
    n_nodes = (nx + 1) * (ny + 1) * (nz + 1)
    if n_nodes > MAX_NODES:
        raise ParameterError(f"mesh {nx}x{ny}x{nz} has {n_nodes} nodes; at most {MAX_NODES}")
    given = (None, None, None) if axes is None else axes
    coords, graded = [], []
    for name, size, n, a in zip("xyz", (length, width, thickness), (nx, ny, nz), given,
                                strict=True):
        uniform = np.linspace(0.0, size, n + 1)
        if a is None:
            coords.append(uniform)
            graded.append(False)
            continue
        c = np.asarray(a, dtype=float)
        if (c.shape != (n + 1,) or not np.all(np.diff(c) > 0.0)
                or not math.isclose(c[0], 0.0, abs_tol=1e-12 * size)
                or not math.isclose(c[-1], size, rel_tol=1e-12)):
            raise ParameterError(f"the {name} coordinates must increase from 0 to {size:g} mm "
                                 f"in {n + 1} nodes")
        c = c.copy()
        c[0], c[-1] = 0.0, size
        same = bool(np.allclose(c, uniform, rtol=0.0, atol=1e-12 * size))
        coords.append(uniform if same else c)
        graded.append(not same)
    x, y, z = coords
    gx, gy, gz = np.meshgrid(x, y, z, indexing="ij")
    nodes = np.stack([gx.ravel(), gy.ravel(), gz.ravel()], axis=1)
    gi, gj, gk = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    i, j, k = gi.ravel(), gj.ravel(), gk.ravel()
    sj, si = nz + 1, (ny + 1) * (nz + 1)
    n0 = (i * (ny + 1) + j) * (nz + 1) + k
    base = np.stack([n0, n0 + si, n0 + si + sj, n0 + sj], axis=1)
    elements = np.concatenate([base, base + 1], axis=1).astype(np.int64)
    for a in (x, y, z):
        a.flags.writeable = False
    return BoxMesh(float(length), float(width), float(thickness), nx, ny, nz, nodes, elements,
                   (x, y, z), (graded[0], graded[1], graded[2]))


def mesh_from_spec(params: ClampParams, spec: Any) -> BoxMesh:
    """A mesh of the clamped zone from a mesh level or ``"NXxNYxNZ"``
    (:mod:`microslip.meshlevels`: counts and node planes from the geometry, graded on a squat
    body, the same as CalculiX's), from counts ``(nx, ny, nz)`` (uniform), or a mesh.

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
    dims = (params.length, params.width, params.thickness)
    counts, graded = mesh_counts(params, spec)
    if isinstance(spec, str):
        return box_mesh(*dims, *counts, axes=level_axes(*dims, counts, graded))
    return box_mesh(*dims, *counts)
