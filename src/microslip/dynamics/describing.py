"""The describing function of a joint: amplitude-dependent stiffness, damping and loss.

For a harmonic relative displacement x = A cos(theta) the joint's periodic force is
projected on its first harmonic, f_1 = A (K_eq cos(theta) - D_eq sin(theta)) = K_eq x +
(D_eq / w) dx/dt with theta = w t: K_eq is the equivalent stiffness, D_eq the equivalent
(hysteretic) damping stiffness, D_eq / w the equivalent viscous damping.

Units: displacement mm, force N, stiffness N/mm, energy N·mm.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from ..errors import ParameterError
from ..named import result
from .operators import HystereticOperator

__all__ = ["DEFAULT_SAMPLES", "DescribingFunction", "amplitude_for_force",
           "describing_function"]

#: Time samples per period of the describing function's quadrature.
DEFAULT_SAMPLES = 512


@result
class DescribingFunction:
    """First-harmonic equivalent stiffness and damping of a joint versus amplitude.

    Attributes
    ----------
    joint : str
        Name of the operator.
    amplitude : ndarray, shape (n,)
        Displacement amplitude A, mm.
    force : ndarray, shape (n,)
        Force amplitude F(A) on the virgin curve (the peak force of the cycle), N.
    stiffness : ndarray, shape (n,)
        Equivalent stiffness K_eq, N/mm.
    damping : ndarray, shape (n,)
        Equivalent damping D_eq (the quadrature part of the force over A), N/mm.
    dissipated_energy : ndarray, shape (n,)
        Energy dissipated per cycle W_d = pi D_eq A^2, N·mm.
    loss_factor : ndarray, shape (n,)
        eta = W_d / (2 pi U) with U = K_eq A^2 / 2, i.e. D_eq / K_eq.
    samples : int
        Time samples per period of the quadrature.
    """

    joint: str
    amplitude: np.ndarray
    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    dissipated_energy: np.ndarray
    loss_factor: np.ndarray
    samples: int


def describing_function(joint: HystereticOperator, amplitude: ArrayLike,
                        samples: int = DEFAULT_SAMPLES) -> DescribingFunction:
    """K_eq(A), D_eq(A), W_d(A) and eta(A) of ``joint`` at displacement amplitudes (mm).

    Notes
    -----
    With theta_j = 2 pi j / N and f_j the closed periodic force at x_j = A cos(theta_j)
    (N = ``samples``): K_eq = (2 / (N A)) sum f_j cos(theta_j) and
    D_eq = -(2 / (N A)) sum f_j sin(theta_j), the rectangle rule of the Fourier integrals
    (taken with an FFT). W_d = closed integral f dx = pi A^2 D_eq exactly, because x has
    one harmonic. The force of an Iwan operator has slope kinks where elements start to
    slip, so the quadrature error is O(N^-2).
    """
    a = _amplitudes(amplitude)
    n = _samples(samples)
    theta = 2.0 * np.pi * np.arange(n) / n
    first = np.empty(a.size, dtype=np.complex128)
    for i, ai in enumerate(a):
        f, _ = joint.periodic_force(ai * np.cos(theta))
        first[i] = np.fft.rfft(f)[1]
    k_eq = 2.0 * first.real / (n * a)
    d_eq = 2.0 * first.imag / (n * a)
    return DescribingFunction(
        joint=joint.name,
        amplitude=a,
        force=np.asarray(joint.backbone_force(a), dtype=np.float64),
        stiffness=k_eq,
        damping=d_eq,
        dissipated_energy=np.pi * d_eq * a**2,
        loss_factor=d_eq / k_eq,
        samples=n,
    )


def amplitude_for_force(joint: HystereticOperator, force: ArrayLike) -> NDArray[np.float64]:
    """Displacement amplitudes (mm) whose virgin-curve force is ``force`` (N).

    The virgin curve of a Masing-type joint gives the peak force of the symmetric cycle
    of that amplitude. Raises :class:`ParameterError` at or above the joint's macroslip
    force, where no amplitude carries the force.
    """
    f = np.asarray(force, dtype=np.float64).reshape(-1)
    if not (f.size and np.all(np.isfinite(f)) and np.all(f > 0.0)):
        raise ParameterError("force amplitudes must be finite and > 0 N")
    out = np.empty(f.size)
    for i, fi in enumerate(f):
        out[i] = _invert_backbone(joint, float(fi))
    return out


def _invert_backbone(joint: HystereticOperator, force: float) -> float:
    def gap(a: float) -> float:
        return float(joint.backbone_force(np.array([a]))[0]) - force

    hi = force / joint.initial_stiffness
    for _ in range(200):
        if gap(hi) > 0.0:
            return float(brentq(gap, 0.0, hi, xtol=1e-15 * hi, rtol=1e-15))
        hi *= 2.0
    limit = float(joint.backbone_force(np.array([hi]))[0])
    raise ParameterError(f"force amplitude must be below the joint's macroslip force "
                         f"{limit:.6g} N, got {force:.6g} N")


def _amplitudes(amplitude: ArrayLike) -> NDArray[np.float64]:
    a = np.asarray(amplitude, dtype=np.float64).reshape(-1)
    if not (a.size and np.all(np.isfinite(a)) and np.all(a > 0.0)):
        raise ParameterError("displacement amplitudes must be finite and > 0 mm")
    return a


def _samples(samples: int) -> int:
    if not (isinstance(samples, int) and 8 <= samples <= 1 << 20):
        raise ParameterError(f"samples must be a whole number in [8, 1048576], got {samples!r}")
    return samples


