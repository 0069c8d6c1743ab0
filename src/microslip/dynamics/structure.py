"""A linear structure with hysteretic joints: the system harmonic balance solves.

The structure is given by matrices in SI units (mass kg, damping N·s/m, stiffness N/m) over
its degrees of freedom (displacements in mm); each joint connects to them through a
participation vector ``w``: the joint's relative displacement is ``u = w . q`` (mm) and its
force ``f(u)`` (N) acts on the structure as ``w f``. A one-mode structure
(:func:`one_mode`) is the 1-DOF case: modal mass, natural frequency with the joint removed,
linear damping ratio, and the joint's displacement per unit modal displacement.
Several degrees of freedom and several joints (reduced FE models) use the same class.

Units: mass kg, frequency Hz, force N, displacement mm; :data:`SI_PER_MM` converts the
structure's forces per mm into N.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError
from ..named import readonly, result
from ..params import check_positive
from .operators import HystereticOperator
from .operators2d import CircularIwan
from .operators3d import Contact3D

__all__ = ["SI_PER_MM", "JointLink", "Structure", "free_frequency", "one_mode"]

#: Metres per millimetre: the structure's matrices (SI) times a displacement in mm give N
#: after multiplication by this factor.
SI_PER_MM = 1e-3


@result
class JointLink:
    """A joint in a structure: its operator and where it sits.

    Attributes
    ----------
    operator : HystereticOperator or CircularIwan
        Force law of the joint (displacement mm -> force N); a two-directional operator
        (``directions = 2``, :mod:`.operators2d`) takes both components at once.
    participation : ndarray, shape (n_dof,) or (n_dof, 2)
        Relative displacement of the joint per unit displacement of each degree of freedom
        (-), one column per direction; the joint force acts on the structure with the same
        weights.
    """

    operator: HystereticOperator | CircularIwan | Contact3D
    participation: np.ndarray

    def __post_init__(self) -> None:
        w = np.array(self.participation, dtype=np.float64)
        d = self.directions
        if not ((w.ndim == 1 and d == 1) or (w.ndim == 2 and w.shape[1] == d)):
            raise ParameterError(f"a joint with {d} direction(s) needs participation of "
                                 f"shape (n_dof,{f' {d}' if d > 1 else ''}), got {w.shape}")
        if not np.all(np.isfinite(w)) or not np.any(w):
            raise ParameterError("joint participation must be finite and not all zero")
        object.__setattr__(self, "participation", readonly(w))

    @property
    def directions(self) -> int:
        """Relative displacement components of the joint (1, 2, or 3 for a contact node's
        3-D element, :mod:`.operators3d`)."""
        return int(getattr(self.operator, "directions", 1))

    @property
    def weights(self) -> np.ndarray:
        """Participation as (n_dof, directions)."""
        return self.participation.reshape(self.participation.shape[0], -1)

    @property
    def stuck_stiffness(self) -> np.ndarray:
        """W S W^T, N/mm, (n_dof, n_dof): the joint's slope from the virgin state S
        (directions x directions; a 2-D joint may be stiffer along one axis) on the
        degrees of freedom."""
        op = self.operator
        w = self.weights
        if isinstance(op, Contact3D):
            return np.asarray((w * np.diag(op.stuck_stiffness)) @ w.T)
        if isinstance(op, CircularIwan) and not op.isotropic:
            return np.asarray((w * np.diag(op.stuck_stiffness)) @ w.T)
        return (w @ w.T) * op.initial_stiffness


@result
class Structure:
    """Linear structure (SI matrices) with joints, displacements in mm.

    Attributes
    ----------
    mass, damping, stiffness : ndarray, shape (n_dof, n_dof)
        M (kg), C (N·s/m) and K (N/m) of the structure with the joints removed.
    joints : tuple of JointLink
        The hysteretic joints.
    output : ndarray, shape (n_dof,)
        Weights of the response coordinate whose amplitude is reported (mm).

    Notes
    -----
    Equation of motion, forces in N and q in mm:
    ``1e-3 (M q'' + C q' + K q) + sum_j w_j f_j(w_j . q) = p(t)``.
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    joints: tuple[JointLink, ...]
    output: np.ndarray

    def __post_init__(self) -> None:
        n = self.mass.shape[0]
        for name, mat in (("mass", self.mass), ("damping", self.damping),
                          ("stiffness", self.stiffness)):
            if mat.shape != (n, n) or not np.all(np.isfinite(mat)):
                raise ParameterError(f"{name} matrix must be finite of shape ({n}, {n}), "
                                     f"got {mat.shape}")
        if self.output.shape != (n,):
            raise ParameterError(f"output weights must have shape ({n},), got "
                                 f"{self.output.shape}")
        for link in self.joints:
            if link.participation.shape[0] != n:
                raise ParameterError(f"joint participation must have {n} rows (the degrees "
                                     f"of freedom), got shape {link.participation.shape}")

    @property
    def dofs(self) -> int:
        """Number of degrees of freedom."""
        return int(self.mass.shape[0])

    def stuck_stiffness(self) -> np.ndarray:
        """K plus every joint's stuck stiffness, N/m (the small-amplitude limit)."""
        k = np.array(self.stiffness, dtype=np.float64)
        for link in self.joints:
            k += link.stuck_stiffness / SI_PER_MM
        return k

    def linear_frequencies(self, stuck: bool) -> np.ndarray:
        """Undamped natural frequencies, Hz, ascending: joints stuck or removed."""
        from scipy.linalg import eigh

        k = self.stuck_stiffness() if stuck else self.stiffness
        lam = eigh(k, self.mass, eigvals_only=True)
        return np.asarray(np.sqrt(np.maximum(lam, 0.0)) / (2.0 * np.pi))


def one_mode(frequency: float, modal_mass: float, damping_ratio: float,
             joint: HystereticOperator, participation: float = 1.0) -> Structure:
    """One mode with one joint.

    Parameters
    ----------
    frequency : float
        Natural frequency f with the joint removed, Hz, > 0.
    modal_mass : float
        Modal mass m, kg, > 0.
    damping_ratio : float
        Linear viscous damping ratio zeta in [0, 1); c = 2 zeta m (2 pi f).
    joint : HystereticOperator
        The joint.
    participation : float
        Joint displacement per unit modal displacement, != 0.

    Examples
    --------
    >>> from microslip.dynamics import jenkins
    >>> s = one_mode(100.0, 2.0, 0.0, jenkins(100.0, 5.0))
    >>> round(float(s.stiffness[0, 0]), 3)  # N/m
    789568.352
    """
    f = check_positive("frequency", frequency, "Hz")
    m = check_positive("modal mass", modal_mass, "kg")
    if not (math.isfinite(damping_ratio) and 0.0 <= damping_ratio < 1.0):
        raise ParameterError(f"damping ratio must be in [0, 1), got {damping_ratio!r}")
    if not (math.isfinite(participation) and participation != 0.0):
        raise ParameterError(f"participation must be finite and != 0, got {participation!r}")
    w = 2.0 * np.pi * f
    return Structure(mass=readonly(np.array([[m]])),
                     damping=readonly(np.array([[2.0 * damping_ratio * m * w]])),
                     stiffness=readonly(np.array([[m * w * w]])),
                     joints=(JointLink(joint, np.array([float(participation)])),),
                     output=np.array([1.0]))


def free_frequency(stuck_frequency: float, modal_mass: float, joint: HystereticOperator,
                   participation: float = 1.0) -> float:
    """Natural frequency with the joint removed, Hz, of one mode whose frequency with the
    joint stuck (the small-amplitude limit, as measured) is ``stuck_frequency``.

    The stuck mode has stiffness m (2 pi f_s)^2 = m (2 pi f)^2 + p^2 k_J, with k_J the
    joint's initial stiffness (N/mm, times 1e3 in N/m) and p the participation, so
    f = sqrt(f_s^2 - p^2 k_J / (m (2 pi)^2)), i.e. f_s = f sqrt(1 + p^2 k_J / (m (2 pi f)^2)).

    Examples
    --------
    >>> from microslip.dynamics import jenkins
    >>> f = free_frequency(300.0, 0.5, jenkins(1000.0, 5.0))
    >>> s = one_mode(f, 0.5, 0.0, jenkins(1000.0, 5.0))
    >>> round(float(s.linear_frequencies(stuck=True)[0]), 9)
    300.0
    """
    fs = check_positive("stuck frequency", stuck_frequency, "Hz")
    m = check_positive("modal mass", modal_mass, "kg")
    if not (math.isfinite(participation) and participation != 0.0):
        raise ParameterError(f"participation must be finite and != 0, got {participation!r}")
    k_joint = participation**2 * joint.initial_stiffness / SI_PER_MM
    joint_alone = math.sqrt(k_joint / m) / (2.0 * math.pi)
    if not fs > joint_alone:
        raise ParameterError(f"stuck frequency must be > {joint_alone:.6g} Hz (the joint's "
                             f"stiffness alone on the modal mass), got {fs:g} Hz")
    return math.sqrt(fs * fs - joint_alone * joint_alone)
