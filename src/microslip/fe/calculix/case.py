"""One finite-element load case of the paper's Section 4, validated once at the boundary.

The paper's FE set-up (Section 4): the Table 1 bar clamped on a rigid base by a uniform
pressure F_N / (L w) on its upper face (first step), Coulomb friction mu on its lower face,
then one step with F_T = F0 sin(2 pi t), t = 0 .. 1.25 s (125 % of a 1 Hz period) in 50 equal
substeps, quasi-static. The first quarter period takes the bar from rest onto the loop; the
remaining full period, t = 0.25 .. 1.25 s, is the closed hysteresis loop.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ...conventions import DEFAULT_MESH
from ...errors import MacroslipError, ParameterError
from ...loading import LOAD_CASES, PERIOD, PERIODS, PaperSine, load_case
from ...params import ClampParams, check_amplitude, check_positive, preset
from ..constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from .mesh import MeshSpec, mesh_spec

__all__ = [
    "DEFAULT_NORMAL_SLOPE",
    "DEFAULT_STICK_SLOPE",
    "ELEMENT_TYPES",
    "LOAD_CASES",
    "PERIOD",
    "FECase",
]

#: The quadratic hexahedron of the box on CalculiX, the counterpart of ANSYS SOLID186 with
#: reduced integration (the mesh deck writes C3D20R for 20-node meshes).
ELEMENT_TYPES = ("C3D20R",)


@dataclass(frozen=True)
class FECase:
    """Everything that defines one CalculiX run of the bar on its rigid base.

    Parameters
    ----------
    model : str
        ``"tip"`` (traction on the end face x = L) or ``"centre"`` (on the section x = L/2).
    params : ClampParams
        Bar, material and clamping (default Table 1).
    amplitude : float
        F0 of F_T = F0 sin(2 pi t), N; below the macroslip force mu F_N.
    mesh : MeshSpec or str
        Mesh level (:mod:`microslip.meshlevels`, the same counts as the built-in solver's on
        this clamped zone) or an explicit MeshSpec.
    stick_slope : float
        lambda of the friction law, N/mm^3.
    normal_slope : float
        Slope of the linear pressure-overclosure law, N/mm^3.
    substeps : int
        Equal load increments over t = 0 .. 1.25 s; a multiple of 5, so that the quarter
        periods (t = 0.25, 0.5, ...) are substep ends (paper: 50).
    element : str
        ``"C3D20R"``.
    max_iterations : int
        Equilibrium iterations allowed per substep before ccx gives up (paper: 26).
    nlgeom : bool
        Geometrically nonlinear analysis (the paper's ANSYS runs used it; here the rotations
        are of order 1e-5 and the loop does not change). The mesh deck has no NLGEOM step:
        :func:`~microslip.fe.calculix.boxrun.run_case` refuses True in one line.

    Examples
    --------
    >>> c = FECase("tip")
    >>> c.mesh.label(), c.amplitude, c.substeps
    ('24x4x1', 267.0, 50)
    >>> FECase("tip", amplitude=400.0)
    Traceback (most recent call last):
    ...
    microslip.errors.MacroslipError: amplitude 400 N must be below mu F_N = 356 N (macroslip)
    """

    model: str
    params: ClampParams = field(default_factory=lambda: preset("table1"))
    amplitude: float = 267.0
    mesh: MeshSpec | str = DEFAULT_MESH
    stick_slope: float = DEFAULT_STICK_SLOPE
    normal_slope: float = DEFAULT_NORMAL_SLOPE
    substeps: int = 50
    element: str = "C3D20R"
    max_iterations: int = 26
    nlgeom: bool = False
    load: PaperSine = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        load_case(self.model)
        if not isinstance(self.params, ClampParams):
            raise ParameterError("params must be a ClampParams")
        f0 = check_amplitude(self.amplitude)
        if f0 >= self.params.macroslip_force:
            raise MacroslipError(
                f"amplitude {f0:g} N must be below mu F_N = "
                f"{self.params.macroslip_force:g} N (macroslip)")
        object.__setattr__(self, "amplitude", f0)
        object.__setattr__(self, "mesh", mesh_spec(self.mesh, self.params))
        object.__setattr__(self, "stick_slope",
                           check_positive("stick_slope", self.stick_slope, "N/mm^3"))
        object.__setattr__(self, "normal_slope",
                           check_positive("normal_slope", self.normal_slope, "N/mm^3"))
        object.__setattr__(self, "load", PaperSine.sampled(f0, self.substeps))
        object.__setattr__(self, "substeps", self.load.increments)
        if self.element not in ELEMENT_TYPES:
            raise ParameterError(
                f"element must be one of {', '.join(ELEMENT_TYPES)}, got {self.element!r}")
        m = self.max_iterations
        if not isinstance(m, (int, np.integer)) or isinstance(m, bool) or not 4 <= m <= 1000:
            raise ParameterError(f"max_iterations must be an integer in [4, 1000], got {m!r}")
        object.__setattr__(self, "max_iterations", int(m))
        object.__setattr__(self, "nlgeom", bool(self.nlgeom))

    @property
    def spec(self) -> MeshSpec:
        """The mesh as a MeshSpec (``mesh`` is converted on construction)."""
        return mesh_spec(self.mesh, self.params)

    @property
    def duration(self) -> float:
        """Length of the load step, s (1.25 periods)."""
        return PERIODS * PERIOD

    @property
    def dt(self) -> float:
        """Substep length, s."""
        return self.duration / self.substeps

    @property
    def times(self) -> NDArray[np.float64]:
        """Substep ends, shape (substeps + 1,), from 0 (clamped state) to 1.25 s."""
        return self.load.time

    def force(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """F_T(t) = F0 sin(2 pi t / period), N, at the substep ends ``t`` (:attr:`times`);
        other times are not load samples."""
        k = np.rint(np.asarray(t, dtype=float) / self.dt).astype(np.int64)
        if not np.allclose(k * self.dt, t, rtol=0.0, atol=1e-9):
            raise ParameterError("FECase.force takes substep ends (FECase.times)")
        return np.asarray(self.load.force[k], dtype=float)

    @property
    def quarter(self) -> int:
        """Substeps per quarter period."""
        return self.load.quarter

    @property
    def pressure(self) -> float:
        """Clamping pressure F_N / (L w) on the upper face, MPa."""
        p = self.params
        return p.normal_force / (p.length * p.width)

    def label(self) -> str:
        return f"{self.model}-{self.spec.label()}-lambda{self.stick_slope:g}"
