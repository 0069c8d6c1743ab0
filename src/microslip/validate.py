"""Finite-element validation of the analytical models (paper, Section 4, Figs 8 and 9).

:func:`run_validation` runs the tip and centre load cases of Table 1 in CalculiX on one or
more mesh levels, compares each FE loop with the analytical model (default reading and
uncorrected) and with the exact closed forms, and writes

- ``fig08_contact_status.png``: stick and slip zones of the lower face at the end of each
  90 degrees of the cycle (the paper's Fig. 8);
- ``fig09_fe_vs_model.png``: FE loops against the analytical loops (the paper's Fig. 9);
- ``validation.csv``: per case and mesh, peak displacement, W_d and loss factor from FE, from
  the model and from the closed form, with relative errors and a verdict.

Acceptance (issue 4): tip, peak displacement within 1 % and W_d within 2 % of
d0 = F0^2/(2 E A q), W_d = 2 F0^3/(3 E A q); centre, 2 % and 3 % of F0^2/(8 E A q) and
F0^3/(6 E A q); and the loop closes, |delta(1.25 s) - delta(0.25 s)| <= 1e-3 delta(0.25 s).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from . import closedform as cf
from .conventions import DEFAULT_MESH
from .energy import DEFAULT_STRAIN_ENERGY, damping, loop_work
from .errors import ParameterError
from .fe.calculix.case import FECase
from .fe.calculix.collect import CalculixDetails
from .fe.calculix.mesh import MeshSpec, mesh_spec
from .fe.constants import DEFAULT_STICK_SLOPE
from .fe.result import FELoopResult
from .fe.run import run_loop
from .io import write_csv
from .loading import LOAD_CASES, load_case
from .options import ModelOptions
from .params import PRESETS, ClampParams, preset
from .plot.validation import LoopPanel, StatusPanel, figure_contact_status, figure_fe_vs_model
from .progress import progress as progress_bar

__all__ = [
    "CLOSURE_TOLERANCE",
    "TOLERANCES",
    "ValidationReport",
    "closed_form",
    "plot_contact_status",
    "plot_fe_vs_model",
    "run_validation",
    "shear_layer_reference",
    "validation_row",
]

#: Acceptance tolerances against the closed form (relative): peak displacement and W_d.
TOLERANCES: dict[str, dict[str, float]] = {
    "tip": {"peak": 0.01, "wd": 0.02},
    "centre": {"peak": 0.02, "wd": 0.03},
}
#: Loop closure tolerance, |delta(1.25 s) - delta(0.25 s)| / delta(0.25 s).
CLOSURE_TOLERANCE = 1e-3
#: Force increments of the analytical backbones compared with FE.
MODEL_INCREMENTS = 1000

FIG08 = "fig08_contact_status.png"
FIG09 = "fig09_fe_vs_model.png"
CSV = "validation.csv"


@dataclass(frozen=True)
class ValidationReport:
    """What :func:`run_validation` produced.

    Attributes
    ----------
    out_dir : Path
    files : tuple of Path
        The files written (figures and CSV).
    rows : tuple of dict
        The rows of ``validation.csv`` (column name -> value; names carry units).
    summary_markdown : str
        A short markdown section: the table and the verdicts.
    results : tuple of FELoopResult
        The FE runs, in row order.
    passed : bool
        Every row within its tolerances and every loop closed.
    """

    out_dir: Path
    files: tuple[Path, ...]
    rows: tuple[dict[str, Any], ...]
    summary_markdown: str
    results: tuple[FELoopResult, ...] = field(default=(), repr=False)
    passed: bool = False


def closed_form(model: str, params: ClampParams, amplitude: float) -> dict[str, float]:
    """Exact rigid-foundation results (shared/REFERENCES.md) of one load case.

    Returns peak displacement (mm), W_d (N·mm), the secant loss factor 4/(3 pi), the slip
    length at the peak (mm, per domain) and the virgin-curve constant c of d = F^2 / c (N/mm).

    >>> p = preset("table1")
    >>> r = closed_form("centre", p, 267.0)
    >>> round(r["wd_Nmm"] / (267.0**3 / (6 * p.axial_stiffness * p.friction_per_length)), 12)
    1.0
    """
    ea, q = params.axial_stiffness, params.friction_per_length
    lc = load_case(model)
    return {"peak_mm": float(lc.displacement(amplitude, ea, q)),
            "wd_Nmm": lc.dissipated_energy(amplitude, ea, q),
            "eta": 4.0 / (3.0 * math.pi), "slip_length_mm": lc.slip_length(amplitude, q),
            "c": lc.virgin_constant(ea, q)}


def shear_layer_reference(model: str, params: ClampParams, amplitude: float,
                          stick_slope: float, samples: int = 4001) -> dict[str, float]:
    """Peak displacement and W_d of the bar on an elastic shear layer (Menq, Bielak & Griffin
    1986) of stiffness k = lambda w per unit length: what a penalty-friction FE model with
    stick slope lambda tends to as the mesh is refined (docs/validation.md, Section 4).

    Tip: one bar of length L loaded by F0; centre: each half, of length L/2, loaded by F0/2
    (the loaded section moves as the tip of either half; the two halves' W_d add). W_d by
    Masing's rule from the virgin curve: linear up to first slip, then
    :func:`microslip.closedform.shear_layer_tip`.

    >>> p = preset("table1")
    >>> r = shear_layer_reference("tip", p, 267.0, 1e12)
    >>> round(r["peak_mm"] / closed_form("tip", p, 267.0)["peak_mm"], 6)
    1.0
    """
    from scipy.optimize import brentq

    ea, q = params.axial_stiffness, params.friction_per_length
    k = stick_slope * params.width
    halves = float(load_case(model).halves)
    length, force = params.length / halves, amplitude / halves

    def residual(a: float) -> float:
        return float(cf.shear_layer_tip(a, ea, k, q, length)[0]) - force

    first_slip = float(cf.shear_layer_tip(0.0, ea, k, q, length)[0])
    a = 0.0 if force <= first_slip else brentq(residual, 0.0, length, xtol=1e-12)
    aa = np.linspace(0.0, a, samples)
    f, d = cf.shear_layer_tip(aa, ea, k, q, length)
    f = np.concatenate([[0.0], np.atleast_1d(f)])
    d = np.concatenate([[0.0], np.atleast_1d(d)])
    if force <= first_slip:  # still fully stuck: linear
        f, d = np.array([0.0, force]), np.array([0.0, force * d[1] / f[1]])
    d0 = float(d[-1])
    wd = halves * (4.0 * force * d0 - 8.0 * float(np.trapezoid(d, f)))
    return {"peak_mm": d0, "wd_Nmm": wd}


def _closed_form_sampled_wd(result: FELoopResult, c: float) -> float:
    """W_d of the exact Masing loop sampled at the FE's force samples (trapezoidal rule):
    separates the bias of 40 samples per cycle from the FE error."""
    f = result.loop.force
    f0 = _case(result).amplitude
    t = np.asarray(result.loop.meta["time_s"])
    g = lambda x: x * x / c  # noqa: E731 - the virgin curve d = F^2 / c
    d0 = g(f0)
    descending = (t >= 0.25 - 1e-12) & (t <= 0.75 + 1e-12)
    d = np.where(descending, d0 - 2.0 * g((f0 - f) / 2.0), -d0 + 2.0 * g((f0 + f) / 2.0))
    return loop_work(f, d)



def _case(result: FELoopResult) -> FECase:
    """The CalculiX load case of a validation run."""
    if not isinstance(result.details, CalculixDetails):
        raise ParameterError(f"the validation compares CalculiX runs, got a {result.solver} run")
    return result.details.case


def _rel(a: float, b: float) -> float:
    return (a - b) / b


def validation_row(result: FELoopResult, mesh: str, options: ModelOptions | None = None) -> dict[
        str, Any]:
    """One row of ``validation.csv``: FE, analytical model and closed form of one run.

    Errors are relative: ``err_X_fe_closed`` = (FE - closed form) / closed form,
    ``err_X_model_fe`` = (model - FE) / FE. Loss factors use the secant strain energy
    (``microslip.energy``), for which the closed form is 4/(3 pi) for both load cases.
    ``wd_closed_sampled_Nmm`` is the exact loop's area by the FE's own 41 samples;
    ``*_shear_layer_*`` the bar on an elastic shear layer with the run's stick slope
    (:func:`shear_layer_reference`), what the penalty FE tends to under mesh refinement.
    """
    case = _case(result)
    p, f0 = case.params, case.amplitude
    kind = result.damping.strain_energy_kind
    model = damping(case.model, p, f0, MODEL_INCREMENTS, options or ModelOptions(), kind)
    unc = damping(case.model, p, f0, MODEL_INCREMENTS, ModelOptions.uncorrected(), kind)
    exact = closed_form(case.model, p, f0)
    layer = shear_layer_reference(case.model, p, f0, case.stick_slope)
    fe = result.damping
    tol = TOLERANCES[case.model]
    err_peak = _rel(fe.peak_displacement, exact["peak_mm"])
    err_wd = _rel(fe.dissipated_energy, exact["wd_Nmm"])
    passed = (abs(err_peak) <= tol["peak"] and abs(err_wd) <= tol["wd"]
              and abs(result.closure) <= CLOSURE_TOLERANCE and result.converged)
    slip = result.slip_lengths()
    return {
        "case": case.model,
        "mesh": mesh,
        "elements": case.spec.label(),
        "dof": result.dof,
        "stick_slope_N_per_mm3": case.stick_slope,
        "substeps": case.substeps,
        "iterations": result.total_iterations,
        "wall_s": result.wall_s,
        "converged": result.converged,
        "amplitude_N": f0,
        "peak_fe_mm": fe.peak_displacement,
        "peak_model_mm": model.peak_displacement,
        "peak_uncorrected_mm": unc.peak_displacement,
        "peak_closed_mm": exact["peak_mm"],
        "wd_fe_Nmm": fe.dissipated_energy,
        "wd_model_Nmm": model.dissipated_energy,
        "wd_uncorrected_Nmm": unc.dissipated_energy,
        "wd_closed_Nmm": exact["wd_Nmm"],
        "wd_closed_sampled_Nmm": _closed_form_sampled_wd(result, exact["c"]),
        "peak_shear_layer_mm": layer["peak_mm"],
        "wd_shear_layer_Nmm": layer["wd_Nmm"],
        "eta_fe": fe.loss_factor,
        "eta_model": model.loss_factor,
        "eta_uncorrected": unc.loss_factor,
        "eta_closed": exact["eta"],
        "strain_energy_definition": kind,
        "err_peak_fe_closed": err_peak,
        "err_wd_fe_closed": err_wd,
        "err_eta_fe_closed": _rel(fe.loss_factor, exact["eta"]),
        "err_peak_model_fe": _rel(model.peak_displacement, fe.peak_displacement),
        "err_wd_model_fe": _rel(model.dissipated_energy, fe.dissipated_energy),
        "err_eta_model_fe": _rel(model.loss_factor, fe.loss_factor),
        "err_peak_uncorrected_fe": _rel(unc.peak_displacement, fe.peak_displacement),
        "err_wd_uncorrected_fe": _rel(unc.dissipated_energy, fe.dissipated_energy),
        "err_eta_uncorrected_fe": _rel(unc.loss_factor, fe.loss_factor),
        "loop_closure": result.closure,
        "loop_offset_mm": result.offset,
        "slip_length_fe_mm": next(iter(slip.values())),
        "slip_length_closed_mm": exact["slip_length_mm"],
        "tolerance_peak": tol["peak"],
        "tolerance_wd": tol["wd"],
        "verdict": "pass" if passed else "FAIL",
    }


# -- figures ---------------------------------------------------------------------------------
def _status_grid(result: FELoopResult, k: int) -> tuple[Any, Any, Any]:
    """Status on the lower face's lattice, with x and y cell edges (mm).

    Face-centre lattice points (not nodes of the 8-node faces) take the status of their two
    neighbours along x when these agree, else stick.
    """
    spec = _case(result).spec
    p = _case(result).params
    grid = np.full((2 * spec.nx + 1, 2 * spec.ny + 1), -1, dtype=np.int64)
    xs = np.linspace(0.0, p.length, 2 * spec.nx + 1)
    ys = np.linspace(0.0, p.width, 2 * spec.ny + 1)
    c = result.contact
    i = np.rint(c.coords[:, 0] / (p.length / (2 * spec.nx))).astype(np.int64)
    j = np.rint(c.coords[:, 1] / (p.width / (2 * spec.ny))).astype(np.int64)
    grid[i, j] = c.status[k]
    for a in range(1, grid.shape[0], 2):
        for b in range(1, grid.shape[1], 2):
            left, right = grid[a - 1, b], grid[a + 1, b]
            grid[a, b] = left if left == right else 1
    def edges(v: Any) -> Any:
        mid = 0.5 * (v[1:] + v[:-1])
        return np.concatenate([[v[0]], mid, [v[-1]]])
    return edges(xs), edges(ys), grid


def _slipping_force(t: float, force: float, amplitude: float) -> float:
    """Force change that sets the zone slipping at time t of F0 sin(2 pi t): |F| on first
    loading (t <= 0.25 s), else |F - F_r| / 2 from the last reversal F_r = +-F0 (Masing)."""
    if t <= 0.25 + 1e-9:
        return abs(force)
    reversal = amplitude if t <= 0.75 + 1e-9 else -amplitude
    return abs(force - reversal) / 2.0


def _status_panel(result: FELoopResult, t: float) -> StatusPanel:
    """The lower face's status at time ``t`` of ``result``, with the closed-form bounds of the
    zone slipping in that substep: the tip zone reaches a distance dF/q from the loaded end,
    the centre zones dF/(2q) each side of L/2, with dF = |F| on first loading and
    |F - F_r|/2 after a reversal at F_r (Masing)."""
    p = _case(result).params
    f0 = _case(result).amplitude
    k = result.contact.index(t)
    xe, ye, grid = _status_grid(result, k)
    f = float(result.force[k])
    f = 0.0 if abs(f) < 1e-9 * f0 else f
    lc = load_case(result.load_case)
    x_load, reach = lc.section * p.length, lc.slip_length(_slipping_force(t, f, f0),
                                                          p.friction_per_length)
    bounds = tuple(x for x, inside in ((x_load - reach, lc.section > 0.0),
                                       (x_load + reach, lc.section < 1.0)) if inside)
    return StatusPanel(result.load_case, t, f, xe, ye, grid, p.length, p.width,
                       x_load if 0.0 < lc.section < 1.0 else None, bounds)


def plot_contact_status(results: Sequence[FELoopResult], path: str | os.PathLike[str],
                        times: Sequence[float] = (0.25, 0.5, 0.75, 1.0, 1.25)) -> None:
    """Fig. 8: stick and slip zones of the lower face at the end of each 90 degrees, one
    column per load case, with the closed-form slip zones (:func:`_status_panel`); drawn by
    :func:`microslip.plot.validation.figure_contact_status`."""
    figure_contact_status([[_status_panel(res, t) for t in times] for res in results], path)


def plot_fe_vs_model(results: Sequence[FELoopResult], labels: Sequence[str],
                     path: str | os.PathLike[str], options: ModelOptions | None = None) -> None:
    """Fig. 9: FE loops against the analytical model (default reading) and the closed form
    (uncorrected model), one panel per load case; drawn by
    :func:`microslip.plot.validation.figure_fe_vs_model`."""
    panels = []
    for m in (m for m in LOAD_CASES if any(r.load_case == m for r in results)):
        runs = [(lab, r.loop) for r, lab in zip(results, labels, strict=True)
                if r.load_case == m]
        ref = _case(next(r for r in results if r.load_case == m))
        model = damping(m, ref.params, ref.amplitude, MODEL_INCREMENTS,
                        options or ModelOptions()).loop
        exact = damping(m, ref.params, ref.amplitude, MODEL_INCREMENTS,
                        ModelOptions.uncorrected()).loop
        panels.append(LoopPanel(m, ref.amplitude, model, exact, tuple(runs)))
    figure_fe_vs_model(panels, path)


# -- running -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Task:
    case: FECase
    mesh: str
    job_dir: Path


def _run_task(case: FECase, job_dir: Path, **options: Any) -> FELoopResult:
    """One CalculiX run of the validation through :func:`microslip.fe.run_loop` (its job files
    and result.json in ``job_dir``; no VTU)."""
    result, _ = run_loop(case.model, case.params, case.amplitude, solver="calculix",
                         out=job_dir, vtu=False, mesh=case.mesh, element=case.element,
                         stick_slope=case.stick_slope, substeps=case.substeps, **options)
    return result


def _run_tasks(tasks: Sequence[_Task], *, scheduler: str | None, show: bool,
               timeout: float | None, threads: int, reuse: bool) -> list[FELoopResult]:
    kwargs: dict[str, Any] = {"timeout": timeout, "threads": threads, "reuse": reuse}
    if scheduler is None:
        return [_run_task(t.case, t.job_dir, **kwargs)
                for t in progress_bar(tasks, "CalculiX runs", total=len(tasks), enabled=show)]
    from functools import partial

    from .cluster import map_on_cluster

    return map_on_cluster(partial(_run_task, **kwargs), [(t.case, t.job_dir) for t in tasks],
                          scheduler, retries=0, key_prefix="microslip-ccx",
                          progress="CalculiX runs" if show else None)


def _summary(rows: Sequence[dict[str, Any]], files: Sequence[Path], bar: str = "Table 1",
             amplitude: float = 267.0) -> str:
    lines = [
        "### Finite-element validation (CalculiX)",
        "",
        f"{bar} bar on a rigid base, Coulomb friction, F_T = {amplitude:g} sin(2 pi t) N in 50 "
        "substeps; "
        "errors relative to the rigid-foundation closed forms (tip: d0 = F0^2/(2EAq), "
        "W_d = 2F0^3/(3EAq); centre: F0^2/(8EAq), F0^3/(6EAq)). Loss factors with the "
        f"{rows[0]['strain_energy_definition'] if rows else DEFAULT_STRAIN_ENERGY} strain energy.",
        "",
        "| case | mesh | DOF | d0 FE (mm) | error | W_d FE (N·mm) | error | η FE | η model "
        "| closure | wall (s) | verdict |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['case']} | {r['mesh']} ({r['elements']}) | {r['dof']} "
            f"| {r['peak_fe_mm']:.5g} | {100 * r['err_peak_fe_closed']:+.2f} % "
            f"| {r['wd_fe_Nmm']:.5g} | {100 * r['err_wd_fe_closed']:+.2f} % "
            f"| {r['eta_fe']:.4f} | {r['eta_model']:.4f} | {r['loop_closure']:.1e} "
            f"| {r['wall_s']:.1f} | {r['verdict']} |")
    lines.append("")
    for m in sorted({r["case"] for r in rows}):
        tol = TOLERANCES[m]
        ok = all(r["verdict"] == "pass" for r in rows if r["case"] == m)
        lines.append(f"- **{m}**: {'pass' if ok else 'FAIL'} (peak within "
                     f"{100 * tol['peak']:g} %, W_d within {100 * tol['wd']:g} % of the closed "
                     f"form, loop closure within {CLOSURE_TOLERANCE:g})")
    lines.append("")
    lines.append("Files: " + ", ".join(f"`{f.name}`" for f in files))
    return "\n".join(lines) + "\n"


def run_validation(out_dir: str | Path, meshes: Sequence[str | MeshSpec] = (DEFAULT_MESH,),
                   models: Sequence[str] = ("tip", "centre"), *, progress: bool = True,
                   timeout: float | None = None, scheduler: str | None = None,
                   stick_slope: float = DEFAULT_STICK_SLOPE, threads: int = 1,
                   reuse: bool = False, preset_name: str = "table1",
                   params: ClampParams | None = None,
                   amplitude: float | None = None) -> ValidationReport:
    """Run the FE validation and write Fig. 8, Fig. 9 and ``validation.csv`` into ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Output directory; the CalculiX job directories go to ``out_dir/jobs/<case>-<mesh>``.
    meshes : sequence of str or MeshSpec
        Mesh levels (:mod:`microslip.meshlevels`) or explicit MeshSpecs.
    models : sequence of str
        Load cases, ``"tip"`` and/or ``"centre"``.
    progress : bool
        Progress bar on standard error (tqdm, if installed).
    timeout : float, optional
        Time-out of each solver run, s (default: per case, see
        :func:`microslip.fe.calculix.runner.default_timeout`).
    scheduler : str, optional
        None: run locally, one case after the other. An address (``tcp://host:8786``): run one
        ccx job per task on that dask.distributed cluster (workers must see ``out_dir`` and
        have ccx); the results are identical to the local ones up to the solver's own
        run-to-run round-off (ccx 2.20 can change the 7th printed digit between two runs of
        the same deck).
    stick_slope : float
        lambda of the friction law, N/mm^3.
    threads : int
        OpenMP threads of each ccx run.
    reuse : bool
        Read the results of a job directory that already holds a successful run of the
        identical deck instead of running it again.
    preset_name : str
        Parameter preset with its amplitude (default Table 1, F0 = 267 N).
    params, amplitude : ClampParams, float, optional
        A clamp of one's own and its load amplitude F0, N, instead of the preset's.

    Returns
    -------
    ValidationReport

    Raises
    ------
    SolverNotFoundError
        ccx is not on PATH (one line that says how to install it).
    SolverError
        A run failed (time-out, killed, not converged, results missing or truncated).
    """
    if not models or any(m not in LOAD_CASES for m in models):
        raise ParameterError(f"models must be among {', '.join(LOAD_CASES)}, got {models!r}")
    if not meshes:
        raise ParameterError("give at least one mesh level")
    if timeout is not None and not (math.isfinite(timeout) and timeout > 0):
        raise ParameterError(f"timeout must be > 0 s, got {timeout!r}")
    params = preset(preset_name) if params is None else params
    amplitude = PRESETS[preset_name][1] if amplitude is None else amplitude
    if amplitude is None:
        raise ParameterError(f"preset {preset_name!r} has no load amplitude")
    out = Path(out_dir)
    specs = [(m if isinstance(m, str) else m.label(), mesh_spec(m, params)) for m in meshes]
    tasks = [
        _Task(FECase(model, params, amplitude, mesh=spec, stick_slope=stick_slope), name,
              out / "jobs" / f"{model}-{name}")
        for model in models for name, spec in specs
    ]
    if scheduler is None and not reuse:
        from .fe.calculix.runner import find_ccx

        find_ccx()  # one clear line before anything is written
    results = _run_tasks(tasks, scheduler=scheduler, show=progress, timeout=timeout,
                         threads=threads, reuse=reuse)
    rows = [validation_row(r, t.mesh) for r, t in zip(results, tasks, strict=True)]

    out.mkdir(parents=True, exist_ok=True)
    columns = {k: [r[k] for r in rows] for k in rows[0]}
    write_csv(out / CSV, columns)
    finest: dict[str, FELoopResult] = {}
    for r in results:
        if r.load_case not in finest or r.dof > finest[r.load_case].dof:
            finest[r.load_case] = r
    plot_contact_status([finest[m] for m in models if m in finest], out / FIG08)
    labels = [f"{t.mesh} ({r.dof} DOF)" for r, t in zip(results, tasks, strict=True)]
    plot_fe_vs_model(results, labels, out / FIG09)
    files = (out / FIG08, out / FIG09, out / CSV)
    return ValidationReport(out_dir=out, files=files, rows=tuple(rows),
                            summary_markdown=_summary(
                                rows, files, "Table 1" if params == preset("table1") else
                                f"{params.length:g} x {params.width:g} x {params.thickness:g} mm",
                                amplitude),
                            results=tuple(results),
                            passed=all(r["verdict"] == "pass" for r in rows))

