"""The ``[[joint]]`` tables of a case file: several joints of a structure, each with its own
model and parameters (docs/casefile.md, "Structures with several joints").

A joint table gives where the joint sits (``dofs``), its ``model`` and that model's
parameters (:data:`~microslip.case.schema.JOINT_KEYS`). A tip or centre joint is the clamp
of the case (``preset`` and the sections ``[geometry]`` ... ``[clamping]``) unless the table
overrides it: its own ``preset`` replaces the base, its own sub-tables (``[joint.geometry]``
...) override single values, exactly as the case's keys override its preset. Its series
spring is ``stiffness`` (N/mm) or ``contact.stick_slope`` x width x length (the table's own,
else the case's), as ``--joint-stiffness`` / ``--stick-slope`` on the command line.

A two-directional tip or centre joint may name what it is across, its second direction
(``transverse``: the clamp's other 1-D model, or ``fe``, the built-in FE's first loading of
the centre force across the bar), and how the elements of the two are paired
(``pairing``). The tables become :class:`~microslip.jointspec.JointSpec`, the same
specification the command line's joint options give; the dynamics builds the operators from
it (:mod:`microslip.meshdynamics.spec`).

Units: N, mm, MPa, N/mm, N/mm^3.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..conventions import CLAMP_MODELS
from ..errors import ParameterError
from ..jointspec import JointSpec, joint_spec
from ..params import PRESETS, ClampParams
from .schema import (
    ACROSS_KEYS,
    CLAMP_KEYS,
    JOINT_CLAMP_SECTIONS,
    JOINT_KEYS,
    JOINT_USES,
    KEYS,
)

if TYPE_CHECKING:
    pass

__all__ = ["JointSpec", "parse_joints"]

_JOINT = {k.name: k for k in JOINT_KEYS}
_CLAMP_SECTION_KEYS = {k.dotted: k for k in KEYS if k.section in JOINT_CLAMP_SECTIONS}
#: Keys of the case's own that a tip or centre joint inherits.
_INHERITED = (*CLAMP_KEYS, "contact.stick_slope", "clamping.pressure")


def parse_joints(tables: Any, case_values: Mapping[str, Any]) -> tuple[JointSpec, ...]:
    """The ``joint`` array of tables of a case; ``case_values`` are the case's own checked
    values (the clamp's base). Each error is one line naming the table and the key."""
    if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
        raise ParameterError("joint must be an array of tables: write each joint as [[joint]]")
    out = []
    for n, table in enumerate(tables, 1):
        try:
            out.append(_joint(n, table, case_values))
        except ParameterError as exc:
            raise ParameterError(f"joint {n} of {len(tables)}: {exc}") from None
    return tuple(out)


def _joint(number: int, table: Mapping[str, Any], case_values: Mapping[str, Any]
           ) -> JointSpec:
    own: dict[str, Any] = {}
    clamp: dict[str, Any] = {}
    for key, value in table.items():
        if key in JOINT_CLAMP_SECTIONS:
            if not isinstance(value, dict):
                raise ParameterError(f"joint.{key} must be a table ([joint.{key}])")
            for name, v in value.items():
                dotted = f"{key}.{name}"
                if dotted not in _CLAMP_SECTION_KEYS:
                    raise ParameterError(f"unknown case key joint.{dotted}; a joint's [{key}] "
                                         "takes the keys of the case's")
                clamp[dotted] = _CLAMP_SECTION_KEYS[dotted].check(f"joint.{dotted}", v)
        elif key == "preset":
            clamp["preset"] = next(k for k in KEYS if k.name == "preset").check(
                "joint.preset", value)
        elif key in _JOINT:
            own[key] = _JOINT[key].check(f"joint.{key}", value)
        else:
            names = ", ".join([*_JOINT, "preset", *JOINT_CLAMP_SECTIONS])
            raise ParameterError(f"unknown case key joint.{key}; a [[joint]] takes {names}")
    for required in ("dofs", "model"):
        if required not in own:
            raise ParameterError(f"joint.{required} is missing ({_JOINT[required].range})")
    model = own.pop("model")
    dofs = own.pop("dofs")
    coupling = own.pop("coupling", None)
    if coupling is not None and len(dofs) == 1:
        raise ParameterError("joint.coupling applies to two-directional joints only (dofs = "
                             "[[I, J], [K, L]])")
    across = {k: own.pop(k) for k in ACROSS_KEYS if k in own}
    _check_across(across, model, len(dofs), coupling)
    unused = sorted(set(own) - JOINT_USES[model])
    if model not in CLAMP_MODELS:
        unused += sorted(f"[joint.{k.split('.')[0]}]" if "." in k else k for k in clamp)
    if unused:
        raise ParameterError(f"{', '.join(unused)} not used by model {model}")
    params, stiffness, slope = _clamp(model, own, clamp, case_values) \
        if model in CLAMP_MODELS else (None, None, None)
    if model in ("jenkins", "iwan"):
        missing = [k for k in sorted(JOINT_USES[model] - {"elements"}) if k not in own]
        if missing:
            raise ParameterError(f"model {model} needs joint.{', joint.'.join(missing)}")
    if across.get("transverse") == "fe" and slope is None:
        raise ParameterError('joint.transverse = "fe" needs contact.stick_slope (N/mm^3, the '
                             "FE's contact stiffness), not joint.stiffness: give the stick "
                             "slope instead")
    return joint_spec(model, own, clamp=params, stiffness=stiffness, stick_slope=slope,
                      number=number, dofs=dofs, coupling=coupling,
                      transverse=across.get("transverse"), pairing=across.get("pairing"),
                      fe_mesh=across.get("fe_mesh"))


def _check_across(across: Mapping[str, Any], model: str, directions: int,
                  coupling: str | None) -> None:
    """The keys of a joint across (transverse, pairing, fe_mesh) where they do something."""
    allowed = {k.name: k.range for k in JOINT_KEYS if k.name in ACROSS_KEYS}
    transverse = across.get("transverse")
    for key in across:
        if model not in CLAMP_MODELS:
            raise ParameterError(f"joint.{key} ({allowed[key]}) applies to two-directional "
                                 f"tip or centre joints only, not to model {model}")
        if directions == 1:
            raise ParameterError(f"joint.{key} ({allowed[key]}) applies to two-directional "
                                 "joints only (dofs = [[I, J], [K, L]])")
    if "pairing" in across and transverse is None:
        raise ParameterError(f"joint.pairing ({allowed['pairing']}) needs joint.transverse "
                             f"({allowed['transverse']}): it matches the elements along with "
                             "those across")
    if "pairing" in across and coupling == "decoupled":
        raise ParameterError(f"joint.pairing ({allowed['pairing']}) applies to coupling "
                             "circular only: the decoupled directions are independent")
    if "fe_mesh" in across and transverse != "fe":
        raise ParameterError(f"joint.fe_mesh ({allowed['fe_mesh']}) needs joint.transverse = "
                             '"fe" (the FE mesh of the joint across)')


def _clamp(model: str, own: Mapping[str, Any], clamp: Mapping[str, Any],
           case_values: Mapping[str, Any]) -> tuple[ClampParams, float | None, float | None]:
    """The clamp of a tip or centre joint and its series spring: ``stiffness`` (N/mm) or the
    stick slope (N/mm^3), the other None (:func:`~microslip.jointspec.joint_spec` makes the
    series stiffness)."""
    if "preset" in clamp:
        base = PRESETS[clamp["preset"]][0].as_dict()
        values = {k: base[f] for k, f in CLAMP_KEYS.items()}
        values.update({k: v for k, v in case_values.items()
                       if k in ("contact.stick_slope", "clamping.pressure")})
    else:
        values = {k: v for k, v in case_values.items() if k in _INHERITED}
    values.update({k: v for k, v in clamp.items() if k != "preset"})
    missing = [k for k in CLAMP_KEYS if k not in values]
    if missing:
        raise ParameterError(f"model {model} needs a clamp: preset = \"...\" (in the case or "
                             f"the joint) or all seven values; missing {', '.join(missing)}")
    if values.get("clamping.pressure", "uniform") != "uniform":
        raise ParameterError(f"clamping.pressure = {values['clamping.pressure']!r}: a joint "
                             "in a structure takes the uniform pressure of the paper's models")
    params = ClampParams(**{f: values[k] for k, f in CLAMP_KEYS.items()})
    if "stiffness" in own and "contact.stick_slope" in clamp:
        raise ParameterError("joint.stiffness and joint.contact.stick_slope exclude each "
                             "other; give one series spring")
    if "stiffness" in own:
        return params, float(own["stiffness"]), None
    if "contact.stick_slope" not in values:
        raise ParameterError(
            f"model {model} needs joint.stiffness (N/mm, a series spring) or "
            "contact.stick_slope (N/mm^3; series spring = stick slope x width x length): a "
            "bar on a rigid Coulomb foundation has no finite stiffness at zero displacement")
    return params, None, float(values["contact.stick_slope"])
