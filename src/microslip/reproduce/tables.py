"""The tables of ``microslip reproduce``, as columns (name with unit -> values): the loss
factor against R (Fig. 12), each model alone at the paper's levels, R = 1 at each equal pair
of levels, and the coupled 2-D friction study. Units: N, mm, N·mm.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from ..energy import damping
from ..errors import MicroslipError
from ..models import macroslip_force
from ..options import ModelOptions
from ..planar import (
    CENTRE_LEVEL_FORCE,
    PAPER_LEVELS,
    TIP_LEVEL_FORCE,
    WORK_STRAIN_ENERGY,
    ComponentEnergy,
    RatioSweep,
    eccentricity,
    planar_damping,
    work_damping,
)

__all__ = [
    "READING_SAMPLES",
    "component_table",
    "coupling_table",
    "equal_level_table",
    "loss_factor_table",
]

#: Samples per cycle of the work-based cycles of the alternative readings and of the R = 1
#: table (the main table uses the library default, 2048); the trapezoidal error of W is about
#: 2.5e-5 relative, the same for every R to first order.
READING_SAMPLES = 512


def loss_factor_table(sweep: RatioSweep, phase90: RatioSweep) -> dict[str, Any]:
    """Columns of ``loss_factor_vs_R.csv``: the sweep's own columns, the 90-degree work
    columns and the reason a case was not computed (``note``)."""
    table = sweep.columns()
    table.update(_phase90_columns(phase90))
    table["note"] = [c.error for c in sweep.cases]
    return table


def _phase90_columns(phase90: RatioSweep) -> dict[str, Any]:
    """W at 90 degrees and eta with both combinations of the component strain energies."""
    cols: dict[str, list[float]] = {"work_dissipated_energy_phase90_Nmm": []}
    for name in WORK_STRAIN_ENERGY:
        cols[f"work_loss_factor_phase90_{name}"] = []
    kind = phase90.strain_energy_kind
    for case in phase90.cases:
        res = case.result
        if res is None:
            for v in cols.values():
                v.append(math.nan)
            continue
        cols["work_dissipated_energy_phase90_Nmm"].append(res.work_dissipated_energy)
        tip_bb, centre_bb = res.tip.backbone, res.centre.backbone
        assert tip_bb is not None and centre_bb is not None
        for name in WORK_STRAIN_ENERGY:
            if name == res.work_energy:
                eta = res.work_loss_factor
            else:
                eta = work_damping(res.work.response,
                                   ComponentEnergy(tip_bb, kind, res.tip_symmetry),
                                   ComponentEnergy(centre_bb, kind, 1), name, kind).loss_factor
            cols[f"work_loss_factor_phase90_{name}"].append(eta)
    return cols


def component_table(tip_params: Any, centre_params: Any, increments: int,
                    options: ModelOptions, strain_energy: str,
                    levels: Sequence[int] = PAPER_LEVELS) -> dict[str, Any]:
    """Each model alone at the paper's levels: peak displacement, secant stiffness, damping.

    Columns of ``stiffness_vs_amplitude.csv``; a level the reading cannot compute (at or
    beyond macroslip) has NaN values and its reason in ``note``.
    """
    col: dict[str, list[Any]] = {k: [] for k in (
        "model", "level", "amplitude_N", "macroslip_force_N", "peak_displacement_mm",
        "secant_stiffness_N_per_mm", "dissipated_energy_Nmm", "strain_energy_Nmm",
        "loss_factor", "loss_factor_secant", "note")}
    for model, params, unit in (("tip", tip_params, TIP_LEVEL_FORCE),
                                ("centre", centre_params, CENTRE_LEVEL_FORCE)):
        limit = macroslip_force(model, params, options)
        for lv in levels:
            a = unit * lv
            col["model"].append(model)
            col["level"].append(lv)
            col["amplitude_N"].append(a)
            col["macroslip_force_N"].append(limit)
            try:
                r = damping(model, params, a, increments, options, strain_energy)
                rs = damping(model, params, a, increments, options, "secant")
            except MicroslipError as exc:
                for k in ("peak_displacement_mm", "secant_stiffness_N_per_mm",
                          "dissipated_energy_Nmm", "strain_energy_Nmm", "loss_factor",
                          "loss_factor_secant"):
                    col[k].append(math.nan)
                col["note"].append(" ".join(str(exc).split()))
                continue
            col["peak_displacement_mm"].append(r.peak_displacement)
            col["secant_stiffness_N_per_mm"].append(r.amplitude / r.peak_displacement)
            col["dissipated_energy_Nmm"].append(r.dissipated_energy)
            col["strain_energy_Nmm"].append(r.strain_energy)
            col["loss_factor"].append(r.loss_factor)
            col["loss_factor_secant"].append(rs.loss_factor)
            col["note"].append("")
    return col


def equal_level_table(tip_params: Any, centre_params: Any, increments: int,
                      options: ModelOptions, strain_energy: str, work_energy: str,
                      levels: Sequence[int] = PAPER_LEVELS) -> dict[str, Any]:
    """R = 1 at each equal pair of levels (1/1 ... 4/4): how eta moves at a fixed R.

    Columns of ``loss_factor_R1_levels.csv``; a pair the reading cannot compute has NaN and
    its reason in ``note``.
    """
    col: dict[str, list[Any]] = {k: [] for k in (
        "level", "tip_amplitude_N", "centre_amplitude_N", "paper_loss_factor",
        "work_loss_factor", "note")}
    for lv in levels:
        at, ac = TIP_LEVEL_FORCE * lv, CENTRE_LEVEL_FORCE * lv
        col["level"].append(lv)
        col["tip_amplitude_N"].append(at)
        col["centre_amplitude_N"].append(ac)
        try:
            r = planar_damping(tip_params, centre_params, at, ac, increments=increments,
                               options=options, strain_energy=strain_energy,
                               work_energy=work_energy, samples_per_cycle=READING_SAMPLES)
        except MicroslipError as exc:
            col["paper_loss_factor"].append(math.nan)
            col["work_loss_factor"].append(math.nan)
            col["note"].append(" ".join(str(exc).split()))
            continue
        col["paper_loss_factor"].append(r.paper.loss_factor)
        col["work_loss_factor"].append(r.work_loss_factor)
        col["note"].append("")
    return col


def coupling_table(sweep: Any) -> dict[str, list[Any]]:
    """Columns of ``coupling_ratio_vs_R.csv`` from a :class:`microslip.fe.builtin.CouplingSweep`."""
    cols: dict[str, list[Any]] = {k: [] for k in (
        "R", "eccentricity", "phase_deg", "tip_amplitude_N", "centre_amplitude_N",
        "dissipated_energy_Nmm", "decoupled_dissipated_energy_Nmm", "coupling_ratio",
        "tip_share", "centre_share", "settled")}
    for phi, row in zip(sweep.phases_deg, sweep.results, strict=True):
        for r, res in zip(sweep.ratios, row, strict=True):
            s = res.summary()
            cols["R"].append(float(r))
            cols["eccentricity"].append(eccentricity(float(r)))
            cols["phase_deg"].append(float(phi))
            cols["tip_amplitude_N"].append(res.tip_amplitude)
            cols["centre_amplitude_N"].append(res.centre_amplitude)
            cols["dissipated_energy_Nmm"].append(res.dissipated_energy)
            cols["decoupled_dissipated_energy_Nmm"].append(res.decoupled_dissipated_energy)
            cols["coupling_ratio"].append(res.coupling_ratio)
            cols["tip_share"].append(s["tip_share"])
            cols["centre_share"].append(s["centre_share"])
            cols["settled"].append(bool(s["converged"]))
    return cols

