"""microslip: friction damping by microslip in clamped joints.

An implementation of Lord & Rongong, "A tangential microslip model for circularly and
elliptically loaded structures", Proc IMechE C (2016): the tip- and centre-loaded
incremental models, Masing's rule, the planar coupling and the energy measures, with exact
references and finite-element validation.

Units throughout: force N, length mm, modulus MPa, energy N·mm.
"""

from __future__ import annotations

from . import closedform, planar
from .energy import (
    DEFAULT_STRAIN_ENERGY,
    STRAIN_ENERGY,
    damping,
    damping_from_loop,
    dissipated_energy,
    loss_factor,
    strain_energy,
)
from .errors import MacroslipError, MicroslipError, ParameterError
from .hysteresis import VirginCurve, masing_loop, masing_response
from .models import MODELS, first_loading, macroslip_force
from .options import CENTRE_READINGS, POISSON_MODES, ModelOptions
from .params import PRESETS, ClampParams, preset
from .results import Backbone, DampingResult, HysteresisLoop

__version__ = "0.1.0"

__all__ = [
    "CENTRE_READINGS",
    "DEFAULT_STRAIN_ENERGY",
    "MODELS",
    "POISSON_MODES",
    "PRESETS",
    "STRAIN_ENERGY",
    "Backbone",
    "ClampParams",
    "DampingResult",
    "HysteresisLoop",
    "MacroslipError",
    "MicroslipError",
    "ModelOptions",
    "ParameterError",
    "VirginCurve",
    "closedform",
    "damping",
    "damping_from_loop",
    "dissipated_energy",
    "first_loading",
    "loss_factor",
    "macroslip_force",
    "masing_loop",
    "masing_response",
    "planar",
    "preset",
    "strain_energy",
]
