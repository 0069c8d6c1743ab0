"""microslip: friction damping by microslip in clamped joints.

An implementation of Lord & Rongong, "A tangential microslip model for circularly and
elliptically loaded structures", Proc IMechE C (2016): the tip- and centre-loaded
incremental models, Masing's rule, the planar coupling and the energy measures, with exact
references and finite-element validation.

Units throughout: force N, length mm, modulus MPa, energy N·mm.

The user-facing entry points, in one flat namespace (as scikit-fem's ``skfem`` and felupe's
``fem``); the rest lives in the subpackages, the layers of pyproject.toml:

- the clamp and its options: :class:`ClampParams`, :func:`preset`, :class:`ModelOptions`,
  :class:`Contact`;
- the 1-D models and their loops (Eqs 2-23): :func:`first_loading`, :func:`masing_loop`,
  :func:`damping`, :func:`damping_from_loop`, :func:`loss_factor`, :func:`batch_damping`;
- circular and elliptical loading: :func:`paper_coupling`, :func:`analytical_response`,
  :func:`loss_factor_vs_ratio`, :func:`ratio_sweep`;
- the finite elements: :func:`run_loop` (either solver), :func:`solve_uniaxial`,
  :func:`fe_backbone`, :func:`coupling_study`;
- the structure on your own mesh: :func:`read_mesh`, :class:`MeshClamp`,
  :func:`clamped_model`, :class:`StructureCase`, :func:`prepare_structure`,
  :func:`linear_modes`, :func:`qsma`, :func:`build_rom`, :func:`structure_rom`,
  :func:`build_whole_joint`, :func:`modal_study`, :func:`frf_study` (docs/ownmesh.md, "From
  Python");
- the joint in a structure: :class:`Structure`, :func:`one_mode`, :func:`from_matrices`,
  :func:`jenkins`, :func:`iwan4`, :func:`clamp_joint`, :func:`describing_function`,
  :func:`frequency_response`, :func:`epmc`, :func:`energy_method`;
- studies: :func:`make_sweep`, :func:`run_sweep`, :func:`write_sweep`, :func:`fit_loops`,
  :func:`write_report`.

``import microslip`` loads only the parameters, options, results and errors; every other name
is imported from its module on first use (PEP 562), so the package starts without numba,
scipy.sparse, matplotlib, xarray or dask. Modules inside the package import from the modules
that define a name, never from this namespace.
"""

from __future__ import annotations

from ._lazy import lazy_names
from .errors import MacroslipError, MicroslipError, ParameterError
from .options import CENTRE_READINGS, POISSON_MODES, ModelOptions
from .params import PRESETS, ClampParams, preset
from .results import Backbone, DampingResult, HysteresisLoop

__version__ = "0.1.0"

#: Public name -> the module that defines it, imported on first use.
_LAZY = {
    # modules
    "closedform": ".closedform",
    "planar": ".planar",
    # the 1-D models, their loops and energies
    "MODELS": ".models",
    "Contact": ".models",
    "first_loading": ".models",
    "macroslip_force": ".models",
    "VirginCurve": ".hysteresis",
    "masing_loop": ".hysteresis",
    "masing_response": ".hysteresis",
    "DEFAULT_STRAIN_ENERGY": ".energy",
    "STRAIN_ENERGY": ".energy",
    "damping": ".energy",
    "damping_from_loop": ".energy",
    "dissipated_energy": ".energy",
    "loss_factor": ".energy",
    "strain_energy": ".energy",
    "batch_damping": ".batch",
    # circular and elliptical loading
    "analytical_response": ".planar",
    "loss_factor_vs_ratio": ".planar",
    "paper_coupling": ".planar",
    "ratio_sweep": ".sweep.ratio",
    # finite elements
    "FELoopResult": ".fe.result",
    "run_loop": ".fe.run",
    "coupling_study": ".fe.builtin.study",
    "fe_backbone": ".fe.builtin.backbone",
    "solve_uniaxial": ".fe.builtin.uniaxial",
    "read_mesh": ".fe.meshfile",
    "Assembly": ".fe.assembly",
    "ContactPair": ".fe.assembly",
    "Preload": ".fe.assembly",
    "Support": ".fe.assembly",
    "Material": ".fe.assembly",
    "Shank": ".fe.assembly",
    "bolt": ".fe.assembly",
    "rigid_base": ".fe.assembly",
    "MeshLoad": ".fe.meshload",
    "run_fe": ".fe.ownmesh",
    "MeshClamp": ".fe.clamp",
    "clamped_model": ".fe.clamp",
    # the structure on a mesh
    "StructureCase": ".meshdynamics.case",
    "prepare_structure": ".meshdynamics.case",
    "structure_rom": ".meshdynamics.case",
    "linear_modes": ".meshdynamics.modes",
    "qsma": ".meshdynamics.qsma",
    "qsma_amplitudes": ".meshdynamics.qsma",
    "build_rom": ".meshdynamics.reduce",
    "rom_structure": ".meshdynamics.reduce",
    "build_whole_joint": ".meshdynamics.wholejoint",
    "whole_joint_epmc": ".meshdynamics.wholejoint",
    "ModalSettings": ".meshdynamics.modalstudy",
    "modal_study": ".meshdynamics.modalstudy",
    "FrfSettings": ".meshdynamics.frfstudy",
    "frf_study": ".meshdynamics.frfstudy",
    "StudyResult": ".meshdynamics.studyresult",
    # the joint in a structure
    "IwanOperator": ".dynamics.operators",
    "jenkins": ".dynamics.operators",
    "clamp_joint": ".dynamics.distributions",
    "iwan4": ".dynamics.distributions",
    "describing_function": ".dynamics.describing",
    "Structure": ".dynamics.structure",
    "one_mode": ".dynamics.structure",
    "from_matrices": ".dynamics.assemble",
    "FrequencyResponse": ".dynamics.response",
    "frequency_response": ".dynamics.response",
    "ModalCurve": ".dynamics.modal",
    "energy_method": ".dynamics.modal",
    "epmc": ".dynamics.modal",
    # studies
    "make_sweep": ".sweep.spec",
    "run_sweep": ".sweep.run",
    "write_sweep": ".sweep.output",
    "fit_loops": ".fit",
    "write_report": ".report",
}

__all__ = [
    "CENTRE_READINGS",
    "POISSON_MODES",
    "PRESETS",
    "Backbone",
    "ClampParams",
    "DampingResult",
    "HysteresisLoop",
    "MacroslipError",
    "MicroslipError",
    "ModelOptions",
    "ParameterError",
    "preset",
    *_LAZY,
]

__getattr__ = lazy_names(__name__, _LAZY)


def __dir__() -> list[str]:
    return sorted({*__all__, "__version__"})
