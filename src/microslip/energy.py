"""Dissipated energy, strain energy and loss factor of a hysteresis loop (Eqs 21-23).

The loss factor eta = W_d / (2 pi U) depends on what U is; for a quadratic virgin curve
the four definitions below give eta = 4/(3 pi), 1/pi, 4/(5 pi) and 2/pi. The default is
``secant``: U = F0 d0 / 2, the peak energy of the equivalent linear spring with the secant
stiffness F0/d0 — the convention of equivalent linearisation, which is what a user needs to
put a modal loss factor into a linear model. The paper's Eq. 22, read as an integral along
the loaded branch of the loop from F = 0 to the peak, is ``branch``.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from .errors import ParameterError
from .results import Backbone, DampingResult, HysteresisLoop

__all__ = [
    "DEFAULT_STRAIN_ENERGY",
    "STRAIN_ENERGY",
    "damping",
    "damping_from_loop",
    "dissipated_energy",
    "loop_work",
    "loss_factor",
    "strain_energy",
]

DEFAULT_STRAIN_ENERGY = "secant"


def loop_work(force: ArrayLike, displacement: ArrayLike) -> float:
    """Work done by the force along a sampled path, integral F d(delta), trapezoidal, N·mm."""
    f = np.asarray(force, dtype=float)
    d = np.asarray(displacement, dtype=float)
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(d)))


def dissipated_energy(loop: HysteresisLoop) -> float:
    """W_d, the closed integral of F d(delta) around the loop (Eq. 21), N·mm.

    Positive for a loop traversed the way hysteresis goes (descending branch at larger
    displacement than the ascending one).
    """
    return loop_work(loop.force, loop.displacement)


def _secant(loop: HysteresisLoop, backbone: Backbone | None) -> float:
    """F0 d0 / 2 with F0, d0 half the peak-to-peak force and displacement: the same as at the
    peak for a Masing loop, and blind to a rigid offset of an FE loop (clamping step)."""
    return 0.5 * loop.amplitude * loop.peak_displacement


def _backbone(loop: HysteresisLoop, backbone: Backbone | None) -> float:
    if backbone is None:
        raise ParameterError("strain energy 'backbone' needs the virgin curve (a Backbone)")
    return loop_work(backbone.force, backbone.displacement)


def _branch(loop: HysteresisLoop, backbone: Backbone | None) -> float:
    """Eq. 22: integral of F d(delta) along the loading branch from F = 0 to the peak."""
    f = np.asarray(loop.force, dtype=float)
    d = np.asarray(loop.displacement, dtype=float)
    i_min = int(np.argmin(f))
    i_max = i_min + int(np.argmax(f[i_min:]))
    fa, da = f[i_min : i_max + 1], d[i_min : i_max + 1]
    j = int(np.argmax(fa >= 0.0))  # first sample at or above zero force
    if j == 0:
        return loop_work(fa, da)
    s = -fa[j - 1] / (fa[j] - fa[j - 1])
    d_zero = da[j - 1] + s * (da[j] - da[j - 1])
    return loop_work(np.r_[0.0, fa[j:]], np.r_[d_zero, da[j:]])


def _stored(loop: HysteresisLoop, backbone: Backbone | None) -> float:
    if backbone is None:
        raise ParameterError("strain energy 'stored' needs the model's Backbone")
    return float(backbone.stored_energy[-1])


#: Definitions of the strain energy U in eta = W_d / (2 pi U): name -> (function, meaning).
STRAIN_ENERGY: dict[str, tuple[Callable[[HysteresisLoop, Backbone | None], float], str]] = {
    "secant": (_secant, "F0 d0 / 2, energy of the secant linear spring at the peak"),
    "backbone": (_backbone, "integral of F dd along the virgin curve from 0 to the peak"),
    "branch": (_branch, "paper's Eq. 22: integral of F dd along the loading branch, F = 0 to peak"),
    "stored": (_stored, "elastic energy held in the bar at peak load, integral N^2/(2EA) dx"),
}


def _check_kind(kind: str) -> Callable[[HysteresisLoop, Backbone | None], float]:
    try:
        return STRAIN_ENERGY[kind][0]
    except (KeyError, TypeError):
        raise ParameterError(
            f"unknown strain-energy definition {kind!r}; choose one of {', '.join(STRAIN_ENERGY)}"
        ) from None


def strain_energy(loop: HysteresisLoop, backbone: Backbone | None = None,
                  kind: str = DEFAULT_STRAIN_ENERGY) -> float:
    """U by the named definition (see :data:`STRAIN_ENERGY`), N·mm."""
    return _check_kind(kind)(loop, backbone)


def loss_factor(dissipated: float, strain: float) -> float:
    """eta = W_d / (2 pi U) (Eq. 23)."""
    if not strain > 0.0:
        raise ParameterError(f"strain energy must be > 0 N·mm to form a loss factor, got {strain}")
    return dissipated / (2.0 * math.pi * strain)


def damping_from_loop(loop: HysteresisLoop, backbone: Backbone | None = None,
                      strain_energy_kind: str = DEFAULT_STRAIN_ENERGY) -> DampingResult:
    """W_d, U and eta of a loop (from any source)."""
    w = dissipated_energy(loop)
    u = strain_energy(loop, backbone, strain_energy_kind)
    return DampingResult(
        dissipated_energy=w,
        strain_energy=u,
        strain_energy_kind=strain_energy_kind,
        loss_factor=loss_factor(w, u),
        amplitude=loop.amplitude,
        peak_displacement=loop.peak_displacement,
        loop=loop,
        backbone=backbone,
    )


def damping(model: str, params: object, amplitude: float, increments: int = 1000,
            options: object = None, strain_energy_kind: str = DEFAULT_STRAIN_ENERGY
            ) -> DampingResult:
    """Backbone, Masing loop, W_d, U and eta of one model at one amplitude.

    Examples
    --------
    >>> from microslip import ModelOptions, preset
    >>> r = damping("tip", preset("table1"), 267.0, 2000, ModelOptions.uncorrected())
    >>> round(r.loss_factor * 3 * math.pi / 4, 5)  # secant: eta = 4/(3 pi) exactly
    1.0
    """
    from .hysteresis import masing_loop
    from .models import first_loading

    _check_kind(strain_energy_kind)
    bb = first_loading(model, params, amplitude, increments, options)  # type: ignore[arg-type]
    return damping_from_loop(masing_loop(bb), bb, strain_energy_kind)
