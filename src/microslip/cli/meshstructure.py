"""The structure of the user's own mesh on the command line, shared by ``modal --mesh`` and
``frf --mesh``: the options that describe it (the mesh, its sets, the contact, the density,
the response set), their one-line checks, the clamped model they build and its stuck and free
linear modes.

Parses and delegates: the model is :func:`microslip.fe.builtin.meshmodel.build_mesh_model`,
the modes :func:`microslip.fe.builtin.modes.linear_modes`. Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import Any

from ..case.table import (
    DEFAULT_ROM_MODES,
    MAX_MODE,
    MODE_MESH,
    MODE_STRUCTURE,
    add_option,
    mesh_file,
    mode_options,
)
from ..errors import ParameterError
from ..fe.constants import DEFAULT_NORMAL_SLOPE
from .ownmesh import REQUIRED as OWN_MESH_REQUIRED
from .ownmesh import given

__all__ = [
    "DEFAULT_ROM_MODES",
    "MAX_MODE",
    "REQUIRED",
    "MeshModes",
    "add_mesh_structure_options",
    "add_reduced_model_options",
    "check_density",
    "check_mesh_structure",
    "mesh_model",
    "mesh_modes",
]

#: The clamp's values and the density a mesh structure needs: destination -> flag.
REQUIRED = {**OWN_MESH_REQUIRED, "density": "--density KG/M3"}
#: The whole joint's backbones (the keys of :data:`microslip.fe.builtin.wholejoint.BACKBONES`,
#: named here so that the parser does not import the FE; a test holds the two equal).
BACKBONE_NAMES = ("fe", "work", "tip", "centre")


@dataclass(frozen=True)
class MeshModes:
    """What every study of a mesh structure starts from (``modal --mesh``, ``frf --mesh``):
    the command line, the clamped model, its stuck and free linear modes and the number
    (1-based) of the mode studied."""

    args: argparse.Namespace
    model: Any
    stuck: Any
    free: Any
    number: int

    @property
    def mode(self) -> Any:
        """The studied stuck mode (:class:`~microslip.fe.builtin.modes.Mode`)."""
        return self.stuck.select(self.number)


def add_mesh_structure_options(g: Any, response_help: str | None = None) -> None:
    """``--mesh``, ``--contact-set``, ``--clamp-set``, ``--normal-contact``,
    ``--normal-slope``, ``--density`` and ``--response-set`` on the argument group ``g``
    (``response_help``: what the command does with the response set, if not the
    amplitude's set)."""
    add_option(g, "mesh_file", flag="--mesh", dest="mesh", type=mesh_file, mode=MODE_MESH,
               help="a hexahedral mesh of your structure with its clamp (.inp, .msh, .vtu, "
                    "...): its modes and the damping its clamp gives them")
    for name in ("contact_set", "clamp_set"):
        add_option(g, name, mode=MODE_MESH)
    add_option(g, "normal_contact", note="default fixed", mode=MODE_MESH)
    add_option(g, "normal_slope", note=f"default {DEFAULT_NORMAL_SLOPE:g}", mode=MODE_MESH)
    add_option(g, "density", mode=MODE_MESH)
    add_option(g, "response_set", help=response_help, mode=MODE_MESH)


def add_reduced_model_options(g: Any) -> None:
    """``--rom-modes`` and ``--backbone``: the reduced models of ``modal --mesh`` and ``frf
    --mesh`` (the contact-node ROM, ``rom``, and the whole joint built on it, ``joint``)."""
    add_option(g, "rom_modes", mode=MODE_MESH,
               note=f"rom, joint; default {DEFAULT_ROM_MODES}: the ROM's stuck frequencies "
               "then equal the full FE's to about 1e-6")
    add_option(g, "backbone", choices=list(BACKBONE_NAMES), mode=MODE_MESH, note="default fe")


def check_density(density: float) -> float:
    """The density, kg/m^3, finite and > 0 (one line otherwise)."""
    if not (isinstance(density, float) and 0.0 < density < float("inf")):
        raise ParameterError(f"--density must be finite and > 0 kg/m^3, got {density!r}")
    return density


def check_mesh_structure(args: argparse.Namespace, not_with: tuple[str, ...] = ()) -> None:
    """Refuse, in one line, the one-mode and structure-file options (and ``not_with``), a
    missing clamp value, set or density, and --normal-slope without penalty contact."""
    # the one-mode, structure-file and joint options (added with mode="structure")
    bad = [f"--{d.replace('_', '-')}" for d in (*mode_options(args, MODE_STRUCTURE), *not_with)
           if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} not used with --mesh (the mesh gives the "
                             "structure, its contact the joint)")
    missing = [flag for dest, flag in REQUIRED.items() if getattr(args, dest, None) is None]
    for dest in ("contact_set", "clamp_set"):
        if getattr(args, dest, None) is None:
            missing.insert(0, f"--{dest.replace('_', '-')} NAME")
    if missing:
        from .main import UsageError  # a required option left out: a usage mistake

        raise UsageError(f"--mesh {args.mesh} needs {', '.join(missing)}")
    if args.normal_contact != "penalty" and args.normal_slope is not None:
        raise ParameterError("--normal-slope needs --normal-contact penalty")


def mesh_model(args: argparse.Namespace, sets: tuple[str, ...] = ()) -> Any:
    """Read the mesh, check its role sets (and the response set and ``sets``), build the
    body on its base and solve the clamping step: a
    :class:`~microslip.fe.builtin.meshmodel.MeshModel`."""
    from ..fe.builtin.meshmodel import build_mesh_model
    from ..fe.constants import DEFAULT_NORMAL_SLOPE
    from ..fe.meshcheck import check_roles, check_set
    from ..fe.meshfile import read_mesh

    mesh = read_mesh(args.mesh)
    if args.response_set:  # named as what it is (not "the set of a load")
        check_set(mesh, args.response_set, "response set")
    check_roles(mesh, args.contact_set, args.clamp_set, sets)
    return build_mesh_model(
        mesh, contact_set=args.contact_set, clamp_set=args.clamp_set,
        normal_force=float(args.normal_force), modulus=float(args.modulus),
        poisson_ratio=float(args.poisson_ratio), friction=float(args.friction),
        stick_slope=float(args.stick_slope),
        normal_contact=args.normal_contact or "fixed",
        normal_slope=DEFAULT_NORMAL_SLOPE if args.normal_slope is None else args.normal_slope)


def mesh_modes(args: argparse.Namespace, model: Any) -> tuple[int, Any, Any]:
    """(the --mode number, 1-based and checked; the stuck and the free linear modes, at least
    six and up to that mode, described by the response set)."""
    from ..fe.builtin.modes import linear_modes

    number = 1 if args.mode is None else args.mode
    if not 1 <= number <= MAX_MODE:
        raise ParameterError(f"--mode must be in [1, {MAX_MODE}] with --mesh, got {number}")
    n = max(6, number)
    stuck = linear_modes(model, args.density, n, "stuck", args.response_set)
    free = linear_modes(model, args.density, n, "free", args.response_set)
    return number, stuck, free
