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

from ..case.table import add_option, mesh_file, number
from ..errors import ParameterError
from .ownmesh import REQUIRED as OWN_MESH_REQUIRED
from .ownmesh import given

__all__ = [
    "DEFAULT_INTERFACE_MODES",
    "DEFAULT_ROM_MODES",
    "MAX_MODE",
    "NOT_WITH_MESH",
    "REQUIRED",
    "MeshModes",
    "add_mesh_structure_options",
    "add_reduced_model_options",
    "check_density",
    "check_mesh_structure",
    "mesh_model",
    "mesh_modes",
]

#: Destinations of the one-mode / structure-file / joint options: refused with --mesh.
NOT_WITH_MESH = ("frequency", "stuck_frequency", "modal_mass", "damping_ratio",
                 "participation", "structure", "joint_dof", "coupling", "joint",
                 "joint_stiffness", "slip_force", "chi", "beta", "elements", "preset",
                 "length", "width", "thickness", "method", "transverse", "pairing",
                 "fe_mesh")
#: Highest mode number ``--mode`` takes with --mesh (the eigen-solve computes that many).
MAX_MODE = 50
#: The clamp's values and the density a mesh structure needs: destination -> flag.
REQUIRED = {**OWN_MESH_REQUIRED, "density": "--density KG/M3"}
#: Fixed-interface modes of the ROM unless --rom-modes says (the cantilever's stuck
#: frequencies then equal the full FE's to about 1e-6).
DEFAULT_ROM_MODES = 60
#: Characteristic constraint modes of the interface-reduced model unless --interface-modes
#: says (the studied mode's first-loading shapes come on top; docs/interpretation.md 14).
DEFAULT_INTERFACE_MODES = 10
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


def mesh_model(args: argparse.Namespace, sets: tuple[str, ...] = ()) -> Any:
    """Read the mesh, check its role sets (and the response set and ``sets``), build the
    body on its base and solve the clamping step: a
    :class:`~microslip.fe.builtin.meshmodel.MeshModel`."""
    from ..fe.builtin.meshmodel import build_mesh_model
    from ..fe.constants import DEFAULT_NORMAL_SLOPE
    from ..fe.meshcheck import check_roles
    from ..fe.meshfile import read_mesh

    mesh = read_mesh(args.mesh)
    check_roles(mesh, args.contact_set, args.clamp_set,
                [*([args.response_set] if args.response_set else []), *sets])
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
