"""The loss factor against R under other readings of the paper (sensitivity): the other
level scheme, the other reading of the centre model, the corrections off, every equation as
printed (``loss_factor_vs_R_readings.csv``). Units: N, mm, N·mm.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from ..named import short_repr
from ..options import ModelOptions
from ..params import ClampParams
from ..planar import LEVEL_SCHEMES, PAPER_RATIOS, RatioSweep, loss_factor_vs_ratio
from .tables import READING_SAMPLES

__all__ = ["Reading", "compute_readings", "readings_table"]


@dataclass(frozen=True, eq=False, repr=False)
class Reading:
    """The loss factor against R under an alternative reading of the paper."""

    name: str
    description: str
    sweep: RatioSweep

    __repr__ = short_repr


def _readings(options: ModelOptions, levels: str, increments: int
              ) -> list[tuple[str, str, str, int, ModelOptions]]:
    """(name, description, levels, increments, options) of the alternative readings."""
    other_levels = next(s for s in LEVEL_SCHEMES if s != levels)
    other_centre = "physical" if options.centre == "paper" else "paper"
    out = [
        (f"levels-{other_levels}", f"level pairs '{other_levels}': "
         f"{LEVEL_SCHEMES[other_levels]}", other_levels, increments, options),
        (f"centre-{other_centre}", f"centre model read '{other_centre}' (macroslip at "
         f"{'μF_N' if other_centre == 'physical' else '2μF_N'})", levels, increments,
         dataclasses.replace(options, centre=other_centre)),
    ]
    if options.corrections:
        out.append(("corrections-off", "Poisson and length updates off (rigid-foundation "
                    "closed forms)", levels, increments,
                    dataclasses.replace(options, poisson="off", length_update=False)))
    lit = ModelOptions.paper()
    if options != lit or increments != 50:
        out.append((f"paper-literal-{increments}", f"every equation as printed "
                    f"(ModelOptions.paper()), {increments} increments", levels, increments,
                    lit))
    if increments != 50:
        out.append(("paper-literal-50", "every equation as printed, 50 increments (the "
                    "number of load steps of the paper's FE runs)", levels, 50, lit))
    return out



def compute_readings(tip_params: ClampParams, centre_params: ClampParams,
                     options: ModelOptions, levels: str, increments: int, strain_energy: str,
                     work_energy: str) -> tuple[Reading, ...]:
    """The paper's seven R under each alternative reading of :func:`_readings`."""
    return tuple(
        Reading(name, desc, loss_factor_vs_ratio(
            PAPER_RATIOS, tip_params=tip_params, centre_params=centre_params, levels=lev,
            increments=inc, options=o, strain_energy=strain_energy, work_energy=work_energy,
            samples_per_cycle=READING_SAMPLES))
        for name, desc, lev, inc, o in _readings(options, levels, increments))


_READING_COLUMNS = ("R", "eccentricity", "tip_amplitude_N", "centre_amplitude_N",
                    "paper_loss_factor", "paper_normalised_loss_factor", "work_loss_factor",
                    "work_normalised_loss_factor")


def readings_table(readings: tuple[Reading, ...]) -> dict[str, list[Any]]:
    """Columns of ``loss_factor_vs_R_readings.csv``: one block of rows per reading."""
    col: dict[str, list[Any]] = {k: [] for k in (
        "reading", "levels", "increments", *_READING_COLUMNS, "note")}
    for rd in readings:
        c = rd.sweep.columns()
        m = len(rd.sweep.cases)
        col["reading"].extend([rd.name] * m)
        col["levels"].extend([rd.sweep.levels] * m)
        col["increments"].extend([rd.sweep.increments] * m)
        for k in _READING_COLUMNS:
            col[k].extend(list(c[k]))
        col["note"].extend(case.error for case in rd.sweep.cases)
    return col
