"""The loops of a run on the user's own mesh (``microslip fe --mesh FILE --plot``): each
load's force against its work-conjugate displacement over the settled cycle, one panel per
load. Units: N, mm (or um for small loops)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..meshdynamics.verdict_modal import DAMPING_CEILING as MICROSLIP_CEILING
from .core import COLOURS, displacement_scale, log_ticks, new_figure, pyplot, save_figure

__all__ = ["compare_figure", "mesh_loops_figure", "node_states", "plot_compare",
           "plot_mesh_loops", "plot_qsma",
           "slip_snapshots"]

#: Slip-pattern panels of the side-by-side figure (at the FE's first, middle and last
#: amplitudes).
SLIP_PANELS = 3


def plot_mesh_loops(loops: Sequence[tuple[str, Any, Any]], works: Sequence[float],
                    path: str | os.PathLike[str], title: str = "") -> None:
    """``loops``: (set name, force N, displacement mm) per load; ``works``: each load's work
    over the cycle, N·mm (in the legend)."""
    save_figure(mesh_loops_figure(loops, works, title), path)


def mesh_loops_figure(loops: Sequence[tuple[str, Any, Any]], works: Sequence[float],
                      title: str = "") -> Any:
    """The figure of :func:`plot_mesh_loops`, unsaved."""
    fig, axes = new_figure(ncols=len(loops), width_mm=75.0)
    for k, ((name, force, disp), work) in enumerate(zip(loops, works, strict=True)):
        ax = axes[0][k]
        scale, unit = displacement_scale(float(np.max(np.abs(disp))) or 1.0)
        ax.plot(np.asarray(disp) * scale, force, color=COLOURS[k % len(COLOURS)],
                label=f"load on {name}: W = {work:.4g} N·mm")
        ax.set_xlabel(f"work-conjugate displacement of {name} ({unit})")
        ax.set_ylabel("load F (N)")
        ax.legend(loc="upper left", fontsize="small")
    if title:
        fig.suptitle(title)
    return fig


def plot_qsma(curve: Mapping[str, Any], path: str | os.PathLike[str]) -> None:
    """Frequency (first harmonic, and the secant one of the full FE) and damping ratio
    against the response set's amplitude, from ``modal --mesh``'s JSON object ``curve`` (of
    any one solver)."""
    fig, axes = new_figure(ncols=2, width_mm=80.0)
    a = np.asarray(curve["amplitude_mm"], dtype=float)
    ax = axes[0][0]
    ax.semilogx(a, curve["frequency_Hz"], color=COLOURS[0], marker=".",
                label="first harmonic (as EPMC)")
    if "secant_frequency_Hz" in curve:  # the full FE's QSMA only
        ax.semilogx(a, curve["secant_frequency_Hz"], color=COLOURS[1], marker=".",
                    linestyle="--", label="secant (Lacayo and Allen)")
    ax.set_xlabel("amplitude of the response set (mm)")
    ax.set_ylabel("natural frequency f (Hz)")
    ax.legend(fontsize="small")
    ax = axes[0][1]
    ax.semilogx(a, curve["damping_ratio"], color=COLOURS[0], marker=".")
    ax.set_xlabel("amplitude of the response set (mm)")
    ax.set_ylabel("damping ratio zeta (-)")
    for ax in axes[0]:
        log_ticks(ax, "x")
    how = {"fe": "full-FE quasi-static modal analysis", "rom": "EPMC on the contact-node ROM"}
    solver = curve.get("solver", "fe")
    fig.suptitle(f"mode {curve['mode']} ({curve['label']}), {how.get(solver, solver)}")
    save_figure(fig, path)


def slip_snapshots(amplitudes: Sequence[float | None], count: int = SLIP_PANELS) -> list[int]:
    """Indices of ``count`` amplitudes spread over those that computed (None or NaN: failed),
    the first and the last among them.

    >>> slip_snapshots([0.1, None, 0.3, 0.4, 0.5, 0.6])
    [0, 3, 5]
    """
    ok = [i for i, a in enumerate(amplitudes) if a is not None and np.isfinite(a)]
    if len(ok) <= count:
        return ok
    picks = np.round(np.linspace(0, len(ok) - 1, count)).astype(int)
    return [ok[int(k)] for k in dict.fromkeys(picks.tolist())]


#: The damping axis starts this factor below the full FE's smallest damping ratio; a model
#: far below it (a whole joint that hardly slips: 1e-27) is named as off the axis instead of
#: squeezing the curves that can be compared into its top decade.
DAMPING_AXIS_DECADES = 30.0


def _damping_floor(ax: Any, solvers: Mapping[str, Any]) -> None:
    truth = solvers.get("fe", next(iter(solvers.values())))
    fe = [v for v in truth["damping_ratio"] if v is not None and v > 0]
    if not fe:
        return
    floor = min(fe) / DAMPING_AXIS_DECADES
    below = [name for name, c in solvers.items()
             if any(v is not None and 0 <= v < floor for v in c["damping_ratio"])]
    ax.set_ylim(bottom=floor)
    if below:
        ax.text(0.02, 0.02, f"below the axis (ζ < {floor:.1g}): {', '.join(below)}",
                transform=ax.transAxes, fontsize="small", color="0.3")


def node_states(pattern: Mapping[str, Any], i: int) -> tuple[np.ndarray, np.ndarray]:
    """(slipped, open) per contact node at the pattern's amplitude ``i``: a node that slid
    while closed is slipped; one open at some state of the cycle that never slid is open
    (drawn hollow: not stick, issue 34 item 9); a pattern without ``open`` has none.

    >>> node_states({"slipped": [[True, False, False]], "open": [[True, True, False]]}, 0)
    (array([ True, False, False]), array([False,  True, False]))
    """
    slipped = np.asarray(pattern["slipped"][i], dtype=bool)
    given = pattern.get("open")
    opened = (np.zeros_like(slipped) if given is None else
              np.asarray(given[i], dtype=bool) & ~slipped)
    return slipped, opened


def compare_figure(out: Mapping[str, Any]) -> Any:
    """The figure of ``modal --mesh ... --solver all``'s JSON object ``out``: frequency and
    damping ratio against amplitude for every solver (top), and the full FE's slip pattern
    (contact nodes in the contact plane, mm; stick or slip over the settled cycle) at
    :data:`SLIP_PANELS` of its amplitudes (bottom)."""
    solvers = out["solvers"]
    fe = solvers.get("fe")
    pattern = None if fe is None else fe.get("slip_pattern")
    picks = [] if pattern is None else slip_snapshots(fe["amplitude_mm"])
    cols = 2 * max(len(picks), 1)
    fig = pyplot().figure(figsize=(170.0 / 25.4, (130.0 if picks else 70.0) / 25.4))
    grid = fig.add_gridspec(2, cols, height_ratios=(1.7, 1.0)) if picks else \
        fig.add_gridspec(1, cols)
    half = cols // 2
    freq, damp = fig.add_subplot(grid[0, :half]), fig.add_subplot(grid[0, half:])
    styles = ("o", "s", "^", "v", "D")
    for k, (name, curve) in enumerate(solvers.items()):
        a = np.array([np.nan if v is None else v for v in curve["amplitude_mm"]], dtype=float)
        c = COLOURS[k % len(COLOURS)]
        for ax, key in ((freq, "frequency_Hz"), (damp, "damping_ratio")):
            y = np.array([np.nan if v is None else v for v in curve[key]], dtype=float)
            draw = ax.loglog if key == "damping_ratio" else ax.semilogx
            draw(a, y, color=c, marker=styles[k % len(styles)], ms=3, label=name)
    stuck = out["linear_frequencies_Hz"][out["mode"] - 1]
    freq.axhline(stuck, color="0.5", lw=0.6, ls=":", label=f"stuck {stuck:.5g} Hz")
    damp.axhline(MICROSLIP_CEILING, color="0.5", lw=0.6, ls=":",
                 label=f"ζ = {MICROSLIP_CEILING:g} (end of the verdicts' range)")
    _damping_floor(damp, solvers)
    freq.set_ylabel("natural frequency f (Hz)")
    damp.set_ylabel("damping ratio ζ (dimensionless)")
    for ax in (freq, damp):
        ax.set_xlabel("amplitude of the response set a (mm)")
        ax.legend(fontsize="small", frameon=False)
        log_ticks(ax, "x")
    log_ticks(damp, "y")
    if pattern is not None and picks:
        x, y = np.asarray(pattern["x_mm"]), np.asarray(pattern["y_mm"])
        for j, i in enumerate(picks):
            ax = fig.add_subplot(grid[1, 2 * j:2 * j + 2])
            slipped, opened = node_states(pattern, i)
            stuck = ~slipped & ~opened
            ax.scatter(x[stuck], y[stuck], s=10, color=COLOURS[0], label="stick")
            ax.scatter(x[slipped], y[slipped], s=10, color=COLOURS[1], label="slip")
            ax.scatter(x[opened], y[opened], s=10, facecolors="none", edgecolors="0.45",
                       linewidths=0.8, label="open (lifted off)")
            ax.set_aspect("equal", adjustable="box")
            share = fe.get("slip_fraction", [None] * len(picks))[i]
            share = slipped.mean() if share is None else share
            gap = f"\n{int(opened.sum())} of {opened.size} nodes open" if opened.any() else ""
            ax.set_title(f"a = {fe['amplitude_mm'][i]:.3g} mm\n{100 * share:.0f} % of the "
                         f"area slips{gap}", fontsize=7)
            ax.set_xlabel("contact plane e1 (mm)")
            if j == 0:
                ax.set_ylabel("contact plane e2 (mm)")
                fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center",
                           ncol=3, fontsize="small", frameon=False)
    fig.suptitle(f"mode {out['mode']} ({out['label']}): every solver on one amplitude grid"
                 + ("\nbelow: the full FE's contact slip pattern over the settled cycle"
                    if picks else ""), fontsize=8)
    return fig


def plot_compare(out: Mapping[str, Any], path: str | os.PathLike[str]) -> None:
    """:func:`compare_figure` saved to ``path`` (atomically)."""
    save_figure(compare_figure(out), path)
