"""A case file read into a :class:`Case`: validated at the boundary, immutable afterwards.

Notes
-----
The slip limit of a uniformly clamped interface is mu F_N (paper, Eq. 5); a case without an
explicit amplitude is loaded to ``amplitude_fraction`` times that limit
(:data:`~microslip.case.schema.DEFAULT_AMPLITUDE_FRACTION`, 0.5).
"""

from __future__ import annotations

import difflib
import os
import sys
from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..named import result
from ..params import PRESETS, ClampParams
from .joints import JointSpec, parse_joints
from .schema import CLAMP_KEYS, KEYS, MESH_LOAD_KEYS, SECTIONS
from .units import check_impossible, plausibility_warnings

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

if TYPE_CHECKING:
    from ..fe.meshload import MeshLoad

__all__ = ["Case", "load_case", "parse_case"]

_BY_DOTTED = {k.dotted: k for k in KEYS}


@result
class Case:
    """One joint and its load case, as a case file gives them (units N, mm, MPa).

    ``values`` holds every key the file sets, by dotted name, validated; the seven clamp
    values are filled in from ``preset`` where the file does not set them. ``params`` is the
    clamp when it is complete (a preset, or all seven values), else None. ``joints`` are the
    ``[[joint]]`` tables of a structure (:mod:`.joints`; empty if the file has none);
    ``mesh_loads`` the ``[[mesh.load]]`` tables of a mesh of the user's own ([mesh] file);
    ``loads_as`` how the file wrote them (``[[mesh.load]]``, or ``[[load]]`` as before).
    """

    source: str | None
    values: Mapping[str, Any]
    params: ClampParams | None
    warnings: tuple[str, ...]
    joints: tuple[JointSpec, ...] = ()
    mesh_loads: tuple[MeshLoad, ...] = ()
    loads_as: str = "[[mesh.load]]"

    @property
    def name(self) -> str:
        return str(self.values.get("name", ""))

    def get(self, dotted: str) -> Any:
        """The value of a key, or its default from the key table (None if it has none)."""
        if dotted in self.values:
            return self.values[dotted]
        default = _BY_DOTTED[dotted].default
        return default if default != "from preset" else None

    def amplitude(self, friction: float | None = None, normal_force: float | None = None
                  ) -> float | None:
        """F0 in N: ``load.amplitude``, or ``load.amplitude_fraction`` times mu F_N.

        ``friction`` and ``normal_force`` replace the case's own (options that override it);
        None if the slip limit is unknown.
        """
        if "load.amplitude" in self.values:
            return float(self.values["load.amplitude"])
        mu = friction if friction is not None else self.values.get("contact.friction")
        fn = normal_force if normal_force is not None else self.values.get(
            "clamping.normal_force")
        if mu is None or fn is None:
            return None
        return float(self.get("load.amplitude_fraction")) * mu * fn


def _suggest(typed: str, names: list[str] | None = None) -> str:
    names = list(_BY_DOTTED) if names is None else names
    last = {k.name: k.dotted for k in KEYS}
    hit = difflib.get_close_matches(typed, names, n=1) or [
        last[m] for m in difflib.get_close_matches(typed.rsplit(".", 1)[-1], list(last), n=1)]
    return f"; did you mean {hit[0]}?" if hit else f"; valid keys: {', '.join(names)}"


def _flatten(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    flat: dict[str, Any] = {}
    for key, value in table.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, dict) and dotted not in _BY_DOTTED:
            if dotted not in SECTIONS:
                raise ParameterError(f"unknown case section [{dotted}]"
                                     f"{_suggest(dotted, [s for s in SECTIONS if s])}")
            flat.update(_flatten(value, dotted + "."))
        elif dotted not in _BY_DOTTED:
            raise ParameterError(f"unknown case key {dotted}{_suggest(dotted)}")
        else:
            flat[dotted] = _BY_DOTTED[dotted].check(dotted, value)
    return flat


def _exclusive(values: Mapping[str, Any], *keys: str) -> None:
    given = [k for k in keys if k in values]
    if len(given) > 1:
        raise ParameterError(f"case keys {' and '.join(given)} exclude each other; give one")


def _clamp(values: dict[str, Any]) -> ClampParams | None:
    if "preset" in values:
        base = PRESETS[values["preset"]][0].as_dict()
        for dotted, field in CLAMP_KEYS.items():
            values.setdefault(dotted, base[field])
    given = [k for k in CLAMP_KEYS if k in values]
    if not given:
        return None
    missing = [k for k in CLAMP_KEYS if k not in values]
    if missing and "mesh.file" in values:
        return None  # a mesh of the user's own: the mesh gives the geometry
    if missing:
        raise ParameterError(f"case gives {', '.join(given)} but not {', '.join(missing)}: "
                             "give preset = \"...\" as the base or all seven values")
    return ClampParams(**{field: values[k] for k, field in CLAMP_KEYS.items()})


