"""Finite-element loops of the clamped bar: one result type, one entry point, two solvers.

:func:`run_loop` runs the paper's FE load step with a solver of :data:`SOLVERS` (the
built-in solver, :mod:`microslip.solver`, or CalculiX) and returns one
:class:`FELoopResult` (:mod:`~microslip.fe.result`) either way; with ``out`` both write
``result.json`` and a VTU series (:mod:`~microslip.fe.vtu`). Constants shared by both
solvers: :mod:`~microslip.fe.constants`; load cases: :mod:`microslip.loading`.

The paper validates its models against ANSYS contact simulations (Section 4, Table 1,
Figs 8-9). This subpackage builds the same model for the open solver CalculiX (``ccx``),
generated, run and read back from Python:

- :mod:`microslip.meshlevels` (re-exported here): the mesh levels of both solvers;
- :mod:`~microslip.fe.mesh`: structured C3D20 mesh of the bar on a rigid C3D8 base;
- :mod:`~microslip.fe.case`: the validated load case (:class:`FECase`);
- :mod:`~microslip.fe.deck`: the ``.inp`` deck, one tested function per keyword card;
- :mod:`~microslip.fe.runner`: ``ccx`` with a time-out and typed failures;
- :mod:`~microslip.fe.readers`: ``.dat``, ``.sta`` and ``.frd`` readers;
- :mod:`~microslip.fe.results`: the CalculiX run read into an :class:`FELoopResult`.

Nothing here is imported by ``import microslip``; meshio is imported only by the VTU export.
"""

from __future__ import annotations

from ..loading import LOAD_CASES
from ..meshlevels import LEVELS, MESH_LEVELS, level_counts
from .case import ELEMENT_TYPES, FECase
from .constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from .deck import build_deck
from .errors import (
    INSTALL_HINT,
    NonConvergenceError,
    ResultsError,
    SolverError,
    SolverKilledError,
    SolverNotFoundError,
    SolverTimeoutError,
)
from .mesh import BarMesh, MeshSpec, bar_mesh, mesh_spec
from .readers import read_dat, read_frd, read_sta
from .result import STATUS, ContactHistory, FELoopResult
from .results import CalculixDetails, contact_status, read_results
from .run import SOLVERS, SolverEntry, run_loop
from .runner import ccx_available, ccx_version, default_timeout, find_ccx, run_case, run_ccx

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
