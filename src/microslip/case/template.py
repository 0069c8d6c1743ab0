"""The commented case-file template of ``microslip case new``, written from the key table.

Every key is written with its meaning, unit, range and default on the line above it. Only
``preset`` and the planar load (:data:`TEMPLATE_VALUES`, so that ``planar --case`` runs on
it) are active; the other keys are commented out with their default (or the preset's value)
as an example, so the template parses back to the preset and the documented defaults, and a
command reads from it only what the user uncomments.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..params import PRESETS
from .schema import CLAMP_KEYS, JOINT_KEYS, KEYS, MESH_LOAD_KEYS, SECTIONS, TABLE_KEYS, Key

if TYPE_CHECKING:
    from .meshroles import MeshOffer

__all__ = ["TEMPLATE_PRESET", "TEMPLATE_VALUES", "MeshTemplate", "mesh_template", "template"]

#: The preset the template starts from.
TEMPLATE_PRESET = "table1"

#: Keys the template sets (besides ``preset``), so that every command runs on it: the planar
#: load is the paper's circular case, R = 1 at 90 degrees (tip/2000 N = centre/4000 N on the
#: paper's levels, so the centre amplitude is twice the tip's), scaled into the table1
#: clamp's slip limit mu F_N = 356 N.
TEMPLATE_VALUES = {
    "load.planar.tip_amplitude": 100.0,
    "load.planar.centre_amplitude": 200.0,
    "load.planar.phase_deg": 90.0,
}


def _toml(value: Any) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _line(key: Key) -> str:
    unit = f"{key.unit}, " if key.unit else ""
    value: object
    if key.dotted in CLAMP_KEYS:
        value = PRESETS[TEMPLATE_PRESET][0].as_dict()[CLAMP_KEYS[key.dotted]]
        note = f"default: from the preset ({TEMPLATE_PRESET}: {value:g})"
    elif key.dotted == "preset":
        value = TEMPLATE_PRESET
        note = "default: none (then give all seven clamp values)"
    elif key.dotted in TEMPLATE_VALUES:
        value = TEMPLATE_VALUES[key.dotted]
        default = "none" if key.default is None else format(key.default, "g")
        note = f"default: {default}; set to the paper's circular case, R = 1 at 90 degrees"
    elif key.default is None:
        value, note = "", "default: none"
    else:
        value = key.default
        shown = _toml(value) if isinstance(value, str) else format(value, "g")
        note = f"default: {shown}"
    active = "" if key.dotted == "preset" or key.dotted in TEMPLATE_VALUES else "# "
    return (f"# {key.meaning}; {unit}{key.range}; {note}\n"
            f"{active}{key.name} = {_toml(value) if value != '' or key.default == '' else ''}")


def template() -> str:
    """The text of a commented case file with every key, its unit, range and default."""
    lines = [
        "# microslip case file (TOML). Units: N, mm, MPa, N/mm^3, degrees.",
        "# Use it with --case FILE.toml on loop, planar, fe, sweep and validate (modal and frf",
        "# read [structure] and [[joint]]); options on the command line override the file.",
        "# See docs/casefile.md.",
        "# Without an amplitude the load is amplitude_fraction x mu F_N (the slip limit).",
    ]
    for section, what in SECTIONS.items():
        lines.append("")
        if section:
            lines.append(f"[{section}]  # {what}")
        lines.extend(_line(k) for k in KEYS if k.section == section
                     and k.dotted not in TABLE_KEYS)
    lines += _table_help()
    lines += ["# the loads of the mesh: [[mesh.load]] tables (set, direction, amplitude, "
              "phase_deg);", "# microslip case new --mesh MESHFILE FILE.toml writes a case "
              "of your own mesh"]
    lines.extend(_joints())
    return "\n".join(lines) + "\n"


#: The example joints of the template (uncommented, they parse: tests/test_case_joints.py).
JOINT_EXAMPLE = (
    "[[joint]]",
    "dofs = [0]",
    'model = "jenkins"',
    "stiffness = 300.0",
    "slip_force = 5.0",
    "",
    "[[joint]]",
    "dofs = [[1, -1], [2, -1]]",
    'model = "tip"',
    'coupling = "circular"',
    "stiffness = 1e5",
    "[joint.clamping]",
    "normal_force = 600.0",
)


def _joints() -> list[str]:
    """The [[joint]] tables, commented out: their keys, then an example of two joints."""
    out = ["", "# [[joint]] tables: the joints of the [structure], one table each (modal, frf).",
           "# A tip or centre joint takes the clamp above unless it gives its own preset or",
           "# [joint.geometry], [joint.material], [joint.contact], [joint.clamping] values."]
    for key in JOINT_KEYS:
        unit = f"{key.unit}, " if key.unit else ""
        out.append(f"#   {key.name}: {key.meaning}; {unit}{key.range}")
    out.append("# Example (uncomment):")
    out.extend(f"#   {line}".rstrip() for line in JOINT_EXAMPLE)
    return out


def _table_help() -> list[str]:
    """The assembly's tables, commented: what each is and its keys (they follow every plain
    key of [mesh]: a table opened in the middle would take the keys after it)."""
    out = ["# the assembly of the mesh (issue 32; docs/casefile.md): [[mesh.contact]],",
           "# [[mesh.preload]], [[mesh.support]] and [[mesh.material]] tables, one per item:"]
    for dotted, fields in TABLE_KEYS.items():
        key = _KEY[dotted]
        out.append(f"#   [[{dotted}]]: {key.meaning}")
        for f in fields:
            unit = f", {f.unit}" if f.unit else ""
            need = "required" if f.required else "optional"
            out.append(f"#     {f.name} ({need}{unit}): {f.meaning}")
    return out


# -- the template of a mesh of the user's own ------------------------------------------------

#: Sections a mesh case holds besides [mesh]: the clamp's values the mesh does not give (its
#: geometry is the mesh's).
MESH_CLAMP_SECTIONS = ("material", "contact", "clamping")
#: Keys of those sections a mesh's commands do not read (the box's pressure law).
MESH_UNUSED_KEYS = ("clamping.pressure",)
#: Set names taken as a role's value when the mesh has them (else the role is left to fill).
ROLE_GUESSES = {"contact_set": ("contact", "base", "bottom"), "clamp_set": ("clamp", "top"),
                "response_set": ("response", "tip")}
#: Set names taken as a bolt's pressed faces (``[[mesh.preload]]``) and as a support
#: (``[[mesh.support]]``) in a mesh of several bodies: ``head``, ``nut2``, ``washer``; ``fix``,
#: ``base_fix``, ``support``.
PRELOAD_NAMES = re.compile(r"^(head|nut|washer|bolt)[_-]?\d*$", re.IGNORECASE)
SUPPORT_NAMES = re.compile(r"^(fix|fixed|support|held|ground)[_-]?\d*$|[_-](fix|fixed)$",
                           re.IGNORECASE)
#: Set names the example load takes first (a load may act on the response set).
LOAD_GUESSES = ("load", "tip", "end", "top")
#: What each role is, for the list of roles a template leaves to fill.
ROLE_MEANINGS = {"contact_set": "the face on the rigid base",
                 "clamp_set": "the face the clamping force presses",
                 "response_set": "the set whose motion is the amplitude (modal, frf)"}


@dataclass(frozen=True)
class MeshTemplate:
    """A case file of a mesh: its ``text``, and the roles it could not fill (``unfilled``:
    one sentence each, the key and why)."""

    text: str
    unfilled: tuple[str, ...]


def _mesh_line(key: Key, value: Any, active: bool, note: str) -> str:
    unit = f"{key.unit}, " if key.unit else ""
    shown = "" if value is None else _toml(value)
    return (f"# {key.meaning}; {unit}{key.range}; {note}\n"
            f"{'' if active else '# '}{key.name} = {shown}".rstrip())


def _roles(offer: MeshOffer) -> dict[str, str | None]:
    """The role sets guessed by name (:data:`ROLE_GUESSES`) among the mesh's faces; a set of
    an interface pair is not a role of the rigid base's shorthand."""
    paired = {n for p in offer.pairs for n in p}
    usable = [n for n in offer.faces if n not in paired]
    return {role: next((n for n in guesses if n in usable), None)
            for role, guesses in ROLE_GUESSES.items()}


