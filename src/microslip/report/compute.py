"""The numbers of a case report: 1-D loops, damping against amplitude, the FE comparison, the
validity indicators and, where the case gives one, the planar coupling.

Every number comes from the computations the commands run on the same case
(:mod:`microslip.case.run`): the 1-D loops are :func:`~microslip.case.run.compute_loop` on the
inputs of ``microslip loop --case`` (the case's contact included), the FE points
:func:`~microslip.case.run.compute_fe` on those of ``microslip fe --case``, the planar section
:func:`~microslip.case.run.compute_planar` on those of ``microslip planar --case`` (the case's
clamp); this module only chooses the amplitudes. :func:`report_json` is the page's numbers as
one JSON object (``microslip report --json``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..case.model import Case
from ..case.run import (
    MODEL_PORTION,
    FeInputs,
    LoopInputs,
    LoopRun,
    PlanarRun,
    case_options,
    compute_fe,
    compute_loop,
    compute_planar,
    fe_inputs,
    fe_json,
    loop_inputs,
    loop_json,
    planar_inputs,
    planar_json,
)
from ..conventions import DEFAULT_MESH
from ..errors import MacroslipError, ParameterError
from ..models.validity import Validity, validity
from ..named import result
from ..params import ClampParams
from ..progress import progress_bar
from ..results import DampingResult
from .structure import structure_section

__all__ = ["LOOP_FRACTIONS", "ReportData", "ReportSettings", "comparison", "compute_bar_report",
           "report_json"]

#: Amplitudes of the loop figure, as fractions of the case amplitude.
LOOP_FRACTIONS = (0.25, 0.5, 0.75, 1.0)
#: Amplitudes of the 1-D damping curve, as fractions of the macroslip force.
CURVE_FRACTIONS = tuple(float(x) for x in np.linspace(0.04, 0.96, 24))
#: FE points of the damping curve, as fractions of the macroslip force (the case amplitude is
#: always added).
FE_FRACTIONS = (0.2, 0.4, 0.6, 0.8)
#: Keys of the case's planar load: with none of them the report has no planar section.
PLANAR_KEYS = ("load.planar.ratio", "load.planar.tip_amplitude",
               "load.planar.centre_amplitude")


@dataclass(frozen=True)
class ReportSettings:
    """How the report computes: 1-D increments, FE solver, mesh and substeps, FE points;
    ``bar``: a case of the user's own mesh gets the 1-D bar report of its ``[geometry]``
    beside its part's (off: the mesh's report is about the mesh alone)."""

    increments: int = 1000
    fe_solver: str = "builtin"
    mesh: str = DEFAULT_MESH
    substeps: int = 50
    fe_points: bool = True
    planar_increments: int = 1000
    bar: bool = False


@result
class ReportData:
    """What a report shows (units N, mm, N·mm; loss factors dimensionless).

    ``one_d`` is the 1-D loop at the case amplitude (``loops[-1]`` is its result), ``fe`` the
    FE run there (None without FE points), ``planar`` the planar case (None if the case gives
    no planar load, or ``planar_error`` says why it could not be computed). ``structure`` is
    the damping of the structure's mode on the case's own mesh, every solver side by side with
    the verdicts (the JSON object of ``modal --mesh ... --solver all``; None without a
    [mesh] file and density).
    """

    case: Case
    settings: ReportSettings
    model: str
    params: ClampParams
    amplitude: float
    macroslip: float
    one_d: LoopRun
    loops: tuple[DampingResult, ...]
    curve_amplitude: np.ndarray
    curve_loss_factor: np.ndarray
    curve_dissipated: np.ndarray
    fe: Any
    fe_curve: np.ndarray
    validity_rigid: Validity
    validity_layer: Validity
    stick_slope: float
    planar_run: PlanarRun | None
    planar_error: str | None
    structure: dict[str, Any] | None = None

    @property
    def planar(self) -> Any:
        """The planar result (:class:`~microslip.planar.PlanarResult`), or None."""
        return None if self.planar_run is None else self.planar_run.result


def _loop(case: Case, s: ReportSettings) -> LoopInputs:
    """The inputs of ``microslip loop --case`` (the case's model, or the key's default)."""
    if case.params is None:
        raise ParameterError(f"case {case.source}: a report needs the whole clamp: give "
                             "preset = \"...\" or all seven clamp values")
    opts = case_options(case, "loop")
    opts.setdefault("model", case.get("load.model"))
    if opts["amplitude"] is None:  # pragma: no cover - a complete clamp always gives mu F_N
        raise ParameterError(f"case {case.source}: give load.amplitude")
    return loop_inputs(opts | {"increments": s.increments})


def _fe(case: Case, model: str, s: ReportSettings) -> FeInputs:
    """The inputs of ``microslip fe --case`` with the report's solver, mesh and substeps."""
    opts = case_options(case, "fe") | {"model": model, "solver": s.fe_solver, "mesh": s.mesh,
                                       "substeps": s.substeps}
    return fe_inputs(opts)


