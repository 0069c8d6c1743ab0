"""The plotting basics: journal style, figure size, atomic saving, force-displacement loops.

Import is lazy: ``import microslip`` never imports matplotlib.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import MicroslipError
from ..io import atomic_path
from ..results import Backbone, DampingResult, HysteresisLoop

__all__ = ["COLOURS", "PLOT_FORMATS", "displacement_scale", "log_ticks", "new_figure",
           "plot_damping", "plot_loops", "pyplot", "save_figure"]

#: One colour per series, the same across the figures of a report.
COLOURS = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000")

#: Figure formats a command writes, by the file's extension.
PLOT_FORMATS = (".png", ".pdf", ".svg")

#: Displacements are drawn in micrometres when the largest is below this, mm.
MICROMETRE_BELOW_MM = 0.1


def displacement_scale(largest_mm: float) -> tuple[float, str]:
    """(factor, unit) to draw displacements in: um for small ones, else mm.

    >>> displacement_scale(0.003), displacement_scale(0.5)
    ((1000.0, 'µm'), (1.0, 'mm'))
    """
    return (1000.0, "µm") if largest_mm < MICROMETRE_BELOW_MM else (1.0, "mm")


def pyplot() -> Any:
    """matplotlib.pyplot with a non-interactive backend, or a clear error if not installed."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise MicroslipError(
            "plotting needs matplotlib: pip install 'microslip[plot]'"
        ) from None
    plt.rcParams.update({
        "font.size": 8, "axes.labelsize": 8, "legend.fontsize": 7, "xtick.labelsize": 7,
        "ytick.labelsize": 7, "lines.linewidth": 1.2, "axes.grid": True, "grid.alpha": 0.3,
        "savefig.dpi": 200, "figure.constrained_layout.use": True,
        "axes.formatter.useoffset": False,  # 0.4244 is read as 0.4244, not +4.2e-1 offsets
    })
    return plt


#: Most labelled ticks on a log axis (a panel 75 mm wide holds five short numbers).
MAX_LOG_LABELS = 5
#: The mantissas of the labelled ticks of a log axis, densest last: the first ladder step
#: whose ticks inside the limits are at most :data:`MAX_LOG_LABELS` is taken.
LOG_SUBS = ((1.0, 1.5, 2.0, 3.0, 5.0, 7.0), (1.0, 2.0, 5.0), (1.0, 3.0), (1.0,))


def log_ticks(ax: Any, axis: str = "x") -> None:
    """Readable ticks on the log axis ``axis`` ("x" or "y") of ``ax``, its limits set: at
    most :data:`MAX_LOG_LABELS` labelled ticks, the densest ladder of :data:`LOG_SUBS` that
    fits (every k-th decade on a long axis), written as plain numbers (0.002, 5e-05), minor ticks
    unlabelled. Matplotlib labels the minor ticks of an axis spanning less than a decade or
    so, and they overlap (issue 34 item 9)."""
    import math

    from matplotlib.ticker import FixedLocator, FuncFormatter, LogLocator, NullFormatter

    target = ax.xaxis if axis == "x" else ax.yaxis
    lo, hi = sorted(ax.get_xlim() if axis == "x" else ax.get_ylim())
    if not (lo > 0.0 and hi > lo and math.isfinite(hi)):
        return
    ticks: list[float] = []
    for subs in LOG_SUBS:
        ticks = [m * 10.0 ** k for k in range(math.floor(math.log10(lo)) - 1,
                                               math.ceil(math.log10(hi)) + 1) for m in subs]
        ticks = [t for t in ticks if lo <= t * (1 + 1e-9) and t <= hi * (1 + 1e-9)]
        if len(ticks) <= MAX_LOG_LABELS:
            break
    else:  # a long axis: every k-th decade
        step = math.ceil(len(ticks) / MAX_LOG_LABELS)
        ticks = ticks[::step]
    if not ticks:  # inside one step of the ladder: its two ends
        ticks = [lo, hi]
    target.set_major_locator(FixedLocator(ticks))
    target.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    target.set_minor_locator(LogLocator(base=10.0, subs=tuple(range(2, 10)), numticks=20))
    target.set_minor_formatter(NullFormatter())


def new_figure(ncols: int = 1, nrows: int = 1, width_mm: float = 85.0,
               height_mm: float = 65.0) -> tuple[Any, Any]:
    """A figure sized for a journal column (85 mm wide per panel column)."""
    plt = pyplot()
    fig, axes = plt.subplots(nrows, ncols, figsize=(width_mm * ncols / 25.4,
                                                    height_mm * nrows / 25.4), squeeze=False)
    return fig, axes


def save_figure(fig: Any, path: str | os.PathLike[str]) -> None:
    """Save atomically (never a half-written image) and close."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=os.path.splitext(str(path))[1].lstrip(".") or "png")
    pyplot().close(fig)


def plot_loops(ax: Any, loops: Sequence[HysteresisLoop], labels: Sequence[str],
               backbones: Sequence[Backbone | None] | None = None,
               colours: Sequence[str] = COLOURS) -> None:
    """Draw loops (solid) and their backbones (dashed) on ``ax``, with units on the axes
    (displacements in um when they are small, :func:`displacement_scale`)."""
    largest = max((float(np.max(np.abs(lp.displacement))) for lp in loops), default=1.0)
    scale, unit = displacement_scale(largest)
    for i, (loop, label) in enumerate(zip(loops, labels, strict=True)):
        c = colours[i % len(colours)]
        ax.plot(scale * loop.displacement, loop.force, color=c, label=label)
        bb = backbones[i] if backbones else None
        if bb is not None:
            ax.plot(scale * bb.displacement, bb.force, color=c, ls="--", lw=0.8)
    ax.set_xlabel(f"Displacement δ ({unit})")
    ax.set_ylabel("Force $F_T$ (N)")
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.axvline(0.0, color="0.5", lw=0.5)
    ax.legend(loc="upper left", frameon=False)


def plot_damping(result: DampingResult, path: str | os.PathLike[str], title: str = "") -> None:
    """One loop with its backbone, and the energies in the legend; saved to ``path``."""
    fig, axes = new_figure()
    ax = axes[0, 0]
    label = (f"loop: $W_d$ = {result.dissipated_energy:.4g} N·mm, "
             f"η = {result.loss_factor:.4f} ({result.strain_energy_kind} U)")
    plot_loops(ax, [result.loop], [label], [result.backbone])
    if result.backbone is not None:
        ax.plot([], [], color="0.3", ls="--", lw=0.8, label="first loading (backbone)")
        ax.legend(loc="upper left", frameon=False)
    if title:
        ax.set_title(title)
    save_figure(fig, path)
