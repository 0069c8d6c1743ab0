"""Exact closed-form references (``shared/REFERENCES.md``), for users and tests.

Units: force N, length mm, modulus MPa, energy N·mm. ``ea`` is the axial stiffness E A (N),
``q`` the limiting friction force per unit length mu F_N / L (N/mm).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "LOSS_FACTOR_QUADRATIC",
    "cattaneo_mindlin_displacement",
    "cattaneo_mindlin_dissipation",
    "cattaneo_mindlin_slip_radius",
    "centre_displacement",
    "centre_dissipated_energy",
    "centre_slip_length",
    "centre_stored_energy",
    "contact_modulus",
    "hertz_approach",
    "hertz_contact_radius",
    "hertz_peak_pressure",
    "hertz_pressure",
    "jenkins_1d_dissipation",
    "jenkins_2d_circular_dissipation",
    "masing_dissipation",
    "mindlin_compliance",
    "shear_layer_tip",
    "tip_displacement",
    "tip_dissipated_energy",
    "tip_slip_length",
    "tip_stored_energy",
    "tip_unloading_displacement",
]

Float = float | NDArray[np.float64]

#: Loss factor eta = W_d / (2 pi U) of any quadratic virgin curve, by definition of U.
LOSS_FACTOR_QUADRATIC: dict[str, float] = {
    "stored": 2.0 / math.pi,
    "secant": 4.0 / (3.0 * math.pi),
    "backbone": 1.0 / math.pi,
    "branch": 4.0 / (5.0 * math.pi),
}


# -- tip-loaded bar on a rigid Coulomb foundation (Goodman & Klumpp 1956) ------------------
def tip_slip_length(force: ArrayLike, q: float) -> Float:
    """a = F / q (paper's Eq. 3), mm."""
    return np.asarray(force, dtype=float) / q


def tip_displacement(force: ArrayLike, ea: float, q: float) -> Float:
    """Virgin curve d = F^2 / (2 E A q), mm."""
    f = np.asarray(force, dtype=float)
    return f * f / (2.0 * ea * q)


def tip_unloading_displacement(force: ArrayLike, amplitude: float, ea: float, q: float) -> Float:
    """Descending branch d = d0 - (F0 - F)^2 / (4 E A q), mm."""
    f = np.asarray(force, dtype=float)
    return tip_displacement(amplitude, ea, q) - (amplitude - f) ** 2 / (4.0 * ea * q)


def tip_dissipated_energy(amplitude: float, ea: float, q: float) -> float:
    """W_d = 2 F0^3 / (3 E A q), N·mm."""
    return 2.0 * amplitude**3 / (3.0 * ea * q)


def tip_stored_energy(amplitude: float, ea: float, q: float) -> float:
    """Elastic energy in the bar at peak, integral N^2/(2EA) dx = F0^3 / (6 E A q), N·mm."""
    return amplitude**3 / (6.0 * ea * q)


# -- centre-loaded bar on a rigid Coulomb foundation ---------------------------------------
def centre_slip_length(force: ArrayLike, q: float) -> Float:
    """Slip length in each half, a = F / (2 q), mm."""
    return np.asarray(force, dtype=float) / (2.0 * q)


def centre_displacement(force: ArrayLike, ea: float, q: float) -> Float:
    """Displacement of the loaded section d = F^2 / (8 E A q), mm."""
    f = np.asarray(force, dtype=float)
    return f * f / (8.0 * ea * q)


def centre_dissipated_energy(amplitude: float, ea: float, q: float) -> float:
    """W_d = F0^3 / (6 E A q), N·mm."""
    return amplitude**3 / (6.0 * ea * q)


def centre_stored_energy(amplitude: float, ea: float, q: float) -> float:
    """Elastic energy in both halves at peak, 2 (F0/2)^2 a / (6 E A) = F0^3 / (24 E A q)."""
    return amplitude**3 / (24.0 * ea * q)


# -- Masing's rule in general ---------------------------------------------------------------
def masing_dissipation(amplitude: float, peak_displacement: float, backbone_integral: float
                       ) -> float:
    """W_d = 4 F0 d0 - 8 integral_0^F0 g(F) dF for any Masing system, N·mm."""
    return 4.0 * amplitude * peak_displacement - 8.0 * backbone_integral


# -- bar on an elastic shear layer (Menq, Bielak & Griffin 1986) ----------------------------
def shear_layer_tip(slip_length: ArrayLike, ea: float, k: float, q: float, length: float
                    ) -> tuple[Float, Float]:
    """Tip force and displacement of a bar on an elastic-plastic shear layer.

    Parameters
    ----------
    slip_length : array_like
        a in [0, L], mm.
    ea : float
        E A, N. ``k``: shear-layer stiffness per unit length, N/mm^2; ``q``: N/mm;
        ``length``: L, mm.

    Returns
    -------
    force, displacement
        F(a) = q a + (q/lambda) tanh(lambda (L - a)) in N and
        d(a) = q/k + (F a - q a^2 / 2) / (E A) in mm, with lambda = sqrt(k / (E A)).
    """
    a = np.asarray(slip_length, dtype=float)
    lam = math.sqrt(k / ea)
    f = q * a + (q / lam) * np.tanh(lam * (length - a))
    d = q / k + (f * a - 0.5 * q * a * a) / ea
    return f, d


# -- Hertz (sphere or paraboloid z = r^2 / (2 R) on a flat, normal load P) -----------------
def contact_modulus(modulus: float, poisson_ratio: float, modulus2: float = math.inf,
                    poisson_ratio2: float = 0.0) -> float:
    """E*, MPa: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; the second body rigid by default
    (E* = E / (1 - nu^2)).

    >>> round(contact_modulus(70000.0, 0.45), 3)
    87774.295
    >>> contact_modulus(200e3, 0.3, 200e3, 0.3) == contact_modulus(200e3, 0.3) / 2
    True
    """
    inv = (1.0 - poisson_ratio**2) / modulus
    if math.isfinite(modulus2):
        inv += (1.0 - poisson_ratio2**2) / modulus2
    return 1.0 / inv


def hertz_contact_radius(force: float, radius: float, e_star: float) -> float:
    """Hertz's contact radius a = (3 P R / (4 E*))^(1/3), mm (``radius`` R of the sphere or
    of the paraboloid's curvature, mm; ``e_star`` :func:`contact_modulus`).

    >>> round(hertz_contact_radius(500.0, 100.0, contact_modulus(70000.0, 0.45)), 4)
    0.7532
    """
    return (3.0 * force * radius / (4.0 * e_star)) ** (1.0 / 3.0)


def hertz_approach(force: float, radius: float, e_star: float) -> float:
    """The approach of distant points delta = a^2 / R, mm.

    >>> round(hertz_approach(500.0, 100.0, 87774.3), 5)
    0.00567
    """
    return hertz_contact_radius(force, radius, e_star) ** 2 / radius


def hertz_peak_pressure(force: float, radius: float, e_star: float) -> float:
    """p0 = 3 P / (2 pi a^2), MPa (the mean pressure is 2 p0 / 3).

    >>> round(hertz_peak_pressure(500.0, 100.0, 87774.3), 1)
    420.9
    """
    a = hertz_contact_radius(force, radius, e_star)
    return 3.0 * force / (2.0 * math.pi * a * a)


def hertz_pressure(r: ArrayLike, force: float, radius: float, e_star: float) -> Float:
    """p(r) = p0 sqrt(1 - r^2 / a^2) inside the contact, 0 outside, MPa.

    >>> float(hertz_pressure(0.0, 500.0, 100.0, 87774.3)) == hertz_peak_pressure(
    ...     500.0, 100.0, 87774.3)
    True
    >>> float(hertz_pressure(1.0, 500.0, 100.0, 87774.3))
    0.0
    """
    a = hertz_contact_radius(force, radius, e_star)
    x = np.asarray(r, dtype=float) / a
    return hertz_peak_pressure(force, radius, e_star) * np.sqrt(np.clip(1.0 - x * x, 0.0, None))


# -- Cattaneo-Mindlin -----------------------------------------------------------------------
def mindlin_compliance(modulus: float, poisson_ratio: float, modulus2: float = math.inf,
                       poisson_ratio2: float = 0.0) -> float:
    """K = (2 - nu1)/G1 + (2 - nu2)/G2, 1/MPa, G = E / (2 (1 + nu)); the second body rigid
    by default (K = (2 - nu)/G).

    >>> round(mindlin_compliance(70000.0, 0.45) * 1e6, 3)
    64.214
    """
    out = (2.0 - poisson_ratio) * 2.0 * (1.0 + poisson_ratio) / modulus
    if math.isfinite(modulus2):
        out += (2.0 - poisson_ratio2) * 2.0 * (1.0 + poisson_ratio2) / modulus2
    return out


def cattaneo_mindlin_slip_radius(q_force: ArrayLike, mu: float, p: float, radius: float
                                 ) -> Float:
    """The stick radius c = a (1 - Q/(mu P))^(1/3) under a tangential force Q rising from 0
    (slip in c < r < a), mm; ``radius`` is Hertz's a.

    >>> round(float(cattaneo_mindlin_slip_radius(125.0, 0.5, 500.0, 0.75)), 4)
    0.5953
    """
    x = np.asarray(q_force, dtype=float) / (mu * p)
    return radius * np.cbrt(1.0 - x)


def cattaneo_mindlin_displacement(q_force: ArrayLike, mu: float, p: float, radius: float,
                                  compliance: float) -> Float:
    """d = (3 mu P K / (16 a)) [1 - (1 - Q/(mu P))^(2/3)], K = (2-nu1)/G1 + (2-nu2)/G2."""
    x = np.asarray(q_force, dtype=float) / (mu * p)
    return 3.0 * mu * p * compliance / (16.0 * radius) * (1.0 - (1.0 - x) ** (2.0 / 3.0))


def cattaneo_mindlin_dissipation(amplitude: float, mu: float, p: float, radius: float,
                                 compliance: float) -> float:
    """Mindlin's W_d per cycle at tangential amplitude Q*, N·mm (``radius`` is Hertz's a,
    ``compliance`` :func:`mindlin_compliance`). Small amplitudes: W_d ~ Q*^3 K / (36 a mu P).

    >>> k = mindlin_compliance(70000.0, 0.45)
    >>> round(cattaneo_mindlin_dissipation(125.0, 0.5, 500.0, 0.7532, k), 6)
    0.028148
    >>> w = cattaneo_mindlin_dissipation(1.0, 0.5, 500.0, 0.75, k)
    >>> round(w / (k / (36 * 0.75 * 250.0)), 2)
    1.0
    """
    x = amplitude / (mu * p)
    return (9.0 * mu**2 * p**2 * compliance / (10.0 * radius)) * (
        1.0 - (1.0 - x) ** (5.0 / 3.0) - (5.0 * x / 6.0) * (1.0 + (1.0 - x) ** (2.0 / 3.0))
    )


# -- Jenkins element -------------------------------------------------------------------------
def jenkins_1d_dissipation(amplitude: float, slip_force: float, stiffness: float) -> float:
    """Harmonic displacement amplitude A: W_d = 4 f_s (A - f_s/k) when A > f_s/k, else 0."""
    ds = slip_force / stiffness
    return 4.0 * slip_force * max(amplitude - ds, 0.0)


def jenkins_2d_circular_dissipation(radius: float, slip_force: float, stiffness: float) -> float:
    """Circular orbit of radius A, circular Coulomb limit: W_d = 2 pi f_s sqrt(A^2 - d_s^2)."""
    ds = slip_force / stiffness
    return 2.0 * math.pi * slip_force * math.sqrt(max(radius**2 - ds**2, 0.0))
