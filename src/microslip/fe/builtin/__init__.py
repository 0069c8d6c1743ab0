"""Built-in frictional finite-element solver: elastic bodies on a rigid Coulomb base or on
each other.

One solver for the engineer's own hexahedral mesh (:func:`build_mesh_model` and
:func:`solve_mesh`: :mod:`.meshmodel`, :mod:`.meshrun`, :mod:`.condense`) and for the clamped
zone of the paper (Section 4's FE model, :mod:`.box`: the box's mesh and its assembly, the
clamp's pressure law the distribution of its preload): hexahedra numbered for a narrow band,
nodal Coulomb friction with a circular limit mu N_i and a penalty stick slope lambda A_i,
normal forces N_i from the clamping step (or a unilateral penalty that follows the load:
:mod:`.normal`), radial return with its consistent tangent, semi-smooth Newton with a
backtracking line search and LAPACK banded Cholesky. The box's mesh levels take their
element counts from the geometry (:func:`level_counts`).
See ``docs/solver.md`` for the formulation, the verification and the coupled-versus-
decoupled study. Units: N, mm, MPa, N·mm, s.

>>> from microslip import preset
>>> from microslip.fe.builtin import solve_uniaxial
>>> r = solve_uniaxial(preset("table1"), "tip", 267.0, mesh=(8, 2, 1))
>>> r.loop.source, r.solver, r.converged
('builtin', 'builtin', True)
"""

from __future__ import annotations

from ...meshlevels import LEVELS, MESH_LEVELS, level_counts
from .backbone import FEBackbone, fe_backbone
from .box import BoxHistory, BoxLoading, box_assembly, box_model
from .clamping import ClampingPressure, clamping_pressure
from .contact import FrictionResponse, friction_dissipation, return_map
from .details import (
    BuiltinDetails,
    CouplingResult,
    CycleWork,
    LoadPathResult,
    SolverStats,
)
from .element import ELEMENTS, assemble_hex8, element_stiffness
from .linalg import LINEAR_SOLVERS, available_linear_solvers
from .meshmodel import MeshModel, build_mesh_model
from .meshrun import LoadFactors, MeshLoadResult, MeshRunResult, SineCycles, solve_mesh
from .model import CENTRE_DIRECTIONS, NewtonOptions
from .normal import NORMAL_CONTACTS, PenaltyNormal
from .pressure import fe_pressure_law
from .study import (
    DEFAULT_MESH,
    CouplingSweep,
    amplitudes_for_ratio,
    as_load_path,
    coupling_study,
    coupling_sweep,
    solve_load_path,
)
from .uniaxial import solve_uniaxial

__all__ = [
    "CENTRE_DIRECTIONS",
    "DEFAULT_MESH",
    "ELEMENTS",
    "LEVELS",
    "LINEAR_SOLVERS",
    "MESH_LEVELS",
    "NORMAL_CONTACTS",
    "BoxHistory",
    "BoxLoading",
    "BuiltinDetails",
    "ClampingPressure",
    "CouplingResult",
    "CouplingSweep",
    "CycleWork",
    "FEBackbone",
    "FrictionResponse",
    "LoadFactors",
    "LoadPathResult",
    "MeshLoadResult",
    "MeshModel",
    "MeshRunResult",
    "NewtonOptions",
    "PenaltyNormal",
    "SineCycles",
    "SolverStats",
    "amplitudes_for_ratio",
    "as_load_path",
    "assemble_hex8",
    "available_linear_solvers",
    "box_assembly",
    "box_model",
    "build_mesh_model",
    "clamping_pressure",
    "coupling_study",
    "coupling_sweep",
    "element_stiffness",
    "fe_backbone",
    "fe_pressure_law",
    "friction_dissipation",
    "level_counts",
    "return_map",
    "solve_load_path",
    "solve_mesh",
    "solve_uniaxial",
]
