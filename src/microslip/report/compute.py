"""The numbers of a case report: 1-D loops, damping against amplitude, the FE comparison, the
validity indicators and, where the case gives one, the planar coupling.

Everything is computed by the library's own entry points (:func:`microslip.damping`,
:func:`microslip.fe.run_loop`, :func:`microslip.models.validity.validity`,
:func:`microslip.planar.planar_damping`); this module only chooses the points.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..case.model import Case
from ..conventions import DEFAULT_MESH
from ..energy import damping
from ..errors import ParameterError
from ..models import macroslip_force
from ..models.validity import Validity, validity
from ..named import result
from ..options import ModelOptions
from ..params import ClampParams, preset
from ..progress import progress_bar
from ..results import DampingResult

__all__ = ["LOOP_FRACTIONS", "ReportData", "ReportSettings", "compute_report"]

#: Amplitudes of the loop figure, as fractions of the case amplitude.
LOOP_FRACTIONS = (0.25, 0.5, 0.75, 1.0)
#: Amplitudes of the 1-D damping curve, as fractions of the macroslip force.
CURVE_FRACTIONS = tuple(float(x) for x in np.linspace(0.04, 0.96, 24))
#: FE points of the damping curve, as fractions of the macroslip force (the case amplitude is
#: always added).
FE_FRACTIONS = (0.2, 0.4, 0.6, 0.8)


@dataclass(frozen=True)
class ReportSettings:
    """How the report computes: 1-D increments, FE solver, mesh and substeps, FE points."""

    increments: int = 1000
    fe_solver: str = "builtin"
    mesh: str = DEFAULT_MESH
    substeps: int = 50
    fe_points: bool = True
    planar_increments: int = 1000


@result
class ReportData:
    """What a report shows (units N, mm, N·mm; loss factors dimensionless)."""

    case: Case
    settings: ReportSettings
    model: str
    params: ClampParams
    amplitude: float
    macroslip: float
    loops: tuple[DampingResult, ...]
    curve_amplitude: np.ndarray
    curve_loss_factor: np.ndarray
    curve_dissipated: np.ndarray
    fe: Any
    fe_curve: np.ndarray
    validity_rigid: Validity
    validity_layer: Validity
    stick_slope: float
    planar: Any


def _clamp(case: Case) -> tuple[str, ClampParams, float]:
    if case.params is None:
        raise ParameterError(f"case {case.source}: a report needs the whole clamp: give "
                             "preset = \"...\" or all seven clamp values")
    amplitude = case.amplitude()
    if amplitude is None:  # pragma: no cover - a complete clamp always gives mu F_N
        raise ParameterError(f"case {case.source}: give load.amplitude")
    return str(case.get("load.model")), case.params, amplitude


def _fe_run(model: str, params: ClampParams, amplitude: float, stick_slope: float,
            s: ReportSettings) -> Any:
    from ..fe import run_loop

    return run_loop(model, params, amplitude, solver=s.fe_solver, mesh=s.mesh,
                    substeps=s.substeps, stick_slope=stick_slope)[0]


def _planar(case: Case, increments: int) -> Any:
    from ..planar import paper_levels, planar_damping

    phase = float(case.get("load.planar.phase_deg") or 0.0)
    if "load.planar.ratio" in case.values:
        at, ac = paper_levels(float(case.values["load.planar.ratio"]))
    elif {"load.planar.tip_amplitude", "load.planar.centre_amplitude"} <= set(case.values):
        at = float(case.values["load.planar.tip_amplitude"])
        ac = float(case.values["load.planar.centre_amplitude"])
    else:
        return None
    return planar_damping(preset("table2-tip"), preset("table2-centre"), at, ac,
                          increments=increments, phase_deg=phase)


def compute_report(case: Case, settings: ReportSettings | None = None, *,
                   progress: bool = True) -> ReportData:
    """Compute every number of the report of ``case``."""
    s = settings or ReportSettings()
    model, params, amplitude = _clamp(case)
    limit = macroslip_force(model, params, ModelOptions())
    if not amplitude < limit:
        raise ParameterError(f"case {case.source}: amplitude {amplitude:g} N is at or beyond "
                             f"the macroslip force; a report needs 0 < amplitude < {limit:g} N")
    stick = float(case.get("contact.stick_slope"))
    curve = np.array(CURVE_FRACTIONS) * limit
    fe_amps = sorted({*(f * limit for f in FE_FRACTIONS), amplitude}) if s.fe_points else []
    with progress_bar(len(fe_amps) + 2, "report", enabled=progress, unit="run") as bar:
        loops = tuple(damping(model, params, f * amplitude, s.increments)
                      for f in LOOP_FRACTIONS)
        runs = [damping(model, params, a, s.increments) for a in curve]
        bar.update(1)
        fe_curve = []
        fe_case = None
        for a in fe_amps:
            r = _fe_run(model, params, a, stick, s)
            fe_curve.append((a, r.damping.loss_factor, r.damping.dissipated_energy,
                             float(r.converged)))
            if a == amplitude:
                fe_case = r
            bar.update(1)
        planar = _planar(case, s.planar_increments)
        bar.update(1)
    return ReportData(
        case=case, settings=s, model=model, params=params, amplitude=amplitude,
        macroslip=limit, loops=loops, curve_amplitude=curve,
        curve_loss_factor=np.array([r.loss_factor for r in runs]),
        curve_dissipated=np.array([r.dissipated_energy for r in runs]),
        fe=fe_case, fe_curve=np.array(fe_curve, dtype=float).reshape(-1, 4),
        validity_rigid=validity(model, params, amplitude),
        validity_layer=validity(model, params, amplitude, stick_slope=stick),
        stick_slope=stick, planar=planar)
