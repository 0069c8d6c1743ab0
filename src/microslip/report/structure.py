"""The report's section "Damping of the structure's mode": the case file's own mesh
([mesh] file, sets, density, mode, response set, normal contact law; the material, contact
and clamping values)
as the library's typed :class:`~microslip.meshdynamics.case.StructureCase`, and every solver
of the modal study side by side with the verdicts
(:func:`microslip.meshdynamics.modalstudy.modal_study`). Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..case.model import Case

if TYPE_CHECKING:
    from ..meshdynamics.case import StructureCase

__all__ = ["REPORT_AMPLITUDES", "case_structure", "structure_section"]

#: Amplitudes of the structure section (first slip to near gross sliding).
REPORT_AMPLITUDES = 6


def case_structure(case: Case) -> StructureCase | None:
    """The structure the case file describes, or None when it gives no mesh file or no
    density (the one place a case file's [mesh] becomes a StructureCase): its assembly as
    the commands build it (the clamp's keys and the ``[[mesh.*]]`` tables,
    :func:`~.part.case_assembly`), its density (``[mesh] density``, or every material's
    own), mode, response set and ``[material] yield_strength``."""
    from ..meshdynamics.case import StructureCase
    from .part import case_assembly, case_density

    v = case.values
    if "mesh.file" not in v:
        return None
    assembly = case_assembly(case)
    density = case_density(case, assembly)
    if density is None:
        return None
    response = case.get("mesh.response_set")
    strength = case.get("material.yield_strength")
    return StructureCase(str(v["mesh.file"]), assembly, density=density,
                         mode=int(case.get("mesh.mode")),
                         response_set=None if response is None else str(response),
                         yield_strength=None if strength is None else float(strength))


def structure_section(case: Case, amplitudes: int = REPORT_AMPLITUDES
                      ) -> dict[str, Any] | None:
    """Every solver of the modal study on the case's structure, side by side with the
    verdicts (the JSON of ``modal --mesh ... --solver all``); None without a structure."""
    from ..meshdynamics.modalstudy import ModalSettings, modal_study

    structure = case_structure(case)
    if structure is None:
        return None
    return modal_study(structure, ModalSettings(amplitudes=amplitudes)).to_dict()
