"""The paper's figures (Figs 1, 10-12, the coupling figure) and the one-case planar figure.

Each figure function draws with :mod:`microslip.plot.core` and returns (or takes) the data it
plots as columns, so that the CSV written beside each PNG holds exactly what the figure shows.
Units: N, mm, N·mm.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..closedform import LOSS_FACTOR_QUADRATIC
from ..planar import (
    CENTRE_LEVEL_FORCE,
    PAPER_RATIOS,
    PAPER_STRAIN_ENERGY,
    TIP_LEVEL_FORCE,
    PlanarResult,
    eccentricity,
    ratio_label,
    trajectory,
)
from .core import COLOURS, new_figure, plot_loops, save_figure

__all__ = [
    "CENTRE_COLOUR",
    "PAPER_COLOUR",
    "RATIO_COLOURS",
    "TIP_COLOUR",
    "WORK_COLOUR",
    "figure_coupling",
    "figure_loops",
    "figure_loss_factor",
    "figure_planar",
    "figure_trajectories",
]

#: One colour per quantity, the same in Figs 10-12 and in ``microslip planar --plot``
#: (the Okabe-Ito palette of :data:`microslip.plot.core.COLOURS`).
TIP_COLOUR, CENTRE_COLOUR, PAPER_COLOUR, WORK_COLOUR = COLOURS[:4]

#: Colour of each of the paper's R in Fig. 1: tip-dominated ellipses in blues, centre-dominated
#: in oranges, the circle black (the families of the tip and centre colours).
RATIO_COLOURS: dict[float, str] = {
    1.0: "#000000",
    2.0: "#6BAED6", 3.0: "#2171B5", 4.0: "#08306B",
    0.5: "#FDAE6B", 1.0 / 3.0: "#E6550D", 0.25: "#7F2704",
}


def _ratio_colour(r: float) -> str:
    for key, colour in RATIO_COLOURS.items():
        if math.isclose(key, r, rel_tol=1e-9):
            return colour
    return "0.4"


def _finite(values: Any) -> np.ndarray:
    return np.asarray(values, dtype=float)


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


def figure_coupling(path: str | os.PathLike[str], table: Mapping[str, Any],
                    coupling: Mapping[str, Any]) -> None:
    """Beside Fig. 12: (a) the paper's normalised eta against R; (b) the coupling ratio
    W_coupled / (W_tip + W_centre) of coupled 2-D friction (built-in FE solver) against R."""
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

