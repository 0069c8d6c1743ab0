"""One joint of a structure, as the command line and a case file both give it.

:class:`JointSpec` is what ``--joint`` and its options (:mod:`microslip.cli.joint`) and a
``[[joint]]`` table (:mod:`microslip.case.joints`) produce; the dynamics builds its operators
from it (:func:`microslip.meshdynamics.spec.joint_operator`). :func:`series_stiffness` is the
series spring of a clamp joint from the contact stick slope, written once.

Units: N, mm, N/mm, N/mm^3.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .conventions import DEFAULT_ELEMENTS
from .named import result
from .params import ClampParams

__all__ = ["JointSpec", "series_stiffness"]


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