def parse_case(table: Mapping[str, Any], source: str | None = None) -> Case:
    """Validate a parsed TOML table (unknown keys and bad values raise ParameterError)."""
    where = f"case {source}: " if source else "case: "
    try:
        table = dict(table)
        joint_tables = table.pop("joint", None)
        load_tables, loads_as = _load_tables(table)
        values = _flatten(table)
        if "structure.file" in values:
            values["structure.file"] = _beside(source, values["structure.file"])
        if "mesh.file" in values:
            values["mesh.file"] = _beside(source, values["mesh.file"])
        mesh_loads = () if load_tables is None else _mesh_loads(load_tables)
        _exclusive(values, "load.amplitude", "load.amplitude_fraction")
        _exclusive(values, "load.planar.ratio", "load.planar.tip_amplitude")
        _exclusive(values, "load.planar.ratio", "load.planar.centre_amplitude")
        params = _clamp(values)
        joints = () if joint_tables is None else parse_joints(joint_tables, values)
        clamp_values = {field: values.get(k) for k, field in CLAMP_KEYS.items()}
        check_impossible(clamp_values, names={f: k for k, f in CLAMP_KEYS.items()})
        warnings = plausibility_warnings(clamp_values, where)
        for j in joints:
            if j.clamp is not None and j.clamp != params:
                check_impossible(j.clamp.as_dict(), f"joint {j.number}: ")
                warnings += plausibility_warnings(j.clamp.as_dict(),
                                                  f"{where}joint {j.number}: ")
    except ParameterError as exc:
        raise ParameterError(f"{where}{exc}") from None
    return Case(source, MappingProxyType(values), params, tuple(warnings), joints, mesh_loads,
                loads_as)


def _load_tables(table: dict[str, Any]) -> tuple[list[Any] | None, str]:
    """Pop the loads of the mesh out of ``table``: ``[[mesh.load]]`` tables (the [mesh]
    section's own, which sit beside the uniaxial ``[load]`` section of the template), or the
    top-level ``[[load]]`` tables of a file without a ``[load]`` section (read as before)."""
    mesh = table.get("mesh")
    inner = None
    if isinstance(mesh, dict) and "load" in mesh:
        mesh = dict(mesh)
        inner = mesh.pop("load")
        table["mesh"] = mesh
        if not isinstance(inner, list):
            raise ParameterError("mesh.load must be [[mesh.load]] tables (set, direction, "
                                 "amplitude, phase_deg)")
    outer = table.pop("load") if isinstance(table.get("load"), list) else None
    if inner is not None and outer is not None:
        raise ParameterError("give the loads of the mesh as [[mesh.load]] tables or as "
                             "[[load]] tables, not both")
    if inner is not None:
        return inner, "[[mesh.load]]"
    return outer, "[[load]]"


#: Keys of a ``[[mesh.load]]`` table (a load on a set of the user's mesh) and their defaults.
LOAD_TABLE_KEYS = {name: default for name, (default, _) in MESH_LOAD_KEYS.items()}


def _mesh_loads(tables: list[Any]) -> tuple[MeshLoad, ...]:
    """The ``[[mesh.load]]`` tables: set, direction = [DX, DY, DZ], amplitude (N),
    phase_deg."""
    from ..fe.meshload import MeshLoad  # only a mesh case pays for the FE package
    out = []
    for k, t in enumerate(tables, 1):
        where = f"mesh.load {k}"
        if not isinstance(t, dict):
            raise ParameterError(f"{where}: a [[mesh.load]] entry must be a table")
        unknown = [key for key in t if key not in LOAD_TABLE_KEYS]
        if unknown:
            hint = difflib.get_close_matches(unknown[0], list(LOAD_TABLE_KEYS), n=1)
            raise ParameterError(f"{where}: unknown key {unknown[0]}"
                                 + (f"; did you mean {hint[0]}?" if hint else
                                    f"; valid keys: {', '.join(LOAD_TABLE_KEYS)}"))
        missing = [key for key, d in LOAD_TABLE_KEYS.items() if d is None and key not in t]
        if missing:
            raise ParameterError(f"{where}: give {', '.join(missing)}")
        d = t["direction"]
        if not (isinstance(d, list) and len(d) == 3 and all(
                isinstance(x, (int, float)) and not isinstance(x, bool) for x in d)):
            raise ParameterError(f"{where}: direction must be [DX, DY, DZ], got {d!r}")
        amplitude, phase = t["amplitude"], t.get("phase_deg", 0.0)
        for name, value in (("amplitude", amplitude), ("phase_deg", phase)):
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ParameterError(f"{where}: {name} must be a number, got {value!r}")
        if not isinstance(t["set"], str):
            raise ParameterError(f"{where}: set must be a string, got {t['set']!r}")
        out.append(MeshLoad(t["set"], (float(d[0]), float(d[1]), float(d[2])),
                            float(amplitude), float(phase)))
    return tuple(out)


def _beside(source: str | None, path: str) -> str:
    """A relative path of a case file, taken relative to the case file's directory."""
    if source is None or os.path.isabs(path):
        return path
    return os.path.join(os.path.dirname(source), path)


def load_case(path: str | os.PathLike[str]) -> Case:
    """Read and validate a TOML case file; every failure is one ParameterError line."""
    name = os.fspath(path)
    try:
        with open(name, "rb") as fh:
            table = tomllib.load(fh)
    except OSError as exc:
        raise ParameterError(f"cannot read case file {name}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise ParameterError(f"case file {name} is not UTF-8 text") from None
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"case file {name} is not valid TOML: {exc}") from None
    return parse_case(table, name)