def _bolt_pairs(names: list[str]) -> tuple[list[tuple[str, str]], list[str]]:
    """(head, nut) pairs of the same number among ``names`` (``head2``, ``nut2``), and the
    names left over."""
    key = {n: re.sub(r"^(head|nut|washer|bolt)", "", n, flags=re.IGNORECASE) for n in names}
    heads = [n for n in names if n.lower().startswith("head")]
    nuts = [n for n in names if n.lower().startswith("nut")]
    pairs = [(h, n) for h in heads for n in nuts if key[h] == key[n]]
    used = {x for p in pairs for x in p}
    return pairs, [n for n in names if n not in used]


def _named(offer: MeshOffer, pattern: re.Pattern[str]) -> list[str]:
    """Face sets of a mesh of several bodies whose names match ``pattern`` (not in a pair)."""
    if len(offer.bodies) < 2:
        return []
    paired = {n for p in offer.pairs for n in p}
    return [n for n in offer.faces if n not in paired and pattern.search(n)]


def mesh_template(mesh_file: str, offer: MeshOffer) -> MeshTemplate:
    """The case file of a mesh of the user's own (``case new --mesh``).

    The [mesh] section with the file (as given, relative to the case file), its sets listed
    by kind, a role's value where the mesh has a set of the usual name
    (:data:`ROLE_GUESSES`; volume groups are never a face), the contact, density, mode and
    response set; the clamp values the mesh does not give (:data:`MESH_CLAMP_SECTIONS`, set
    to the :data:`TEMPLATE_PRESET` values as an example to edit). A mesh of several bodies
    also gets a ``[[mesh.material]]`` table per element set of a body (the [material]
    values, to edit) and a ``[[mesh.contact]]`` table per interface found (sets of two
    bodies whose nodes coincide one to one). Every role left to fill is named, in the file
    and in :attr:`MeshTemplate.unfilled`. No preset and no [geometry]: the mesh gives the
    geometry."""
    base = PRESETS[TEMPLATE_PRESET][0].as_dict()
    faces = ", ".join(offer.faces) or "none"
    several = len(offer.bodies) > 1
    roles = _roles(offer)
    bolts = _named(offer, PRELOAD_NAMES) if roles["clamp_set"] is None else []
    unfilled: list[str] = []
    for role, hit in roles.items():
        if hit is None and not (several and role == "contact_set") and not (
                role == "clamp_set" and bolts):
            names = " or ".join(ROLE_GUESSES[role])
            unfilled.append(f"mesh.{role} ({ROLE_MEANINGS[role]}): no face set named {names}; "
                            f"one of: {faces}")
    lines = [
        "# microslip case file (TOML) of your own part: the mesh and its clamp. Units: N, mm,",
        "# MPa, N/mm^3, kg/m^3, degrees. Use it with --case FILE.toml on fe, validate, modal,",
        "# frf, reduce and report (docs/casefile.md, docs/ownmesh.md); options on the command",
        "# line override the file. The mesh gives the geometry: no preset, no [geometry].",
        "",
        _mesh_line(_KEY["name"], "", True, "default: none"),
    ]
    for section in MESH_CLAMP_SECTIONS:
        lines += ["", f"[{section}]  # {SECTIONS[section]}"]
        if section == "material" and several:
            lines.append("# the material of every element no [[mesh.material]] table names")
        for key in KEYS:
            if key.section != section or key.dotted in MESH_UNUSED_KEYS:
                continue
            active = True
            if key.dotted == "clamping.normal_force" and bolts:
                value, active = base["normal_force"], False
                note = ("the force of mesh.clamp_set (the shorthand's preload); the "
                        "[[mesh.preload]] tables below give each face its own")
            elif key.dotted in CLAMP_KEYS:
                value = base[CLAMP_KEYS[key.dotted]]
                note = f"no default: set to {TEMPLATE_PRESET}'s {value:g} as an example, edit it"
            elif key.default is None:  # optional, nothing assumed (yield_strength)
                value, active, note = None, False, "default: none"
            else:
                value, note = key.default, f"default: {key.default:g}"
            lines.append(_mesh_line(key, value, active, note))
    lines += ["", f"[mesh]  # {SECTIONS['mesh']}",
              f"# sets of {mesh_file}: node sets: {', '.join(offer.node_sets) or 'none'}; "
              f"element-face surfaces: {', '.join(offer.surfaces) or 'none'}; element sets: "
              f"{', '.join(offer.element_sets) or 'none'}"]
    if offer.volumes:
        lines.append(f"# volume groups (never a face or a load): {', '.join(offer.volumes)}")
    if several:
        lines.append(f"# {len(offer.bodies)} bodies: {'; '.join(offer.body_names)}")
    for key in KEYS:
        if key.section != "mesh" or key.dotted in TABLE_KEYS:
            continue
        role = key.name
        if key.dotted == "mesh.file":
            lines.append(_mesh_line(key, mesh_file, True, "required"))
        elif role in ROLE_GUESSES:
            hit = roles[role]
            need = ("" if role == "response_set" else
                    "; with several bodies, for a body on the rigid base" if several
                    and role == "contact_set" else "; required")
            lines.append(_mesh_line(key, hit if hit is not None else "", hit is not None,
                                    f"one of: {faces}{need}"))
        elif key.default is None:
            lines.append(_mesh_line(key, None, False, "default: none"))
        else:
            shown = _toml(key.default) if isinstance(key.default, str) else \
                format(key.default, "g")
            lines.append(_mesh_line(key, key.default, False, f"default: {shown}"))
    if several:
        lines += _assembly_tables(offer, base, unfilled, roles, bolts)
    taken = ({roles["contact_set"], roles["clamp_set"], *bolts, *_named(offer, SUPPORT_NAMES)}
             | {n for p in offer.pairs for n in p})
    free = [n for n in offer.faces if n not in taken]
    loaded = next((n for n in LOAD_GUESSES if n in free), None) or next(
        (n for n in free if n != roles["response_set"]), None) or next(iter(free), None)
    if loaded is None:
        unfilled.append(f"[[mesh.load]] (the loads of fe and validate): no face set is left "
                        f"for a load besides the roles; name one of: {faces}")
    lines += ["", "# [[mesh.load]] tables: the loads of the mesh (fe, validate), one table "
              "each:", *(f"#   {name}: {what}" for name, (_, what) in MESH_LOAD_KEYS.items()),
              "# Example (uncomment; two loads at 90 degrees make a planar load):",
              "# [[mesh.load]]", f'# set = "{loaded or "SET"}"',
              "# direction = [1.0, 0.0, 0.0]", "# amplitude = 100.0", "# phase_deg = 0.0"]
    if unfilled:
        head = ["# Roles left to fill (case check names what is still missing):"]
        head += [f"#   {u}" for u in unfilled]
        lines = lines[:5] + head + lines[5:]
    return MeshTemplate("\n".join(lines) + "\n", tuple(unfilled))


