"""One joint of a structure, as the command line and a case file both give it.

:class:`JointSpec` is what ``--joint`` and its options (:mod:`microslip.cli.joint`) and a
``[[joint]]`` table (:mod:`microslip.case.joints`) produce; the dynamics builds its operators
from it (:func:`microslip.meshdynamics.spec.joint_operator`). :func:`series_stiffness` is the
series spring of a clamp joint from the contact stick slope, written once.

Units: N, mm, N/mm, N/mm^3.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from .conventions import CLAMP_MODELS, DEFAULT_ELEMENTS, JOINT_MODELS
from .errors import ParameterError
from .named import result
from .params import ClampParams

__all__ = ["JOINT_USES", "JointSpec", "joint_spec", "series_stiffness"]

#: Joint model -> the values it takes (the keys of a ``[[joint]]`` table, the command line's
#: joint options by those names), besides where it sits, its coupling and the joint across.
#: A tip or centre joint's ``stiffness`` is its series spring (or the stick slope gives it).
JOINT_USES: dict[str, frozenset[str]] = {
    "jenkins": frozenset({"stiffness", "slip_force"}),
    "iwan": frozenset({"stiffness", "slip_force", "chi", "beta", "elements"}),
    **{m: frozenset({"stiffness", "elements"}) for m in CLAMP_MODELS},
}
assert tuple(JOINT_USES) == JOINT_MODELS


def series_stiffness(params: ClampParams, stick_slope: float) -> float:
    """The series spring of a tip or centre joint, N/mm: the contact's tangential stiffness
    per area (stick slope lambda, N/mm^3) over the contact area w x L.

    >>> from microslip import preset
    >>> series_stiffness(preset("table1"), 1e4)  # 1e4 x 25.4 x 254
    64516000.0
    """
    return stick_slope * params.width * params.length


@result
class JointSpec:
    """One joint of a structure, validated: a ``[[joint]]`` table of a case file, or the
    joint options of the command line (``--joint``, ``number`` 0, no ``dofs``).

    Attributes
    ----------
    number : int
        Position of the table in the file, 1-based (for messages); 0 for the command line.
    dofs : tuple of (int, int)
        ``(i, j)`` per direction, 0-based, ``j = -1`` for the ground (empty: placed by the
        structure, as ``--joint-dof`` or the structure file's joints).
    model : str
        ``jenkins``, ``iwan``, ``tip`` or ``centre``.
    coupling : str or None
        Two-directional joints: ``circular`` or ``decoupled`` (None: the structure's).
    values : mapping
        The joint's own parameters (``stiffness``, ``slip_force``, ``chi``, ``beta``,
        ``elements``), N/mm, N, -, -, -; the names of the ``[[joint]]`` keys.
    clamp : ClampParams or None
        Tip and centre joints: the clamp (case's base with the table's overrides).
    series_stiffness : float or None
        Tip and centre joints: the series spring, N/mm.
    transverse : str or None
        Two-directional tip and centre joints: the joint across (second direction), a name
        of :data:`microslip.conventions.TRANSVERSE`; None: the joint's own model.
    pairing : str or None
        With ``transverse``: a name of :data:`microslip.conventions.PAIRINGS`
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
        """1 or 2 (a joint of the command line is placed by the structure: 1)."""
        return max(len(self.dofs), 1)

    @property
    def elements(self) -> int:
        """Jenkins elements of an iwan, tip or centre joint."""
        return int(self.values.get("elements", DEFAULT_ELEMENTS))


def joint_spec(model: str, values: Mapping[str, Any], *, clamp: ClampParams | None = None,
               stiffness: float | None = None, stick_slope: float | None = None,
               number: int = 0, dofs: tuple[tuple[int, int], ...] = (),
               coupling: str | None = None, transverse: str | None = None,
               pairing: str | None = None, fe_mesh: str | None = None) -> JointSpec:
    """The one factory of :class:`JointSpec`, for a ``[[joint]]`` table
    (:func:`microslip.case.joints.parse_joints`) and for the command line's joint options
    (:func:`microslip.cli.joint.spec_from_args`), each having checked its own input and
    named its own keys or flags in the messages.

    ``values`` are the joint's own checked values (:data:`JOINT_USES`). A tip or centre
    joint takes its ``clamp`` and exactly one of ``stiffness`` (its series spring, N/mm) or
    ``stick_slope`` (N/mm^3; series spring = stick slope x width x length,
    :func:`series_stiffness`), here and nowhere else turned into ``series_stiffness``.

    >>> from microslip import preset
    >>> joint_spec("tip", {}, clamp=preset("table1"), stick_slope=1e4).series_stiffness
    64516000.0
    >>> joint_spec("jenkins", {"stiffness": 100.0, "slip_force": 5.0}).values["slip_force"]
    5.0
    """
    if model not in JOINT_USES:
        raise ParameterError(f"unknown joint model {model!r}; choose one of "
                             f"{', '.join(JOINT_USES)}")
    unused = sorted(set(values) - JOINT_USES[model])
    if unused:
        raise ParameterError(f"{', '.join(unused)} not used by model {model}")
    series: float | None = None
    if model in CLAMP_MODELS:
        if clamp is None or (stiffness is None) == (stick_slope is None):
            raise ParameterError(f"the {model} joint needs its clamp and exactly one of a "
                                 "series stiffness (N/mm) or the stick slope (N/mm^3)")
        series = series_stiffness(clamp, stick_slope) if stick_slope is not None \
            else float(stiffness) if stiffness is not None else None
    elif clamp is not None or stiffness is not None or stick_slope is not None:
        raise ParameterError(f"a {model} joint has no clamp: its stiffness is a value")
    return JointSpec(number=number, dofs=dofs, model=model, coupling=coupling,
                     values=MappingProxyType(dict(values)), clamp=clamp,
                     series_stiffness=series, transverse=transverse, pairing=pairing,
                     fe_mesh=fe_mesh, stick_slope=stick_slope)
