"""The keys of a case file: section, name, unit, range, default, meaning (one table).

Every key a case file may hold is one :class:`Key` in :data:`KEYS`; the parser, the
commented template and the documentation (docs/casefile.md) all read this table. The keys
that are also command-line options (all but ``name``, ``description``, ``preset``,
``load.amplitude_fraction`` and a joint's ``dofs``) are built from the one option table,
:data:`microslip.case.table.OPTIONS`, so a key and its flag share unit, range, check and
meaning. A key is addressed by its dotted name, ``section.name`` (``geometry.length``,
``load.planar.ratio``); top-level keys have no section.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from ..conventions import (
    CLAMP_MODELS,
    COUPLINGS,
    DEFAULT_MESH,
    JOINT_MODELS,
    PAIRINGS,
    TRANSVERSE,
)
from ..errors import ParameterError
from ..jointspec import JOINT_USES
from ..params import PRESETS, ClampParams
from .assembly import TABLES, Field
from .table import (
    OPTIONS,
    PRESSURE_LAWS,
    Check,
    Option,
    choice,
    positive,
    text,
)

__all__ = [
    "ACROSS_KEYS",
    "CLAMP_KEYS",
    "COUPLINGS",
    "DEFAULT_AMPLITUDE_FRACTION",
    "DEFAULT_FE_MESH",
    "FUTURE_PRESSURE_LAWS",
    "JOINT_CLAMP_SECTIONS",
    "JOINT_KEYS",
    "JOINT_MODELS",
    "JOINT_USES",
    "KEYS",
    "MESH_LOAD_KEYS",
    "PAIRINGS",
    "PRESSURE_LAWS",
    "SECTIONS",
    "TABLE_KEYS",
    "TRANSVERSE",
    "Key",
]

#: Default load amplitude of a case, as a fraction of the slip limit mu F_N of its clamp.
DEFAULT_AMPLITUDE_FRACTION = 0.5

#: Clamping pressure laws planned (issue 11) but not yet available.
FUTURE_PRESSURE_LAWS: tuple[str, ...] = ()

#: Uniaxial load cases of a case file: the clamp's two models.
LOAD_MODELS = CLAMP_MODELS

#: Mesh of the FE's first loading across the bar (``transverse = "fe"``) unless given.
DEFAULT_FE_MESH = DEFAULT_MESH


def _dof(name: str, value: Any, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise ParameterError(f"case key {name} must hold whole DOF numbers >= {low} (0-based, "
                             f"-1 for the ground as J), got {value!r}")
    return int(value)


def joint_dofs(name: str, value: Any) -> tuple[tuple[int, int], ...]:
    """A check: where a joint sits, as ``[i, j]`` per direction (j = -1: the ground).

    ``[I]`` or ``[I, J]``: one direction, between DOF I and the ground or DOF J (as
    ``--joint-dof``); ``[[I, J], [K, L]]`` (or ``[[I], [K]]``): two directions, one pair per
    direction (as the (n, 2, 2) ``joints`` array of a structure file).
    """
    shape = ("must be [I], [I, J] (one direction) or [[I, J], [K, L]] (two directions), "
             "0-based")
    if not isinstance(value, list) or not value:
        raise ParameterError(f"case key {name} {shape}, got {value!r}")
    rows = value if all(isinstance(v, list) for v in value) else [value]
    if len(rows) > 2 or any(not 1 <= len(r) <= 2 for r in rows):
        raise ParameterError(f"case key {name} {shape}, got {value!r}")
    out = tuple((_dof(name, r[0], 0), _dof(name, r[1], -1) if len(r) == 2 else -1)
                for r in rows)
    if any(i == j for i, j in out):
        raise ParameterError(f"case key {name}: a joint connects two different DOFs, got "
                             f"{value!r}")
    return out


@dataclass(frozen=True)
class Key:
    """One key of a case file."""

    section: str
    name: str
    check: Check
    unit: str
    range: str
    default: Any
    meaning: str

    @property
    def dotted(self) -> str:
        return f"{self.section}.{self.name}" if self.section else self.name


#: Sections of a case file, in the order of the template, with what they describe.
SECTIONS = {
    "": "the case",
    "geometry": "clamped zone (paper, Fig. 3)",
    "material": "the clamped body",
    "contact": "the interface",
    "clamping": "the clamping load",
    "load": "uniaxial load case (read by loop, fe, sweep, validate)",
    "load.planar": "planar load case (read by planar)",
    "structure": "a structure from a file with its joints (read by modal and frf)",
    "mesh": "a mesh of your own part: its sets, contact, density, mode, response set, its "
            "assembly's [[mesh.contact]], [[mesh.preload]], [[mesh.support]] and "
            "[[mesh.material]] tables and its [[mesh.load]] tables (read by fe, validate, "
            "modal, frf, reduce, report)",
}

#: The keys of a ``[[mesh.load]]`` table: name -> (default, None if required; meaning).
MESH_LOAD_KEYS: dict[str, tuple[Any, str]] = {
    "set": (None, "a set of the mesh (element faces or nodes) that carries the load"),
    "direction": (None, "[DX, DY, DZ], global axes (normalised)"),
    "amplitude": (None, "A, N: the load is F(t) = A sin(2 pi t + phase), A in total over "
                        "the set"),
    "phase_deg": (0.0, "the phase, degrees (default 0)"),
}

def _meaning(opt: Option) -> str:
    note = f"; {opt.case_note}" if opt.case_note else ""
    flag = "fe --mesh FILE" if opt.key == "mesh.file" else opt.flag
    return f"{opt.help}{note} (as {flag})"


def _key(section: str, name: str, opt: Option) -> Key:
    """The case key ``section.name`` of the option ``opt`` (its check, unit, range, meaning)."""
    assert opt.check is not None, opt.name  # every option with a key has a check
    return Key(section, name, opt.check, opt.unit, opt.range, opt.case_default, _meaning(opt))


def _option_keys() -> tuple[Key, ...]:
    out = []
    for opt in OPTIONS.values():
        if opt.key is not None:
            section, _, name = opt.key.rpartition(".")
            out.append(_key(section, name, opt))
    return tuple(out)


#: Every key of a case file: the case's own (name, description, preset), the options'
#: (:data:`microslip.case.table.OPTIONS`) and the amplitude as a fraction of the slip limit.
KEYS: tuple[Key, ...] = (
    Key("", "name", text, "", "any text", "", "short name of the case, shown in outputs"),
    Key("", "description", text, "", "any text", "", "what the case is"),
    Key("", "preset", choice(tuple(sorted(PRESETS))), "", " | ".join(sorted(PRESETS)), None,
        "paper parameter set used as the base that the keys below override"),
    *_option_keys(),
    Key("load", "amplitude_fraction", positive("", 1.0), "", "(0, 1)",
        DEFAULT_AMPLITUDE_FRACTION, "load amplitude as a fraction of the slip limit mu F_N"),
)

#: The assembly's tables of the case file (``[[mesh.contact]]``, ``[[mesh.preload]]``,
#: ``[[mesh.support]]``, ``[[mesh.material]]``): dotted key -> the keys of one table. Each is
#: the key of a repeatable option (``--contact``, ...), whose check reads the tables.
TABLE_KEYS: dict[str, tuple[Field, ...]] = {f"mesh.{name}": fields
                                            for name, (_, fields) in TABLES.items()}
assert all(k in {o.key for o in OPTIONS.values()} for k in TABLE_KEYS)

#: The keys of one ``[[joint]]`` table (section ``joint``): where it sits, and the options
#: of ``--joint`` with a ``joint_key``; a tip or centre joint also takes ``preset`` and the
#: clamp sections of :data:`JOINT_CLAMP_SECTIONS`.
JOINT_KEYS: tuple[Key, ...] = (
    Key("joint", "dofs", joint_dofs, "", "[I], [I, J] or [[I, J], [K, L]]", None,
        "where the joint sits: DOF I (0-based) to the ground, I to J, or one pair per "
        "direction for a two-directional joint (J = -1: the ground) (as --joint-dof)"),
    *(_key("joint", o.joint_key, o) for o in OPTIONS.values() if o.joint_key is not None),
)


#: The keys of a joint across (:data:`JOINT_KEYS`): transverse and what only it uses.
ACROSS_KEYS = ("transverse", "pairing", "fe_mesh")

#: Clamp sections a tip or centre joint may hold, overriding the case's own clamp.
JOINT_CLAMP_SECTIONS = ("geometry", "material", "contact", "clamping")

#: Dotted key -> ClampParams field, for the seven values that make a clamp.
CLAMP_KEYS: dict[str, str] = {str(OPTIONS[f.name].key): f.name
                              for f in dataclasses.fields(ClampParams)}
