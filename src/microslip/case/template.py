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
from .schema import CLAMP_KEYS, JOINT_KEYS, KEYS, SECTIONS, Key

__all__ = ["TEMPLATE_PRESET", "TEMPLATE_VALUES", "template"]

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
