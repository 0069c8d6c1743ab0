"""The mesh levels of the box on CalculiX: :class:`MeshSpec` (20-node elements along the
length, width and thickness of the bar) and :func:`mesh_spec`.

The element counts and the node planes of a mesh level come from :mod:`microslip.meshlevels`,
shared with the built-in solver (a squat bar is graded). The mesh itself is
:func:`~microslip.fe.calculix.boxrun.box20_mesh` (``box_hexmesh`` with mid-side nodes half-way
between the corner planes) on a rigid base (:func:`~microslip.fe.calculix.meshdeck.base_slab`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...errors import ParameterError
from ...meshlevels import mesh_counts
from ...params import ClampParams

__all__ = ["ELEMENT", "MeshSpec", "mesh_spec"]

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
