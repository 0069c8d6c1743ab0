"""Structured hexahedral mesh of the clamped bar and its rigid base (paper, Section 4, Fig. 7).

Coordinates (mm): x along the bar, 0 <= x <= L (the tip load acts on the face x = L, the
centre load on the plane x = L/2); y across the width, 0 <= y <= w; z through the thickness,
0 <= z <= t. The bar's lower face z = 0 rests on the base, a one-layer slab of 8-node bricks
under it, larger than the bar by one bar element all round and held fixed (the rigid clamp).

The element counts and the node planes of a mesh level come from :mod:`microslip.meshlevels`,
shared with the built-in solver (a squat bar is graded; mid-side nodes sit half-way between
the corner planes). The bar is meshed with 20-node serendipity bricks on a quadratic lattice:
lattice point (i, j, k), 0 <= i <= 2 nx, 0 <= j <= 2 ny, 0 <= k <= 2 nz, carries a node when
at most one of i, j, k is odd (corners and edge mid-points; no face or body centres). Element
connectivity is in the CalculiX/Abaqus C3D20 order, which is also VTK's quadratic hexahedron order.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ...conventions import DEFAULT_MESH
from ...errors import ParameterError
from ...meshlevels import level_axes, mesh_counts
from ...params import ClampParams

__all__ = ["ELEMENT", "BarMesh", "MeshSpec", "bar_mesh", "mesh_spec"]

#: The element type of the CalculiX bar (the default of
#: :data:`~microslip.fe.calculix.case.ELEMENT_TYPES`).
ELEMENT = "C3D20R"

IntArray = NDArray[np.int64]
FloatArray = NDArray[np.float64]

#: Upper bound on the number of bar elements (memory and run-time guard).
MAX_ELEMENTS = 200_000


@dataclass(frozen=True)
class MeshSpec:
    """Numbers of 20-node elements along the length, width and thickness of the bar.

    ``nx`` must be even (a node plane at L/2 carries the centre load) and ``ny`` even (a node
    plane at w/2 carries the symmetry condition u_y = 0). ``graded``: node planes crowd
    towards the loaded sections and the interface (:func:`~microslip.meshlevels.level_axes`).

    Examples
    --------
    >>> MeshSpec(20, 2, 1).elements
    40
    >>> MeshSpec(21, 2, 1)
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: nx must be an even integer >= 2 (node plane at L/2), got 21
    """

    nx: int
    ny: int = 2
    nz: int = 1
    graded: bool = False

    def __post_init__(self) -> None:
        for name, value, even, why in (("nx", self.nx, True, " (node plane at L/2)"),
                                       ("ny", self.ny, True, " (node plane at w/2)"),
                                       ("nz", self.nz, False, "")):
            ok = isinstance(value, (int, np.integer)) and not isinstance(value, bool)
            if not ok or value < (2 if even else 1) or (even and value % 2):
                rule = "an even integer >= 2" if even else "an integer >= 1"
                raise ParameterError(f"{name} must be {rule}{why}, got {value!r}")
            object.__setattr__(self, name, int(value))
        if self.elements > MAX_ELEMENTS:
            raise ParameterError(
                f"mesh {self.nx} x {self.ny} x {self.nz} has {self.elements} elements; "
                f"at most {MAX_ELEMENTS} are allowed")

    @property
    def elements(self) -> int:
        """Number of bar elements."""
        return self.nx * self.ny * self.nz

    @property
    def nodes(self) -> int:
        """Number of bar nodes (corners and edge mid-points)."""
        nx, ny, nz = self.nx, self.ny, self.nz
        return ((nx + 1) * (ny + 1) * (nz + 1) + nx * (ny + 1) * (nz + 1)
                + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz)

    @property
    def dof(self) -> int:
        """Free degrees of freedom of the bar: 3 per node, less u_y on the plane y = w/2."""
        nx, nz = self.nx, self.nz
        symmetry_nodes = (2 * nx + 1) * (nz + 1) + (nx + 1) * nz
        return 3 * self.nodes - symmetry_nodes

    def label(self) -> str:
        return f"{self.nx}x{self.ny}x{self.nz}"


def mesh_spec(mesh: str | MeshSpec | tuple[int, int, int], params: ClampParams) -> MeshSpec:
    """A :class:`MeshSpec` of a mesh level or ``NXxNYxNZ`` (counts and grading of the clamped
    zone ``params``) or of counts (nx, ny, nz) (uniform), by the one reading of both solvers
    (:func:`microslip.meshlevels.mesh_counts`); a MeshSpec is returned as is.

    >>> from microslip import preset
    >>> mesh_spec("coarse", preset("table1")), mesh_spec("paper", preset("table1")).dof
    (MeshSpec(nx=24, ny=4, nz=1, graded=False), 9090)
    """
    if isinstance(mesh, MeshSpec):
        return mesh
    counts, graded = mesh_counts(params, mesh)
    return MeshSpec(*counts, graded=graded)


#: Corner lattice offsets of a C3D20 element (nodes 1-8), then its edge mid-points (9-20).
_CORNERS = ((0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2))
_MIDSIDES = ((1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2),
             (0, 1, 2), (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1))
#: Corner and mid-side offsets (in a face's own two lattice directions) of an 8-node face.
_FACE_CORNERS = ((0, 0), (2, 0), (2, 2), (0, 2))
_FACE_MIDSIDES = ((1, 0), (2, 1), (1, 2), (0, 1))


@dataclass(frozen=True, eq=False)
class BarMesh:
    """The bar (C3D20 lattice) and the rigid base (C3D8 slab), node ids from 1.

    Attributes
    ----------
    spec : MeshSpec
    length, width, thickness : float
        Bar dimensions L, w, t, mm.
    nodes : ndarray, shape (n, 3)
        Coordinates of every node, mm; node id = row + 1. Bar nodes come first.
    grid : ndarray of int, shape (2 nx + 1, 2 ny + 1, 2 nz + 1)
        Node id at each lattice point of the bar, 0 where there is no node.
    elements : ndarray of int, shape (nx ny nz, 20)
        Bar connectivity (C3D20 order); element id = row + 1. Row order: x fastest, then y,
        then z, so the first nx ny elements form the bottom layer.
    base_elements : ndarray of int, shape (m, 8)
        Base connectivity (C3D8 order); element ids follow the bar's.
    """

    spec: MeshSpec
    length: float
    width: float
    thickness: float
    nodes: FloatArray
    grid: IntArray
    elements: IntArray
    base_elements: IntArray

    @property
    def n_bar_nodes(self) -> int:
        return int(np.count_nonzero(self.grid))

    @cached_property
    def base_nodes(self) -> IntArray:
        """Ids of the base nodes (all held fixed)."""
        return np.arange(self.n_bar_nodes + 1, self.nodes.shape[0] + 1, dtype=np.int64)

    @property
    def bar_element_ids(self) -> IntArray:
        return np.arange(1, self.elements.shape[0] + 1, dtype=np.int64)

    @property
    def base_element_ids(self) -> IntArray:
        first = self.elements.shape[0] + 1
        return np.arange(first, first + self.base_elements.shape[0], dtype=np.int64)

    @property
    def bottom_elements(self) -> IntArray:
        """Bar elements with a face on z = 0 (their face S1 is the contact slave surface)."""
        return self.bar_element_ids[: self.spec.nx * self.spec.ny]

    @property
    def top_elements(self) -> IntArray:
        """Bar elements with a face on z = t (their face S2 carries the clamping pressure)."""
        return self.bar_element_ids[-self.spec.nx * self.spec.ny:]

    def plane_nodes(self, axis: int, index: int) -> IntArray:
        """Sorted ids of the bar nodes on lattice plane ``index`` normal to ``axis`` (0, 1, 2)."""
        sl: list[slice | int] = [slice(None)] * 3
        sl[axis] = index
        ids = self.grid[tuple(sl)]
        return np.sort(ids[ids > 0]).astype(np.int64)

    @property
    def symmetry_nodes(self) -> IntArray:
        """Nodes on the mid-width plane y = w/2 (u_y = 0 there by symmetry)."""
        return self.plane_nodes(1, self.spec.ny)

    @property
    def contact_nodes(self) -> IntArray:
        """Nodes of the bar's lower face z = 0 (the contact points)."""
        return self.plane_nodes(2, 0)

    def load_plane(self, model: str) -> int:
        """Lattice index i of the loaded cross-section (:attr:`LoadCase.section` of the 2 nx
        lattice spacings): 2 nx for the tip (x = L), nx for the centre."""
        from ...loading import load_case

        return round(load_case(model).section * 2 * self.spec.nx)

    def load_weights(self, model: str) -> tuple[IntArray, FloatArray]:
        """Nodes of the loaded cross-section and their share of the total force.

        The shares are the consistent nodal loads of a uniform traction on the 8-node faces of
        the plane (each face: -1/12 of its force at a corner, 1/3 at a mid-side node); they sum
        to 1. The force-weighted mean of u_x with these shares is the displacement that is work
        conjugate to the total force.
        """
        i = self.load_plane(model)
        ny, nz = self.spec.ny, self.spec.nz
        dy = np.diff(self.nodes[self.grid[0, ::2, 0] - 1, 1]) / self.width
        dz = np.diff(self.nodes[self.grid[0, 0, ::2] - 1, 2]) / self.thickness
        acc: dict[int, float] = {}
        for ez in range(nz):
            for ey in range(ny):
                share = float(dy[ey] * dz[ez]) if self.spec.graded else 1.0 / (ny * nz)
                for offsets, w in ((_FACE_CORNERS, -share / 12.0), (_FACE_MIDSIDES, share / 3.0)):
                    for dj, dk in offsets:
                        n = int(self.grid[i, 2 * ey + dj, 2 * ez + dk])
                        acc[n] = acc.get(n, 0.0) + w
        ids = np.array(sorted(acc), dtype=np.int64)
        return ids, np.array([acc[int(n)] for n in ids], dtype=float)

    def contact_lattice(self) -> tuple[IntArray, IntArray, IntArray]:
        """Ids of the lower-face nodes with their lattice indices (i along x, j along y)."""
        g = self.grid[:, :, 0]
        i, j = np.nonzero(g)
        ids = g[i, j]
        order = np.argsort(ids)
        return ids[order].astype(np.int64), i[order].astype(np.int64), j[order].astype(np.int64)


