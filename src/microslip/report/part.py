"""A case of the user's own mesh as the commands read it: whether a case is one
(:func:`is_mesh_case`), its assembly (:func:`case_assembly`: the clamp's shorthand keys and
the ``[[mesh.contact]]``, ``[[mesh.preload]]``, ``[[mesh.support]]``, ``[[mesh.material]]``
and ``[[mesh.bolt]]`` tables, as ``fe --case`` and ``modal --case`` build it) and its
density. Units: N, mm, MPa, kg/m^3.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..case.model import Case
from ..errors import ParameterError

if TYPE_CHECKING:
    from ..fe.assembly import Assembly

__all__ = ["case_assembly", "case_density", "is_mesh_case"]


def is_mesh_case(case: Case) -> bool:
    """Whether ``case`` is a part of the user's own mesh (``[mesh] file``)."""
    return "mesh.file" in case.values


def _spell(dest: str) -> str:
    """A destination as the case file names it (``mesh.clamp_set``, ``[[mesh.contact]]``)."""
    from ..case.schema import TABLE_KEYS
    from ..case.table import CASE_DESTS

    for key, (d, _) in CASE_DESTS.items():
        if d == dest:
            return f"[[{key}]]" if key in TABLE_KEYS else key
    return dest


def case_assembly(case: Case) -> Assembly:
    """The assembly of a mesh case, as ``fe --case``, ``modal --case`` and ``case check``
    build it (:func:`microslip.case.assembly.build_assembly` on the case's keys and its
    ``[[mesh.*]]`` tables); what is missing is one line naming the case's keys."""
    from ..case.assembly import MissingInput, build_assembly
    from ..case.table import CASE_DESTS

    values = {dest: case.values[k] for k, (dest, _) in CASE_DESTS.items() if k in case.values}
    values.setdefault("normal_contact", case.get("mesh.normal_contact"))
    try:
        return build_assembly(values, _spell)
    except MissingInput as exc:
        raise ParameterError(f"case {case.source}: the part needs "
                             f"{', '.join(exc.missing)}") from None
    except ParameterError as exc:
        raise ParameterError(f"case {case.source}: {exc}") from None


def case_density(case: Case, assembly: Assembly) -> float | None:
    """The structure's density, kg/m^3: ``[mesh] density``, else the materials' own when
    every one gives it; None: no structure to study."""
    if "mesh.density" in case.values:
        return float(case.values["mesh.density"])
    own = [m.density for m in assembly.materials if m.density is not None]
    if not own or len(own) < len(assembly.materials):
        return None
    return float(own[0])
