"""Reproduce the paper: every figure and table our models can produce, and a check of its claims.

:func:`reproduce` writes into one directory

* ``fig01_trajectories.png`` (Fig. 1), ``fig10_loops_R_ge_1.png`` and ``fig11_loops_R_le_1.png``
  (Figs 10-11), ``fig12_loss_factor_vs_R.png`` (Fig. 12), and, when the finite-element
  validation is available and asked for, its ``fig08_contact_status.png``,
  ``fig09_fe_vs_model.png`` and ``validation.csv``;
* the data behind each figure as CSV (``fig01_trajectories.csv``, ``fig10_loops_R_ge_1.csv``,
  ``fig11_loops_R_le_1.csv``, ``loss_factor_vs_R.csv`` for Fig. 12), the stiffness and damping
  of each model at the paper's levels (``stiffness_vs_amplitude.csv``), the loss factor
  against R under other readings of the paper (``loss_factor_vs_R_readings.csv``) and of the
  circle R = 1 at each equal pair of levels (``loss_factor_R1_levels.csv``);
* ``report.md``: what was computed, the readings in force, the results and a point-by-point
  check of the paper's claims, each verdict computed from the CSV columns by
  :func:`check_claims` (never written by hand).

The figure functions are also used by ``microslip planar --plot``. Units: N, mm, N·mm.
"""

from __future__ import annotations

import dataclasses
import importlib
import importlib.util
import math
import os
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .energy import STRAIN_ENERGY
from .errors import MicroslipError, ParameterError
from .io import atomic_write, write_csv
from .models import check_increments, macroslip_force
from .options import ModelOptions
from .params import preset
from .planar import (
    LEVEL_SCHEMES,
    PAPER_LEVELS,
    PAPER_RATIOS,
    PAPER_STRAIN_ENERGY,
    TIP_LEVEL_FORCE,
    WORK_STRAIN_ENERGY,
    ComponentEnergy,
    PlanarResult,
    RatioSweep,
    eccentricity,
    loss_factor_vs_ratio,
    planar_damping,
    ratio_label,
    trajectory,
    work_damping,
)
from .planar.trajectories import CENTRE_LEVEL_FORCE
from .progress import progress as progress_bar

__all__ = [
    "CENTRE_COLOUR",
    "FE_MESHES",
    "PAPER_COLOUR",
    "RATIO_COLOURS",
    "TIP_COLOUR",
    "WORK_COLOUR",
    "Claim",
    "Reading",
    "ReproduceResult",
    "check_claims",
    "component_table",
    "equal_level_table",
    "figure_loops",
    "figure_loss_factor",
    "figure_planar",
    "figure_trajectories",
    "read_csv",
    "reproduce",
]

#: Meshes the finite-element validation accepts (passed through to ``run_validation``).
FE_MESHES = ("coarse", "medium", "paper")

#: One colour per quantity, the same in Figs 10-12 and in ``microslip planar --plot``
#: (taken from :data:`microslip.plot.COLOURS`, the Okabe-Ito palette).
TIP_COLOUR = "#0072B2"
CENTRE_COLOUR = "#D55E00"
PAPER_COLOUR = "#009E73"
WORK_COLOUR = "#CC79A7"

#: Colour of each of the paper's R in Fig. 1: tip-dominated ellipses in blues, centre-dominated
#: in oranges, the circle black (the families of the tip and centre colours).
RATIO_COLOURS: dict[float, str] = {
    1.0: "#000000",
    2.0: "#6BAED6", 3.0: "#2171B5", 4.0: "#08306B",
    0.5: "#FDAE6B", 1.0 / 3.0: "#E6550D", 0.25: "#7F2704",
}

VERDICTS = ("confirmed", "not confirmed", "cannot be checked")

#: Relative tolerance for "the same R" when reading R back from a CSV.
_R_TOL = 1e-9
#: Samples per cycle of the work-based cycles of the alternative readings (the main table uses
#: the library default, 2048); the trapezoidal error of W is about 2.5e-5 relative, the same
#: for every R to first order.
_READING_SAMPLES = 512
#: Loss factors closer than this (relative) over all R count as equal (round-off).
_TIE = 1e-9


def _ratio_colour(r: float) -> str:
    for key, colour in RATIO_COLOURS.items():
        if math.isclose(key, r, rel_tol=1e-9):
            return colour
    return "0.4"


# =============================================================================================
# Claims
# =============================================================================================
@dataclass(frozen=True)
class Claim:
    """One of the paper's claims, checked against our numbers.

    Attributes
    ----------
    key : str
        Short name (``softening``, ``centre-stiffer``, ``eta-extremes-paper``, ...).
    claim : str
        What the paper says, with its section.
    verdict : str
        ``confirmed``, ``not confirmed`` or ``cannot be checked``.
    evidence : str
        The numbers the verdict rests on, with units.
    reason : str
        Why our implementation gives this verdict.
    source : str
        The CSV file whose columns were used.
    """

    key: str
    claim: str
    verdict: str
    evidence: str
    reason: str
    source: str


def _finite(values: Any) -> np.ndarray:
    return np.asarray(values, dtype=float)


def _rows_at(ratios: np.ndarray, r: float) -> np.ndarray:
    return np.isclose(ratios, r, rtol=_R_TOL, atol=0.0)


def _fmt(x: float, digits: int = 6) -> str:
    return "n/a" if not math.isfinite(x) else f"{x:.{digits}g}"


def _claim_softening(comp: Mapping[str, Any]) -> Claim:
    models = [str(m) for m in comp["model"]]
    amp = _finite(comp["amplitude_N"])
    k = _finite(comp["secant_stiffness_N_per_mm"])
    parts, falls, missing, enough = [], [], [], True
    for name in ("tip", "centre"):
        sel = np.array([m == name for m in models], dtype=bool)
        a, kk = amp[sel], k[sel]
        good = np.isfinite(kk)
        if np.any(~good):
            missing.append(f"{name} at {', '.join(f'{x:g}' for x in a[~good])} N")
        a, kk = a[good], kk[good]
        order = np.argsort(a)
        a, kk = a[order], kk[order]
        enough = enough and kk.size >= 2
        falls.append(bool(np.all(np.diff(kk) < 0.0)))
        parts.append(f"{name}: F_T/δ0 = " + ", ".join(
            f"{_fmt(x)} N/mm at {y:g} N" for x, y in zip(kk, a, strict=True)))
    ok = all(falls)
    verdict = ("cannot be checked" if not enough else "confirmed" if ok else "not confirmed")
    evidence = "; ".join(parts)
    if missing:
        evidence += f" (not computable in this reading: {'; '.join(missing)})"
    reason = ("the slip length grows in proportion to F_T (Eqs 3-4, 11), so the stiffness "
              "2EA/u of the slipping part (Eqs 9, 16) falls as 1/F_T; the secant stiffness "
              "F_T/δ0 of each model's loop " + ("falls" if ok else "does not fall")
              + " monotonically over the paper's amplitudes")
    return Claim("softening", "As F_T increases for each of the models the stiffness decreases "
                 "(softening; Section 5, Figs 10-11).", verdict, evidence, reason,
                 "stiffness_vs_amplitude.csv")


