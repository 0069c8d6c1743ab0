"""Loading: where a load acts and how it varies in time, defined once for every solver.

:mod:`~microslip.loading.cases` holds the registry of load cases (:data:`LOAD_CASES`:
name -> the loaded section and the slip-length domains it is reported by);
:mod:`~microslip.loading.sine` the paper's load step F = F0 sin(2 pi t / T) over 1.25
periods, sampled once (:class:`PaperSine`) for the analytical models and both FE solvers;
:mod:`~microslip.loading.path` the planar load paths (:class:`LoadPath`: named force
components, a start-up, one closed cycle) of the analytical planar model and the built-in
solver, and next of the structure-dynamics code.
This package imports numpy and the basics only: :mod:`microslip.closedform` (the slip
lengths a load case is reported by), :mod:`microslip.errors`, :mod:`microslip.named`,
:mod:`microslip.params` (the bottom floor of the import-linter contracts, pyproject.toml).
"""

from __future__ import annotations

from .cases import LOAD_CASES, LoadCase, load_case
from .path import COMPONENTS, LoadPath
from .sine import PERIOD, PERIODS, PaperSine, paper_sine

__all__ = ["COMPONENTS", "LOAD_CASES", "PERIOD", "PERIODS", "LoadCase", "LoadPath", "PaperSine",
           "load_case", "paper_sine"]
