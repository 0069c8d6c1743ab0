"""Finite-element validation with CalculiX: deck writer, solver driver and result readers.

The paper validates its models against ANSYS contact simulations (Section 4, Table 1,
Figs 8-9). This subpackage builds the same model for the open solver CalculiX (``ccx``),
generated, run and read back from Python:

- :mod:`~microslip.fe.mesh`: structured C3D20 mesh of the bar on a rigid C3D8 base;
- :mod:`~microslip.fe.case`: the validated load case (:class:`FECase`);
- :mod:`~microslip.fe.deck`: the ``.inp`` deck, one tested function per keyword card;
- :mod:`~microslip.fe.runner`: ``ccx`` with a time-out and typed failures;
- :mod:`~microslip.fe.readers`: ``.dat``, ``.sta`` and ``.frd`` readers;
- :mod:`~microslip.fe.results`: the named result (:class:`FEResult`): the loop as a
  :class:`~microslip.results.HysteresisLoop`, its damping, the contact status history;
- :mod:`~microslip.fe.vtu`: export for ParaView (meshio).

Nothing here is imported by ``import microslip``; meshio is imported only by the VTU export.
"""

from __future__ import annotations

from .case import (
    DEFAULT_NORMAL_SLOPE,
    DEFAULT_STICK_SLOPE,
    ELEMENT_TYPES,
    LOAD_CASES,
    FECase,
)
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
from .mesh import MESHES, BarMesh, MeshSpec, bar_mesh, mesh_spec
from .readers import read_dat, read_frd, read_sta
from .results import STATUS, ContactHistory, FEResult, contact_status, read_results
from .runner import ccx_available, ccx_version, default_timeout, find_ccx, run_case, run_ccx

__all__ = [
    "DEFAULT_NORMAL_SLOPE",
    "DEFAULT_STICK_SLOPE",
    "ELEMENT_TYPES",
    "INSTALL_HINT",
    "LOAD_CASES",
    "MESHES",
    "STATUS",
    "BarMesh",
    "ContactHistory",
    "FECase",
    "FEResult",
    "MeshSpec",
    "NonConvergenceError",
    "ResultsError",
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
    "mesh_spec",
    "read_dat",
    "read_frd",
    "read_results",
    "read_sta",
    "run_case",
    "run_ccx",
]