def _claim_centre_stiffer(comp: Mapping[str, Any], table: Mapping[str, Any]) -> Claim:
    r = _finite(table["R"])
    kt = _finite(table["tip_secant_stiffness_N_per_mm"])
    kc = _finite(table["centre_secant_stiffness_N_per_mm"])
    good = np.isfinite(kt) & np.isfinite(kc)
    if not np.any(good):
        return Claim("centre-stiffer", _CENTRE_CLAIM, "cannot be checked",
                     "no case computed", "", "loss_factor_vs_R.csv")
    ratio = kc[good] / kt[good]
    stiffer = bool(np.all(ratio > 1.0))
    i_min = int(np.argmin(ratio))
    at_one = _rows_at(r[good], 1.0)
    parts = []
    if np.any(at_one):
        parts.append(f"at R = 1 (Fig. 10a) the centre loop is {ratio[at_one][0]:.4g} times "
                     f"as stiff as the tip loop")
    parts.append(f"smallest centre/tip secant-stiffness ratio over the computed R: "
                 f"{ratio[i_min]:.6g} at R = {ratio_label(r[good][i_min])}")
    # At equal amplitude level (stiffness_vs_amplitude.csv).
    models = [str(m) for m in comp["model"]]
    lev = _finite(comp["level"])
    ks = _finite(comp["secant_stiffness_N_per_mm"])
    eq = []
    for lv in sorted(set(lev.tolist())):
        t = [ks[i] for i in range(len(models)) if models[i] == "tip" and lev[i] == lv]
        c = [ks[i] for i in range(len(models)) if models[i] == "centre" and lev[i] == lv]
        if t and c and math.isfinite(t[0]) and math.isfinite(c[0]):
            eq.append(c[0] / t[0])
    if eq:
        parts.append(f"at equal level the ratio is {min(eq):.4g} to {max(eq):.4g}")
    verdict = "confirmed" if stiffer else "not confirmed"
    reason = ("on a rigid foundation the centre displacement is F^2/(8EAq) against the tip's "
              "F^2/(2EAq) (two halves in parallel, each with half the force and half the slip "
              "length), and Table 2's centre section is twice the tip's; the secant stiffness "
              "of the centre loop is " + ("above" if stiffer else "not above")
              + " the tip's at every computed R")
    return Claim("centre-stiffer", _CENTRE_CLAIM, verdict, "; ".join(parts), reason,
                 "loss_factor_vs_R.csv, stiffness_vs_amplitude.csv")


_CENTRE_CLAIM = ("The stiffness of the centre model is greater than that of the tip model "
                 "(Section 5, 'obvious from Figure 8a', i.e. the loops of Fig. 10a).")


def eta_extremes(r: np.ndarray, eta: np.ndarray) -> tuple[str, str, str]:
    """Verdict, evidence and ranking for "eta lowest at R = 1, highest at R = 0.25 and 4".

    Returns ``(verdict, evidence, ranking)``; the verdict is ``cannot be checked`` when R = 1,
    0.25 or 4 has no finite loss factor.
    """
    good = np.isfinite(eta)
    needed = [x for x in (1.0, 0.25, 4.0) if not np.any(_rows_at(r[good], x))]
    order = np.argsort(eta[good], kind="stable")
    rg, eg = r[good][order], eta[good][order]
    ranking = " < ".join(ratio_label(x) for x in rg)
    if eg.size:
        spread = (eg[-1] - eg[0]) / eg[0] * 100.0
        evidence = (f"R ordered by rising eta: {ranking}; eta from {eg[0]:.6g} "
                    f"(R = {ratio_label(rg[0])}) to {eg[-1]:.6g} (R = {ratio_label(rg[-1])}), "
                    f"a spread of {spread:.3g} %")
    else:
        evidence = "no case computed"
    missing = [x for x in range(r.size) if not good[x]]
    if missing:
        evidence += "; not computed: R = " + ", ".join(ratio_label(r[i]) for i in missing)
    if needed:
        return "cannot be checked", evidence, ranking
    if eg[-1] - eg[0] <= _TIE * abs(eg[0]):
        return ("not confirmed", f"eta is the same at every R to {_TIE:g} (relative): "
                f"{eg[0]:.9g}", "all equal")
    lowest_is_one = math.isclose(rg[0], 1.0, rel_tol=_R_TOL)
    top_two = {round(float(x), 9) for x in rg[-2:]}
    highest_ok = top_two == {0.25, 4.0}
    verdict = "confirmed" if (lowest_is_one and highest_ok) else "not confirmed"
    return verdict, evidence, ranking


def _claim_eta(table: Mapping[str, Any], comp: Mapping[str, Any], coupling: str) -> Claim:
    r = _finite(table["R"])
    eta = _finite(table[f"{coupling}_loss_factor"])
    verdict, evidence, _ = eta_extremes(r, eta)
    models = [str(m) for m in comp["model"]]
    amp = _finite(comp["amplitude_N"])
    le = _finite(comp["loss_factor"])
    drift = []
    for name in ("tip", "centre"):
        sel = np.array([m == name for m in models]) & np.isfinite(le)
        if np.count_nonzero(sel) >= 2:
            a, e = amp[sel], le[sel]
            lo, hi = int(np.argmin(a)), int(np.argmax(a))
            drift.append(f"{name} {(e[hi] / e[lo] - 1.0) * 100.0:+.3g} % from {a[lo]:g} N to "
                         f"{a[hi]:g} N")
    what = ("the paper's resultant loop (Eqs 19-23)" if coupling == "paper"
            else "the work of the load (W = 2 W_tip + W_centre, U summed over the components)")
    reason = (f"eta of {what}. For quadratic backbones (corrections off) every loop has the "
              "same shape, the resultant is a scaled copy and eta is the same at every R; what "
              "varies here comes only from the Poisson and length corrections, through the "
              "amplitude dependence of each model's own eta (" + "; ".join(drift) + "), so the "
              "order over R follows the amplitudes each R uses")
    return Claim(f"eta-extremes-{coupling}",
                 "The loss factor is lowest at R = 1 and largest at R = 0.25 and R = 4 "
                 "(Section 5, Fig. 12).", verdict, evidence, reason, "loss_factor_vs_R.csv")


