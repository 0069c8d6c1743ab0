"""The one option table: every option the command line and the case files share.

Each :class:`Option` states its name (argparse destination, ``--flag`` spelling), its type,
unit, range, meaning and the case-file key that gives it (``contact.stick_slope``) or the key
of a ``[[joint]]`` table (``stiffness``). The command line builds its arguments from it
(:func:`add_option`), the case schema its keys (:mod:`.schema`), and ``--case`` maps keys
onto options through it (:data:`CASE_DESTS`), so a flag and its key cannot drift apart.

The checks here (:func:`positive`, :func:`interval`, ...) validate a case file's values and
name the key, the unit and the allowed range; the command line checks its values where the
library takes them (``ClampParams``, the joints), with the same ranges.

Units: N, mm, MPa, N/mm, N/mm^3, degrees.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from typing import Any

from ..conventions import (
    CCX_CONTACT_FORMULATIONS,
    CLAMP_MODELS,
    COUPLINGS,
    DEFAULT_ELEMENTS,
    DEFAULT_MESH,
    DEFAULT_NORMAL_SLOPE,
    DEFAULT_ROM_MODES,
    DEFAULT_STICK_SLOPE,
    JOINT_MODELS,
    MAX_MODE,
    MAX_ROM_MODES,
    PAIRINGS,
    TRANSVERSE,
)
from ..meshlevels import FIXED_COUNTS, LEVELS, MESH_LEVELS
from .assembly import (
    FORMS,
    bolt_option,
    contact_option,
    fixed_option,
    material_option,
    preload_option,
    table_check,
)
from .checks import (
    PRESSURE_LAWS,
    Check,
    Option,
    choice,
    exponent,
    harmonics_count,
    interval,
    mesh_file,
    mesh_level,
    mesh_or_file,
    mesh_text,
    number,
    positive,
    pressure_text,
    set_name,
    text,
    whole,
)
from .runflags import RUN_OPTIONS
from .units import DENSITY_RANGE, density

__all__ = [
    "CASE_DESTS",
    "DEFAULT_ROM_MODES",
    "MAX_MODE",
    "MAX_ROM_MODES",
    "MESH_HELP",
    "MODES_KEY",
    "MODE_BOX",
    "MODE_MESH",
    "MODE_STRUCTURE",
    "OPTIONS",
    "PRESSURE_LAWS",
    "SOLVERS",
    "Check",
    "Option",
    "add_option",
    "add_solver",
    "choice",
    "exponent",
    "interval",
    "mesh_file",
    "mesh_level",
    "mesh_or_file",
    "mesh_text",
    "mode_options",
    "number",
    "positive",
    "pressure_text",
    "set_name",
    "text",
    "whole",
]

_FROM_PRESET = "from preset"

#: Normal contact laws of a mesh's base (``fixed``: the built-in solver's default).
NORMAL_CONTACTS = ("fixed", "penalty")

#: --mesh help: the mesh levels of :mod:`microslip.meshlevels`.
MESH_HELP = (
    f"mesh level, the same elements for both solvers (builtin C3D8I, calculix C3D20R): "
    f"{', '.join(MESH_LEVELS)} are accuracy levels with counts from the geometry (on the "
    f"Table 1 bar 24x4x1, 48x4x1, 96x8x2; a squat body, L < 20 t, gets graded layers), "
    + ", ".join(f"{k} {'x'.join(map(str, v))}" for k, v in FIXED_COUNTS.items())
    + f", or NXxNYxNZ counts (default {DEFAULT_MESH}; docs/solver.md 8.4)")

_OPTIONS: tuple[Option, ...] = (
    # the clamp (ClampParams fields)
    Option("length", "clamped length L along the load", "mm", "> 0", metavar="MM",
           key="geometry.length", check=positive("mm"), case_default=_FROM_PRESET),
    Option("width", "depth w of the cross-section", "mm", "> 0", metavar="MM",
           key="geometry.width", check=positive("mm"), case_default=_FROM_PRESET),
    Option("thickness", "thickness t of the cross-section", "mm", "> 0", metavar="MM",
           key="geometry.thickness", check=positive("mm"), case_default=_FROM_PRESET),
    Option("modulus", "Young's modulus E", "MPa", "> 0", metavar="MPA",
           key="material.modulus", check=positive("MPa"), case_default=_FROM_PRESET),
    Option("poisson_ratio", "Poisson's ratio nu", "", "[0, 0.5)", metavar="X",
           key="material.poisson_ratio", check=interval(0.0, 0.5), case_default=_FROM_PRESET),
    Option("friction", "Coulomb friction coefficient mu", "", "> 0", metavar="X",
           key="contact.friction", check=positive(), case_default=_FROM_PRESET),
    Option("normal_force", "clamping (normal) force F_N", "N", "> 0", metavar="N",
           key="clamping.normal_force", check=positive("N"), case_default=_FROM_PRESET),
    # the contact
    Option("stick_slope", "tangential contact stiffness per area before slip (FE stick slope "
           "lambda; machined metal 1e3-1e5)", "N/mm^3", "> 0", metavar="N/MM3",
           key="contact.stick_slope", check=positive("N/mm^3"),
           case_default=DEFAULT_STICK_SLOPE,
           case_note="given, the 1-D models sit on this elastic layer, omitted they keep the "
           "paper's rigid foundation while fe uses the default"),
    Option("pressure_law", "clamping pressure law along the length (uniform is the paper's)",
           "", " | ".join(PRESSURE_LAWS), type=None, metavar="LAW", key="clamping.pressure",
           check=pressure_text, case_default="uniform"),
    # the uniaxial load case
    Option("model", "tip: load on the end face; centre: on the mid-length section", "",
           " | ".join(CLAMP_MODELS), type=None, choices=CLAMP_MODELS, key="load.model",
           check=choice(CLAMP_MODELS), scope="load", case_default="tip"),
    Option("amplitude", "load amplitude F0", "N", "> 0", metavar="N", key="load.amplitude",
           check=positive("N"), scope="load", case_note="give this or amplitude_fraction"),
    # the planar load case
    Option("tip_amplitude", "amplitude of the tip model (one symmetric half)", "N", "> 0",
           metavar="N", key="load.planar.tip_amplitude", check=positive("N"), scope="planar",
           case_note="with centre_amplitude, or give ratio"),
    Option("centre_amplitude", "amplitude of the centre model", "N", "> 0", metavar="N",
           key="load.planar.centre_amplitude", check=positive("N"), scope="planar"),
    Option("ratio", "force ratio R = F_T(tip)/F_T(centre) on the paper's levels", "", "> 0",
           metavar="R", key="load.planar.ratio", check=positive(), scope="planar"),
    Option("phase", "phase of the centre force ahead of the tip force", "degrees",
           "[-360, 360]", metavar="DEG", key="load.planar.phase_deg",
           check=interval(-360.0, 360.0, "degrees", closed=True), scope="planar",
           case_default=0.0, default=0.0),
    # the finite-element model
    Option("mesh", MESH_HELP, "", f"{' | '.join(LEVELS)} | NXxNYxNZ", type=mesh_level,
           metavar="LEVEL"),
    # the user's own mesh (fe --mesh FILE)
    Option("mesh_file", "a mesh of your own clamp: .inp, .msh, .vtu, ...; hexahedra with "
           "named sets", "", "path", type=None, metavar="FILE",
           key="mesh.file", check=text, scope="mesh", case_note="relative to the case file; "
           "its loads are [[mesh.load]] tables: set, direction = [DX, DY, DZ], amplitude (N), "
           "phase_deg"),
    Option("contact_set", "set of the mesh on the rigid base (node set or element-face "
           "surface; the shorthand of --contact NAME)", "", "a set name of the mesh file",
           type=set_name, metavar="NAME", key="mesh.contact_set", check=text, scope="mesh"),
    Option("clamp_set", "set of the mesh that carries the clamping pressure F_N / area "
           "(with --normal-force F_N the shorthand of --preload NAME:F_N)", "",
           "a set name of the mesh file", type=set_name, metavar="NAME", key="mesh.clamp_set",
           check=text, scope="mesh"),
    # the assembly of the user's own mesh (issue 32, item 5): each repeatable, each a
    # [[mesh.<table>]] of the case file; the clamp's options above stay as its shorthand
    Option("contact", "a contact: the face SET of one body on the face COUNTER_SET of "
           "another (coincident nodes), or without a counter set on the rigid flat base; "
           "repeat for several", "", FORMS["contact"], type=contact_option, action="append",
           metavar="SET[:COUNTER_SET]", key="mesh.contact", check=table_check("contact"),
           scope="mesh", case_note="[[mesh.contact]] tables: face, counter; --contact-set X "
           "is --contact X"),
    Option("preload", "a preload: FORCE pressing the face SET inward, as a uniform traction "
           "(a bolt: its head and its nut face); repeat for several", "", FORMS["preload"],
           type=preload_option, action="append", metavar="SET:FORCE", key="mesh.preload",
           check=table_check("preload"), scope="mesh", case_note="[[mesh.preload]] tables: "
           "face, force; --clamp-set Y --normal-force F is --preload Y:F"),
    Option("fixed", "a support: the nodes of SET held in the global DIRECTIONS (letters of "
           "xyz, default xyz); repeat for several", "", FORMS["fixed"], type=fixed_option,
           action="append", metavar="SET[:DIRECTIONS]", key="mesh.support",
           check=table_check("support"), scope="mesh",
           case_note="[[mesh.support]] tables: set, directions"),
    Option("material", "the material of the element set ELSET (a gmsh volume group or an "
           "*ELSET): modulus MPa, Poisson's ratio, density kg/m^3 (default --density); "
           "repeat for several; --modulus and --poisson-ratio give every other element",
           "", FORMS["material"], type=material_option, action="append",
           metavar="ELSET:E:NU[:RHO]", key="mesh.material", check=table_check("material"),
           scope="mesh", case_note="[[mesh.material]] tables: elset, modulus, poisson_ratio, "
           "density; [material] gives every other element"),
    Option("bolt", "a bolt: its HEAD and NUT faces each pressed inward by FORCE and, with a "
           "DIAMETER, a shank between them (an elastic beam between the faces' mean motions "
           "after the preload); repeat for several", "", FORMS["bolt"], type=bolt_option,
           action="append", metavar="HEAD:NUT:FORCE[:DIAMETER]", key="mesh.bolt",
           check=table_check("bolt"), scope="mesh", case_note="[[mesh.bolt]] tables: head, "
           "nut, force, diameter, modulus"),
    Option("contact_formulation", "CalculiX's contact on the mesh: node-to-surface solves the "
           "built-in solver's nodal equations, face-to-face integrates the tractions over the "
           "faces", "", " | ".join(CCX_CONTACT_FORMULATIONS), type=None,
           choices=CCX_CONTACT_FORMULATIONS),
    # the structure of the user's own mesh (modal --mesh FILE; the report's structure section)
    Option("density", "density of the body of the mesh (aluminium 2700, steel 7850; a "
           "value outside it is a unit mistake: t/mm^3, g/cm^3)", "kg/m^3",
           f"[{DENSITY_RANGE[0]:g}, {DENSITY_RANGE[1]:g}]", metavar="KG/M3",
           key="mesh.density", check=density,
           scope="mesh", case_note="with it, report adds the damping of the structure's mode"),
    Option("yield_strength", "yield strength of the part's material: the automatic "
           "amplitude grid of modal --mesh stops where the studied stuck mode's largest von "
           "Mises stress reaches it (without it, at a hundredth of the part's largest "
           "extent)", "MPa", "> 0",
           metavar="MPA", key="material.yield_strength", check=positive("MPa"),
           scope="mesh"),
    Option("mode", "the structure's mode followed, 1-based by stuck frequency (1: the lowest "
           "stuck mode)", "", f"[1, {MAX_MODE}]", type=int, metavar="N", key="mesh.mode",
           check=whole(1, MAX_MODE), scope="mesh", case_default=1),
    Option("response_set", "set of the mesh whose mean displacement along the mode is the "
           "amplitude", "", "a set name of the mesh file", type=set_name, metavar="NAME",
           key="mesh.response_set", check=text, scope="mesh"),
    Option("normal_contact", "normal contact of the contact set on its base: fixed, the "
           "clamping step's normal forces (u_z = 0, the paper's reading); penalty, the linear "
           "pressure-overclosure law of normal_slope, lift-off allowed", "",
           " | ".join(NORMAL_CONTACTS), type=None, choices=NORMAL_CONTACTS,
           key="mesh.normal_contact", check=choice(NORMAL_CONTACTS), scope="mesh",
           case_default="fixed", case_note="validate compares fixed as a hard penalty "
           "contact; fe --solver calculix takes penalty only"),
    Option("normal_slope", "penalty normal stiffness per area (slope of the pressure-"
           "overclosure law)", "N/mm^3", "> 0", metavar="N/MM3", key="mesh.normal_slope",
           check=positive("N/mm^3"), scope="mesh", case_default=DEFAULT_NORMAL_SLOPE,
           case_note="with normal_contact = \"penalty\""),
    # mesh convergence of the user's own mesh (fe --mesh FILE, modal --mesh FILE; issue 29)
    Option("refine", "subdivide every hexahedron of the mesh N times in each direction (N^3 "
           "children, sets carried) before the run, N in [1, 8]", "", "[1, 8]", type=int,
           metavar="N", scope="mesh"),
    Option("convergence", "run the mesh and its refinements x2 and report Richardson's "
           "estimate of the converged values, the observed order and the given mesh's "
           "discretisation error", "", "", type=None, action="store_true", scope="mesh"),
    Option("mesh_levels", "with --convergence: meshes run, the given one and 1 or 2 refinements x2 "
           "(3 observes the order, 2 assumes the element's)", "", "2 | 3", type=int,
           metavar="N", choices=None, spelling="--levels", scope="mesh"),
    # the element of the user's own mesh (fe, modal, frf --mesh FILE; issue 29, item 3); fe's
    # --element takes the box's elements too (one option there, checked by mode)
    Option("mesh_element", "the built-in's hexahedra on a mesh file: hex8 (C3D8I) or hex20 "
           "(C3D20R; an 8-node mesh gets a node at the middle of every edge, its sets carried)",
           "", "hex8 | hex20", type=None, metavar=None, choices=("hex8", "hex20"),
           spelling="--element", scope="mesh"),
    # the interface-reduced model of modal --mesh (--solver interface; issue 28, item 4)
    Option("interface_modes", "interface: characteristic constraint modes of the contact "
           "kept (the studied mode's first-loading shapes come on top)", "", "[1, the "
           "contact's boundary dofs]", type=int, metavar="N", scope="mesh"),
    # a structure and its joints
    Option("structure", "reduced model: FILE.npz (M, K, optional C, joints) or a Matrix "
           "Market directory, SI units", "", "path", type=None, metavar="FILE",
           key="structure.file", check=text, case_note="relative to the case file"),
    Option("joint", "jenkins: one spring-slider; iwan: Segalman's 4-parameter Iwan; tip, "
           "centre: the clamp's microslip model behind a series spring", "",
           " | ".join(JOINT_MODELS), type=None, choices=JOINT_MODELS, joint_key="model",
           check=choice(JOINT_MODELS)),
    Option("joint_stiffness", "jenkins: spring stiffness; iwan: initial stiffness K_T; tip, "
           "centre: the series spring", "N/mm", "> 0", metavar="N/MM", joint_key="stiffness",
           check=positive("N/mm"), case_note="or give contact.stick_slope for tip, centre"),
    Option("slip_force", "jenkins, iwan: macroslip force F_S", "N", "> 0", metavar="N",
           joint_key="slip_force", check=positive("N")),
    Option("chi", "iwan: density exponent", "", "(-1, 0]", metavar="X", joint_key="chi",
           check=exponent),
    Option("beta", "iwan: macroslip elements' share of the stiffness", "", "[0, inf)",
           metavar="X", joint_key="beta", check=interval(0.0, math.inf)),
    Option("elements", f"iwan, tip, centre: Jenkins elements (default {DEFAULT_ELEMENTS}, "
           "more for a smoother curve)",
           "", "[2, 100000]", type=int, metavar="N", joint_key="elements",
           check=whole(2, 100_000)),
    Option("coupling", "two-directional joints: one circular Coulomb limit or the paper's "
           "decoupled sum", "", " | ".join(COUPLINGS), type=None, choices=COUPLINGS,
           key="structure.coupling", joint_key="coupling", check=choice(COUPLINGS),
           case_note="circular if none is given; a [[joint]] table's own wins over "
           "[structure]'s"),
    Option("transverse", "a two-directional tip or centre joint: the joint across the bar "
           "(second direction): the clamp's tip or centre model (same clamp and series "
           "spring) or fe, the built-in FE's first loading of the centre force across the bar "
           "(needs the stick slope)", "", " | ".join(TRANSVERSE), type=None,
           choices=TRANSVERSE, joint_key="transverse", check=choice(TRANSVERSE),
           case_note="omitted, the joint's own model"),
    Option("pairing", "with transverse and circular coupling: how the elements along and "
           "across are matched: by position on the bar (spatial, the default) or by slip "
           "order (ordered)", "", " | ".join(PAIRINGS), type=None, choices=PAIRINGS,
           joint_key="pairing", check=choice(PAIRINGS)),
    # the harmonic balance (modal, frf: docs/dynamics.md, "Harmonics chosen by an error
    # estimate")
    Option("harmonics", "harmonics of the balance: auto raises them (and the AFT samples) "
           "until the damping ratio and frequency change by less than --harmonic-tolerance; "
           "a number fixes them, 1 = single-harmonic (describing-function) balance", "",
           "auto | [1, 256]", type=harmonics_count, metavar="auto|H", scope="all"),
    Option("harmonic_tolerance", "with --harmonics auto: largest relative change of the "
           "damping ratio and frequency between two levels of harmonics (1, 3, 7, 15, 31, "
           "63) that a point accepts", "", "(0, 0.5)", metavar="X", scope="all"),
    Option("fe_mesh", f"with transverse fe: the FE mesh, as --mesh ({', '.join(LEVELS)} or "
           f"NXxNYxNZ; default {DEFAULT_MESH})", "", f"{' | '.join(LEVELS)} | NXxNYxNZ",
           type=mesh_level, metavar="LEVEL", joint_key="fe_mesh", check=mesh_text,
           case_default=DEFAULT_MESH),
)

#: Option name -> :class:`Option`.
OPTIONS: dict[str, Option] = {o.name: o for o in (*_OPTIONS, *RUN_OPTIONS)}
assert len(OPTIONS) == len(_OPTIONS) + len(RUN_OPTIONS), "an option is in the table twice"

#: Case key -> (argparse destination, which load case reads it: "all", "load" or "planar").
#: ``load.amplitude_fraction`` also gives the amplitude (resolved after the parse).
CASE_DESTS: dict[str, tuple[str, str]] = {
    **{o.key: (o.name, o.scope) for o in _OPTIONS if o.key is not None},
    "load.amplitude_fraction": ("amplitude", "load"),
    "mesh.file": ("mesh", "mesh"),  # the mesh file is fe's --mesh FILE
}

#: What ``--solver`` means, per command: its choices and their meaning (the default first).
SOLVERS: dict[str, dict[str, str]] = {
    "fe": {"builtin": "the built-in finite-element solver (docs/solver.md)",
           "calculix": "CalculiX (ccx; docs/validation.md)"},
    "planar": {"analytical": "the paper's decoupled 1-D models, Table 2 zones",
               "fe": "the built-in frictional FE solver, one body with coupled 2-D friction, "
                     "against its two uni-axial runs"},
    "sweep": {"batch": "the 1-D models' compiled engine",
              "fe": "one finite-element run per amplitude of --amplitude-range, saved to --out "
                    "FILE.csv as it finishes, resumed by running the same command again"},
}


def _help(opt: Option, default: Any, note: str, help_text: str | None) -> str:
    body = opt.help if help_text is None else help_text
    unit = f", {opt.unit}" if opt.unit else ""
    rng = f", {opt.range}" if opt.range and opt.choices is None and opt.type is number else ""
    hidden = default is None or default is argparse.SUPPRESS or isinstance(default, bool) \
        or default == []
    value = " ".join(map(str, default)) if isinstance(default, (list, tuple)) else default
    shown = "" if hidden else f" (default {default:g})" if isinstance(default, float) \
        else f" (default {value})"
    return f"{body}{unit}{rng}{shown}{'; ' + note if note else ''}"


#: The modes of a command that :func:`add_option` records (``mode=``): a mesh of the user's
#: own (``--mesh FILE``), the built-in box (``fe``, ``validate`` without a mesh file), a
#: structure file or one mode (``modal``, ``frf`` without ``--mesh``).
MODE_MESH, MODE_BOX, MODE_STRUCTURE = "mesh", "box", "structure"

#: What the help of an option of one mode says (``modal --help``: ``--method`` is for a
#: structure file or one mode, not for ``--mesh``).
MODE_NOTES = {MODE_MESH: "[--mesh FILE only]",
              MODE_BOX: "[the box only: not with --mesh FILE]",
              MODE_STRUCTURE: "[1-D structure (--structure FILE or one mode) only: not with "
                              "--mesh]"}

#: The parser default under which :func:`add_option` records the mode an option belongs to
#: (``mode="mesh"``): destination -> mode, for :func:`mode_options`.
MODES_KEY = "option_modes"


def mode_options(args: argparse.Namespace, mode: str) -> tuple[str, ...]:
    """The destinations of the options that ``add_option(..., mode=mode)`` added to the
    command of ``args``: the options that do something in that mode only."""
    modes: dict[str, str] = getattr(args, MODES_KEY, {})
    return tuple(d for d, m in modes.items() if m == mode)


#: ``add_option``'s "no default of the command's own": the option's table default.
_TABLE_DEFAULT: Any = object()


def add_option(group: Any, name: str, *, default: Any = _TABLE_DEFAULT, note: str = "",
               help: str | None = None, flag: str | None = None, mode: str | None = None,
               **extra: Any) -> argparse.Action:
    """Add the option ``name`` of :data:`OPTIONS` to a parser or argument group.

    ``default`` is the command's default if it has its own (else the table's,
    :attr:`Option.default`; shown in the help), ``note`` a command-specific
    sentence after the shared help, ``help`` a replacement of the shared help text, ``flag``
    another spelling (``case new --mesh`` for ``mesh_file``), ``mode`` the mode of the
    command the option belongs to (``"mesh"``: with ``--mesh FILE`` only; the command refuses
    it in its other modes, :func:`mode_options`); ``extra`` goes to ``add_argument``
    (``required=True``, the choices of a library registry, ...).
    ``--solver`` is not here: :func:`add_solver` documents what it means per command.
    """
    opt = OPTIONS[name]
    if default is _TABLE_DEFAULT:
        default = opt.default
    kwargs: dict[str, Any] = {"dest": opt.name, "help": _help(opt, default, note, help)}
    if mode is not None:
        kwargs["help"] += f" {MODE_NOTES[mode]}"
    if opt.action == "store_true":
        kwargs["action"] = "store_true"
        kwargs["default"] = False if default is None else default
    else:
        kwargs["default"] = default
        if opt.action is not None:
            kwargs["action"] = opt.action
        if opt.nargs is not None:
            kwargs["nargs"] = opt.nargs
        if opt.choices is not None:
            kwargs["choices"] = list(opt.choices)
        elif opt.metavar is not None:
            kwargs["metavar"] = opt.metavar
        if opt.type is not None:
            kwargs["type"] = opt.type
    kwargs.update(extra)
    action = group.add_argument(flag or opt.flag, **kwargs)
    if mode is not None:
        _record_mode(group, action.dest, mode)
    return action


def _record_mode(group: Any, dest: str, mode: str) -> None:
    """Record that the option ``dest`` of ``group``'s parser belongs to ``mode``."""
    modes = dict(group.get_default(MODES_KEY) or {})
    modes[dest] = mode
    group.set_defaults(**{MODES_KEY: modes})


def add_solver(group: Any, command: str, choices: Sequence[str] | None = None,
               meaning: dict[str, str] | None = None, mode: str | None = None,
               note: str = "") -> argparse.Action:
    """``--solver`` of ``command``, its choices and what each means (:data:`SOLVERS`, or
    ``meaning`` from a library registry: ``modal --mesh``'s solvers), the first the default.
    With ``mode`` (:func:`add_option`) the option belongs to that mode only and defaults to
    nothing (the command takes the first where it applies)."""
    meaning = SOLVERS[command] if meaning is None else meaning
    names = list(meaning if choices is None else choices)
    action = group.add_argument(
        "--solver", choices=names, default=names[0] if mode is None else None,
        help="; ".join(f"{k}: {meaning[k]}" for k in names) + f" (default {names[0]})"
        + (f"; {note}" if note else "") + (f" {MODE_NOTES[mode]}" if mode else ""))
    if mode is not None:
        _record_mode(group, action.dest, mode)
    return action
