"""The ``microslip reproduce`` job: compute, write every table and figure, check the claims,
write ``report.md``. Each step is a small function that returns what it made (named results
and columns), and :func:`reproduce` passes them on; nothing is read back from disk.

Units: N, mm, N·mm.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..conventions import DEFAULT_MESH
from ..energy import STRAIN_ENERGY
from ..errors import MicroslipError, ParameterError
from ..io import atomic_write, write_csv
from ..models import check_increments
from ..named import short_repr
from ..options import ModelOptions
from ..params import preset
from ..planar import (
    LEVEL_SCHEMES,
    PAPER_RATIOS,
    PAPER_STRAIN_ENERGY,
    WORK_STRAIN_ENERGY,
    RatioSweep,
    loss_factor_vs_ratio,
)
from ..plot.paper import figure_coupling, figure_loops, figure_loss_factor, figure_trajectories
from ..progress import progress, progress_bar
from .claims import Claim, check_claims
from .readings import Reading, compute_readings, readings_table
from .report import Settings, report_markdown
from .tables import component_table, coupling_table, equal_level_table, loss_factor_table

__all__ = ["FE_MESHES", "FEOutcome", "ReproduceResult", "reproduce"]

#: Meshes the finite-element validation accepts (passed through to ``run_validation``).
FE_MESHES = ("coarse", "medium", "paper")

Echo = Callable[[str], None]


@dataclass(frozen=True, eq=False, repr=False)
class ReproduceResult:
    """What :func:`reproduce` computed and wrote.

    Attributes
    ----------
    out_dir : Path
    files : tuple of Path
        Every file written, in order.
    sweep : RatioSweep
        The paper's seven R in the reading in force, zero phase (Figs 10-12).
    phase90 : RatioSweep
        The same with the work-based cycle at 90 degrees phase (the ellipses of Fig. 1).
    readings : tuple of Reading
        The same sweep under other readings (``loss_factor_vs_R_readings.csv``).
    components : dict
        Columns of ``stiffness_vs_amplitude.csv``.
    table : dict
        Columns of ``loss_factor_vs_R.csv``.
    equal_levels : dict
        Columns of ``loss_factor_R1_levels.csv`` (R = 1 at each equal pair of levels).
    claims : tuple of Claim
    fe_status : str
        ``done``, ``skipped`` or ``failed``.
    fe_message : str
        Why, in one line.
    fe_report : object or None
        The ``ValidationReport`` when the FE validation ran.
    elapsed_s : float
        Wall time, s.
    coupling : dict or None
        Columns of ``coupling_ratio_vs_R.csv`` (coupled 2-D friction, built-in FE solver), when
        the finite-element part ran.
    table2_fe : dict or None
        Columns of ``table2_fe_vs_1d.csv`` (the Table 2 zones in the built-in FE solver beside
        the 1-D models), when the finite-element part ran.
    joint_fe : dict or None
        Columns of ``joint2d_vs_fe.csv`` (the bar reduced to a two-directional joint against
        the built-in FE), when the finite-element part ran.
    """

    out_dir: Path
    files: tuple[Path, ...]
    sweep: RatioSweep
    phase90: RatioSweep
    readings: tuple[Reading, ...]
    components: dict[str, Any]
    table: dict[str, Any]
    equal_levels: dict[str, Any]
    claims: tuple[Claim, ...]
    fe_status: str
    fe_message: str
    fe_report: Any
    elapsed_s: float
    coupling: dict[str, Any] | None = None
    table2_fe: dict[str, Any] | None = None
    joint_fe: dict[str, Any] | None = None

    __repr__ = short_repr


def _fe_module() -> tuple[Any, str]:
    """(run_validation, "") when the FE validation can run, else (None, reason)."""
    from ..fe import ccx_available
    from ..validate import run_validation

    if not ccx_available():
        return None, ("CalculiX (ccx) is not available; install it with scripts/setup.sh to "
                      "get Fig. 9")
    return run_validation, ""



@dataclass(frozen=True, eq=False, repr=False)
class FEOutcome:
    """How the finite-element validation went.

    Attributes
    ----------
    status : str
        ``done``, ``skipped`` or ``failed``.
    message : str
        Why, in one line.
    report : object or None
        The ``ValidationReport`` when it ran.
    files : tuple of Path
        The files it wrote.
    """

    status: str
    message: str
    report: Any = None
    files: tuple[Path, ...] = ()

    __repr__ = short_repr

    def columns(self) -> dict[str, list[Any]] | None:
        """The validation's rows as columns (those of ``validation.csv``), when it ran."""
        rows = getattr(self.report, "rows", ()) if self.status == "done" else ()
        if not rows:
            return None
        return {k: [row[k] for row in rows] for k in rows[0]}