def _claim_fe(validation: Mapping[str, Any]) -> Claim:
    claim = ("Both 1-D models agree well with the finite-element results (Section 5, Fig. 9; "
             "Section 6).")
    need = ("case", "mesh", "err_peak_model_fe", "err_wd_model_fe", "tolerance_peak",
            "tolerance_wd")
    if any(k not in validation for k in need) or not validation["case"]:
        return Claim("fe-agreement", claim, "cannot be checked",
                     "validation.csv lacks the model-vs-FE columns", "", "validation.csv")
    parts, ok = [], True
    for i, case in enumerate(validation["case"]):
        ep = float(validation["err_peak_model_fe"][i])
        ew = float(validation["err_wd_model_fe"][i])
        tp_, tw = float(validation["tolerance_peak"][i]), float(validation["tolerance_wd"][i])
        conv = str(validation.get("converged", ["True"] * (i + 1))[i]) in ("True", "1", "1.0")
        within = conv and abs(ep) <= tp_ and abs(ew) <= tw
        ok = ok and within
        parts.append(f"{case} ({validation['mesh'][i]} mesh): model − FE {100 * ep:+.2f} % in "
                     f"peak displacement (tolerance {100 * tp_:g} %), {100 * ew:+.2f} % in W_d "
                     f"(tolerance {100 * tw:g} %)" + ("" if conv else ", FE not converged"))
    return Claim("fe-agreement", claim, "confirmed" if ok else "not confirmed",
                 "; ".join(parts),
                 "the FE model (Table 1 bar, rigid base, Coulomb friction, CalculiX) is what the "
                 "1-D models idealise; agreement is judged against the validation's own "
                 "tolerances, with the models in the reading of the validation",
                 "validation.csv")


def check_claims(components: Mapping[str, Any], table: Mapping[str, Any],
                 validation: Mapping[str, Any] | None = None) -> tuple[Claim, ...]:
    """The paper's qualitative claims, judged from the columns of the two CSV files.

    Parameters
    ----------
    components : mapping
        Columns of ``stiffness_vs_amplitude.csv`` (:func:`component_table`).
    table : mapping
        Columns of ``loss_factor_vs_R.csv`` (:meth:`RatioSweep.columns`).

    validation : mapping, optional
        Columns of ``validation.csv`` when the finite-element validation ran.

    Returns
    -------
    tuple of Claim
        Softening, centre stiffer than tip, the loss-factor extremes for the paper's
        coupling and for the work-based result, and (with ``validation``) the agreement of
        the models with finite elements.
    """
    claims: tuple[Claim, ...] = (
        _claim_softening(components),
        _claim_centre_stiffer(components, table),
        _claim_eta(table, components, "paper"),
        _claim_eta(table, components, "work"),
    )
    if validation is not None:
        claims = (*claims, _claim_fe(validation))
    return claims


def component_table(tip_params: Any, centre_params: Any, increments: int,
                    options: ModelOptions, strain_energy: str,
                    levels: Sequence[int] = PAPER_LEVELS) -> dict[str, Any]:
    """Each model alone at the paper's levels: peak displacement, secant stiffness, damping.

    Columns of ``stiffness_vs_amplitude.csv``; a level the reading cannot compute (at or
    beyond macroslip) has NaN values and its reason in ``note``.
    """
    from .energy import damping

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
                               work_energy=work_energy, samples_per_cycle=_READING_SAMPLES)
        except MicroslipError as exc:
            col["paper_loss_factor"].append(math.nan)
            col["work_loss_factor"].append(math.nan)
            col["note"].append(" ".join(str(exc).split()))
            continue
        col["paper_loss_factor"].append(r.paper.loss_factor)
        col["work_loss_factor"].append(r.work_loss_factor)
        col["note"].append("")
    return col


def read_csv(path: str | os.PathLike[str]) -> dict[str, list[Any]]:
    """Columns of a CSV written by :func:`microslip.io.write_csv`; numbers as float where
    every value of the column parses as one."""
    import csv

    with open(path, encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    names, data = rows[0], rows[1:]
    out: dict[str, list[Any]] = {}
    for j, name in enumerate(names):
        values = [row[j] for row in data]
        try:
            out[name] = [float(v) for v in values]
        except ValueError:
            out[name] = values
    return out


# =============================================================================================
# Figures
# =============================================================================================
def _log_ratio_axis(ax: Any, ratios: Sequence[float], top: bool = True) -> None:
    ax.set_xscale("log")
    rs = sorted(set(float(r) for r in ratios))
    ax.set_xticks(rs)
    ax.set_xticklabels([_frac_label(r) for r in rs])
    ax.minorticks_off()
    ax.set_xlabel("Force ratio $R = F_{T(tip)} / F_{T(centre)}$ (-)")
    if top:
        sec = ax.secondary_xaxis("top")
        sec.set_xticks(rs)
        sec.set_xticklabels([f"{eccentricity(r):.2f}" for r in rs])
        sec.minorticks_off()
        sec.set_xlabel("Eccentricity ε (-)")


def _frac_label(r: float) -> str:
    if r < 1.0 and math.isclose(1.0 / r, round(1.0 / r), rel_tol=1e-9):
        return f"1/{round(1.0 / r)}"
    return ratio_label(r)


def figure_trajectories(path: str | os.PathLike[str], ratios: Sequence[float] = PAPER_RATIOS,
                        levels: str = "base", samples: int = 181) -> dict[str, Any]:
    """Fig. 1: the load paths of each R, as the paper draws them (90 degrees phase, ellipses)
    and as its zero-phase loading traces them (lines). Returns the plotted data as columns."""
    from .plot import new_figure, save_figure

    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=80.0)
    col: dict[str, list[Any]] = {k: [] for k in (
        "R", "eccentricity", "phase_deg", "theta_rad", "normalised_tip_force",
        "normalised_centre_force")}
    for ax, phase, title in ((axes[0, 0], 90.0, "(a) ellipses of Fig. 1 (phase 90°)"),
                             (axes[0, 1], 0.0, "(b) paths of the zero-phase loading")):
        for r in ratios:
            t = trajectory(r, phase_deg=phase, samples=samples, scheme=levels)
            ax.plot(t.tip, t.centre, color=_ratio_colour(r),
                    label=f"R = {ratio_label(r)}, ε = {t.eccentricity:.2f}")
            for name, values in (("R", [r] * samples), ("eccentricity", [t.eccentricity] * samples),
                                 ("phase_deg", [phase] * samples), ("theta_rad", t.theta),
                                 ("normalised_tip_force", t.tip),
                                 ("normalised_centre_force", t.centre)):
                col[name].extend(list(values))
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"Normalised tip force $F_{{tip}}$ / {TIP_LEVEL_FORCE:g} N (-)")
        ax.set_ylabel(f"Normalised centre force $F_{{centre}}$ / {CENTRE_LEVEL_FORCE:g} N (-)")
        ax.set_title(title, loc="left", fontsize=8)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, frameon=False)
    save_figure(fig, path)
    return col


