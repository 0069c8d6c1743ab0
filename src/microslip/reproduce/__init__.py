"""Reproduce the paper: every figure and table our models can produce, and a check of its claims.

:func:`reproduce` writes into one directory Figs 1, 10, 11 and 12 (and, with the
finite-element validation, Figs 8-9 and ``validation.csv``), the data behind each figure as
CSV, the stiffness and damping of each model at the paper's levels, the loss factor against R
under other readings of the paper, and ``report.md`` with a point-by-point check of the
paper's claims, each verdict computed from the CSV columns by :func:`check_claims`. The
package holds the job runner (:mod:`~microslip.reproduce.job`), the tables
(:mod:`~microslip.reproduce.tables`), the alternative readings
(:mod:`~microslip.reproduce.readings`), the claims (:mod:`~microslip.reproduce.claims`) and
the report text (:mod:`~microslip.reproduce.report`); the figures live in
:mod:`microslip.plot.paper` and are re-exported here. It may import the computing packages
(planar, models, energy, fe, dynamics), :mod:`microslip.validate`, :mod:`microslip.plot`,
:mod:`microslip.io` and :mod:`microslip.progress`; nothing imports it but the CLI (the
import-linter contracts, pyproject.toml). Units: N, mm, N·mm.
"""

from __future__ import annotations

from ..io import read_csv
from ..plot.paper import (
    CENTRE_COLOUR,
    PAPER_COLOUR,
    RATIO_COLOURS,
    TIP_COLOUR,
    WORK_COLOUR,
    figure_coupling,
    figure_loops,
    figure_loss_factor,
    figure_planar,
    figure_trajectories,
)
from .claims import VERDICTS, Claim, check_claims, eta_extremes
from .job import FE_MESHES, FEOutcome, ReproduceResult, reproduce
from .readings import Reading, compute_readings, readings_table
from .report import Settings, report_markdown
from .tables import (
    READING_SAMPLES,
    component_table,
    coupling_table,
    equal_level_table,
    loss_factor_table,
)

__all__ = [
    "CENTRE_COLOUR",
    "FE_MESHES",
    "PAPER_COLOUR",
    "RATIO_COLOURS",
    "READING_SAMPLES",
    "TIP_COLOUR",
    "VERDICTS",
    "WORK_COLOUR",
    "Claim",
    "FEOutcome",
    "Reading",
    "ReproduceResult",
    "Settings",
    "check_claims",
    "component_table",
    "compute_readings",
    "coupling_table",
    "equal_level_table",
    "eta_extremes",
    "figure_coupling",
    "figure_loops",
    "figure_loss_factor",
    "figure_planar",
    "figure_trajectories",
    "loss_factor_table",
    "read_csv",
    "readings_table",
    "report_markdown",
    "reproduce",
]