def reproduce(out_dir: str | os.PathLike[str], *, increments: int = 1000,
              options: ModelOptions | None = None,
              strain_energy: str = PAPER_STRAIN_ENERGY, levels: str = "base",
              work_energy: str = "sum", fe: bool | None = None, fe_mesh: str = DEFAULT_MESH,
              progress: bool = True, echo: Echo | None = None) -> ReproduceResult:
    """Regenerate the paper's figures and tables into ``out_dir`` and check its claims.

    Parameters
    ----------
    out_dir : path
        Output directory (created).
    increments : int
        Force increments of each first loading.
    options : ModelOptions, optional
        Reading of both models. Default ``ModelOptions(centre="paper")``: the library's
        default corrections, and the centre model read with Eq. 11's printed factor 4, the
        only reading in which the paper's top centre level (16000 N = mu F_N) is below
        macroslip.
    strain_energy : str
        Definition of U (default ``branch``, the paper's Eq. 22); ``secant`` is reported
        beside it.
    levels : str
        How R maps onto the paper's amplitude levels (:data:`LEVEL_SCHEMES`).
    work_energy : str
        Combination of the component strain energies in the work-based result.
    fe : bool or None
        Run the finite-element validation (Fig. 9); None: when CalculiX is available.
    fe_mesh : str
        Mesh of the validation, one of :data:`FE_MESHES`.
    progress : bool
        Show progress bars on standard error.
    echo : callable, optional
        Receives one-line status messages (e.g. why the FE part was skipped).

    Returns
    -------
    ReproduceResult
    """
    t0 = time.perf_counter()
    s = _settings(increments, options, strain_energy, levels, work_energy, fe_mesh)
    say = echo or (lambda msg: None)
    out = _output_dir(out_dir)
    with progress_bar(9, "reproduce", enabled=progress) as steps:
        sweep, phase90 = _ratio_sweeps(s, progress)
        steps.update(1)
        readings = compute_readings(s.tip_params, s.centre_params, s.options, s.levels,
                                    s.increments, s.strain_energy, s.work_energy)
        r1 = equal_level_table(s.tip_params, s.centre_params, s.increments, s.options,
                               s.strain_energy, s.work_energy)
        steps.update(1)
        table = loss_factor_table(sweep, phase90)
        components = component_table(s.tip_params, s.centre_params, s.increments, s.options,
                                     s.strain_energy)
        files = _write_tables(out, table, components, readings_table(readings), r1)
        steps.update(1)
        files += _write_figures(out, s, sweep, table, say, steps)
        fe_run = _run_fe(out, fe, fe_mesh, progress, say)
        files += fe_run.files
        steps.update(1)
        coupling, coupling_files = _run_coupling(out, fe, table, say)
        files += coupling_files
        table2, table2_files = _run_table2_fe(out, fe, say)
        files += table2_files
        joint, joint_files = _run_joint_fe(out, fe, say)
        files += joint_files
        steps.update(1)
    res = ReproduceResult(
        out_dir=out, files=(*files, out / "report.md"), sweep=sweep, phase90=phase90,
        readings=readings, components=components, table=table, equal_levels=r1,
        claims=check_claims(components, table, fe_run.columns()), fe_status=fe_run.status,
        fe_message=fe_run.message, fe_report=fe_run.report,
        elapsed_s=time.perf_counter() - t0, coupling=coupling, table2_fe=table2,
        joint_fe=joint)
    with atomic_write(out / "report.md") as fh:
        fh.write(report_markdown(res, s))
    return res


