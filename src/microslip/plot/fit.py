"""The figure of ``microslip fit --plot``: measured loops against the fitted model."""

from __future__ import annotations

import os
from typing import Any

from .core import COLOURS, new_figure, save_figure

__all__ = ["plot_fit"]


def plot_fit(result: Any, path: str | os.PathLike[str]) -> None:
    """Each measured loop (points, centred as the fit sees it) and the model's Masing loop at
    the same forces (line), with the identified values and the fit quality in the title.

    ``result`` is a :class:`microslip.fit.FitResult`.
    """
    fig, axes = new_figure(width_mm=120.0, height_mm=85.0)
    ax = axes[0, 0]
    for i, (loop, model) in enumerate(zip(result.loops, result.predicted, strict=True)):
        c = COLOURS[i % len(COLOURS)]
        f, d = loop.centred()
        name = os.path.basename(loop.source) or f"loop {i + 1}"
        ax.plot(d, f, "o", ms=2.0, color=c, alpha=0.5,
                label=f"measured: {name}, F0 = {loop.amplitude:.4g} N")
        ax.plot(model, f, "-", color=c, lw=1.0, label="fitted model")
    ax.set_xlabel("Displacement δ, centred (mm)")
    ax.set_ylabel("Force $F_T$, centred (N)")
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.axvline(0.0, color="0.5", lw=0.5)
    ax.legend(loc="upper left", frameon=False, fontsize=6)
    values = ", ".join(f"{p.name} = {p.value:.4g}{' ' + p.unit if p.unit else ''}"
                       + ("" if p.identified else " (not identified)")
                       for p in result.parameters)
    ax.set_title(f"{result.model} model: {values}\nrms residual {result.rms_residual_mm:.3g} mm, "
                 f"R² = {result.r_squared:.5f}", fontsize=7)
    save_figure(fig, path)
