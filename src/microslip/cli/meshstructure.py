"""The structure of the user's own mesh on the command line, shared by ``modal --mesh``,
``frf --mesh`` and ``reduce``: the options that describe it (the mesh, its sets, the contact,
the density, the response set), their one-line refusals, and :func:`structure_case`, the one
function that turns them into the library's typed
:class:`~microslip.meshdynamics.case.StructureCase`. Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from ..case.table import (
    DEFAULT_ROM_MODES,
    MAX_MODE,
    MODE_MESH,
    MODE_STRUCTURE,
    add_option,
    mesh_file,
    mode_options,
)
from ..conventions import BACKBONE_NAMES
from ..errors import ParameterError
from ..fe.constants import DEFAULT_NORMAL_SLOPE
from .common import flagged
from .ownmesh import add_assembly_options, check_mesh_input, given, mesh_clamp

if TYPE_CHECKING:
    from ..meshdynamics.case import StructureCase

__all__ = [
    "MAX_MODE",
    "add_mesh_structure_options",
    "add_reduced_model_options",
    "check_density",
    "check_mesh_structure",
    "density_needed",
    "structure_case",
    "structure_density",
]


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
    add_assembly_options(g)
    add_option(g, "normal_contact", note="default fixed", mode=MODE_MESH)
    add_option(g, "normal_slope", note=f"default {DEFAULT_NORMAL_SLOPE:g}", mode=MODE_MESH)
    add_option(g, "mesh_element", note="default: as the file", mode=MODE_MESH)
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
    """The density, kg/m^3, finite and > 0 (one line otherwise; a value outside every
    engineering material's is refused when the command line is read)."""
    if not (isinstance(density, float) and 0.0 < density < float("inf")):
        raise ParameterError(f"--density must be finite and > 0 kg/m^3, got {density!r}")
    return density


def density_needed(args: argparse.Namespace) -> tuple[str, ...]:
    """``("--density KG/M3",)`` when a material has no density of its own and no
    ``--density`` gives one, else ``()``."""
    if getattr(args, "density", None) is not None:
        return ()
    own = getattr(args, "material", None) or []
    if own and all(m.density is not None for m in own) and getattr(args, "modulus",
                                                                   None) is None:
        return ()
    return ("--density KG/M3",)


def structure_density(args: argparse.Namespace, assembly: Any) -> float:
    """The structure's density, kg/m^3: ``--density`` (``[mesh] density``), the density of
    every material that gives none; without it, a material's own (each body's mass takes its
    material's density, :func:`microslip.meshdynamics.modes.modal_mass`)."""
    if args.density is not None:
        return float(args.density)
    own = [m.density for m in assembly.materials if m.density is not None]
    if len(own) < len(assembly.materials):  # density_needed said so before, as usage
        raise ParameterError("--density KG/M3 is needed (the structure's mass)")
    return float(own[0])


def check_mesh_structure(args: argparse.Namespace, not_with: tuple[str, ...] = ()) -> None:
    """Refuse, in one line, the one-mode and structure-file options (and ``not_with``), a
    missing clamp value, set or density, and --normal-slope without penalty contact."""
    # the one-mode, structure-file and joint options (added with mode="structure")
    bad = [f"--{d.replace('_', '-')}" for d in (*mode_options(args, MODE_STRUCTURE), *not_with)
           if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} not used with --mesh (the mesh gives the "
                             "structure, its contact the joint)")
    mesh_clamp(args, needs=density_needed(args))  # one usage line names all left out
    if args.normal_contact != "penalty" and args.normal_slope is not None:
        raise ParameterError("--normal-slope needs --normal-contact penalty")


def structure_case(args: argparse.Namespace) -> StructureCase:
    """The typed case of the structure the command line describes (the one place a mesh
    study's namespace becomes a :class:`~microslip.meshdynamics.case.StructureCase`): the
    assembly (:func:`.ownmesh.mesh_clamp`, checked against the mesh), the density, the mode,
    the response set and the reduced models' settings, each validated once by the case (its
    one-line message naming the option)."""
    from ..meshdynamics.case import StructureCase

    assembly = mesh_clamp(args, needs=density_needed(args))
    sets = tuple((name, role) for name, role in (
        (getattr(args, "response_set", None), "response set"),
        (getattr(args, "load_set", None), "load set")) if name is not None)
    check_mesh_input(args.mesh, assembly, (), sets, warn=True)
    density = structure_density(args, assembly)
    optional = {k: v for k, v in (
        ("mode", getattr(args, "mode", None)), ("rom_modes", getattr(args, "rom_modes", None)),
        ("backbone", getattr(args, "backbone", None)),
        ("interface_modes", getattr(args, "interface_modes", None)),
        ("element", getattr(args, "mesh_element", None)),
        ("yield_strength", getattr(args, "yield_strength", None))) if v is not None}
    with flagged():
        return StructureCase(args.mesh, assembly, density=density,
                             response_set=args.response_set, **optional)
