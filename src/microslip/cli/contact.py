"""The contact options of the 1-D commands and the validity warnings they print.

``--stick-slope N/MM3`` (the contact's tangential stiffness per area, as ``fe`` takes it),
``--pressure-law`` and ``--no-shear-lag`` choose the :class:`~microslip.models.Contact` under
the tip and centre models; without them the paper's rigid foundation. Every 1-D result is
checked by :func:`microslip.models.validity.validity`; its warnings go to standard error
(one line each) and into the JSON as ``warnings``.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..case.run import contact_from_options, law_from_text, validity_warnings
from ..case.table import add_option
from ..models import Contact
from ..models.interface import PRESSURE_LAWS
from ..params import ClampParams

__all__ = ["add_contact_options", "contact_from_args", "contact_json", "law_from_text",
           "report_warnings", "warnings_for"]

_LAW_HELP = (f"clamping pressure along the length: {', '.join(PRESSURE_LAWS)}, "
             "power:N[:EDGE] (p ~ 1 + (EDGE-1)|2x/L-1|^N, edges EDGE x the middle, default 2) "
             "or table:FILE.csv (columns x_mm,pressure); default uniform (the paper's)")


def add_contact_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("contact (docs/interpretation.md §6)")
    add_option(g, "stick_slope", note="puts the bar on an elastic shear layer (this "
               "stiffness in series with the body's shear lag); inf or omitted: the paper's "
               "rigid foundation")
    add_option(g, "pressure_law", help=_LAW_HELP)
    add_option(g, "no_shear_lag")


def contact_from_args(args: argparse.Namespace, params: ClampParams) -> Contact | None:
    """The contact the options ask for; None when they leave the paper's foundation."""
    return contact_from_options(vars(args), params)


def warnings_for(model: str, params: ClampParams, amplitude: float,
                 contact: Contact | None) -> list[str]:
    """The validity warnings of a 1-D result (sentences; empty within the model's range)."""
    return validity_warnings(model, params, amplitude, contact)


def report_warnings(warnings: list[str], *, quiet: bool = False) -> None:
    """One line per warning on standard error."""
    if quiet:
        return
    for w in warnings:
        print(f"warning: {w}", file=sys.stderr)


def contact_json(contact: Contact | None) -> dict[str, Any]:
    return (contact or Contact()).summary()
