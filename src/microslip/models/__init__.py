"""The paper's two incremental 1-D microslip models and the registry that names them.

Every caller that needs to know something model-specific asks :data:`MODELS`; nothing
outside this package compares a model's name with a string. Adding a model (a Menq
shear-layer bar, a pressure law q(x), a Jenkins or Iwan element) means writing its module
and adding one :class:`ModelSpec` entry, which must provide:

* ``name``, ``label`` (for headers) and ``equations`` (the paper's equation numbers);
* ``domains``: the names of its slip domains (one column of a Backbone each);
* ``load_case``: where a finite-element model applies the force (a key of the load-case
  registry :mod:`microslip.loading`: ``"tip"`` or ``"centre"``);
* ``macroslip_factor(options)``: the macroslip force as a multiple of mu F_N;
* ``reading(options)``: the name of the reading of the paper it follows, or None;
* ``backbone``: a kernel (``@jit``) recording the first loading of one case, with the
  signature of :func:`~microslip.models.tip.tip_backbone` (the seven ClampParams fields
  as numbers, then the three :attr:`ModelOptions.codes`);
* ``batch_kernel``: a compiled function (loaded on first use) running many cases with the
  signature of :func:`~microslip.models.batch_kernels.tip_kernel`; both call the model's one scalar
  step function (state in, state out, a per-case constants tuple), so the physics is
  written once;
* ``layer_backbone`` and ``layer_kernel``: the same two on a contact (shear layer and
  pressure law, :mod:`~microslip.models.layered`), taking after the options' codes the
  contact's :attr:`~microslip.models.contact.Contact.kernel_args`; both call the model's one
  compiled layer step;
* ``stored_energy``: the kernel of the elastic energy of a state (what strain energy ``stored``
  reports);
* ``exact``: the closed forms of its rigid-foundation limit (:class:`RigidLimit`).

The step functions return flat tuples (state first, then what is observed): numba's parallel
analysis fails on a nested tuple returned by a function inlined in ``prange``.

**Plain and compiled, one text** (issue 27). The kernels are plain Python functions marked
``@jit`` (:mod:`._jit`; their modules do not import numba). The batch kernels and long loops
run their compiled copies (:mod:`.compiled`, numba's on-disk cache stamped with the whole
folder, :mod:`microslip._kernelcache`, so that a kernel inlining an edited step is rebuilt,
never loaded stale); a short single loop runs the plain functions, which is cheaper than
loading numba (:func:`kernel`, :data:`PLAIN_STEPS`, :mod:`.dispatch`). The two agree bit for bit.

This package may import ``closedform``, ``options``, ``params``, ``results``, ``named``,
``errors`` and (:mod:`.compiled`, :mod:`.batch_kernels`) ``_kernelcache``; never ``energy``
(it imports the models; the Masing sums the kernels share with it are :mod:`.masing`,
here), ``batch``, ``planar``, the FE code or the command line.

>>> from microslip import preset, first_loading, ModelOptions
>>> b = first_loading("tip", preset("table1"), 267.0, increments=100,
...                   options=ModelOptions.uncorrected())
>>> p = preset("table1")
>>> round(b.peak_displacement / (267.0**2 / (2 * p.axial_stiffness * p.friction_per_length)), 12)
1.0
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import closedform
from ..errors import MacroslipError, ParameterError
from ..options import ModelOptions
from ..params import ClampParams, check_amplitude
from ..results import Backbone
from .centre import centre_backbone, centre_step, centre_stored_energy
from .contact import DEFAULT_CONTACT, Contact, check_reading
from .dispatch import LAYER_STEP, PLAIN_STEPS, kernel
from .layered import centre_layer_backbone, tip_layer_backbone
from .tip import tip_backbone, tip_step, tip_stored_energy

__all__ = [
    "DEFAULT_CONTACT",
    "LAYER_STEP",
    "MAX_INCREMENTS",
    "MAX_STRAIN",
    "MODELS",
    "PLAIN_STEPS",
    "Contact",
    "ModelSpec",
    "RigidLimit",
    "centre_step",
    "check_increments",
    "check_small_strain",
    "first_loading",
    "get_model",
    "kernel",
    "macroslip_force",
    "tip_step",
]

#: Upper bound on the number of increments of one backbone (memory guard).
MAX_INCREMENTS = 10_000_000

#: Largest mean axial strain F0 / (E w t) of the clamped zone the models accept. They are
#: small-strain elastic bars whose Poisson and length updates are first-order terms; far
#: beyond any elastic metal strain (~0.5 %) those terms stop being small, and at strains
#: above about 10 (E = 1000 MPa on a 1 mm^2 section, F0 = 20 kN) the loop turned inside out
#: (negative W_d). 10 % keeps every physical clamp and refuses the nonsense.
MAX_STRAIN = 0.1


@dataclass(frozen=True)
class RigidLimit:
    """Closed forms of a model with both updates off (bar on a rigid Coulomb foundation).

    Each takes ``(force or amplitude, ea, q)`` (``slip_length`` only ``(force, q)``) with
    ea = E A in N and q = mu F_N / L in N/mm; see :mod:`microslip.closedform`.
    """

    displacement: Callable[..., Any]
    slip_length: Callable[..., Any]
    dissipated_energy: Callable[..., float]
    stored_energy: Callable[..., float]


@dataclass(frozen=True)
class ModelSpec:
    """One incremental model: everything a caller may need to know about it."""

    name: str
    label: str
    equations: str
    domains: tuple[str, ...]
    load_case: str
    #: Macroslip force as a multiple of mu F_N, for the reading in the options.
    macroslip_factor: Callable[[ModelOptions], float]
    #: Name of the reading of the paper the model follows (None: only one reading).
    reading: Callable[[ModelOptions], str | None]
    backbone: Callable[..., tuple[np.ndarray, ...]]
    layer_backbone: Callable[..., tuple[np.ndarray, ...]]
    stored_energy: Callable[..., float]
    exact: RigidLimit

    @property
    def batch_kernel(self) -> Callable[..., None]:
        """The compiled batch kernel (:mod:`.batch_kernels`; loads numba on first use)."""
        from .batch_kernels import BATCH_KERNELS
        return BATCH_KERNELS[self.name][0]

    @property
    def layer_kernel(self) -> Callable[..., None]:
        """The compiled batch kernel on a contact (:mod:`.batch_kernels`)."""
        from .batch_kernels import BATCH_KERNELS
        return BATCH_KERNELS[self.name][1]


def _one(opt: ModelOptions) -> float:
    return 1.0


def _no_reading(opt: ModelOptions) -> str | None:
    return None


def _centre_factor(opt: ModelOptions) -> float:
    return 1.0 if opt.centre == "physical" else 2.0


def _centre_reading(opt: ModelOptions) -> str | None:
    return opt.centre


MODELS: dict[str, ModelSpec] = {
    "tip": ModelSpec(
        name="tip",
        label="tip-loaded bar",
        equations="Eqs 2-10",
        domains=("tip",),
        load_case="tip",
        macroslip_factor=_one,
        reading=_no_reading,
        backbone=tip_backbone,
        layer_backbone=tip_layer_backbone,
        stored_energy=tip_stored_energy,
        exact=RigidLimit(closedform.tip_displacement, closedform.tip_slip_length,
                         closedform.tip_dissipated_energy, closedform.tip_stored_energy),
    ),
    "centre": ModelSpec(
        name="centre",
        label="centre-loaded bar",
        equations="Eqs 11-18",
        domains=("tension", "compression"),
        load_case="centre",
        macroslip_factor=_centre_factor,
        reading=_centre_reading,
        backbone=centre_backbone,
        layer_backbone=centre_layer_backbone,
        stored_energy=centre_stored_energy,
        exact=RigidLimit(closedform.centre_displacement, closedform.centre_slip_length,
                         closedform.centre_dissipated_energy, closedform.centre_stored_energy),
    ),
}


def get_model(name: str) -> ModelSpec:
    """The registered model called ``name``; an unknown name lists the valid ones."""
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise ParameterError(
            f"unknown model {name!r}; choose one of {', '.join(MODELS)}"
        ) from None


def macroslip_force(model: str, params: ClampParams, options: ModelOptions | None = None) -> float:
    """The force (N) at which the whole interface slips for ``model`` in its reading.

    Tip (Eq. 5) and physical centre: mu F_N. Centre read with Eq. 11's printed factor 4:
    the slip length F L / (4 mu F_N) reaches the half length L/2 at 2 mu F_N.
    """
    opt = options or ModelOptions()
    return get_model(model).macroslip_factor(opt) * params.macroslip_force


def check_increments(increments: Any) -> int:
    """Validate a number of increments (whole number in [1, MAX_INCREMENTS])."""
    try:
        n = operator.index(increments)
    except TypeError:
        if isinstance(increments, float) and increments.is_integer():
            n = int(increments)
        else:
            raise ParameterError(
                f"increments must be a whole number in [1, {MAX_INCREMENTS}], got {increments!r}"
            ) from None
    if not 1 <= n <= MAX_INCREMENTS:
        raise ParameterError(
            f"increments must be a whole number in [1, {MAX_INCREMENTS}], got {increments!r}"
        )
    return n


def check_below_macroslip(model: str, params: ClampParams, amplitude: float,
                          options: ModelOptions) -> None:
    limit = macroslip_force(model, params, options)
    if amplitude >= limit:
        name = get_model(model).reading(options)
        reading = f", {name} reading" if name else ""
        raise MacroslipError(
            f"amplitude {amplitude:g} N is at or beyond the macroslip limit of the {model} "
            f"model ({limit:g} N{reading}); microslip needs 0 < amplitude < {limit:g} N"
        )


def check_small_strain(amplitude: Any, width: Any, thickness: Any, modulus: Any,
                       where: Callable[[int], str] = lambda i: "") -> None:
    """Refuse amplitudes whose mean axial strain F0 / (E w t) reaches :data:`MAX_STRAIN`
    (scalars or equal-length arrays; ``where(i)`` names case i in the message)."""
    amp = np.atleast_1d(np.asarray(amplitude, dtype=float))
    limit = MAX_STRAIN * np.asarray(modulus) * np.asarray(width) * np.asarray(thickness)
    limit = np.broadcast_to(limit, amp.shape)
    bad = amp >= limit
    if bad.any():
        i = int(np.argmax(bad))
        raise ParameterError(
            f"amplitude {amp[i]:g} N strains the clamped zone by F0/(E w t) = "
            f"{amp[i] / limit[i] * MAX_STRAIN:.3g}, beyond the small-strain models' "
            f"{MAX_STRAIN:g}{where(i)}; microslip needs amplitude < {limit[i]:.6g} N here"
        )


def first_loading(model: str, params: ClampParams, amplitude: float, increments: int = 1000,
                  options: ModelOptions | None = None,
                  contact: Contact | None = None) -> Backbone:
    """Run an incremental model from rest to ``amplitude`` in equal force increments.

    Parameters
    ----------
    model : {"tip", "centre"}
    params : ClampParams
    amplitude : float
        Peak force F0, N; must lie below the model's macroslip limit
        (:func:`macroslip_force`).
    increments : int
        Number n of equal force increments F0/n ("backward finite difference").
    options : ModelOptions, optional
        Reading of the paper's equations; default :class:`ModelOptions()`.
    contact : Contact, optional
        The interface under the bar (:class:`~microslip.models.contact.Contact`): its stick
        slope, the body's shear lag and the clamping-pressure law. Default: the paper's rigid
        foundation under uniform pressure.

    Returns
    -------
    Backbone
        Force, displacement, slip length, cross-section and stored energy at each of the
        n + 1 increments (the unloaded state first); force i is ``amplitude * (i / n)``.

    Notes
    -----
    The recurrence is the model's one compiled step function (tip: Eqs 2-10,
    :func:`~microslip.models.tip.tip_step`; centre: Eqs 11-18,
    :func:`~microslip.models.centre.centre_step`), the same the batch engine runs. On a
    contact that is not rigid, the exact shear-layer curve with the recurrence's corrections,
    the model's compiled layer step (:mod:`~microslip.models.layered`), also the batch
    engine's.

    Raises
    ------
    ParameterError
        Unknown model, bad amplitude or increments.
    MacroslipError
        ``amplitude`` at or beyond the macroslip limit.
    """
    spec = get_model(model)
    opt = options if options is not None else ModelOptions()
    f0 = check_amplitude(amplitude)
    n = check_increments(increments)
    check_below_macroslip(model, params, f0, opt)
    check_small_strain(f0, params.width, params.thickness, params.modulus)
    if contact is None or contact.is_rigid:
        return _loading(spec, params, f0, n, opt, None)
    check_reading(opt, len(spec.domains))
    return _loading(spec, params, f0, n, opt, contact)


def _loading(spec: ModelSpec, params: ClampParams, f0: float, n: int, opt: ModelOptions,
             contact: Contact | None) -> Backbone:
    model = spec.name
    p = params
    args = (f0, n, p.length, p.width, p.thickness, p.modulus, p.poisson_ratio, p.friction,
            p.normal_force, *opt.codes)
    if contact is None:
        forces, disp, stored, slip, width, thickness = kernel(spec.backbone, n)(*args)
    else:
        forces, disp, stored, slip, width, thickness = kernel(spec.layer_backbone,
                                                              n * LAYER_STEP)(
            *args, *contact.kernel_args)
    section_ok = np.all(width > 0) and np.all(thickness > 0)
    if not (np.all(np.isfinite(disp)) and section_ok):
        hint = (" (the paper-literal Poisson update shrinks the section at every increment; "
                "use fewer increments or poisson='consistent')" if opt.poisson == "paper-literal"
                else "")
        raise ParameterError(
            f"the {model} model broke down at {n} increments: non-finite displacement or "
            f"cross-section <= 0 mm{hint}"
        )
    return Backbone(
        model=spec.name,
        force=forces,
        displacement=disp,
        domains=spec.domains,
        slip_length=slip,
        width=width,
        thickness=thickness,
        stored_energy=stored,
        params=params,
        options=opt,
    )
