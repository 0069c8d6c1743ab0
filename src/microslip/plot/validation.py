"""The figures of ``microslip validate`` (paper, Section 4): the stick and slip zones of the
lower face (Fig. 8) and the FE loops against the analytical models (Fig. 9).

:mod:`microslip.validate` computes each panel (:class:`StatusPanel`, :class:`LoopPanel`);
these functions only draw. Units: N, mm, s.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..results import HysteresisLoop
from .core import COLOURS, new_figure, plot_loops, save_figure

__all__ = ["STATUS_COLOURS", "LoopPanel", "StatusPanel", "figure_contact_status",
           "figure_fe_vs_model"]

#: Colour of each contact status, open (-1 drawn white), stick (dark), slip (light), Fig. 8.
STATUS_COLOURS = ("#ffffff", "#404040", "#bdbdbd")
#: Colour of the closed-form slip zone's bounds.
_BOUND_COLOUR = "#D55E00"


@dataclass(frozen=True)
class StatusPanel:
    """The lower face's contact status at one time of one load case.

    ``x_edges``, ``y_edges`` (mm) bound the cells of ``status`` (shape (nx, ny), -1 open,
    1 stick, 2 slip); ``section_x`` (mm) is the loaded section when it lies inside the bar
    (else None); ``slip_bounds`` (mm) are the closed-form slip zone's bounds inside the bar.
    """

    load_case: str
    time: float  # s
    force: float  # N
    x_edges: Any
    y_edges: Any
    status: Any
    length: float  # mm
    width: float  # mm
    section_x: float | None
    slip_bounds: tuple[float, ...]


@dataclass(frozen=True)
class LoopPanel:
    """One load case of Fig. 9: the analytical model (default reading), the closed form
    (uncorrected model) and the FE loops, each FE loop with its label (the mesh)."""

    load_case: str
    amplitude: float  # N
    model: HysteresisLoop
    closed_form: HysteresisLoop
    fe: tuple[tuple[str, HysteresisLoop], ...]


def figure_contact_status(panels: Sequence[Sequence[StatusPanel]],
                          path: str | os.PathLike[str]) -> None:
    """Fig. 8: stick (dark) and slip (light) zones of the lower face, one column per load case
    and one row per time (``panels[column][row]``). Dashed lines bound the closed-form zone
    slipping in that substep; the solid line is the loaded section inside the bar."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    nrows = len(panels[0]) if panels else 0
    fig, axes = new_figure(ncols=len(panels), nrows=nrows, width_mm=85.0, height_mm=22.0)
    cmap = ListedColormap(list(STATUS_COLOURS))
    for col, column in enumerate(panels):
        for row, p in enumerate(column):
            ax = axes[row, col]
            ax.pcolormesh(p.x_edges, p.y_edges, p.status.T, cmap=cmap, vmin=-0.5, vmax=2.5,
                          shading="flat")
            if p.section_x is not None:
                ax.axvline(p.section_x, color="k", lw=1.0)
            for xb in p.slip_bounds:
                ax.axvline(xb, color=_BOUND_COLOUR, lw=0.9, ls="--")
            ax.set_xlim(0.0, p.length)
            ax.set_ylim(0.0, p.width)
            ax.set_yticks([0.0, p.width])
            ax.grid(False)
            ax.set_title(f"{p.load_case}: t = {p.time:g} s ({round(360 * p.time)}°), "
                         f"$F_T$ = {p.force:.0f} N", fontsize=7)
            if col == 0:
                ax.set_ylabel("y (mm)")
            if row == nrows - 1:
                ax.set_xlabel("x along the bar (mm)")
    handles = [Patch(facecolor=STATUS_COLOURS[1], label="stick"),
               Patch(facecolor=STATUS_COLOURS[2], label="slip"),
               Patch(facecolor="none", edgecolor=_BOUND_COLOUR, ls="--",
                     label="closed-form slip zone")]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, frameon=False)
    save_figure(fig, path)


def figure_fe_vs_model(panels: Sequence[LoopPanel], path: str | os.PathLike[str]) -> None:
    """Fig. 9: FE loops (markers) against the analytical model (default reading) and the
    closed form (uncorrected model, dashed), one panel per load case."""
    fig, axes = new_figure(ncols=len(panels), nrows=1)
    for col, p in enumerate(panels):
        ax = axes[0, col]
        loops = [p.model, p.closed_form] + [loop for _, loop in p.fe]
        names = ["model (default reading)", "closed form (rigid base)"] + \
            [f"FE, {lab}" for lab, _ in p.fe]
        plot_loops(ax, loops, names, colours=COLOURS)
        ax.lines[1].set_linestyle("--")
        for line in ax.lines[2:2 + len(p.fe)]:
            line.set_marker("o")
            line.set_markersize(2.5)
            line.set_linestyle("none")
        ax.legend(loc="upper left", frameon=False)
        ax.set_title(f"({'ab'[col]}) {p.load_case} loading, $F_0$ = {p.amplitude:g} N")
    save_figure(fig, path)