def _planar(case: Case, increments: int) -> tuple[PlanarRun | None, str | None]:
    """``microslip planar --case`` on the case's own clamp and contact, or why not."""
    if not any(k in case.values for k in PLANAR_KEYS):
        return None, None
    try:
        inputs = planar_inputs(case_options(case, "planar") | {"increments": increments})
        return compute_planar(inputs), None
    except (ParameterError, MacroslipError) as exc:
        return None, str(exc)


def compute_bar_report(case: Case, settings: ReportSettings | None = None, *,
                       progress: bool = True, structure: bool = True) -> ReportData:
    """Compute every number of the 1-D bar report of ``case`` (its preset or [geometry]
    and clamp); with ``structure`` the section of the structure's mode too, last, when the
    case's [mesh] gives a file and a density
    (:func:`microslip.report.structure.structure_section`)."""
    s = settings or ReportSettings()
    inputs = _loop(case, s)
    model, amplitude, limit = inputs.model, inputs.amplitude, inputs.macroslip
    if not amplitude < limit:
        raise ParameterError(f"case {case.source}: amplitude {amplitude:g} N is at or beyond "
                             f"the macroslip force; a report needs 0 < amplitude < {limit:g} N")
    fe = _fe(case, model, s) if s.fe_points else None
    stick = float(case.get("contact.stick_slope"))
    curve = np.array(CURVE_FRACTIONS) * limit
    fe_amps = sorted({*(f * limit for f in FE_FRACTIONS), amplitude}) if fe else []
    with progress_bar(len(fe_amps) + 2, "report", enabled=progress, unit="run") as bar:
        runs = [compute_loop(inputs, f * amplitude) for f in LOOP_FRACTIONS[:-1]]
        one_d = compute_loop(inputs)
        loops = tuple(r.result for r in (*runs, one_d))
        curve_runs = [compute_loop(inputs, a).result for a in curve]
        bar.update(1)
        fe_curve = []
        fe_case = None
        for a in fe_amps:
            assert fe is not None
            r = compute_fe(fe, a)[0]
            fe_curve.append((a, r.damping.loss_factor, r.damping.dissipated_energy,
                             float(r.converged)))
            if a == amplitude:
                fe_case = r
            bar.update(1)
        planar, planar_error = _planar(case, s.planar_increments)
        bar.update(1)
    return ReportData(
        case=case, settings=s, model=model, params=inputs.params, amplitude=amplitude,
        macroslip=limit, one_d=one_d, loops=loops, curve_amplitude=curve,
        curve_loss_factor=np.array([r.loss_factor for r in curve_runs]),
        curve_dissipated=np.array([r.dissipated_energy for r in curve_runs]),
        fe=fe_case, fe_curve=np.array(fe_curve, dtype=float).reshape(-1, 4),
        validity_rigid=validity(model, inputs.params, amplitude),
        validity_layer=validity(model, inputs.params, amplitude, stick_slope=stick),
        stick_slope=stick, planar_run=planar, planar_error=planar_error,
        structure=structure_section(case) if structure else None)