def _settings(increments: int, options: ModelOptions | None, strain_energy: str, levels: str,
              work_energy: str, fe_mesh: str) -> Settings:
    """The checked arguments of :func:`reproduce` (one-line errors naming the bad value)."""
    n = check_increments(increments)
    for value, allowed, what in ((strain_energy, STRAIN_ENERGY, "strain-energy definition"),
                                 (levels, LEVEL_SCHEMES, "level scheme"),
                                 (work_energy, WORK_STRAIN_ENERGY,
                                  "work strain-energy combination"),
                                 (fe_mesh, FE_MESHES, "FE mesh")):
        if value not in allowed:
            raise ParameterError(f"unknown {what} {value!r}; choose one of "
                                 f"{', '.join(allowed)}")
    return Settings(preset("table2-tip"), preset("table2-centre"), n,
                    options if options is not None else ModelOptions(centre="paper"),
                    strain_energy, levels, work_energy)


def _output_dir(out_dir: str | os.PathLike[str]) -> Path:
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ParameterError(f"--out must be a directory, got the file {str(out)!r}")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise MicroslipError(f"cannot create the output directory {str(out)!r}: "
                             f"{exc.strerror}") from None
    return out


def _ratio_sweeps(s: Settings, show: bool) -> tuple[RatioSweep, RatioSweep]:
    """The paper's seven R at zero phase (Figs 10-12) and with the work cycle at 90 degrees."""
    def bar(items: Any, desc: str, total: int | None = None) -> Any:
        return progress(items, desc, total=total, enabled=show)

    common: dict[str, Any] = {
        "tip_params": s.tip_params, "centre_params": s.centre_params,
        "increments": s.increments, "options": s.options, "strain_energy": s.strain_energy,
        "work_energy": s.work_energy, "levels": s.levels, "progress": bar}
    return (loss_factor_vs_ratio(PAPER_RATIOS, **common),
            loss_factor_vs_ratio(PAPER_RATIOS, phase_deg=90.0, **common))


def _write_tables(out: Path, table: dict[str, Any], components: dict[str, Any],
                  readings: dict[str, Any], r1: dict[str, Any]) -> tuple[Path, ...]:
    files = (("loss_factor_vs_R.csv", table), ("stiffness_vs_amplitude.csv", components),
             ("loss_factor_vs_R_readings.csv", readings), ("loss_factor_R1_levels.csv", r1))
    for name, cols in files:
        write_csv(out / name, cols)
    return tuple(out / name for name, _ in files)


def _write_figures(out: Path, s: Settings, sweep: RatioSweep, table: dict[str, Any],
                   say: Echo, steps: Any) -> tuple[Path, ...]:
    """Figs 1, 10, 11 and 12, each PNG with the CSV of what it shows (Fig. 12's is
    ``loss_factor_vs_R.csv``)."""
    files = [out / "fig01_trajectories.png", out / "fig01_trajectories.csv"]
    write_csv(files[1], figure_trajectories(files[0], PAPER_RATIOS, s.levels))
    steps.update(1)
    for name, ratios in (("fig10_loops_R_ge_1", (1.0, 2.0, 3.0, 4.0)),
                         ("fig11_loops_R_le_1", (1.0, 0.5, 1.0 / 3.0, 0.25))):
        files += _loop_figure(out, name, sweep, ratios, say)
        steps.update(1)
    figure_loss_factor(out / "fig12_loss_factor_vs_R.png", table, s.strain_energy)
    files.append(out / "fig12_loss_factor_vs_R.png")
    steps.update(1)
    return tuple(files)


