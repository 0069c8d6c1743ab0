"""The assembly of a mesh as the command line and the case file give it.

Four repeatable options and their case tables describe the bodies of a mesh
(:class:`~microslip.fe.assembly.Assembly`):

===========================================  ======================  ========================
option                                       case table              piece
===========================================  ======================  ========================
``--contact SET[:COUNTER_SET]``              ``[[mesh.contact]]``    ``Contact(face, counter)``
``--preload SET:FORCE``                      ``[[mesh.preload]]``    ``Preload(face, force)``
``--fixed SET[:DIRECTIONS]``                 ``[[mesh.support]]``    ``Support(set, directions)``
``--material ELSET:MODULUS:POISSON[:RHO]``   ``[[mesh.material]]``   ``Material(...)``
``--bolt HEAD:NUT:FORCE[:DIAMETER]``          ``[[mesh.bolt]]``       two preloads, a shank
===========================================  ======================  ========================

The clamp's options stay as the shorthand: ``--contact-set X`` is ``--contact X``,
``--clamp-set Y --normal-force F`` is ``--preload Y:F``, and ``--modulus`` with
``--poisson-ratio`` (and ``--density``) is the material of every element no ``--material``
names. :func:`build_assembly` is the one place these values become an assembly; a value is
checked once, by the piece it makes, and its message names the option or the key.
Units: N, mm, MPa, kg/m^3.

>>> contact_option("bar_int:base_int")
Contact(face='bar_int', counter='base_int')
>>> preload_option("clamp:2e3")
Preload(face='clamp', force=2000.0)
>>> preload_option("clamp")
Traceback (most recent call last):
...
argparse.ArgumentTypeError: 'clamp' is not SET:FORCE (FORCE in N, > 0)
"""

from __future__ import annotations

import argparse
import difflib
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError

if TYPE_CHECKING:  # the FE package is imported when an assembly is built, not to read a case
    from ..fe.assembly import Assembly, Contact, Material, Preload, Shank, Support

__all__ = ["ASSEMBLY_DESTS", "FORMS", "TABLES", "Bolt", "Field", "MissingInput",
           "bolt_option", "build_assembly", "contact_option", "fixed_option",
           "material_option", "preload_option", "table_check"]

#: The command-line form of each assembly option (destination -> form, with units).
FORMS = {
    "contact": "SET[:COUNTER_SET] (no counter set: the rigid base)",
    "preload": "SET:FORCE (FORCE in N, > 0)",
    "fixed": "SET[:DIRECTIONS] (DIRECTIONS letters of xyz, default xyz)",
    "material": "ELSET:MODULUS:POISSON[:DENSITY] (MPa, -, kg/m^3)",
    "bolt": "HEAD:NUT:FORCE[:DIAMETER] (FORCE in N on each face, DIAMETER of the shank in mm)",
}

#: The destinations of the assembly options, in the order of :data:`FORMS`.
ASSEMBLY_DESTS = tuple(FORMS)


