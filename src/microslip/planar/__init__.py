"""Planar (circular and elliptical) loading of a clamped zone (paper, Sections 1, 3 and 5).

* :mod:`~microslip.planar.trajectories`: force ratio R, eccentricity, the paper's load
  levels and trajectories (Fig. 1, Table 2).
* :mod:`~microslip.planar.coupling`: the paper's resultant loop and its damping (Eqs 19-23).
* :mod:`~microslip.planar.loadpath`: general sampled load paths, the decoupled analytical
  response to them and the work-based energy (beyond the paper).
* :mod:`~microslip.planar.damping`: both side by side for one case
  (:func:`planar_damping`) and against R (:func:`loss_factor_vs_ratio`, Fig. 12).

Decisions and their algebra: ``docs/planar.md``. Units: N, mm, N·mm.

Examples
--------
>>> from microslip import planar, preset
>>> planar.paper_levels(4.0)
(8000.0, 4000.0)
>>> r = planar.planar_damping(preset("table2-tip"), preset("table2-centre"), 8000.0, 4000.0,
...                           increments=200, samples_per_cycle=512)
>>> round(r.ratio, 6), round(r.eccentricity, 2)
(4.0, 0.97)
"""

from __future__ import annotations

from .coupling import (
    paper_coupling,
    paper_loss_factors,
    resultant,
    resultant_backbone,
    resultant_loop,
)
from .damping import (
    PAPER_STRAIN_ENERGY,
    PlanarResult,
    RatioCase,
    RatioSweep,
    loss_factor_vs_ratio,
    planar_damping,
)
from .loadpath import (
    DEFAULT_WORK_STRAIN_ENERGY,
    WORK_STRAIN_ENERGY,
    ComponentEnergy,
    LoadPath,
    PathResponse,
    WorkResult,
    analytical_response,
    closure_error,
    cycle_work,
    truncate_backbone,
    work_damping,
)
from .trajectories import (
    CENTRE_LEVEL_FORCE,
    LEVEL_SCHEMES,
    PAPER_LEVELS,
    PAPER_RATIOS,
    TIP_LEVEL_FORCE,
    TIP_SYMMETRY,
    Trajectory,
    eccentricity,
    force_ratio,
    paper_level_pair,
    paper_levels,
    ratio_from_eccentricity,
    ratio_label,
    trajectory,
)

__all__ = [
    "CENTRE_LEVEL_FORCE",
    "DEFAULT_WORK_STRAIN_ENERGY",
    "LEVEL_SCHEMES",
    "PAPER_LEVELS",
    "PAPER_RATIOS",
    "PAPER_STRAIN_ENERGY",
    "TIP_LEVEL_FORCE",
    "TIP_SYMMETRY",
    "WORK_STRAIN_ENERGY",
    "ComponentEnergy",
    "LoadPath",
    "PathResponse",
    "PlanarResult",
    "RatioCase",
    "RatioSweep",
    "Trajectory",
    "WorkResult",
    "analytical_response",
    "closure_error",
    "cycle_work",
    "eccentricity",
    "force_ratio",
    "loss_factor_vs_ratio",
    "paper_coupling",
    "paper_level_pair",
    "paper_levels",
    "paper_loss_factors",
    "planar_damping",
    "ratio_from_eccentricity",
    "ratio_label",
    "resultant",
    "resultant_backbone",
    "resultant_loop",
    "trajectory",
    "truncate_backbone",
    "work_damping",
]