def _loop_figure(out: Path, name: str, sweep: RatioSweep, ratios: Sequence[float],
                 say: Echo) -> list[Path]:
    res = [c.result for c in sweep.cases
           if c.result is not None and any(math.isclose(c.ratio, x) for x in ratios)]
    if not res:
        say(f"{name}: no case computable in this reading; figure skipped")
        return []
    write_csv(out / f"{name}.csv", figure_loops(out / f"{name}.png", res, ""))
    return [out / f"{name}.png", out / f"{name}.csv"]


def _run_fe(out: Path, fe: bool | None, fe_mesh: str, show: bool, say: Echo) -> FEOutcome:
    """The CalculiX validation (Figs 8-9, validation.csv), unless not asked for or not there."""
    if fe is False:
        say("finite elements: skipped (--no-fe); Fig. 9 not produced")
        return FEOutcome("skipped", "not asked for (--no-fe)")
    run, why = _fe_module()
    if run is None:
        say(f"finite elements: skipped, {why}; Fig. 9 not produced")
        return FEOutcome("skipped", why)
    try:
        rep = run(out, meshes=(fe_mesh,), models=("tip", "centre"), progress=show)
    except MicroslipError as exc:
        msg = " ".join(str(exc).split())
        say(f"finite elements: failed, {msg}")
        return FEOutcome("failed", msg)
    return FEOutcome("done", f"{fe_mesh} mesh", rep,
                     tuple(Path(f) for f in getattr(rep, "files", ())))


def _run_coupling(out: Path, fe: bool | None, table: dict[str, Any], say: Echo
                  ) -> tuple[dict[str, Any] | None, tuple[Path, ...]]:
    """Coupled 2-D friction with the built-in FE solver: its columns and files."""
    if fe is False:
        return None, ()
    from ..fe.builtin import coupling_sweep

    try:
        sweep = coupling_sweep(preset("table1"), sorted(PAPER_RATIOS), (0.0, 90.0))
    except MicroslipError as exc:
        say(f"coupled friction: failed, {' '.join(str(exc).split())}")
        return None, ()
    cols = coupling_table(sweep)
    write_csv(out / "coupling_ratio_vs_R.csv", cols)
    figure_coupling(out / "fig12b_coupling_ratio_vs_R.png", table, cols)
    return cols, (out / "coupling_ratio_vs_R.csv", out / "fig12b_coupling_ratio_vs_R.png")


def _run_table2_fe(out: Path, fe: bool | None, say: Echo
                   ) -> tuple[dict[str, Any] | None, tuple[Path, ...]]:
    """The Table 2 zones in the built-in FE solver beside the 1-D models (table2_fe.py)."""
    if fe is False:
        return None, ()
    from .table2_fe import table2_fe_table

    cols = table2_fe_table(say=say)
    if not cols["model"]:
        return None, ()
    write_csv(out / "table2_fe_vs_1d.csv", cols)
    return cols, (out / "table2_fe_vs_1d.csv",)


def _run_joint_fe(out: Path, fe: bool | None, say: Echo
                  ) -> tuple[dict[str, Any] | None, tuple[Path, ...]]:
    """The bar reduced to a two-directional joint against the built-in FE (joint_fe.py)."""
    if fe is False:
        return None, ()
    from .joint_fe import joint_fe_figure, joint_fe_study

    cols, runs = joint_fe_study(say=say)
    if not runs:
        return None, ()
    write_csv(out / "joint2d_vs_fe.csv", cols)
    joint_fe_figure(out / "fig13_joint2d_vs_fe.png", cols, runs)
    return cols, (out / "joint2d_vs_fe.csv", out / "fig13_joint2d_vs_fe.png")
