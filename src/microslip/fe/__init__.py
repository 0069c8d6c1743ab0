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
Importing this package loads only the constants, the errors and the mesh levels; every other
name is imported from its module on first use (PEP 562), so that a module needing one FE
constant does not pay for the solvers.
"""

from __future__ import annotations

from .._lazy import lazy_names
from ..meshlevels import LEVELS, MESH_LEVELS, level_counts
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

#: Public name -> the module that defines it, imported on first use.
_LAZY = {
    "LOAD_CASES": "..loading",
    "ELEMENT_TYPES": ".calculix.case",
    "FECase": ".calculix.case",
    "CalculixDetails": ".calculix.collect",
    "contact_status": ".calculix.collect",
    "read_results": ".calculix.boxrun",
    "MeshSpec": ".calculix.mesh",
    "mesh_spec": ".calculix.mesh",
    "read_dat": ".calculix.readers",
    "read_frd": ".calculix.readers",
    "read_sta": ".calculix.readers",
    "ccx_available": ".calculix.runner",
    "ccx_version": ".calculix.runner",
    "default_timeout": ".calculix.runner",
    "find_ccx": ".calculix.runner",
    "run_case": ".calculix.boxrun",
    "run_ccx": ".calculix.runner",
    "STATUS": ".result",
    "ContactHistory": ".result",
    "FELoopResult": ".result",
    "MeshClamp": ".clamp",
    "clamped_model": ".clamp",
    "SOLVERS": ".run",
    "SolverEntry": ".run",
    "run_loop": ".run",
}

__all__ = [
    "DEFAULT_NORMAL_SLOPE",
    "DEFAULT_STICK_SLOPE",
    "INSTALL_HINT",
    "LEVELS",
    "MESH_LEVELS",
    "NonConvergenceError",
    "ResultsError",
    "SolverError",
    "SolverKilledError",
    "SolverNotFoundError",
    "SolverTimeoutError",
    "level_counts",
    *_LAZY,
]

__getattr__ = lazy_names(__name__, _LAZY)


def __dir__() -> list[str]:
    return sorted(__all__)