def figure_loops(path: str | os.PathLike[str], results: Sequence[PlanarResult],
                 caption: str = "") -> dict[str, Any]:
    """Figs 10-11: the tip, centre and resultant loops of each R, one panel per R (2 x 2).

    Returns the plotted data as long-format columns (R, curve, point, force, displacement).
    """
    from .plot import new_figure, plot_loops, save_figure

    n = len(results)
    ncols = 2 if n > 1 else 1
    nrows = (n + ncols - 1) // ncols
    fig, axes = new_figure(ncols=ncols, nrows=nrows, width_mm=85.0, height_mm=62.0)
    col: dict[str, list[Any]] = {k: [] for k in (
        "R", "eccentricity", "curve", "amplitude_N", "point", "force_N", "displacement_mm")}
    for i, res in enumerate(results):
        ax = axes[i // ncols, i % ncols]
        loops = [res.tip.loop, res.centre.loop, res.paper.loop]
        labels = ["tip model", "centre model", "resultant (paper's Eqs 19-20)"]
        plot_loops(ax, loops, labels, colours=(TIP_COLOUR, CENTRE_COLOUR, PAPER_COLOUR))
        handles, names = ax.get_legend_handles_labels()
        ax.get_legend().remove()
        ax.set_title(f"({chr(ord('a') + i)}) R = {ratio_label(res.ratio)}, "
                     f"ε = {res.eccentricity:.2f}: tip {res.tip_amplitude:g} N, "
                     f"centre {res.centre_amplitude:g} N", loc="left", fontsize=7)
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 2))
        for name, loop, amp in (("tip", res.tip.loop, res.tip_amplitude),
                                ("centre", res.centre.loop, res.centre_amplitude),
                                ("resultant", res.paper.loop, res.paper.amplitude)):
            m = loop.force.size
            col["R"].extend([res.ratio] * m)
            col["eccentricity"].extend([res.eccentricity] * m)
            col["curve"].extend([name] * m)
            col["amplitude_N"].extend([amp] * m)
            col["point"].extend(range(m))
            col["force_N"].extend(loop.force.tolist())
            col["displacement_mm"].extend(loop.displacement.tolist())
    for j in range(n, nrows * ncols):
        axes[j // ncols, j % ncols].set_visible(False)
    if results:
        fig.legend(handles, names, loc="outside lower center", ncol=3, frameon=False)
    if caption:
        fig.suptitle(caption, fontsize=8)
    save_figure(fig, path)
    return col


def figure_loss_factor(path: str | os.PathLike[str], table: Mapping[str, Any],
                       strain_energy: str = PAPER_STRAIN_ENERGY) -> None:
    """Fig. 12: loss factor against R, the paper's coupling and the work-based result.

    (a) eta of the resultant loop, of the work of the load, and of each model alone;
    (b) eta normalised by its value at R = 1. ``table`` is ``loss_factor_vs_R.csv``'s columns.
    """
    from .plot import new_figure, save_figure

    r = _finite(table["R"])
    order = np.argsort(r)
    r = r[order]

    def col(name: str) -> np.ndarray:
        return _finite(table[name])[order]

    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=72.0)
    ax = axes[0, 0]
    ax.plot(r, col("paper_loss_factor"), "o-", color=PAPER_COLOUR,
            label="paper's coupling (Eqs 19-23)")
    ax.plot(r, col("work_loss_factor"), "s--", color=WORK_COLOUR, mfc="none",
            label="work of the load (this work)")
    ax.plot(r, col("tip_loss_factor"), ":", color=TIP_COLOUR, lw=0.9, label="tip model alone")
    ax.plot(r, col("centre_loss_factor"), ":", color=CENTRE_COLOUR, lw=0.9,
            label="centre model alone")
    from .closedform import LOSS_FACTOR_QUADRATIC

    if strain_energy in LOSS_FACTOR_QUADRATIC:
        ax.axhline(LOSS_FACTOR_QUADRATIC[strain_energy], color="0.5", ls="--", lw=0.8,
                   label="corrections off (any R)")
    ax.set_ylabel(f"Loss factor η ({strain_energy} U) (-)")
    ax.set_title("(a)", loc="left", fontsize=8)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.legend(loc="best", frameon=False)
    _log_ratio_axis(ax, r.tolist())
    ax = axes[0, 1]
    ax.plot(r, col("paper_normalised_loss_factor"), "o-", color=PAPER_COLOUR,
            label="paper's coupling")
    ax.plot(r, col("work_normalised_loss_factor"), "s--", color=WORK_COLOUR, mfc="none",
            label="work of the load")
    ax.axhline(1.0, color="0.5", lw=0.5)
    ax.set_ylabel("Normalised loss factor η / η(R = 1) (-)")
    ax.set_title("(b)", loc="left", fontsize=8)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.legend(loc="best", frameon=False)
    _log_ratio_axis(ax, r.tolist())
    save_figure(fig, path)


def coupling_table(sweep: Any) -> dict[str, list[Any]]:
    """Columns of ``coupling_ratio_vs_R.csv`` from a :class:`microslip.solver.CouplingSweep`."""
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


