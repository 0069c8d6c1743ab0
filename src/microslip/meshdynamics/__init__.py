"""The structure on the user's own mesh: its linear modes, the full FE's quasi-static modal
analysis, the contact-node reduced model, the whole joint, the interface's first loading, the
two-mode study and their verdicts; the layer above the frictional FE (:mod:`microslip.fe`)
and the structural dynamics (:mod:`microslip.dynamics`), which do not import each other.

The study of a mode (:func:`modal_study`) and the forced response (:func:`frf_study`) take one
:class:`StructureCase` (the mesh, its :class:`~microslip.fe.clamp.MeshClamp`, the density, the
mode, the response set). Importing this package loads no solver: every name is imported from
its module on first use (PEP 562). Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

from .._lazy import lazy_names

#: Public name -> the module that defines it, imported on first use.
_LAZY = {
    "DEFAULT_ROM_MODES": ".case",
    "PreparedStructure": ".case",
    "StructureCase": ".case",
    "amplitude_grid": ".case",
    "prepare_structure": ".case",
    "structure_rom": ".case",
    "Mode": ".modes",
    "Modes": ".modes",
    "linear_modes": ".modes",
    "QSMACurve": ".qsma",
    "qsma": ".qsma",
    "qsma_amplitudes": ".qsma",
    "Rom": ".reduce",
    "build_rom": ".reduce",
    "rom_structure": ".reduce",
    "write_rom": ".reduce",
    "build_whole_joint": ".wholejoint",
    "whole_joint_epmc": ".wholejoint",
    "backbone_operator": ".febackbone",
    "modal_verdict": ".verdict_modal",
    "MESH_SOLVERS": ".modalstudy",
    "ModalSettings": ".modalstudy",
    "compare_output": ".modalstudy",
    "modal_study": ".modalstudy",
    "run_solvers": ".modalstudy",
    "DEFAULT_MESH_HARMONICS": ".frfstudy",
    "FRF_MESH_SOLVERS": ".frfstudy",
    "FrfSettings": ".frfstudy",
    "equivalent_damping": ".frfstudy",
    "frf_study": ".frfstudy",
    "stuck_response": ".frfstudy",
}

__all__ = [*_LAZY]

__getattr__ = lazy_names(__name__, _LAZY)


def __dir__() -> list[str]:
    return sorted(__all__)
