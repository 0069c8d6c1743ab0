"""Settings of the frictional finite-element solver: the semi-smooth Newton iteration
(:class:`NewtonOptions`) and the directions of the box's centre load. The model itself is
:class:`~microslip.fe.builtin.meshmodel.MeshModel` (the box's: :mod:`.box`)."""

from __future__ import annotations

from dataclasses import dataclass

from ...errors import ParameterError
from ...params import check_positive

__all__ = ["CENTRE_DIRECTIONS", "NewtonOptions"]

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