def figure_coupling(path: str | os.PathLike[str], table: Mapping[str, Any],
                    coupling: Mapping[str, Any]) -> None:
    """Beside Fig. 12: (a) the paper's normalised eta against R; (b) the coupling ratio
    W_coupled / (W_tip + W_centre) of coupled 2-D friction (built-in FE solver) against R."""
    from .plot import new_figure, save_figure

    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=72.0)
    r = _finite(table["R"])
    order = np.argsort(r)
    ax = axes[0, 0]
    ax.plot(r[order], _finite(table["paper_normalised_loss_factor"])[order], "o-",
            color=PAPER_COLOUR, label="paper's coupling (Eqs 19-23)")
    ax.axhline(1.0, color="0.5", lw=0.5)
    ax.set_ylabel("Normalised loss factor η / η(R = 1) (-)")
    ax.set_title("(a) decoupled 1-D models (Fig. 12)", loc="left", fontsize=8)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.legend(loc="best", frameon=False)
    _log_ratio_axis(ax, r.tolist())
    ax = axes[0, 1]
    rc = _finite(coupling["R"])
    phase = _finite(coupling["phase_deg"])
    ratio = _finite(coupling["coupling_ratio"])
    for k, phi in enumerate(sorted(set(phase.tolist()))):
        m = phase == phi
        o = np.argsort(rc[m])
        ax.plot(rc[m][o], ratio[m][o], "o-" if k == 0 else "s--", mfc="none" if k else None,
                color=(TIP_COLOUR, CENTRE_COLOUR, WORK_COLOUR)[k % 3],
                label=f"phase φ = {phi:g}°")
    ax.axhline(1.0, color="0.5", lw=0.8, ls=":", label="paper's decoupling (ratio 1)")
    ax.set_ylabel("Coupling ratio $W_{coupled} / (W_{tip} + W_{centre})$ (-)")
    ax.set_title("(b) coupled 2-D friction, built-in FE", loc="left", fontsize=8)
    ax.legend(loc="best", frameon=False)
    _log_ratio_axis(ax, sorted(set(rc.tolist())))
    save_figure(fig, path)


def figure_planar(result: PlanarResult, path: str | os.PathLike[str]) -> None:
    """One planar case: (a) tip, centre and resultant loops; (b) the load path in the force
    plane (whole-clamp forces), at the work cycle's phase and at the paper's zero phase."""
    from matplotlib.ticker import MaxNLocator

    from .plot import new_figure, plot_loops, save_figure

    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=72.0)
    ax = axes[0, 0]
    plot_loops(ax, [result.tip.loop, result.centre.loop, result.paper.loop],
               [f"tip, {result.tip_amplitude:g} N: η = {result.tip.loss_factor:.4f}",
                f"centre, {result.centre_amplitude:g} N: η = {result.centre.loss_factor:.4f}",
                f"resultant (Eqs 19-20): η = {result.paper.loss_factor:.4f}"],
               colours=(TIP_COLOUR, CENTRE_COLOUR, PAPER_COLOUR))
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False, fontsize=6)
    ax.set_title(f"(a) R = {result.ratio:.4g}, ε = {result.eccentricity:.3f} "
                 f"({result.strain_energy_kind} U)", loc="left", fontsize=8)
    ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 2))
    ax = axes[0, 1]
    p = result.work.response.path
    c = p.cycle
    ax.plot(p.tip_force[c], p.centre_force[c], color=WORK_COLOUR,
            label=f"phase {result.phase_deg:g}°: W = {result.work_dissipated_energy:.4g} N·mm, "
                  f"η = {result.work_loss_factor:.4f}")
    at, ac = p.tip_amplitude, p.centre_amplitude
    ax.plot([-at, at], [-ac, ac], color=PAPER_COLOUR, ls="--", lw=0.9,
            label="zero phase (the paper's loading)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    ax.set_xlabel("Tip force on the clamp $F_{tip}$ (N)")
    ax.set_ylabel("Centre force $F_{centre}$ (N)")
    ax.set_title("(b) load path of the work cycle", loc="left", fontsize=8)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False, fontsize=6)
    save_figure(fig, path)


# =============================================================================================
# The job
# =============================================================================================
@dataclass(frozen=True)
class Reading:
    """The loss factor against R under an alternative reading of the paper."""

    name: str
    description: str
    sweep: RatioSweep


@dataclass(frozen=True)
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


def _fe_module() -> tuple[Any, str]:
    """(run_validation, "") when the FE validation can run, else (None, reason)."""
    if importlib.util.find_spec("microslip.validate") is None:
        return None, "the finite-element validation (microslip.validate) is not in this version"
    try:
        validate = importlib.import_module("microslip.validate")
        fe = importlib.import_module("microslip.fe")
    except ImportError as exc:
        return None, f"the finite-element validation cannot be imported: {exc}"
    ccx_available = getattr(fe, "ccx_available", None)
    if ccx_available is None or not ccx_available():
        return None, ("CalculiX (ccx) is not available; install it with scripts/setup.sh to "
                      "get Fig. 9")
    run = getattr(validate, "run_validation", None)
    if run is None:
        return None, "microslip.validate has no run_validation"
    return run, ""


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


