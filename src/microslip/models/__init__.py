"""The paper's two incremental 1-D microslip models and the registry that names them.

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

from ..errors import MacroslipError, ParameterError
from ..options import ModelOptions
from ..params import ClampParams, check_amplitude
from ..results import Backbone
from .centre import CentreState, centre_initial, centre_step
from .tip import TipState, tip_initial, tip_step

__all__ = [
    "MAX_INCREMENTS",
    "MODELS",
    "CentreState",
    "ModelSpec",
    "TipState",
    "centre_step",
    "check_increments",
    "first_loading",
    "get_model",
    "macroslip_force",
    "tip_step",
]

#: Upper bound on the number of increments of one backbone (memory guard).
MAX_INCREMENTS = 10_000_000


@dataclass(frozen=True)
class ModelSpec:
    """One incremental model: its kernel and how to read its state."""

    name: str
    domains: tuple[str, ...]
    initial: Callable[[Any], Any]
    step: Callable[[Any, Any, Any, ModelOptions], Any]
    #: Macroslip force as a multiple of mu F_N, for each reading of the centre model.
    macroslip_factor: Callable[[ModelOptions], float]
    #: Stored elastic energy from a state (N·mm): sum over domains of F_d delta_d / 3.
    stored_energy: Callable[[Any], Any]
    equations: str


MODELS: dict[str, ModelSpec] = {
    "tip": ModelSpec(
        name="tip",
        domains=("tip",),
        initial=tip_initial,
        step=tip_step,
        macroslip_factor=lambda opt: 1.0,
        stored_energy=lambda s: s.force * s.displacement / 3.0,
        equations="Eqs 2-10",
    ),
    "centre": ModelSpec(
        name="centre",
        domains=("tension", "compression"),
        initial=centre_initial,
        step=centre_step,
        macroslip_factor=lambda opt: 1.0 if opt.centre == "physical" else 2.0,
        # Physically each half carries F/2 over its slip length, whatever the reading.
        stored_energy=lambda s: 0.5 * s.force * s.domain_displacement.sum(axis=0) / 3.0,
        equations="Eqs 11-18",
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
        reading = f", {options.centre} reading" if model == "centre" else ""
        raise MacroslipError(
            f"amplitude {amplitude:g} N is at or beyond the macroslip limit of the {model} "
            f"model ({limit:g} N{reading}); microslip needs 0 < amplitude < {limit:g} N"
        )


def first_loading(model: str, params: ClampParams, amplitude: float, increments: int = 1000,
                  options: ModelOptions | None = None) -> Backbone:
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

    Returns
    -------
    Backbone
        Force, displacement, slip length, cross-section and stored energy at each of the
        n + 1 increments (the unloaded state first).

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

    forces = f0 * np.arange(n + 1) / n
    state = spec.initial(params)
    states = [state]
    for f in forces[1:]:
        state = spec.step(f, state, params, opt)
        states.append(state)

    def col(name: str) -> np.ndarray:
        arr = np.array([getattr(s, name) for s in states], dtype=float)
        return arr.reshape(n + 1, -1)

    disp = np.array([s.displacement for s in states], dtype=float)
    stored = np.array([spec.stored_energy(s) for s in states], dtype=float)
    section_ok = np.all(col("width") > 0) and np.all(col("thickness") > 0)
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
        slip_length=col("slip_length"),
        width=col("width"),
        thickness=col("thickness"),
        stored_energy=stored,
        params=params,
        options=opt,
    )
