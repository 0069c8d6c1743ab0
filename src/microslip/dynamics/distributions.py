"""Iwan operators from distributions: a sampled backbone, Segalman's 4-parameter model.

Both build an :class:`~microslip.dynamics.operators.IwanOperator` whose virgin curve is a
piecewise-linear curve through given nodes, exactly: element i slips at node displacement
``d_i`` and its stiffness is the drop of slope there, the discrete form of rho = -F''.

Units: displacement mm, force N, stiffness N/mm.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..conventions import DEFAULT_ELEMENTS
from ..errors import ParameterError
from ..models import first_loading, macroslip_force
from ..options import ModelOptions
from ..params import ClampParams, check_positive
from .operators import IwanOperator

__all__ = ["CONCAVITY_TOLERANCE", "DEFAULT_ELEMENTS", "clamp_joint", "from_backbone", "iwan4",
           "iwan4_segalman"]


#: Relative slope rise (of the initial slope) tolerated as round-off before a sampled
#: backbone counts as not concave and is refused.
CONCAVITY_TOLERANCE = 1e-9


def from_backbone(name: str, displacement: ArrayLike, force: ArrayLike, *,
                  macroslip_force: float | None = None) -> IwanOperator:
    """The Iwan operator whose virgin curve interpolates ``(displacement, force)`` linearly.

    Parameters
    ----------
    name : str
        Label of the operator.
    displacement, force : array_like, shape (n + 1,)
        Virgin-curve nodes from ``(0, 0)``, strictly increasing, mm and N; the curve must
        be concave (slopes not increasing), with a finite first slope.
    macroslip_force : float, optional
        Force (N) at which the joint slides as a whole, >= ``force[-1]``. The last segment
        is extended with its own slope up to it (linear extrapolation); without it the
        curve saturates at ``force[-1]``.

    Notes
    -----
    Slopes s_j of the segments, s_n = 0 after the last node; element j (j = 1..n) has
    slip displacement d_j and stiffness s_(j-1) - s_j (REFERENCES.md, Iwan representation:
    rho(d) = -F''(d)). Then F(a) = sum_j k_j min(a, d_j) equals the interpolant at every a.

    Examples
    --------
    >>> op = from_backbone("x", [0.0, 1.0, 3.0], [0.0, 2.0, 3.0])
    >>> op.stiffness.tolist(), op.slip.tolist()
    ([1.5, 0.5], [1.0, 3.0])
    """
    d = np.asarray(displacement, dtype=np.float64)
    f = np.asarray(force, dtype=np.float64)
    if d.ndim != 1 or d.shape != f.shape or d.size < 2:
        raise ParameterError("backbone needs 1-D displacement and force of one length >= 2")
    if d[0] != 0.0 or f[0] != 0.0:
        raise ParameterError(f"backbone must start at (0, 0), got ({d[0]!r} mm, {f[0]!r} N)")
    if not (np.all(np.diff(d) > 0.0) and np.all(np.diff(f) > 0.0)):
        raise ParameterError("backbone displacement (mm) and force (N) must increase strictly")
    if macroslip_force is not None and macroslip_force > f[-1]:
        slope = (f[-1] - f[-2]) / (d[-1] - d[-2])
        d = np.append(d, d[-1] + (macroslip_force - f[-1]) / slope)
        f = np.append(f, macroslip_force)
    slope = np.diff(f) / np.diff(d)
    drop = -np.diff(np.append(slope, 0.0))
    if np.any(drop < -CONCAVITY_TOLERANCE * slope[0]):
        j = int(np.argmin(drop))
        raise ParameterError(
            f"backbone is not concave at {d[j + 1]:.6g} mm (slope rises by {-drop[j]:.3g} "
            "N/mm): not representable by parallel Jenkins elements")
    return IwanOperator(name, np.maximum(drop, 0.0), d[1:])


def iwan4(chi: float, phi_max: float, r: float, s: float,
          elements: int = DEFAULT_ELEMENTS) -> IwanOperator:
    """Segalman's 4-parameter Iwan element, discretised into ``elements`` + 1 elements.

    Parameters
    ----------
    chi : float
        Exponent of the slip-displacement density, in (-1, 0].
    phi_max : float
        Largest slip displacement, mm (macroslip at displacement phi_max).
    r : float
        Density coefficient R, N/mm^(2 + chi): rho(phi) = R phi^chi on (0, phi_max).
    s : float
        Stiffness S of the elements that slip at phi_max, N/mm, >= 0.
    elements : int
        Number of bins of (0, phi_max).

    Notes
    -----
    Bin edges e_i = phi_max (i / n)^p with p = 2 / (1 + chi), graded towards the
    integrable singularity at 0. Each bin becomes one element with its stiffness
    k = integral rho and its slip at the centroid integral phi rho / k, so the virgin curve
    F(a) = R a^(chi+2)/(chi+2) + a (R (phi_max^(chi+1) - a^(chi+1))/(chi+1) + S),
    a <= phi_max, is exact at every edge. The dissipation
    below macroslip, W_d = 4 R A^(3+chi) / ((chi+2)(chi+3)) (REFERENCES.md), is approached
    with an error O(n^-2) (the second moment of each bin is not kept).
    """
    if not (math.isfinite(chi) and -1.0 < chi <= 0.0):
        raise ParameterError(f"chi must be in (-1, 0], got {chi!r}")
    phi_max = check_positive("phi_max", phi_max, "mm")
    r = check_positive("R", r, "N/mm^(2+chi)")
    if not (math.isfinite(s) and s >= 0.0):
        raise ParameterError(f"S must be finite and >= 0 N/mm, got {s!r}")
    if not (isinstance(elements, int) and 1 <= elements <= 100_000):
        raise ParameterError(f"elements must be a whole number in [1, 100000], got {elements!r}")
    edges = phi_max * (np.arange(elements + 1) / elements) ** (2.0 / (1.0 + chi))
    m0 = r * np.diff(edges ** (chi + 1.0)) / (chi + 1.0)
    m1 = r * np.diff(edges ** (chi + 2.0)) / (chi + 2.0)
    k = np.append(m0, s)
    phi = np.append(m1 / m0, phi_max)
    if s == 0.0:
        k, phi = k[:-1], phi[:-1]
    return IwanOperator("iwan", k, phi)


def iwan4_segalman(stiffness: float, slip_force: float, chi: float, beta: float,
                   elements: int = DEFAULT_ELEMENTS) -> IwanOperator:
    """:func:`iwan4` from Segalman's physical parameters (K_T, F_S, chi, beta).

    ``stiffness`` K_T (N/mm) is the initial stiffness, ``slip_force`` F_S (N) the
    macroslip force, ``beta`` >= 0 the ratio S / (R phi_max^(chi+1) / (chi+1)).

    Notes
    -----
    With c = (chi+1)/(chi+2) (Segalman 2005): phi_max = F_S (1 + beta) / (K_T (beta + c)),
    R = F_S (chi+1) / (phi_max^(chi+2) (beta + c)), S = F_S beta / (phi_max (beta + c)),
    so that K_T = R phi_max^(chi+1)/(chi+1) + S and F_S = R phi_max^(chi+2)/(chi+2) + S phi_max.
    """
    kt = check_positive("joint stiffness", stiffness, "N/mm")
    fs = check_positive("slip force", slip_force, "N")
    if not (math.isfinite(chi) and -1.0 < chi <= 0.0):
        raise ParameterError(f"chi must be in (-1, 0], got {chi!r}")
    if not (math.isfinite(beta) and beta >= 0.0):
        raise ParameterError(f"beta must be finite and >= 0, got {beta!r}")
    c = (chi + 1.0) / (chi + 2.0)
    phi_max = fs * (1.0 + beta) / (kt * (beta + c))
    r = fs * (chi + 1.0) / (phi_max ** (chi + 2.0) * (beta + c))
    s = fs * beta / (phi_max * (beta + c))
    return iwan4(chi, phi_max, r, s, elements)


def clamp_joint(model: str, params: ClampParams, series_stiffness: float, *,
                elements: int = DEFAULT_ELEMENTS, options: ModelOptions | None = None
                ) -> IwanOperator:
    """The Iwan operator of a microslip model (tip, centre) behind a series spring.

    Parameters
    ----------
    model : str
        A name of :data:`microslip.MODELS`.
    params : ClampParams
        The clamped zone.
    series_stiffness : float
        Stiffness of a spring in series with the clamped zone, N/mm, finite and > 0: the
        bar on a rigid Coulomb foundation has no finite stiffness at zero load
        (F ~ sqrt(d)), so a displacement-driven joint needs one (a contact layer, the
        clamp's own compliance; e.g. a stick slope S (N/mm^3) times width times length).
    elements : int
        Force increments of the model's first loading, one Jenkins element each.
    options : ModelOptions, optional
        Reading of the paper's equations.

    Notes
    -----
    The virgin curve is the model's first loading in ``elements`` equal force steps of
    F_ms / (elements + 1) (F_ms = :func:`microslip.macroslip_force`), with displacement
    d(F) + F / k_s, extended with its last slope to F_ms (:func:`from_backbone`). A Masing
    model behind a linear spring is again a Masing model, so the operator reproduces the
    joint's loops exactly at the nodes, and its nested loops by the extended rules.
    """
    k_s = check_positive("series stiffness", series_stiffness, "N/mm")
    if not (isinstance(elements, int) and 2 <= elements <= 100_000):
        raise ParameterError(f"elements must be a whole number in [2, 100000], got {elements!r}")
    f_ms = macroslip_force(model, params, options)
    bb = first_loading(model, params, f_ms * elements / (elements + 1), elements, options)
    return from_backbone(model, bb.displacement + bb.force / k_s, bb.force,
                         macroslip_force=f_ms)
