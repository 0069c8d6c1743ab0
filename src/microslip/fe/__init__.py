"""Finite elements of the clamp: one package, two solvers, one result type, one entry point.

- :mod:`microslip.fe.builtin`: the built-in frictional FE solver (8-node hexahedra, nodal
  Coulomb friction, semi-smooth Newton); fast, and the one every study uses;
- :mod:`microslip.fe.calculix`: the same model for the open solver CalculiX (``ccx``), as a
  check: C3D20R deck, run with a time-out, read back.

:func:`run_loop` runs the paper's FE load step (Section 4, Table 1, Figs 8-9) with a solver
of :data:`SOLVERS` and returns one :class:`FELoopResult` (:mod:`~microslip.fe.result`) either
way; with ``out`` both write ``result.json`` and a VTU series (:mod:`~microslip.fe.vtu`).
Constants shared by both solvers: :mod:`~microslip.fe.constants`; errors:
:mod:`~microslip.fe.errors`; mesh levels: :mod:`microslip.meshlevels` (re-exported here);
load cases: :mod:`microslip.loading`.

Nothing here is imported by ``import microslip``; meshio is imported only by the VTU export.
"""

from __future__ import annotations

from ..loading import LOAD_CASES
from ..meshlevels import LEVELS, MESH_LEVELS, level_counts
from .calculix.case import ELEMENT_TYPES, FECase
from .calculix.collect import CalculixDetails, contact_status, read_results
from .calculix.deck import build_deck
from .calculix.mesh import BarMesh, MeshSpec, bar_mesh, mesh_spec
from .calculix.readers import read_dat, read_frd, read_sta
from .calculix.runner import (
    ccx_available,
    ccx_version,
    default_timeout,
    find_ccx,
    run_case,
    run_ccx,
)
from .constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from .errors import (
    INSTALL_HINT,
    NonConvergenceError,
    ResultsError,
    SolverError,
    SolverKilledError,
    SolverNotFoundError,
    SolverTimeoutError,
)
from .result import STATUS, ContactHistory, FELoopResult
from .run import SOLVERS, SolverEntry, run_loop

__all__ = [
    "DEFAULT_NORMAL_SLOPE",
    "DEFAULT_STICK_SLOPE",
    "ELEMENT_TYPES",
    "INSTALL_HINT",
    "LEVELS",
    "LOAD_CASES",
    "MESH_LEVELS",
    "SOLVERS",
    "STATUS",
    "BarMesh",
    "CalculixDetails",
    "ContactHistory",
    "FECase",
    "FELoopResult",
    "MeshSpec",
    "NonConvergenceError",
    "ResultsError",
    "SolverEntry",
    "SolverError",
    "SolverKilledError",
    "SolverNotFoundError",
    "SolverTimeoutError",
    "bar_mesh",
    "build_deck",
    "ccx_available",
    "ccx_version",
    "contact_status",
    "default_timeout",
    "find_ccx",
    "level_counts",
    "mesh_spec",
    "read_dat",
    "read_frd",
    "read_results",
    "read_sta",
    "run_case",
    "run_ccx",
    "run_loop",
]
