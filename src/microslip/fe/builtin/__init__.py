"""Built-in frictional finite-element solver: an elastic box on a rigid Coulomb base.

A purpose-made solver for the clamped zone of the paper (Section 4's FE model): trilinear
hexahedra numbered slice by slice along the bar (a band matrix), the bottom face held at
u_z = 0, nodal Coulomb friction with a circular limit mu N_i and a penalty stick slope
lambda A_i, normal forces N_i from the clamping step (or a unilateral penalty that follows
the load: :mod:`.normal`), a clamping pressure law (:mod:`.clamping`), radial return with its
consistent tangent, semi-smooth Newton with a backtracking line search and LAPACK banded
Cholesky. Mesh levels take their element counts from the geometry (:func:`level_counts`).
The same physics on the engineer's own hexahedral mesh: :func:`build_mesh_model` and
:func:`solve_mesh` (:mod:`.meshmodel`, :mod:`.meshrun`, :mod:`.condense`).
See ``docs/solver.md`` for the formulation, the verification and the coupled-versus-
decoupled study. Units: N, mm, MPa, N·mm, s.

>>> from microslip import preset
>>> from microslip.fe.builtin import solve_uniaxial
>>> r = solve_uniaxial(preset("table1"), "tip", 267.0, mesh=(8, 2, 1))
>>> r.loop.source, r.solver, r.converged
('builtin', 'builtin', True)
"""

from __future__ import annotations

from .backbone import FEBackbone, fe_backbone
from .clamping import ClampingPressure, clamp_forces, clamping_pressure
from .contact import FrictionResponse, friction_dissipation, return_map
from .details import (
    BuiltinDetails,
    CouplingResult,
    CycleWork,
    LoadPathResult,
    SolverStats,
)
from .element import ELEMENTS, assemble_stiffness, element_stiffness
from .linalg import LINEAR_SOLVERS, available_linear_solvers
from .mesh import LEVELS, MESH_LEVELS, BoxMesh, box_mesh, level_counts, mesh_from_spec
from .meshmodel import MeshModel, build_mesh_model
from .meshrun import LoadFactors, MeshLoadResult, MeshRunResult, SineCycles, solve_mesh
from .normal import NORMAL_CONTACTS, PenaltyNormal
from .pressure import fe_pressure_law
from .solve import (
    CENTRE_DIRECTIONS,
    FrictionModel,
    History,
    NewtonOptions,
    Simulation,
    build_model,
    run_history,
)
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
    "BoxMesh",
    "BuiltinDetails",
    "ClampingPressure",
    "CouplingResult",
    "CouplingSweep",
    "CycleWork",
    "FEBackbone",
    "FrictionModel",
    "FrictionResponse",
    "History",
    "LoadFactors",
    "LoadPathResult",
    "MeshLoadResult",
    "MeshModel",
    "MeshRunResult",
    "NewtonOptions",
    "PenaltyNormal",
    "Simulation",
    "SineCycles",
    "SolverStats",
    "amplitudes_for_ratio",
    "as_load_path",
    "assemble_stiffness",
    "available_linear_solvers",
    "box_mesh",
    "build_mesh_model",
    "build_model",
    "clamp_forces",
    "clamping_pressure",
    "coupling_study",
    "coupling_sweep",
    "element_stiffness",
    "fe_backbone",
    "fe_pressure_law",
    "friction_dissipation",
    "level_counts",
    "mesh_from_spec",
    "return_map",
    "run_history",
    "solve_load_path",
    "solve_mesh",
    "solve_uniaxial",
]
