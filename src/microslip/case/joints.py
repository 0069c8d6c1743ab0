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
(``pairing``); :data:`TRANSVERSE` builds the joint across, the coupling
(:data:`microslip.dynamics.operators2d.COUPLINGS`) the two-directional joint.

Units: N, mm, MPa, N/mm, N/mm^3.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import lru_cache
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from ..conventions import CLAMP_MODELS
from ..conventions import TRANSVERSE as TRANSVERSE_NAMES
from ..errors import ParameterError
from ..named import result
from ..params import PRESETS, ClampParams
from .schema import (
    ACROSS_KEYS,
    CLAMP_KEYS,
    DEFAULT_FE_MESH,
    JOINT_CLAMP_SECTIONS,
    JOINT_KEYS,
    JOINT_USES,
    KEYS,
)

if TYPE_CHECKING:
    from ..dynamics.operators import IwanOperator
    from ..options import ModelOptions

__all__ = ["TRANSVERSE", "JointSpec", "across_operator", "joint_operator", "parse_joints",
           "transverse_operator"]

_JOINT = {k.name: k for k in JOINT_KEYS}
_CLAMP_SECTION_KEYS = {k.dotted: k for k in KEYS if k.section in JOINT_CLAMP_SECTIONS}
#: Keys of the case's own that a tip or centre joint inherits.
_INHERITED = (*CLAMP_KEYS, "contact.stick_slope", "clamping.pressure")


@result
class JointSpec:
    """One ``[[joint]]`` table, validated.

    Attributes
    ----------
    number : int
        Position of the table in the file, 1-based (for messages).
    dofs : tuple of (int, int)
        ``(i, j)`` per direction, 0-based, ``j = -1`` for the ground.
    model : str
        ``jenkins``, ``iwan``, ``tip`` or ``centre``.
    coupling : str or None
        Two-directional joints: ``circular`` or ``decoupled`` (None: the structure's).
    values : mapping
        The table's own keys (``stiffness``, ``slip_force``, ``chi``, ``beta``,
        ``elements``), N/mm, N, -, -, -.
    clamp : ClampParams or None
        Tip and centre joints: the clamp (case's base with the table's overrides).
    series_stiffness : float or None
        Tip and centre joints: the series spring, N/mm.
    transverse : str or None
        Two-directional tip and centre joints: the joint across (second direction), a name
        of :data:`TRANSVERSE`; None: the joint's own model.
    pairing : str or None
        With ``transverse``: a name of :data:`microslip.dynamics.operators2d.PAIRINGS`
        (None: its default).
    fe_mesh : str or None
        With ``transverse = "fe"``: the FE mesh (level or ``NXxNYxNZ``; None: the default).
    stick_slope : float or None
        Tip and centre joints whose series spring is the contact stick slope: it, N/mm^3
        (None if ``stiffness`` is given).
    """

    number: int
    dofs: tuple[tuple[int, int], ...]
    model: str
    coupling: str | None
    values: Mapping[str, Any]
    clamp: ClampParams | None
    series_stiffness: float | None
    transverse: str | None = None
    pairing: str | None = None
    fe_mesh: str | None = None
    stick_slope: float | None = None

    @property
    def directions(self) -> int:
        """1 or 2."""
        return len(self.dofs)


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
    params, series, slope = _clamp(model, own, clamp, case_values) \
        if model in CLAMP_MODELS else (None, None, None)
    if model in ("jenkins", "iwan"):
        missing = [k for k in sorted(JOINT_USES[model] - {"elements"}) if k not in own]
        if missing:
            raise ParameterError(f"model {model} needs joint.{', joint.'.join(missing)}")
    if across.get("transverse") == "fe" and slope is None:
        raise ParameterError('joint.transverse = "fe" needs contact.stick_slope (N/mm^3, the '
                             "FE's contact stiffness), not joint.stiffness: give the stick "
                             "slope instead")
    return JointSpec(number=number, dofs=dofs, model=model, coupling=coupling,
                     values=MappingProxyType(own), clamp=params, series_stiffness=series,
                     transverse=across.get("transverse"), pairing=across.get("pairing"),
                     fe_mesh=across.get("fe_mesh"), stick_slope=slope)


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
           case_values: Mapping[str, Any]) -> tuple[ClampParams, float, float | None]:
    """The clamp of a tip or centre joint, its series stiffness (N/mm) and the stick slope
    it comes from (N/mm^3; None if ``stiffness`` is given)."""
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
    slope = float(values["contact.stick_slope"])
    return params, slope * params.width * params.length, slope


