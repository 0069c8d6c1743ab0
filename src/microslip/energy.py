"""Dissipated energy, strain energy and loss factor of a hysteresis loop (Eqs 21-23).

The loss factor eta = W_d / (2 pi U) depends on what U is; for a quadratic virgin curve
the four definitions below give eta = 4/(3 pi), 1/pi, 4/(5 pi) and 2/pi. The default is
``secant``: U = F0 d0 / 2, the peak energy of the equivalent linear spring with the secant
stiffness F0/d0 — the convention of equivalent linearisation, which is what a user needs to
put a modal loss factor into a linear model. The paper's Eq. 22, read as an integral along
the loaded branch of the loop from F = 0 to the peak, is ``branch``.

Two ways in, one set of definitions:

* any loop (a finite-element loop, the planar resultant): :func:`damping_from_loop`
  integrates the sampled loop (trapezoidal rule) by the functions of :data:`STRAIN_ENERGY`;
* a Masing loop completed from a model's backbone (:func:`damping`, the batch engine): the
  same integrals over the 2n + 1 loop points reduce to sums accumulated along the first
  loading, :func:`masing_energies` (compiled, in :mod:`microslip.models.masing` below the
  models; the batch kernels call it per case and :func:`damping_from_backbone` once). The
  two agree to rounding (tested).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .conventions import check_choice
from .errors import ParameterError
from .models.dispatch import kernel
from .models.masing import backbone_sums, masing_energies
from .options import ModelOptions
from .params import ClampParams
from .results import Backbone, DampingResult, HysteresisLoop

if TYPE_CHECKING:
    from .models.contact import Contact

__all__ = [
    "DEFAULT_STRAIN_ENERGY",
    "STRAIN_ENERGY",
    "STRAIN_ENERGY_CODES",
    "backbone_sums",
    "damping",
    "damping_from_backbone",
    "damping_from_loop",
    "dissipated_energy",
    "loop_work",
    "loss_factor",
    "masing_energies",
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


#: Integer code of each definition, as the compiled :func:`masing_energies` takes it.
STRAIN_ENERGY_CODES: dict[str, int] = {k: i for i, k in enumerate(STRAIN_ENERGY)}


def _kind_name(kind: str) -> str:
    _check_kind(kind)
    return kind


def _check_kind(kind: str) -> Callable[[HysteresisLoop, Backbone | None], float]:
    return STRAIN_ENERGY[check_choice("strain-energy definition", kind, STRAIN_ENERGY)][0]


def strain_energy(loop: HysteresisLoop, backbone: Backbone | None = None,
                  kind: str = DEFAULT_STRAIN_ENERGY) -> float:
    """U by the named definition (see :data:`STRAIN_ENERGY`), N·mm."""
    return _check_kind(kind)(loop, backbone)


def loss_factor(dissipated: float, strain: float) -> float:
    """eta = W_d / (2 pi U) (Eq. 23)."""
    if not strain > 0.0:
        raise ParameterError(f"strain energy must be > 0 N·mm to form a loss factor, got {strain}")
    return dissipated / (2.0 * math.pi * strain)


#: The function :func:`strain_energy`, for the functions whose keyword of that name hides it.
_strain_energy_of = strain_energy


def damping_from_loop(loop: HysteresisLoop, backbone: Backbone | None = None,
                      strain_energy: str = DEFAULT_STRAIN_ENERGY) -> DampingResult:
    """W_d, U and eta of a loop (from any source); ``strain_energy`` names U
    (:data:`STRAIN_ENERGY`)."""
    w = dissipated_energy(loop)
    u = _strain_energy_of(loop, backbone, strain_energy)
    return DampingResult(
        dissipated_energy=w,
        strain_energy=u,
        strain_energy_kind=strain_energy,
        loss_factor=loss_factor(w, u),
        amplitude=loop.amplitude,
        peak_displacement=loop.peak_displacement,
        loop=loop,
        backbone=backbone,
    )


def damping_from_backbone(backbone: Backbone,
                          strain_energy: str = DEFAULT_STRAIN_ENERGY) -> DampingResult:
    """W_d, U and eta of the Masing loop of a model's backbone (:func:`masing_energies`).

    The loop is completed by :func:`microslip.hysteresis.masing_loop` and kept in the result;
    the energies are the batch engine's, bit for bit.
    """
    from .hysteresis import masing_loop

    code = STRAIN_ENERGY_CODES[_kind_name(strain_energy)]
    f = np.ascontiguousarray(backbone.force, dtype=np.float64)
    d = np.ascontiguousarray(backbone.displacement, dtype=np.float64)
    n = f.shape[0] - 1
    if n < 1:
        raise ParameterError("a Masing loop needs a backbone of at least 1 increment")
    if not (d[-1] > 0.0 and f[-1] > 0.0):
        raise ParameterError(
            f"amplitude {f[-1]:g} N gives a peak displacement of {d[-1]:g} mm: too small to form "
            "a loop in double precision; give a larger amplitude")
    q, q_k0, d_km1, d_k0, k0 = kernel(backbone_sums, n)(f, d)
    w, u, _ = masing_energies(f[-1], d[-1], q, q_k0, d_km1, d_k0, (k0 - 1) / n, k0 / n,
                              float(backbone.stored_energy[-1]), code)
    loop = masing_loop(backbone)
    return DampingResult(
        dissipated_energy=float(w),
        strain_energy=float(u),
        strain_energy_kind=strain_energy,
        loss_factor=loss_factor(float(w), float(u)),
        amplitude=loop.amplitude,
        peak_displacement=loop.peak_displacement,
        loop=loop,
        backbone=backbone,
    )


def damping(model: str, params: ClampParams, amplitude: float, increments: int = 1000,
            options: ModelOptions | None = None,
            strain_energy: str = DEFAULT_STRAIN_ENERGY,
            contact: Contact | None = None) -> DampingResult:
    """Backbone, Masing loop, W_d, U and eta of one model at one amplitude; ``strain_energy``
    names U (:data:`STRAIN_ENERGY`, default secant: the one keyword and default of loop,
    planar and sweep, docs/interpretation.md section 5).

    ``contact`` (:class:`~microslip.models.contact.Contact`): the interface under the bar;
    default the paper's rigid foundation. On a contact that is not rigid the ``stored``
    strain energy (the bar's own elastic energy) is not defined and is refused.

    Examples
    --------
    >>> from microslip import ModelOptions, preset
    >>> r = damping("tip", preset("table1"), 267.0, 2000, ModelOptions.uncorrected())
    >>> round(r.loss_factor * 3 * math.pi / 4, 5)  # secant: eta = 4/(3 pi) exactly
    1.0
    """
    from .models import first_loading
    from .models.contact import check_strain_energy

    _check_kind(strain_energy)
    check_strain_energy(contact, strain_energy)
    bb = first_loading(model, params, amplitude, increments, options, contact)
    return damping_from_backbone(bb, strain_energy)
