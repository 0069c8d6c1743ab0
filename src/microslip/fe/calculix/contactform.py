"""CalculiX's contact formulations of the mesh deck (issue 29): which ``*CONTACT PAIR`` and
``*SURFACE INTERACTION`` cards the contact set on the rigid base gets
(:func:`~.meshdeck.build_mesh_deck`'s ``formulation``). Units: N, mm, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...errors import ParameterError
from .deck import contact_pair_card, surface_interaction_card

__all__ = ["CONTACT_FORMULATIONS", "N2S_TENSION_RATIO", "ContactFormulation",
           "check_formulation", "interaction_cards"]

#: sigma_inf of node-to-surface contact relative to the mean contact pressure F_N / A_contact:
#: CalculiX rounds the kink of p = K d over the overclosure eps = pi sigma_inf / K and shifts
#: the pressure of a closed node by up to -sigma_inf (:func:`~.deck.surface_interaction_card`);
#: 1e-5 of the mean pressure keeps W within 3e-4 of the built-in solver's sharp kink on the
#: bolt pad, where the few slipping nodes carry little pressure (1e-4: 3.3e-3; docs/
#: interpretation.md §21).
N2S_TENSION_RATIO = 1e-5


@dataclass(frozen=True)
class ContactFormulation:
    """How CalculiX enforces the contact of the body with its base.

    Attributes
    ----------
    pair : str
        The ``*CONTACT PAIR`` type (a key of :data:`~.deck.CONTACT_PAIR_TYPES`).
    description : str
    tension_ratio : float or None
        sigma_inf / mean contact pressure, for the types that need a sigma_inf.
    """

    pair: str
    description: str
    tension_ratio: float | None = None


#: Contact formulations of the mesh deck: name -> formulation. ``node-to-surface`` is the one
#: the built-in solver's nodal law equals (a spring per slave node of stiffness K A_i and
#: lambda A_i, A_i the node's share of the contact faces, Coulomb limit mu N_i at the node);
#: ``face-to-face`` integrates the penalty tractions over the faces (CalculiX's recommended,
#: and this deck's, default).
CONTACT_FORMULATIONS = {
    "face-to-face": ContactFormulation(
        "face-to-face", "face-to-face penalty (SURFACE TO SURFACE): tractions integrated over "
        "the slave faces"),
    "node-to-surface": ContactFormulation(
        "node-to-surface", "node-to-surface penalty (NODE TO SURFACE): one spring per slave "
        "node, stiffness K A_i and lambda A_i, Coulomb limit mu N_i at the node (the built-in "
        "solver's nodal law)", N2S_TENSION_RATIO),
}


def check_formulation(name: str) -> ContactFormulation:
    """The formulation called ``name``; one line naming the choices otherwise."""
    if name not in CONTACT_FORMULATIONS:
        raise ParameterError(f"contact formulation must be one of "
                             f"{', '.join(CONTACT_FORMULATIONS)}, got {name!r}")
    return CONTACT_FORMULATIONS[name]


def interaction_cards(formulation: str, normal_slope: float, friction: float,
                       stick_slope: float, mean_pressure: float) -> list[str]:
    """``*SURFACE INTERACTION`` and ``*CONTACT PAIR`` of the contact set on the base."""
    f = check_formulation(formulation)
    tension = None if f.tension_ratio is None else f.tension_ratio * mean_pressure
    return [surface_interaction_card("SI", normal_slope, friction, stick_slope, tension),
            contact_pair_card("SI", "SCONTACT", "SBASE", f.pair)]