def reproduce(out_dir: str | os.PathLike[str], *, increments: int = 1000,
              options: ModelOptions | None = None,
              strain_energy: str = PAPER_STRAIN_ENERGY, levels: str = "base",
              work_energy: str = "sum", fe: bool | None = None, fe_mesh: str = "coarse",
              progress: bool = True, echo: Callable[[str], None] | None = None
              ) -> ReproduceResult:
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
    n = check_increments(increments)
    opt = options if options is not None else ModelOptions(centre="paper")
    if strain_energy not in STRAIN_ENERGY:
        raise ParameterError(f"unknown strain-energy definition {strain_energy!r}; choose one "
                             f"of {', '.join(STRAIN_ENERGY)}")
    if levels not in LEVEL_SCHEMES:
        raise ParameterError(f"unknown level scheme {levels!r}; choose one of "
                             f"{', '.join(LEVEL_SCHEMES)}")
    if work_energy not in WORK_STRAIN_ENERGY:
        raise ParameterError(f"unknown work strain-energy combination {work_energy!r}; "
                             f"choose one of {', '.join(WORK_STRAIN_ENERGY)}")
    if fe_mesh not in FE_MESHES:
        raise ParameterError(f"unknown FE mesh {fe_mesh!r}; choose one of {', '.join(FE_MESHES)}")
    say = echo or (lambda msg: None)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ParameterError(f"--out must be a directory, got the file {str(out)!r}")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise MicroslipError(f"cannot create the output directory {str(out)!r}: "
                             f"{exc.strerror}") from None
    tp, cp = preset("table2-tip"), preset("table2-centre")
    files: list[Path] = []
    state: dict[str, Any] = {}

    def bar(items: Iterable[Any], desc: str, total: int | None = None) -> Iterable[Any]:
        return progress_bar(items, desc, total=total, enabled=progress)

    common: dict[str, Any] = {"tip_params": tp, "centre_params": cp, "increments": n,
                              "options": opt, "strain_energy": strain_energy,
                              "work_energy": work_energy}

    def compute_sweeps() -> None:
        state["sweep"] = loss_factor_vs_ratio(PAPER_RATIOS, levels=levels, progress=bar,
                                              **common)
        state["phase90"] = loss_factor_vs_ratio(PAPER_RATIOS, levels=levels, phase_deg=90.0,
                                                progress=bar, **common)

    def compute_readings() -> None:
        readings = []
        for name, desc, lev, inc, o in _readings(opt, levels, n):
            s = loss_factor_vs_ratio(PAPER_RATIOS, tip_params=tp, centre_params=cp,
                                     levels=lev, increments=inc, options=o,
                                     strain_energy=strain_energy, work_energy=work_energy,
                                     samples_per_cycle=_READING_SAMPLES)
            readings.append(Reading(name, desc, s))
        state["readings"] = tuple(readings)
        state["r1"] = equal_level_table(tp, cp, n, opt, strain_energy, work_energy)

    def write_tables() -> None:
        sweep: RatioSweep = state["sweep"]
        table = sweep.columns()
        table.update(_phase90_columns(state["phase90"]))
        table["note"] = [c.error for c in sweep.cases]
        state["table"] = table
        comp = component_table(tp, cp, n, opt, strain_energy)
        state["components"] = comp
        write_csv(out / "loss_factor_vs_R.csv", table)
        write_csv(out / "stiffness_vs_amplitude.csv", comp)
        files.extend([out / "loss_factor_vs_R.csv", out / "stiffness_vs_amplitude.csv"])
        rcol: dict[str, list[Any]] = {k: [] for k in (
            "reading", "levels", "increments", "R", "eccentricity", "tip_amplitude_N",
            "centre_amplitude_N", "paper_loss_factor", "paper_normalised_loss_factor",
            "work_loss_factor", "work_normalised_loss_factor", "note")}
        for rd in state["readings"]:
            c = rd.sweep.columns()
            m = len(rd.sweep.cases)
            rcol["reading"].extend([rd.name] * m)
            rcol["levels"].extend([rd.sweep.levels] * m)
            rcol["increments"].extend([rd.sweep.increments] * m)
            for k in ("R", "eccentricity", "tip_amplitude_N", "centre_amplitude_N",
                      "paper_loss_factor", "paper_normalised_loss_factor", "work_loss_factor",
                      "work_normalised_loss_factor"):
                rcol[k].extend(list(c[k]))
            rcol["note"].extend(c2.error for c2 in rd.sweep.cases)
        state["readings_table"] = rcol
        write_csv(out / "loss_factor_vs_R_readings.csv", rcol)
        write_csv(out / "loss_factor_R1_levels.csv", state["r1"])
        files.extend([out / "loss_factor_vs_R_readings.csv", out / "loss_factor_R1_levels.csv"])

    def fig01() -> None:
        col = figure_trajectories(out / "fig01_trajectories.png", PAPER_RATIOS, levels)
        write_csv(out / "fig01_trajectories.csv", col)
        files.extend([out / "fig01_trajectories.png", out / "fig01_trajectories.csv"])

    def fig_loops(name: str, ratios: Sequence[float], caption: str) -> None:
        sweep: RatioSweep = state["sweep"]
        res = [c.result for c in sweep.cases
               if c.result is not None and any(math.isclose(c.ratio, x) for x in ratios)]
        if not res:
            say(f"{name}: no case computable in this reading; figure skipped")
            return
        col = figure_loops(out / f"{name}.png", res, caption)
        write_csv(out / f"{name}.csv", col)
        files.extend([out / f"{name}.png", out / f"{name}.csv"])

    def fig12() -> None:
        figure_loss_factor(out / "fig12_loss_factor_vs_R.png", state["table"], strain_energy)
        files.append(out / "fig12_loss_factor_vs_R.png")

    def run_fe() -> None:
        state["fe"] = ("skipped", "not asked for (--no-fe)", None)
        if fe is False:
            say("finite elements: skipped (--no-fe); Fig. 9 not produced")
            return
        run, why = _fe_module()
        if run is None:
            state["fe"] = ("skipped", why, None)
            say(f"finite elements: skipped, {why}; Fig. 9 not produced")
            return
        try:
            rep = run(out, meshes=(fe_mesh,), models=("tip", "centre"), progress=progress)
        except MicroslipError as exc:
            msg = " ".join(str(exc).split())
            state["fe"] = ("failed", msg, None)
            say(f"finite elements: failed, {msg}")
            return
        files.extend(Path(f) for f in getattr(rep, "files", ()))
        state["fe"] = ("done", f"{fe_mesh} mesh", rep)

    def run_coupling() -> None:
        state["coupling"] = None
        if fe is False:
            return
        from .solver import coupling_sweep

        try:
            sweep = coupling_sweep(preset("table1"), sorted(PAPER_RATIOS), (0.0, 90.0))
        except MicroslipError as exc:
            say(f"coupled friction: failed, {' '.join(str(exc).split())}")
            return
        cols = coupling_table(sweep)
        state["coupling"] = cols
        write_csv(out / "coupling_ratio_vs_R.csv", cols)
        figure_coupling(out / "fig12b_coupling_ratio_vs_R.png", state["table"], cols)
        files.extend([out / "coupling_ratio_vs_R.csv", out / "fig12b_coupling_ratio_vs_R.png"])

    steps: list[tuple[str, Callable[[], None]]] = [
        ("loss factor vs R", compute_sweeps),
        ("other readings", compute_readings),
        ("tables", write_tables),
        ("fig01", fig01),
        ("fig10", lambda: fig_loops("fig10_loops_R_ge_1", (1.0, 2.0, 3.0, 4.0),
                                    "")),
        ("fig11", lambda: fig_loops("fig11_loops_R_le_1", (1.0, 0.5, 1.0 / 3.0, 0.25), "")),
        ("fig12", fig12),
        ("finite elements", run_fe),
        ("coupled 2-D friction", run_coupling),
    ]
    for _, step in bar(steps, "reproduce", total=len(steps)):
        step()
    validation = None
    if state["fe"][0] == "done" and (out / "validation.csv").is_file():
        validation = read_csv(out / "validation.csv")
    claims = check_claims(state["components"], state["table"], validation)
    fe_status, fe_message, fe_report = state["fe"]
    elapsed = time.perf_counter() - t0
    result = ReproduceResult(
        out_dir=out, files=(*files, out / "report.md"), sweep=state["sweep"],
        phase90=state["phase90"], readings=state["readings"],
        components=state["components"], table=state["table"], equal_levels=state["r1"],
        claims=claims,
        fe_status=fe_status, fe_message=fe_message, fe_report=fe_report, elapsed_s=elapsed,
        coupling=state["coupling"])
    with atomic_write(out / "report.md") as fh:
        fh.write(_report(result, opt, levels, strain_energy, work_energy, n,
                         state["readings_table"]))
    return result