def joint_operator(spec: JointSpec, options: ModelOptions | None = None) -> IwanOperator:
    """The 1-D joint operator of a joint table (a two-directional joint is built from it by
    its coupling, :data:`microslip.dynamics.operators2d.COUPLINGS`)."""
    from ..dynamics.distributions import DEFAULT_ELEMENTS, clamp_joint, iwan4_segalman
    from ..dynamics.operators import jenkins

    v = spec.values
    elements = int(v.get("elements", DEFAULT_ELEMENTS))
    if spec.model == "jenkins":
        return jenkins(v["stiffness"], v["slip_force"])
    if spec.model == "iwan":
        return iwan4_segalman(v["stiffness"], v["slip_force"], v["chi"], v["beta"], elements)
    assert spec.clamp is not None and spec.series_stiffness is not None
    return clamp_joint(spec.model, spec.clamp, spec.series_stiffness, elements=elements,
                       options=options)


#: A joint across: (clamp, series spring N/mm, elements, model options, stick slope N/mm^3
#: or None, FE mesh) -> its 1-D operator.
Across = Callable[[ClampParams, float, int, "ModelOptions | None", "float | None", str],
                  "IwanOperator"]


def _clamp_model(model: str) -> Across:
    def build(clamp: ClampParams, series: float, elements: int,
              options: ModelOptions | None, stick_slope: float | None, fe_mesh: str
              ) -> IwanOperator:
        from ..dynamics.distributions import clamp_joint

        return clamp_joint(model, clamp, series, elements=elements, options=options)
    return build


def _fe(clamp: ClampParams, series: float, elements: int, options: ModelOptions | None,
        stick_slope: float | None, fe_mesh: str) -> IwanOperator:
    if stick_slope is None:
        raise ParameterError("the FE joint across needs the contact stick slope (N/mm^3), not "
                             "a series stiffness")
    return _fe_across(clamp, fe_mesh, stick_slope)


@lru_cache(maxsize=8)
def _fe_across(clamp: ClampParams, mesh: str, stick_slope: float) -> IwanOperator:
    """The FE's first loading of the centre force across the bar as a 1-D joint (cached:
    an FE run, the same for the structure and its description)."""
    from ..fe.builtin import fe_backbone

    op: IwanOperator = fe_backbone(clamp, "centre", mesh=mesh,
                                   stick_slope=stick_slope).operator()
    return op


#: Transverse name (:data:`microslip.conventions.TRANSVERSE`) -> the 1-D joint across a bar:
#: ``tip``, ``centre`` the clamp's 1-D model
#: behind the same series spring; ``fe`` the built-in FE's first loading of the centre force
#: across the bar (:func:`microslip.fe.builtin.fe_backbone`, its contact compliance inside).
TRANSVERSE: dict[str, Across] = dict(zip(
    TRANSVERSE_NAMES, (*(_clamp_model(m) for m in CLAMP_MODELS), _fe), strict=True))


def across_operator(transverse: str, clamp: ClampParams, series: float, *, elements: int,
                    options: ModelOptions | None = None, stick_slope: float | None = None,
                    fe_mesh: str | None = None) -> IwanOperator:
    """The 1-D joint across (:data:`TRANSVERSE`) of a clamp with the series spring
    ``series`` (N/mm) from the contact stick slope ``stick_slope`` (N/mm^3)."""
    return TRANSVERSE[transverse](clamp, series, elements, options, stick_slope,
                                  DEFAULT_FE_MESH if fe_mesh is None else fe_mesh)


def transverse_operator(spec: JointSpec, options: ModelOptions | None = None
                        ) -> IwanOperator | None:
    """The 1-D joint across a joint table (its second direction), None without
    ``transverse``."""
    if spec.transverse is None:
        return None
    from ..dynamics.distributions import DEFAULT_ELEMENTS

    assert spec.clamp is not None and spec.series_stiffness is not None
    return across_operator(spec.transverse, spec.clamp, spec.series_stiffness,
                           elements=int(spec.values.get("elements", DEFAULT_ELEMENTS)),
                           options=options, stick_slope=spec.stick_slope,
                           fe_mesh=spec.fe_mesh)
