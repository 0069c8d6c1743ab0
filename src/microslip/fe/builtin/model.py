"""The frictional finite-element model: Newton settings and the assembled body on its rigid
base with its friction and normal contact (:func:`.solve.build_model` makes it from a clamp).

The box (the clamped zone) rests on a rigid base: the bottom face is held at u_z = 0 and each
bottom node carries the Coulomb friction of :mod:`.contact`; the clamping step gives the
nodal normal forces (:mod:`.clamping`; fixed, or following the load with the penalty normal
contact of :mod:`.normal`). The solver that steps it is :mod:`.solve`. Units: N, mm, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...errors import ParameterError
from ...models.interface import PressureLaw
from ...params import ClampParams, check_positive
from .linalg import Backend
from .mesh import BoxMesh
from .normal import PenaltyNormal

__all__ = ["CENTRE_DIRECTIONS", "FrictionModel", "NewtonOptions"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

#: Direction of the centre load on the mid-length section.
CENTRE_DIRECTIONS: dict[str, int] = {"axial": 0, "transverse": 1}


@dataclass(frozen=True)
class NewtonOptions:
    """Controls of the semi-smooth Newton iteration.

    Attributes
    ----------
    rtol : float
        Converged when max |r_j| <= rtol * mu F_N (N).
    max_iterations : int
        Newton iterations per increment before giving up.
    max_halvings : int
        Step halvings of the backtracking line search.
    armijo : float
        Sufficient decrease: accept step alpha if |r(u + alpha du)| <= (1 - armijo alpha)|r(u)|.
    reuse : bool
        Keep a factorisation while the set of slipping nodes is unchanged and it still cuts
        the residual by ``1 / reuse_ratio`` per step (chord steps; see ``_Stepper``). False:
        plain semi-smooth Newton, one factorisation per iteration.
    reuse_ratio : float
        Largest residual ratio of the last step for which the factorisation is kept.
    same_set : bool
        Reuse a factorisation only while the set of slipping nodes is the one it was built
        with (besides the residual ratio).
    max_cuts : int
        An increment whose Newton iteration fails is cut into 2, 4, ... up to ``max_cuts``
        equal sub-increments along the straight load segment (1: no cutting).
    """

    rtol: float = 1e-9
    max_iterations: int = 40
    max_halvings: int = 12
    armijo: float = 1e-4
    reuse: bool = True
    reuse_ratio: float = 0.1
    same_set: bool = True
    max_cuts: int = 64

    def __post_init__(self) -> None:
        check_positive("rtol", self.rtol, upper=1e-2, inclusive_upper=True)
        for name in ("max_iterations", "max_halvings", "max_cuts"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ParameterError(f"{name} must be an integer >= 1, got {v!r}")
        check_positive("armijo", self.armijo, upper=0.5)
        check_positive("reuse_ratio", self.reuse_ratio, upper=1.0)


@dataclass(frozen=True, eq=False)
class FrictionModel:
    """An assembled clamped zone after the clamping step, ready for tangential loading.

    Attributes
    ----------
    params : ClampParams
    mesh : BoxMesh
    element : str
        Element formulation (:data:`~microslip.fe.builtin.element.ELEMENTS`).
    stick_slope : float
        lambda, N/mm^3.
    pressure_law : PressureLaw or None
        Shape of the clamping traction on the top face (None: uniform, the paper's).
    normal : PenaltyNormal or None
        The unilateral penalty of ``normal_contact="penalty"``; None: u_z = 0 held at the
        interface and the normal forces fixed after clamping (the paper's reading).
    free : ndarray of int
        Global dof numbers (3 node + component) of the unknowns, in increasing order.
    stiffness : scipy.sparse.csr_matrix
        K of the free dofs, N/mm.
    contact_nodes : ndarray of int, shape (n_c,)
        Bottom-face nodes.
    contact_dofs : ndarray of int, shape (n_c, 2)
        Free-dof positions of their x and y dofs.
    contact_area : ndarray, shape (n_c,)
        Tributary areas A_i, mm^2.
    contact_stiffness : ndarray, shape (n_c,)
        k_i = lambda A_i, N/mm.
    normal_force : ndarray, shape (n_c,)
        N_i from the clamping step, N (sum F_N).
    friction_limit : ndarray, shape (n_c,)
        mu N_i, N.
    loads : dict of str -> ndarray
        Unit load vectors on the free dofs (total force 1 N): ``tip``, ``centre-axial``,
        ``centre-transverse``; each is also the weight vector of its work-conjugate displacement.
    clamp_load : ndarray
        Nodal forces of the clamping pressure on the free dofs, N.
    u0 : ndarray
        Displacements after clamping, mm. ``slip0``: slip after clamping (n_c, 2), mm.
    clamp_iterations : int
        Newton iterations of the clamping step (all fixed-point passes).
    backend : object
        The linear-solver backend (keeps K).
    setup_s : float
        Wall time of assembly and clamping, s.
    """

    params: ClampParams
    mesh: BoxMesh
    element: str
    stick_slope: float
    pressure_law: PressureLaw | None
    normal: PenaltyNormal | None
    free: IntArray = field(repr=False)
    stiffness: sp.csr_matrix = field(repr=False)
    contact_nodes: IntArray = field(repr=False)
    contact_dofs: IntArray = field(repr=False)
    contact_area: FloatArray = field(repr=False)
    contact_stiffness: FloatArray = field(repr=False)
    normal_force: FloatArray = field(repr=False)
    friction_limit: FloatArray = field(repr=False)
    loads: dict[str, FloatArray] = field(repr=False)
    clamp_load: FloatArray = field(repr=False)
    u0: FloatArray = field(repr=False)
    slip0: FloatArray = field(repr=False)
    clamp_iterations: int
    backend: Backend = field(repr=False)
    setup_s: float
    newton: NewtonOptions

    @property
    def dof(self) -> int:
        """Number of unknowns (free dofs)."""
        return int(self.free.size)

    @property
    def total_dof(self) -> int:
        """3 x number of nodes."""
        return 3 * self.mesh.n_nodes

    @property
    def normal_contact(self) -> str:
        """``fixed`` or ``penalty`` (:data:`~microslip.fe.builtin.normal.NORMAL_CONTACTS`)."""
        return "fixed" if self.normal is None else "penalty"

    @property
    def force_scale(self) -> float:
        """mu F_N, N: the scale of the residual tolerance."""
        return self.params.macroslip_force

    def centre_load(self, direction: str) -> str:
        """Key of :attr:`loads` for a centre direction (``axial`` or ``transverse``)."""
        if direction not in CENTRE_DIRECTIONS:
            raise ParameterError(
                f"unknown centre direction {direction!r}; choose one of "
                f"{', '.join(CENTRE_DIRECTIONS)}")
        return f"centre-{direction}"