# =============================================================================================
# The report
# =============================================================================================
def _md_table(header: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def _options_text(o: ModelOptions) -> str:
    return f"poisson={o.poisson}, length_update={o.length_update}, centre={o.centre}"


def _report(res: ReproduceResult, opt: ModelOptions, levels: str, kind: str,
            work_energy: str, n: int, readings_table: Mapping[str, Any]) -> str:
    t = res.table
    tp, cp = preset("table2-tip"), preset("table2-centre")
    lines: list[str] = []
    add = lines.append
    add("# Reproduction of Lord & Rongong (2016): planar microslip damping\n")
    add("Generated by `microslip reproduce`. Units: force N, displacement mm, energy N·mm; "
        "loss factors are dimensionless. Every verdict below is computed by "
        "`microslip.reproduce.check_claims` from the columns written to the CSV files in this "
        "directory.\n")

    add("## What was computed\n")
    add(f"- The tip model (Eqs 2-10) with Table 2's tip zone (`table2-tip`: L = {tp.length:g} mm, "
        f"w = {tp.width:g} mm, t = {tp.thickness:g} mm, E = {tp.modulus:g} MPa, ν = "
        f"{tp.poisson_ratio:g}, μ = {tp.friction:g}, F_N = {tp.normal_force:g} N) and the centre "
        f"model (Eqs 11-18) with the centre zone (`table2-centre`, t = {cp.thickness:g} mm), "
        f"each run from rest in {n} equal force increments and closed with Masing's rule.")
    add("- For each of the paper's seven force ratios R (Fig. 1) the two loops at the paper's "
        "amplitudes, the paper's resultant loop (Eqs 19-20) and its W_d, U and η (Eqs 21-23): "
        "Figs 10-12.")
    add("- Beside it, the work done by the load on the whole clamp over one cycle, "
        "F_tip = A_t sin θ, F_centre = A_c sin(θ + φ), each model following its own force "
        "history by the extended Masing rules: W = ∮(F_tip dδ_tip + F_centre dδ_centre), "
        "at φ = 0 (the paper's zero phase) and φ = 90° (the ellipses the paper draws).")
    add("- The same loss factors under other readings of the paper (sensitivity), and each "
        "model alone at the paper's four amplitudes.\n")

    add("## Interpretation choices in force\n")
    add("Details and algebra: `docs/planar.md` (planar model) and `docs/interpretation.md` "
        "(1-D models).\n")
    add(f"- Model reading: {_options_text(opt)}. The centre model is read with Eq. 11's "
        f"printed factor 4 (`centre=\"{opt.centre}\"`)"
        + (" because the paper's top centre level, 16000 N, equals μF_N = "
           f"{cp.macroslip_force:g} N, the macroslip limit of the physical reading (each half "
           "carries F/2 and slips over F/(2q)); with the printed factor the limit is 2μF_N = "
           f"{2 * cp.macroslip_force:g} N." if opt.centre == "paper" else "."))
    add(f"- R = F_T(tip)/F_T(centre) of normalised forces (Eq. 1, Fig. 1): level l is "
        f"l × {TIP_LEVEL_FORCE:g} N on the tip model (one of two symmetric halves) and "
        f"l × {CENTRE_LEVEL_FORCE:g} N on the centre model, so R is also the ratio of the total "
        f"forces on the clamp. Level pairs: `{levels}` ({LEVEL_SCHEMES[levels]}).")
    add("- Eccentricity ε = sqrt(1 − min(R, 1/R)²).")
    add(f"- Strain energy U: `{kind}` ({STRAIN_ENERGY[kind][1]}); `secant` is reported beside "
        "it.")
    add("- Paper's coupling: both loops at the same load fraction (zero phase), "
        "δ_r = sqrt(δ_t² + δ_c²) sign(δ_t), F_r = sqrt(F_t² + F_c²) sign(F_t), the tip loop "
        "being the half model's, as in the paper.")
    add(f"- Work-based: the tip force on the whole clamp is twice the half model's; U of the "
        f"combined motion `{work_energy}` ({WORK_STRAIN_ENERGY[work_energy][1]}).")
    add("- η normalised by its value at R = 1.\n")

    add("## Results\n")
    rows = []
    for i in range(len(t["R"])):
        rows.append([
            ratio_label(t["R"][i]), f"{t['eccentricity'][i]:.3f}",
            f"{t['tip_amplitude_N'][i]:g}", f"{t['centre_amplitude_N'][i]:g}",
            _fmt(t["paper_loss_factor"][i]), _fmt(t["paper_normalised_loss_factor"][i]),
            _fmt(t.get("paper_loss_factor_secant", t["paper_loss_factor"])[i]),
            _fmt(t["work_loss_factor"][i]), _fmt(t["work_normalised_loss_factor"][i]),
            _fmt(t["work_dissipated_energy_Nmm"][i]),
            _fmt(t["work_dissipated_energy_phase90_Nmm"][i]),
            _fmt(t["work_loss_factor_phase90_peak"][i]),
        ])
    add(_md_table(["R", "ε", "tip F0 (N)", "centre F0 (N)", f"paper η ({kind})",
                   "paper η/η(1)", "paper η (secant)", "work η", "work η/η(1)",
                   "W, φ = 0 (N·mm)", "W, φ = 90° (N·mm)", "work η, φ = 90°, peak U"], rows))
    add("")
    notes = [f"R = {ratio_label(t['R'][i])}: {t['note'][i]}" for i in range(len(t["R"]))
             if t["note"][i]]
    if notes:
        add("Not computable in this reading:\n")
        add("\n".join(f"- {x}" for x in notes) + "\n")
    w0 = _finite(t["work_dissipated_energy_Nmm"])
    w90 = _finite(t["work_dissipated_energy_phase90_Nmm"])
    ok = np.isfinite(w0) & np.isfinite(w90)
    if np.any(ok):
        dev = float(np.max(np.abs(w90[ok] / w0[ok] - 1.0)))
        add(f"The work per cycle at 90° phase differs from that at zero phase by at most "
            f"{dev:.2g} (relative): the two decoupled models do not know the phase. With U "
            "summed over the component peaks η is phase-independent as well; with U the "
            "largest simultaneous stored energy (last column) it is not, because the "
            "components peak at different times.\n")

    add("## The paper's claims\n")
    add(_md_table(["claim", "coupling", "verdict", "evidence", "reason"],
                  [[c.claim, _claim_scope(c.key), f"**{c.verdict}**", c.evidence, c.reason]
                   for c in res.claims]))
    add("")
    add("Summary: " + "; ".join(f"{_claim_short(c.key)}: {c.verdict}" for c in res.claims)
        + ".\n")

    add("## Sensitivity to the reading\n")
    add("Loss factor at the paper's seven R under other readings "
        "(`loss_factor_vs_R_readings.csv`), with the verdict on the η-extremes claim computed "
        f"the same way. The work-based cycles here use {_READING_SAMPLES} samples per cycle "
        "(trapezoidal error of W about 2.5e-5 relative, common to all R).\n")
    rr = readings_table
    rows = []
    names = list(dict.fromkeys(rr["reading"]))
    for name in names:
        idx = [i for i, x in enumerate(rr["reading"]) if x == name]
        r = _finite([rr["R"][i] for i in idx])
        for coupling in ("paper", "work"):
            eta = _finite([rr[f"{coupling}_loss_factor"][i] for i in idx])
            verdict, evidence, _ = eta_extremes(r, eta)
            rows.append([f"`{name}`", coupling, f"**{verdict}**", evidence])
    add(_md_table(["reading", "coupling", "η lowest at 1, highest at 1/4 and 4", "evidence"],
                  rows))
    add("")
    add("\n".join(f"- `{rd.name}`: {rd.description}" for rd in res.readings) + "\n")

    e1 = res.equal_levels
    add("### R = 1 at each equal pair of levels\n")
    add("R = 1 can be any equal pair; η of the circle at each (`loss_factor_R1_levels.csv`):\n")
    add(_md_table(["levels", "tip F0 (N)", "centre F0 (N)", "paper η", "work η", "note"],
                  [[f"{e1['level'][i]:g}/{e1['level'][i]:g}", f"{e1['tip_amplitude_N'][i]:g}",
                    f"{e1['centre_amplitude_N'][i]:g}", _fmt(e1["paper_loss_factor"][i]),
                    _fmt(e1["work_loss_factor"][i]), e1["note"][i]]
                   for i in range(len(e1["level"]))]))
    add("")

    add("## Finite elements (Figs 8-9)\n")
    if res.fe_status == "done":
        add(f"Validation run ({res.fe_message}).\n")
        summary = getattr(res.fe_report, "summary_markdown", "")
        if summary:
            add(str(summary).strip() + "\n")
    else:
        add(f"Not run ({res.fe_status}): {res.fe_message}. `fig09_fe_vs_model.png` was not "
            "produced.\n")

    add("## Coupled 2-D friction: how wrong is the decoupling? (beyond the paper)\n")
    if res.coupling:
        add(_coupling_section(res.coupling))
    else:
        add("Not run (finite elements not asked for, `--no-fe`).\n")

    add("## Files\n")
    add("\n".join(f"- `{f.name}`" for f in res.files) + "\n")
    return "\n".join(lines)


def _coupling_section(c: Mapping[str, Any]) -> str:
    """Table and conclusion, both computed from ``coupling_ratio_vs_R.csv``'s columns."""
    lines = [
        "The paper adds two independent 1-D loops, as if each direction had the full friction "
        "capacity. In a real clamp both directions share one Coulomb limit per contact point "
        "(a circle). The built-in frictional FE solver (`docs/solver.md`) runs the Table 1 "
        "bar with the tip force along the bar on its end face and the centre force across it "
        "on the mid-length section, F_tip = A_t sin θ, F_centre = A_c sin(θ + φ), every path "
        "scaled to the same largest resultant force (0.75 μF_N), until the work per cycle "
        "settles; then each force alone. Coupling ratio = W_coupled / (W_tip alone + "
        "W_centre alone): 1 is what the paper's decoupling assumes "
        "(`coupling_ratio_vs_R.csv`, `fig12b_coupling_ratio_vs_R.png`).\n",
        _md_table(["R", "ε", "φ (°)", "A_t (N)", "A_c (N)", "W coupled (N·mm)",
                   "W decoupled (N·mm)", "coupling ratio", "tip share"],
                  [[ratio_label(c["R"][i]), f"{c['eccentricity'][i]:.3f}",
                    f"{c['phase_deg'][i]:g}", f"{c['tip_amplitude_N'][i]:.4g}",
                    f"{c['centre_amplitude_N'][i]:.4g}", _fmt(c["dissipated_energy_Nmm"][i]),
                    _fmt(c["decoupled_dissipated_energy_Nmm"][i]),
                    _fmt(c["coupling_ratio"][i], 4), f"{c['tip_share'][i]:.3f}"]
                   for i in range(len(c["R"]))]),
        "",
    ]
    ratio = _finite(c["coupling_ratio"])
    r = _finite(c["R"])
    phase = _finite(c["phase_deg"])
    words = []
    for phi in sorted(set(phase.tolist())):
        m = phase == phi
        lo, hi = float(np.min(ratio[m])), float(np.max(ratio[m]))
        r_hi = ratio_label(float(r[m][int(np.argmax(ratio[m]))]))
        words.append(f"at φ = {phi:g}° the ratio runs from {lo:.3f} to {hi:.3f}, largest at "
                     f"R = {r_hi}")
    if float(np.min(ratio)) > 1.0:
        verdict = ("the decoupled model **underestimates** the dissipation at every R and "
                   "phase computed")
    elif float(np.max(ratio)) < 1.0:
        verdict = ("the decoupled model **overestimates** the dissipation at every R and "
                   "phase computed")
    else:
        verdict = "the decoupled model is off in both directions, depending on R and phase"
    unsettled = [i for i, ok in enumerate(c["settled"]) if not ok]
    why = (" Where the ratio is near 1 one direction dominates the dissipation and the shared "
           "friction circle hardly matters; with balanced loads each direction uses up part of "
           "the other's friction capacity, so the interface slips more than either 1-D model "
           "predicts." if float(np.min(ratio)) > 1.0 else "")
    lines.append(f"Conclusion: {verdict}; " + "; ".join(words) + "." + why
                 + (f" {len(unsettled)} case(s) did not settle to the cycle tolerance."
                    if unsettled else " Every case settled to the cycle tolerance.") + "\n")
    return "\n".join(lines)


def _claim_scope(key: str) -> str:
    if key.endswith("-paper"):
        return "paper's (Eqs 19-23)"
    if key.endswith("-work"):
        return "work-based"
    if key == "fe-agreement":
        return "FE validation"
    return "each model"


def _claim_short(key: str) -> str:
    return {"softening": "softening", "centre-stiffer": "centre stiffer than tip",
            "eta-extremes-paper": "η extremes (paper's coupling)",
            "eta-extremes-work": "η extremes (work-based)",
            "fe-agreement": "models agree with FE"}.get(key, key)