def _assembly_tables(offer: MeshOffer, base: dict[str, Any], unfilled: list[str],
                     roles: dict[str, str | None], bolts: list[str]) -> list[str]:
    """The [[mesh.material]] tables of the bodies' element sets, the [[mesh.contact]] tables
    of the interfaces found, the preloads of a bolt's faces and the supports found by name
    (:data:`PRELOAD_NAMES`, :data:`SUPPORT_NAMES`), or their examples commented."""
    out = ["", "# The bodies' materials: one [[mesh.material]] table per element set (the "
           "values of", "# [material] as an example: edit them)."]
    for body, (sets, name) in enumerate(zip(offer.bodies, offer.body_names, strict=True), 1):
        if not sets:
            unfilled.append(f"[[mesh.material]] of {name}: it has no element set of its own; "
                            "[material] gives it (or name its elements: *ELSET, a gmsh "
                            "volume group)")
        for elset in sets:
            out += ["[[mesh.material]]", f"elset = {_toml(elset)}  # body {body}",
                    f"modulus = {_toml(float(base['modulus']))}",
                    f"poisson_ratio = {_toml(float(base['poisson_ratio']))}",
                    "# density = 7850.0", ""]
    if offer.pairs:
        out += ["# The interfaces found (sets of two bodies whose nodes coincide one to one): "
                "face on", "# counter, the counter on the body with fewer elements."]
        for face, counter in offer.pairs:
            out += ["[[mesh.contact]]", f"face = {_toml(face)}", f"counter = {_toml(counter)}",
                    ""]
    else:
        unfilled.append("[[mesh.contact]] (the interfaces between the bodies): no two sets of "
                        "different bodies with coincident nodes; name each side's face")
    held = _named(offer, SUPPORT_NAMES)
    if held:
        out += ["# The supports found by name: each set held in x, y and z (edit directions)."]
        for name in held:
            out += ["[[mesh.support]]", f"set = {_toml(name)}", 'directions = "xyz"', ""]
    else:
        if roles.get("contact_set") is None:
            unfilled.append("[[mesh.support]] (what holds the assembly: set, directions), or "
                            "mesh.contact_set for a body on the rigid base")
        out += ["# [[mesh.support]] tables: what holds the assembly (set, directions = "
                "\"xyz\"):", "# [[mesh.support]]", '# set = "SET"', '# directions = "xyz"',
                ""]
    force = float(base["normal_force"])
    pairs, singles = _bolt_pairs(bolts)
    if pairs:
        out += ["# The bolts found by name (a head and a nut face of the same number), each "
                "pressed by", f"# the bolt's force ({force:g} N of {TEMPLATE_PRESET} as an "
                "example: edit it). Give a diameter (mm)", "# for a shank between the faces: "
                "without it a lateral load past the friction's limit has", "# no equilibrium."]
        for head, nut in pairs:
            out += ["[[mesh.bolt]]", f"head = {_toml(head)}", f"nut = {_toml(nut)}",
                    f"force = {_toml(force)}", "# diameter = 10.0", ""]
    if singles:
        out += [f"# Faces named like a bolt's, each pressed by a force ({force:g} N of "
                f"{TEMPLATE_PRESET} as an example: edit it)."]
        for name in singles:
            out += ["[[mesh.preload]]", f"face = {_toml(name)}", f"force = {_toml(force)}", ""]
    if not bolts:
        out += ["# [[mesh.preload]] tables: more pressed faces (face, force N; a bolt: its "
                "head and nut faces):", "# [[mesh.preload]]", '# face = "SET"',
                f"# force = {_toml(force)}"]
    return out


_KEY = {k.dotted: k for k in KEYS}
