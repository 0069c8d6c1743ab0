"""The structure of the user's own mesh on the command line, shared by ``modal --mesh``,
``frf --mesh`` and ``reduce``: the options that describe it (the mesh, its sets, the contact,
the density, the response set), their one-line refusals, and :func:`structure_case`, the one
function that turns them into the library's typed
:class:`~microslip.meshdynamics.case.StructureCase`. Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from ..case.table import add_option, mesh_file, number
from ..errors import ParameterError
from ..meshdynamics.case import BACKBONE_NAMES, DEFAULT_ROM_MODES
from .common import flagged
from .ownmesh import REQUIRED as OWN_MESH_REQUIRED
from .ownmesh import given, mesh_clamp

if TYPE_CHECKING:
    from ..meshdynamics.case import StructureCase

__all__ = [
    "NOT_WITH_MESH",
    "REQUIRED",
    "add_mesh_structure_options",
    "add_reduced_model_options",
    "check_density",
    "check_mesh_structure",
    "structure_case",
]

#: Destinations of the one-mode / structure-file / joint options: refused with --mesh.
NOT_WITH_MESH = ("frequency", "stuck_frequency", "modal_mass", "damping_ratio",
                 "participation", "structure", "joint_dof", "coupling", "joint",
                 "joint_stiffness", "slip_force", "chi", "beta", "elements", "preset",
                 "length", "width", "thickness", "method", "transverse", "pairing",
                 "fe_mesh")
#: The clamp's values and the density a mesh structure needs: destination -> flag.
REQUIRED = {**OWN_MESH_REQUIRED, "density": "--density KG/M3"}


def add_mesh_structure_options(g: Any, response_help: str | None = None) -> None:
    """``--mesh``, ``--contact-set``, ``--clamp-set``, ``--normal-contact``,
    ``--normal-slope``, ``--density`` and ``--response-set`` on the argument group ``g``
    (``response_help``: what the command does with the response set, if not the
    amplitude's set)."""
    g.add_argument("--mesh", metavar="FILE", type=mesh_file,
                   help="a hexahedral mesh of your structure with its clamp (.inp, .msh, "
                        ".vtu, ...): its modes and the damping its clamp gives them")
    add_option(g, "contact_set")
    add_option(g, "clamp_set")
    g.add_argument("--normal-contact", choices=["fixed", "penalty"], default=None,
                   help="fixed: the clamping step's normal forces; penalty: --normal-slope, "
                        "lift-off allowed (default fixed)")
    g.add_argument("--normal-slope", type=number, default=None, metavar="N/MM3",
                   help="penalty normal stiffness per area, N/mm^3 (default 1e5)")
    g.add_argument("--density", type=number, default=None, metavar="KG/M3",
                   help="density of the body, kg/m^3 (aluminium 2700, steel 7850)")
    g.add_argument("--response-set", metavar="NAME", default=None,
                   help=response_help or "set whose mean displacement along the mode is the "
                                         "amplitude (amplitude_mm)")


def add_reduced_model_options(g: Any) -> None:
    """``--rom-modes`` and ``--backbone``: the reduced models of ``modal --mesh`` and ``frf
    --mesh`` (the contact-node ROM, ``rom``, and the whole joint built on it, ``joint``)."""
    g.add_argument("--rom-modes", type=int, default=None, metavar="N",
                   help=f"rom, joint: fixed-interface modes kept (default {DEFAULT_ROM_MODES}"
                        "; the ROM's stuck frequencies then equal the full FE's to about "
                        "1e-6)")
    g.add_argument("--backbone", choices=list(BACKBONE_NAMES), default=None,
                   help="joint: the whole joint's backbone, the FE's own first loading by "
                        "the mode (fe, default), the same with work-equivalent "
                        "displacements (work), or the paper's 1-D clamp model on the "
                        "contact patch (tip, centre)")


def check_density(density: float) -> float:
    """The density, kg/m^3, finite and > 0 (one line otherwise)."""
    if not (isinstance(density, float) and 0.0 < density < float("inf")):
        raise ParameterError(f"--density must be finite and > 0 kg/m^3, got {density!r}")
    return density


def check_mesh_structure(args: argparse.Namespace, not_with: tuple[str, ...] = ()) -> None:
    """Refuse, in one line, the one-mode and structure-file options (and ``not_with``), a
    missing clamp value, set or density, and --normal-slope without penalty contact."""
    bad = [f"--{d.replace('_', '-')}" for d in (*NOT_WITH_MESH, *not_with) if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} not used with --mesh (the mesh gives the "
                             "structure, its contact the joint)")
    missing = [flag for dest, flag in REQUIRED.items() if getattr(args, dest, None) is None]
    for dest in ("contact_set", "clamp_set"):
        if getattr(args, dest, None) is None:
            missing.insert(0, f"--{dest.replace('_', '-')} NAME")
    if missing:
        raise ParameterError(f"--mesh {args.mesh} needs {', '.join(missing)}")
    if args.normal_contact != "penalty" and args.normal_slope is not None:
        raise ParameterError("--normal-slope needs --normal-contact penalty")


def structure_case(args: argparse.Namespace) -> StructureCase:
    """The typed case of the structure the command line describes (the one place a mesh
    study's namespace becomes a :class:`~microslip.meshdynamics.case.StructureCase`): the
    clamp (:class:`~microslip.fe.clamp.MeshClamp`), the density, the mode, the response set
    and the reduced models' settings, each validated once by the case (its one-line message
    naming the option)."""
    from ..meshdynamics.case import StructureCase

    clamp = mesh_clamp(args)
    optional = {k: v for k, v in (
        ("mode", getattr(args, "mode", None)), ("rom_modes", getattr(args, "rom_modes", None)),
        ("backbone", getattr(args, "backbone", None))) if v is not None}
    with flagged():
        return StructureCase(args.mesh, clamp, density=args.density,
                             response_set=args.response_set, **optional)