def _number(what: str, text: str, unit: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise ParameterError(f"{what} must be a number ({unit}), got {text!r}") from None
    if not math.isfinite(x):
        raise ParameterError(f"{what} must be finite ({unit}), got {text!r}")
    return x


def _parts(text: str, low: int, high: int, dest: str) -> list[str]:
    parts = [p.strip() for p in str(text).split(":")]
    if not low <= len(parts) <= high or not all(parts):
        raise argparse.ArgumentTypeError(f"{text!r} is not {FORMS[dest]}")
    return parts


def _typed(dest: str, text: str, make: Callable[[list[str]], Any], low: int,
           high: int) -> Any:
    """The piece of ``text``, or one ArgumentTypeError naming the value and the form (argparse
    prefixes the option)."""
    parts = _parts(text, low, high, dest)
    try:
        return make(parts)
    except ParameterError as exc:
        raise argparse.ArgumentTypeError(f"{text!r}: {exc}; expected {FORMS[dest]}") from None


def contact_option(text: str) -> Contact:
    """argparse type of ``--contact SET[:COUNTER_SET]``."""
    return _typed("contact", text, lambda p: _fe().Contact(*p), 1, 2)


def preload_option(text: str) -> Preload:
    """argparse type of ``--preload SET:FORCE``."""
    return _typed("preload", text, lambda p: _fe().Preload(p[0], _number("the force", p[1], "N")),
                  2, 2)


def fixed_option(text: str) -> Support:
    """argparse type of ``--fixed SET[:DIRECTIONS]``."""
    return _typed("fixed", text, lambda p: _fe().Support(*p), 1, 2)


def _material(p: list[str]) -> Material:
    rho = None if len(p) < 4 else _number("the density", p[3], "kg/m^3")
    return _fe().Material(_number("the modulus", p[1], "MPa"),
                    _number("the Poisson ratio", p[2], "-"), rho, p[0])


def material_option(text: str) -> Material:
    """argparse type of ``--material ELSET:MODULUS:POISSON[:DENSITY]``."""
    return _typed("material", text, _material, 3, 4)


@dataclass(frozen=True)
class Bolt:
    """A bolt as the command line and the case file give it: its ``head`` and ``nut`` faces
    each pressed by ``force`` (N) and, with a ``diameter`` (mm), a shank between them of
    ``modulus`` (MPa; None: the first material's); checked by
    :func:`microslip.fe.assembly.bolt`, which makes its preloads and its shank."""

    head: str
    nut: str
    force: float
    diameter: float | None = None
    modulus: float | None = None

    def __post_init__(self) -> None:
        if self.head == self.nut:
            raise ParameterError(f"bolt {self.head}: the head and the nut are one face")
        self.parts()

    def parts(self) -> tuple[tuple[Preload, ...], tuple[Shank, ...]]:
        """The bolt's preloads and shank (none without a diameter)."""
        return _fe().bolt(self.head, self.nut, self.force, self.diameter, self.modulus)

    @property
    def label(self) -> str:
        return f"{self.head}:{self.nut}"


def _bolt(p: list[str]) -> Bolt:
    diameter = None if len(p) < 4 else _number("the shank's diameter", p[3], "mm")
    return Bolt(p[0], p[1], _number("the force", p[2], "N"), diameter)


def bolt_option(text: str) -> Bolt:
    """argparse type of ``--bolt HEAD:NUT:FORCE[:DIAMETER]``."""
    return _typed("bolt", text, _bolt, 3, 4)


# -- the case file's tables -------------------------------------------------------------------

@dataclass(frozen=True)
class Field:
    """One key of an assembly table: its name, whether it is a set name or a number, its unit,
    whether it is required, and what it means."""

    name: str
    kind: str  # "name", "number" or "text"
    unit: str
    required: bool
    meaning: str


#: The case file's assembly tables (``[[mesh.contact]]``, ...): table -> (destination, keys).
TABLES: dict[str, tuple[str, tuple[Field, ...]]] = {
    "contact": ("contact", (
        Field("face", "name", "", True, "a face (node set or surface) of one body: its nodes "
              "are the contact nodes"),
        Field("counter", "name", "", False, "the face of another body it meets (coincident "
                                            "nodes); left out: the rigid flat base"))),
    "preload": ("preload", (
        Field("face", "name", "", True, "the face pressed (a bolt: its head face and its nut "
                                        "face, one table each)"),
        Field("force", "number", "N", True, "the force pressing it inward, > 0"))),
    "support": ("fixed", (
        Field("set", "name", "", True, "a node set or surface held"),
        Field("directions", "text", "", False, "the global directions held, letters of xyz "
                                               "(default xyz)"))),
    "material": ("material", (
        Field("elset", "name", "", True, "an element set of the mesh (*ELSET, gmsh volume "
                                         "group)"),
        Field("modulus", "number", "MPa", True, "Young's modulus E"),
        Field("poisson_ratio", "number", "", True, "Poisson's ratio nu, in (-1, 0.5)"),
        Field("density", "number", "kg/m^3", False, "density, in [100, 30000] (default: "
                                                    "[mesh] density)"))),
    "bolt": ("bolt", (
        Field("head", "name", "", True, "the head's face (the washer under the head)"),
        Field("nut", "name", "", True, "the nut's face, on the other body"),
        Field("force", "number", "N", True, "the bolt's preload, pressing each face inward"),
        Field("diameter", "number", "mm", False, "the shank's diameter: an elastic beam "
              "between the two faces after the preload (left out: no shank)"),
        Field("modulus", "number", "MPa", False, "the shank's modulus (default: the first "
                                                 "material's)"))),
}

_MAKERS: dict[str, Callable[[dict[str, Any]], Any]] = {
    "contact": lambda t: _fe().Contact(t["face"], t.get("counter")),
    "preload": lambda t: _fe().Preload(t["face"], t["force"]),
    "support": lambda t: _fe().Support(t["set"], t.get("directions", "xyz")),
    "material": lambda t: _fe().Material(t["modulus"], t["poisson_ratio"], t.get("density"),
                                   t["elset"]),
    "bolt": lambda t: Bolt(t["head"], t["nut"], t["force"], t.get("diameter"),
                           t.get("modulus")),
}


def table_check(table: str) -> Callable[[str, Any], tuple[Any, ...]]:
    """The case-file check of ``[[mesh.<table>]]``: a list of tables -> the pieces, each
    failure one line naming the table's number and the key (unknown keys get the closest)."""
    fields = {f.name: f for f in TABLES[table][1]}

    def check(name: str, value: Any) -> tuple[Any, ...]:
        if not isinstance(value, list) or not all(isinstance(t, dict) for t in value):
            raise ParameterError(f"{name} must be [[{name}]] tables ("
                                 f"{', '.join(fields)}), got {value!r}")
        out = []
        for k, t in enumerate(value, 1):
            where = f"[[{name}]] {k}"
            for key in t:
                if key not in fields:
                    hint = difflib.get_close_matches(key, list(fields), n=1)
                    raise ParameterError(f"{where}: unknown key {key}"
                                         + (f"; did you mean {hint[0]}?" if hint else
                                            f"; valid keys: {', '.join(fields)}"))
            missing = [f.name for f in fields.values() if f.required and f.name not in t]
            if missing:
                raise ParameterError(f"{where}: give {', '.join(missing)}")
            for key, v in t.items():
                f = fields[key]
                if f.kind == "number" and (isinstance(v, bool)
                                           or not isinstance(v, (int, float))):
                    unit = f" ({f.unit})" if f.unit else ""
                    raise ParameterError(f"{where}: {key} must be a number{unit}, got {v!r}")
                if f.kind != "number" and not isinstance(v, str):
                    raise ParameterError(f"{where}: {key} must be a string, got {v!r}")
            try:
                out.append(_MAKERS[table](t))
            except ParameterError as exc:
                raise ParameterError(f"{where}: {exc}") from None
        return tuple(out)

    return check


# -- the assembly ----------------------------------------------------------------------------

class MissingInput(ParameterError):
    """Values an assembly needs and nothing gives (a usage mistake on the command line, a
    missing key in a case file); ``missing`` names each, in the caller's spelling."""

    def __init__(self, missing: Sequence[str]) -> None:
        self.missing = tuple(missing)
        super().__init__(f"needs {', '.join(self.missing)}")


def _given(values: Mapping[str, Any], dest: str) -> Any:
    v = values.get(dest)
    return None if v is None or v == [] or v == () else v


def build_assembly(values: Mapping[str, Any], spell: Callable[[str], str],
                   normal_contact: str | None = None) -> Assembly:
    """The assembly that ``values`` (argparse destinations -> values: the shorthand's
    ``contact_set``, ``clamp_set``, ``normal_force``, ``modulus``, ``poisson_ratio``,
    ``density``; the pieces ``contact``, ``preload``, ``fixed``, ``material``, ``bolt``; the
    contact law
    ``friction``, ``stick_slope``, ``normal_contact``, ``normal_slope``) describe.

    ``spell(dest)`` is how the caller names a value in messages (``--clamp-set``, or
    ``mesh.clamp_set``); ``normal_contact`` overrides ``values["normal_contact"]``.
    Raises :class:`MissingInput` naming every value left out, ParameterError (one line
    naming the option) for a value that does not fit.
    """
    missing: list[str] = []
    contacts = list(_given(values, "contact") or ())
    if _given(values, "contact_set") is not None:
        contacts.insert(0, _fe().Contact(values["contact_set"]))
    if not contacts:
        missing.append(f"{spell('contact_set')} NAME (or {spell('contact')} "
                       "SET[:COUNTER_SET])")
    preloads = list(_given(values, "preload") or ())
    shanks: list[Shank] = []
    for b in _given(values, "bolt") or ():
        pre, sh = b.parts()
        preloads += pre
        shanks += sh
    clamp_set, force = _given(values, "clamp_set"), _given(values, "normal_force")
    if clamp_set is not None and force is None:
        missing.append(f"{spell('normal_force')} N (the force on {spell('clamp_set')} "
                       f"{clamp_set})")
    elif clamp_set is None and force is not None and preloads:
        raise ParameterError(f"{spell('normal_force')} {force:g} presses no face: it is the "
                             f"force of {spell('clamp_set')}; with {spell('preload')} or "
                             f"{spell('bolt')} give each its own force")
    elif clamp_set is None and not preloads:
        missing.append(f"{spell('clamp_set')} NAME with {spell('normal_force')} N (or "
                       f"{spell('preload')} SET:FORCE, or {spell('bolt')} HEAD:NUT:FORCE)")
    if clamp_set is not None and force is not None:
        try:
            preloads.insert(0, _fe().Preload(clamp_set, force))
        except ParameterError:
            raise ParameterError(f"{spell('normal_force')} must be finite and > 0 N, got "
                                 f"{force!r}") from None
    density = _given(values, "density")
    materials = [m if m.density is not None or density is None else
                 _with_density(m, density, spell) for m in _given(values, "material") or ()]
    modulus, nu = _given(values, "modulus"), _given(values, "poisson_ratio")
    if modulus is not None and nu is not None:
        materials.insert(0, _default_material(modulus, nu, density, spell))
    elif modulus is not None or nu is not None or not materials:
        lacking = [f"{spell(d)} {m}" for d, m in (("modulus", "MPA"), ("poisson_ratio", "X"))
                   if _given(values, d) is None]
        missing.append(" and ".join(lacking) + ("" if materials else
                                                f" (or {spell('material')} per element set)"))
    if _given(values, "friction") is None:
        missing.append(f"{spell('friction')} X")
    if missing:
        raise MissingInput(missing)
    law: dict[str, Any] = {k: v for k, v in (("stick_slope", _given(values, "stick_slope")),
                             ("normal_contact", normal_contact
                              or _given(values, "normal_contact")),
                             ("normal_slope", _given(values, "normal_slope")))
           if v is not None}
    try:
        return _fe().Assembly(contacts=tuple(contacts), preloads=tuple(preloads),
                        materials=tuple(materials), friction=values["friction"],
                        supports=tuple(_given(values, "fixed") or ()), shanks=tuple(shanks),
                        **law)
    except ParameterError as exc:
        raise ParameterError(_spelled(str(exc), spell)) from None


def _default_material(modulus: Any, nu: Any, density: Any,
                      spell: Callable[[str], str]) -> Material:
    try:
        return _fe().Material(modulus, nu, density)
    except ParameterError as exc:
        raise ParameterError(_spelled(str(exc), spell)) from None


def _with_density(material: Material, density: Any, spell: Callable[[str], str]) -> Material:
    try:
        return replace(material, density=density)
    except ParameterError as exc:
        raise ParameterError(f"{spell('density')}: {exc}") from None


def _spelled(text: str, spell: Callable[[str], str]) -> str:
    """A library message that starts with a value's name (``modulus must be ...``,
    ``density = ...``, ``friction must ...``) with the caller's spelling of it."""
    for dest in ("poisson_ratio", "modulus", "density", "friction", "stick_slope",
                 "normal_slope"):
        if text.startswith(dest + " "):
            return spell(dest) + text[len(dest):]
    return text


def _fe() -> Any:
    """:mod:`microslip.fe.assembly`, imported on first use (reading a case file does not load
    the FE package)."""
    from ..fe import assembly

    return assembly
