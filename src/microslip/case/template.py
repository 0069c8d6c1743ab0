"""The commented case-file template of ``microslip case new``, written from the key table.

Every key is written with its meaning, unit, range and default on the line above it. Only
``preset`` and the planar load (:data:`TEMPLATE_VALUES`, so that ``planar --case`` runs on
it) are active; the other keys are commented out with their default (or the preset's value)
as an example, so the template parses back to the preset and the documented defaults, and a
command reads from it only what the user uncomments.
"""

from __future__ import annotations

from typing import Any

from ..params import PRESETS
from .schema import CLAMP_KEYS, JOINT_KEYS, KEYS, MESH_LOAD_KEYS, SECTIONS, Key

__all__ = ["TEMPLATE_PRESET", "TEMPLATE_VALUES", "mesh_template", "template"]

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
        lines.extend(_line(k) for k in KEYS if k.section == section)
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


# -- the template of a mesh of the user's own ------------------------------------------------

#: Sections a mesh case holds besides [mesh]: the clamp's values the mesh does not give (its
#: geometry is the mesh's).
MESH_CLAMP_SECTIONS = ("material", "contact", "clamping")
#: Keys of those sections a mesh's commands do not read (the box's pressure law).
MESH_UNUSED_KEYS = ("clamping.pressure",)
#: Set names taken as a role's value when the mesh has them (else the role is left to fill).
ROLE_GUESSES = {"contact_set": ("contact", "base", "bottom"), "clamp_set": ("clamp", "top"),
                "response_set": ("response", "tip")}


def _mesh_line(key: Key, value: Any, active: bool, note: str) -> str:
    unit = f"{key.unit}, " if key.unit else ""
    shown = "" if value is None else _toml(value)
    return (f"# {key.meaning}; {unit}{key.range}; {note}\n"
            f"{'' if active else '# '}{key.name} = {shown}".rstrip())


def mesh_template(mesh_file: str, node_sets: tuple[str, ...], surfaces: tuple[str, ...]
                  ) -> str:
    """The text of a case file of a mesh of the user's own: the [mesh] section with the
    file (as given, relative to the case file), its sets (listed from the file; a role's
    value where the file has a set of the usual name, :data:`ROLE_GUESSES`), the contact,
    density, mode and response set, an example of its ``[[mesh.load]]`` tables, and the
    clamp values the mesh does not give (:data:`MESH_CLAMP_SECTIONS`, set to the
    :data:`TEMPLATE_PRESET` values as an example to edit). No preset and no [geometry]: the
    mesh gives the geometry."""
    base = PRESETS[TEMPLATE_PRESET][0].as_dict()
    names = (*node_sets, *(s for s in surfaces if s not in node_sets))
    listed = ", ".join(names) if names else "none"
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
        for key in KEYS:
            if key.section != section or key.dotted in MESH_UNUSED_KEYS:
                continue
            if key.dotted in CLAMP_KEYS:
                value = base[CLAMP_KEYS[key.dotted]]
                note = f"no default: set to {TEMPLATE_PRESET}'s {value:g} as an example, edit it"
            else:
                value, note = key.default, f"default: {key.default:g}"
            lines.append(_mesh_line(key, value, True, note))
    lines += ["", f"[mesh]  # {SECTIONS['mesh']}",
              f"# sets of {mesh_file}: node sets: {', '.join(node_sets) or 'none'}; "
              f"element-face surfaces: {', '.join(surfaces) or 'none'}"]
    roles = {role: next((n for n in guesses if n in names), None)
             for role, guesses in ROLE_GUESSES.items()}
    for key in KEYS:
        if key.section != "mesh":
            continue
        role = key.name
        if key.dotted == "mesh.file":
            lines.append(_mesh_line(key, mesh_file, True, "required"))
        elif role in ROLE_GUESSES:
            hit = roles[role]
            note = f"one of: {listed}" + ("" if role == "response_set" else "; required")
            lines.append(_mesh_line(key, hit if hit is not None else "", hit is not None,
                                    note))
        elif key.default is None:
            lines.append(_mesh_line(key, None, False, "default: none"))
        else:
            shown = _toml(key.default) if isinstance(key.default, str) else \
                format(key.default, "g")
            lines.append(_mesh_line(key, key.default, False, f"default: {shown}"))
    loaded = next((n for n in names if n not in roles.values()), "SET")
    lines += ["", "# [[mesh.load]] tables: the loads of the mesh (fe, validate), one table "
              "each:", *(f"#   {name}: {what}" for name, (_, what) in MESH_LOAD_KEYS.items()),
              "# Example (uncomment; two loads at 90 degrees make a planar load):",
              "# [[mesh.load]]", f'# set = "{loaded}"', "# direction = [1.0, 0.0, 0.0]",
              "# amplitude = 100.0", "# phase_deg = 0.0"]
    return "\n".join(lines) + "\n"


_KEY = {k.dotted: k for k in KEYS}
