"""The contact under a 1-D model: its stiffness and clamping pressure, applied to a backbone.

The paper's tip and centre models sit on a rigid Coulomb foundation under uniform pressure.
A :class:`Contact` replaces that foundation by the elastic shear layer of
:mod:`microslip.models.interface` (the contact's stick slope in series with the body's shear
lag) and lets the pressure follow a law q(x). The model's backbone on that contact
(:mod:`microslip.models.layered`, one compiled step per model, run by the single loop and
the batch engine alike) keeps the model's Poisson and length corrections (ModelOptions)
exactly as the paper's recurrence applies them.

How the corrections are kept: both updates change the rigid-foundation displacement by a
factor c(F) = d_corrected(F) / d_uncorrected(F) = 1 + O(nu F / (E A), d / L), a few 1e-5 for
real clamps (and the slip length by its own such factor). The backbone on the contact is the
exact shear-layer curve d_layer(F) times the same factor. In the rigid limit d_layer is the
closed form d_uncorrected, so the paper's corrected recurrence is recovered exactly (to
rounding); with a finite layer the factor's dependence on the layer is of second order in
quantities of 1e-5.

The stored energy (the bar's elastic energy) has no counterpart on a layer: it is NaN, and the
``stored`` strain-energy definition is refused on such a contact.

This module may import ``interface``, ``options``, ``params``, ``results`` and ``errors``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..options import ModelOptions
from .interface import PRESSURE_LAWS, PressureLaw, pressure_law

__all__ = ["DEFAULT_CONTACT", "RIGID_ONLY_ENERGIES", "Contact", "check_reading",
           "check_strain_energy", "energy_defined"]


@dataclass(frozen=True)
class Contact:
    """The interface under a 1-D clamp model.

    Parameters
    ----------
    stick_slope : float
        Tangential contact stiffness per unit area before slip, N/mm^3 (the FE's stick slope
        lambda). ``math.inf``: a rigid contact. Machined metal contacts: about 1e3 (rough,
        light pressure) to 1e5 (ground, high pressure); FE default 1e5 (docs/interpretation.md).
    shear_lag : bool
        Add the body's own through-thickness shear compliance t / (3 G w) in series with the
        contact (what the FE includes whatever the stick slope).
    law : PressureLaw, optional
        Clamping-pressure shape along the length; None: uniform (the paper's).

    The paper's rigid foundation is ``Contact()``: infinite stick slope, no shear lag,
    uniform pressure (:attr:`is_rigid`).
    """

    stick_slope: float = math.inf
    shear_lag: bool = False
    law: PressureLaw | None = None

    def __post_init__(self) -> None:
        k = self.stick_slope
        if isinstance(k, bool) or not isinstance(k, (int, float)) or math.isnan(k) or k <= 0:
            raise ParameterError(f"stick slope must be > 0 N/mm^3 (inf: rigid), got {k!r}")

    @classmethod
    def layer(cls, stick_slope: float, law: str | PressureLaw | None = None) -> Contact:
        """The physical contact: ``stick_slope`` in series with the body's shear lag."""
        return cls(float(stick_slope), True, pressure_law(law) if isinstance(law, str) else law)

    @property
    def is_rigid(self) -> bool:
        """The paper's foundation: nothing of this contact changes the model's recurrence."""
        uniform = self.law is None or self.law.name == "uniform"
        return math.isinf(self.stick_slope) and not self.shear_lag and uniform

    @property
    def law_name(self) -> str:
        return "uniform" if self.law is None else self.law.name

    @property
    def kernel_args(self) -> tuple[float, int, int, np.ndarray, int]:
        """What the compiled layer models take (:mod:`microslip.models.layered`):
        ``stick_slope, shear_lag, law code, law data, symmetric``."""
        law = self.law if self.law is not None else pressure_law("uniform")
        return float(self.stick_slope), int(self.shear_lag), law.code, law.data, \
            int(law.symmetric)

    def summary(self) -> dict[str, object]:
        """JSON form; the stick slope as a number in N/mm^3 (None when rigid)."""
        return {"stick_slope_N_per_mm3": None if math.isinf(self.stick_slope)
                else self.stick_slope, "shear_lag": self.shear_lag,
                "pressure_law": self.law_name}


#: The paper's rigid, uniformly pressed foundation.
DEFAULT_CONTACT = Contact()


#: Strain-energy definitions that need the rigid-foundation bar's own elastic energy.
RIGID_ONLY_ENERGIES = ("stored",)


def energy_defined(contact: Contact | None, kind: str) -> bool:
    """Whether the strain energy ``kind`` is defined on ``contact`` (None: rigid)."""
    return contact is None or contact.is_rigid or kind not in RIGID_ONLY_ENERGIES


def check_strain_energy(contact: Contact | None, kind: str) -> None:
    """Refuse, in one line, a strain energy ``kind`` that ``contact`` does not define."""
    if not energy_defined(contact, kind):
        raise ParameterError(
            f"strain energy {kind!r} is the rigid-foundation bar's own elastic energy; on a "
            "contact with a stick slope or pressure law use secant, backbone or branch")


def check_reading(options: ModelOptions | None, domains: int) -> None:
    """Refuse, in one line, the paper's reading of the centre model on a contact."""
    if options is not None and options.centre != "physical" and domains > 1:
        raise ParameterError(
            "a contact stiffness or pressure law needs the physical centre reading (each half "
            "carries F/2); the paper reading of Eq. 11 has no shear-layer counterpart")


def pressure_law_names() -> tuple[str, ...]:
    """Names a command line accepts for ``--pressure-law`` (besides ``table:FILE.csv``)."""
    return tuple(PRESSURE_LAWS)