def _lattice(corners: FloatArray) -> FloatArray:
    """Corner planes and the mid-planes between them (quadratic lattice), mm."""
    out = np.empty(2 * corners.size - 1)
    out[::2] = corners
    out[1::2] = 0.5 * (corners[1:] + corners[:-1])
    return out


def bar_mesh(params: ClampParams, spec: MeshSpec | str = DEFAULT_MESH) -> BarMesh:
    """Mesh the bar of ``params`` (L, w, t) on its base.

    Examples
    --------
    >>> from microslip import preset
    >>> m = bar_mesh(preset("table1"), MeshSpec(2, 2, 1))
    >>> m.elements.shape, m.n_bar_nodes, m.spec.dof
    ((4, 20), 51, 140)
    >>> ids, w = m.load_weights("tip")
    >>> round(float(w.sum()), 12)
    1.0
    """
    spec = mesh_spec(spec, params)
    nx, ny, nz = spec.nx, spec.ny, spec.nz
    L, w, t = params.length, params.width, params.thickness
    shape = (2 * nx + 1, 2 * ny + 1, 2 * nz + 1)
    i, j, k = np.meshgrid(*(np.arange(s) for s in shape), indexing="ij")
    present = (i % 2 + j % 2 + k % 2) <= 1
    grid = np.zeros(shape, dtype=np.int64)
    # number nodes with x fastest, then y, then z
    order = np.argwhere(present.transpose(2, 1, 0))[:, ::-1]
    grid[order[:, 0], order[:, 1], order[:, 2]] = np.arange(1, order.shape[0] + 1)
    if spec.graded:
        lattice = [_lattice(a) for a in level_axes(L, w, t, (nx, ny, nz), True)]
        bar_xyz = np.column_stack([lattice[a][order[:, a]] for a in range(3)])
    else:
        bar_xyz = np.column_stack([order[:, 0] * (L / (2 * nx)), order[:, 1] * (w / (2 * ny)),
                                   order[:, 2] * (t / (2 * nz))])

    ex, ey, ez = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    ex, ey, ez = (a.transpose(2, 1, 0).ravel() for a in (ex, ey, ez))  # x fastest
    conn = np.stack([grid[2 * ex + di, 2 * ey + dj, 2 * ez + dk]
                     for di, dj, dk in _CORNERS + _MIDSIDES], axis=1)

    # base: one layer of C3D8, one bar element larger than the bar all round, below z = 0
    dx, dy = L / nx, w / ny
    bx = np.linspace(-dx, L + dx, nx + 3)
    if spec.graded:
        bx[1:-1] = lattice[0][::2]
    by = np.linspace(-dy, w + dy, ny + 3)
    bz = np.array([-t, 0.0])
    bgi, bgj, bgk = np.meshgrid(np.arange(bx.size), np.arange(by.size), np.arange(2), indexing="ij")
    bgi, bgj, bgk = (a.transpose(2, 1, 0).ravel() for a in (bgi, bgj, bgk))
    first = order.shape[0] + 1
    bid = np.zeros((bx.size, by.size, 2), dtype=np.int64)
    bid[bgi, bgj, bgk] = np.arange(first, first + bgi.size)
    base_xyz = np.column_stack([bx[bgi], by[bgj], bz[bgk]])
    ci, cj = np.meshgrid(np.arange(nx + 2), np.arange(ny + 2), indexing="ij")
    ci, cj = ci.T.ravel(), cj.T.ravel()
    base_conn = np.stack([bid[ci + di // 2, cj + dj // 2, dk // 2]
                          for di, dj, dk in _CORNERS], axis=1)

    return BarMesh(spec=spec, length=L, width=w, thickness=t,
                   nodes=np.vstack([bar_xyz, base_xyz]), grid=grid,
                   elements=conn.astype(np.int64), base_elements=base_conn.astype(np.int64))
