"""The options of a structure on the user's own mesh, written once for the commands that take
it (``modal --mesh FILE``, ``reduce``): the mesh file, its contact law in the structure
(``--normal-contact``, ``--normal-slope``), the density, the response set, the ROM's
fixed-interface modes; and the clamped model they describe (:func:`mesh_model_from_args`).

The clamp's values (``--normal-force``, ``--friction``, ``--modulus``, ``--poisson-ratio``,
``--stick-slope``) and the role sets come from the option table (:mod:`microslip.case.table`).
Units: N, mm, MPa, N/mm^3, kg/m^3, Hz.
"""

from __future__ import annotations

import argparse
from typing import Any

from ..case.table import mesh_file, number
from ..errors import ParameterError

__all__ = ["NORMAL_CONTACTS", "add_mesh_file", "add_mesh_structure_options",
           "add_rom_modes", "check_density", "mesh_model_from_args"]

#: ``--normal-contact``: what the contact does normally.
NORMAL_CONTACTS = {
    "fixed": "the clamping step's normal forces",
    "penalty": "--normal-slope, lift-off allowed",
}


def add_mesh_file(g: Any, help: str) -> argparse.Action:
    """``--mesh FILE``: a mesh file that exists."""
    return g.add_argument("--mesh", metavar="FILE", type=mesh_file, help=help)


def add_mesh_structure_options(g: Any, response_help: str | None = None) -> None:
    """``--normal-contact``, ``--normal-slope``, ``--density`` and ``--response-set``
    (``response_help``: what the command does with it, if not the amplitude's set)."""
    g.add_argument("--normal-contact", choices=list(NORMAL_CONTACTS), default=None,
                   help="; ".join(f"{k}: {v}" for k, v in NORMAL_CONTACTS.items())
                   + " (default fixed)")
    g.add_argument("--normal-slope", type=number, default=None, metavar="N/MM3",
                   help="penalty normal stiffness per area, N/mm^3 (default 1e5)")
    g.add_argument("--density", type=number, default=None, metavar="KG/M3",
                   help="density of the body, kg/m^3 (aluminium 2700, steel 7850)")
    g.add_argument("--response-set", metavar="NAME", default=None,
                   help=response_help or "set whose mean displacement along the mode is the "
                                         "amplitude (amplitude_mm)")


def add_rom_modes(g: Any, note: str) -> argparse.Action:
    """``--rom-modes N``: the ROM's fixed-interface modes; ``note`` the command's default."""
    return g.add_argument("--rom-modes", type=int, default=None, metavar="N",
                          help=f"fixed-interface modes kept in the reduced model{note}")


def check_density(density: float) -> float:
    """The density, kg/m^3, finite and > 0 (one line otherwise)."""
    if not (isinstance(density, float) and 0.0 < density < float("inf")):
        raise ParameterError(f"--density must be finite and > 0 kg/m^3, got {density!r}")
    return density


def mesh_model_from_args(args: argparse.Namespace, sets: list[str] | None = None) -> Any:
    """The clamped model of ``--mesh`` (:func:`~microslip.fe.builtin.meshmodel.
    build_mesh_model`: its clamping step done), the role sets and ``sets`` checked first."""
    from ..fe.builtin.meshmodel import build_mesh_model
    from ..fe.constants import DEFAULT_NORMAL_SLOPE
    from ..fe.meshcheck import check_roles
    from ..fe.meshfile import read_mesh

    mesh = read_mesh(args.mesh)
    check_roles(mesh, args.contact_set, args.clamp_set, sets or [])
    return build_mesh_model(
        mesh, contact_set=args.contact_set, clamp_set=args.clamp_set,
        normal_force=float(args.normal_force), modulus=float(args.modulus),
        poisson_ratio=float(args.poisson_ratio), friction=float(args.friction),
        stick_slope=float(args.stick_slope),
        normal_contact=args.normal_contact or "fixed",
        normal_slope=DEFAULT_NORMAL_SLOPE if args.normal_slope is None else args.normal_slope)