def comparison(data: ReportData) -> list[tuple[str, float, float | None, float | None]]:
    """The rows of the 1-D against FE table: (quantity with unit, 1-D, FE, 1-D / FE - 1 in
    %); FE and the difference are None without an FE run."""
    one = data.one_d.result
    rows = [("peak displacement d0 (mm)", one.peak_displacement),
            ("dissipated energy W_d (N·mm)", one.dissipated_energy),
            ("strain energy U (N·mm)", one.strain_energy),
            ("loss factor η (dimensionless)", one.loss_factor)]
    if data.fe is None:
        return [(name, x, None, None) for name, x in rows]
    fe = data.fe
    values = (fe.peak_displacement, fe.damping.dissipated_energy, fe.damping.strain_energy,
              fe.damping.loss_factor)
    return [(name, x, v, 100.0 * (x / v - 1.0))
            for (name, x), v in zip(rows, values, strict=True)]


def _validity_json(v: Validity) -> dict[str, Any]:
    return {"slenderness": v.slenderness, "slip_fraction": v.slip_fraction,
            "stiffness_sensitivity": v.stiffness_sensitivity,
            "shear_lag_effect": v.shear_lag_effect, "warnings": list(v.warnings)}


def _loop_point(r: DampingResult) -> dict[str, Any]:
    return {"amplitude_N": r.amplitude, "peak_displacement_mm": r.peak_displacement,
            "dissipated_energy_Nmm": r.dissipated_energy, "strain_energy_Nmm": r.strain_energy,
            "loss_factor": r.loss_factor}


def report_json(data: ReportData) -> dict[str, Any]:
    """Every number of the page as one JSON object (``microslip report --json``).

    ``one_d`` is the object of ``microslip loop --case --json`` and ``fe`` that of
    ``microslip fe --case --json`` (None without FE runs), ``planar`` that of
    ``microslip planar --case --json`` (None without a planar load, ``planar_error`` when it
    could not be computed), each at the case amplitude and on the case's clamp and contact;
    ``structure`` that of ``microslip modal --mesh ... --solver all --json`` on the case's
    mesh (None without a [mesh] file and density).
    """
    s = data.settings
    keys = ("peak_displacement_mm", "dissipated_energy_Nmm", "strain_energy_Nmm",
            "loss_factor")
    return {
        "case_name": data.case.name,
        "model": data.model,
        "units": {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm",
                  "stick_slope": "N/mm^3"},
        "inputs": {k: v for k, v in data.case.values.items()},
        "settings": {"increments": s.increments, "fe_solver": s.fe_solver, "mesh": s.mesh,
                     "substeps": s.substeps, "fe_points": s.fe_points,
                     "planar_increments": s.planar_increments},
        "amplitude_N": data.amplitude,
        "macroslip_force_N": data.macroslip,
        "clamp_portion": MODEL_PORTION[data.model],
        "one_d": loop_json(data.one_d),
        "fe": None if data.fe is None else fe_json(data.fe),
        "one_d_over_fe_minus_1_percent": (
            None if data.fe is None else
            {k: row[3] for k, row in zip(keys, comparison(data), strict=True)}),
        "validity": {"rigid_foundation": _validity_json(data.validity_rigid),
                     "shear_layer": {"stick_slope_N_per_mm3": data.stick_slope,
                                     **_validity_json(data.validity_layer)}},
        "loops": [_loop_point(r) for r in data.loops],
        "curve": {"amplitude_N": data.curve_amplitude,
                  "loss_factor": data.curve_loss_factor,
                  "dissipated_energy_Nmm": data.curve_dissipated},
        "fe_curve": [{"amplitude_N": a, "loss_factor": e, "dissipated_energy_Nmm": w,
                      "converged": bool(c)} for a, e, w, c in data.fe_curve],
        "planar": None if data.planar_run is None else planar_json(data.planar_run),
        "planar_error": data.planar_error,
        "structure": data.structure,
    }

