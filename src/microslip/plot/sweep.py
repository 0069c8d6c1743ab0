"""The summary figures of ``microslip sweep``: eta and W_d against the swept parameter, and
eta against R.

Units: N, mm, MPa; the axis labels come from :data:`microslip.sweep.spec.PARAMETERS`.
"""

from __future__ import annotations

import os
import textwrap
import warnings
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..sweep.spec import PARAMETERS, GridAxis, SweepSpec
from .core import COLOURS, new_figure, save_figure

__all__ = ["PANELS", "plot_ratio_sweep", "plot_sweep"]

_MAX_POINTS = 2000
_MAX_SERIES = 6


def _thin(n: int, m: int = _MAX_POINTS) -> NDArray[np.intp]:
    return np.unique(np.linspace(0, n - 1, min(n, m)).round().astype(np.intp))


#: The quantities of the sweep figure, one panel each: result attribute, axis label.
PANELS = (("loss_factor", "Loss factor η (–)"),
          ("dissipated_energy", "Dissipated energy $W_d$ (N·mm)"))


def plot_sweep(result: Any, path: str | os.PathLike[str]) -> None:
    """Loss factor and dissipated energy against the swept parameter, saved to ``path``.

    The x axis is the first grid axis (or, without a grid, the first sampled parameter,
    case by case as points). A second grid axis gives one curve per value (at most six,
    evenly picked). With random samples each curve is the median over the samples with
    bands from the 25th to the 75th and from the 5th to the 95th percentile. Cases that
    were not computed (NaN) are left out. W_d is on a log axis when it spans more than two
    decades. ``result`` is a :class:`microslip.sweep.SweepResult`.
    """
    spec = result.spec
    fig, axes = new_figure(ncols=len(PANELS))
    for ax, (name, label) in zip(axes[0], PANELS, strict=True):
        values = getattr(result, name).reshape(spec.shape)
        ax.set_ylabel(label)
        with warnings.catch_warnings():  # a grid point whose every draw failed: a gap
            warnings.simplefilter("ignore", RuntimeWarning)
            if not spec.grid:
                _draw_draws(ax, spec, values)
            else:
                _draw_grid(ax, spec, values)
        finite = values[np.isfinite(values) & (values > 0)]
        if name == "dissipated_energy" and finite.size and finite.max() > 100 * finite.min():
            ax.set_yscale("log")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(frameon=False)
    fig.suptitle(_sweep_title(spec), fontsize=7)
    save_figure(fig, path)


def _draw_draws(ax: Any, spec: SweepSpec, values: NDArray[np.float64]) -> None:
    """No grid: every draw as a point against the first sampled parameter, and percentiles."""
    s = spec.samples[0]
    idx = _thin(spec.size, 20000)
    ax.plot(s.values[idx], values[idx], ".", ms=1.5, color=COLOURS[0], alpha=0.5,
            label=f"{spec.size} draws")
    for q, ls, label in ((50, "-", "median"), (5, ":", "5th and 95th percentiles"),
                         (95, ":", None)):
        ax.axhline(float(np.nanpercentile(values, q)), color=COLOURS[1], ls=ls, lw=0.8,
                   label=label)
    ax.set_xlabel(PARAMETERS[s.name][2])


def _series(spec: SweepSpec) -> tuple[list[int], list[str]]:
    """Column indices into the flattened non-x grid axes, and their labels (second axis)."""
    if len(spec.grid) < 2:
        return [0], [""]
    second: GridAxis = spec.grid[1]
    inner = int(np.prod(spec.shape[2:len(spec.grid)], dtype=np.int64))
    picks = _thin(second.values.size, _MAX_SERIES)
    unit = PARAMETERS[second.name][1]
    labels = [f"{second.name.replace('_', ' ')} = {second.values[int(p)]:g}"
              + (f" {unit}" if unit else "") for p in picks]
    return [int(p) * inner for p in picks], labels


def _draw_grid(ax: Any, spec: SweepSpec, values: NDArray[np.float64]) -> None:
    """A quantity against the first grid axis: one curve per picked value of the second axis,
    with percentile bands over the samples (labelled once, in the first curve's colour)."""
    x_axis = spec.grid[0]
    x = x_axis.values
    ix = _thin(x.size)
    rest = spec.shape[1:len(spec.grid)]
    e = values.reshape((x.size, int(np.prod(rest, dtype=np.int64)),
                        spec.n_samples if spec.samples else 1))
    for c, (j, label) in enumerate(zip(*_series(spec), strict=True)):
        colour = COLOURS[c % len(COLOURS)]
        ej = e[ix, j, :]
        if spec.samples:
            p5, p25, p50, p75, p95 = np.nanpercentile(ej, [5, 25, 50, 75, 95], axis=1)
            ax.fill_between(x[ix], p5, p95, color=colour, alpha=0.15, lw=0,
                            label="5–95 %" if c == 0 else None)
            ax.fill_between(x[ix], p25, p75, color=colour, alpha=0.3, lw=0,
                            label="25–75 %" if c == 0 else None)
            ax.plot(x[ix], p50, color=colour, label=(label + " median").strip())
        else:
            ax.plot(x[ix], ej[:, 0], color=colour, label=label or None)
    ax.set_xlabel(PARAMETERS[x_axis.name][2])


def _sweep_title(spec: SweepSpec) -> str:
    title = f"{spec.model} model, U: {spec.strain_energy}, {spec.increments} increments"
    if spec.samples:
        draws = "; ".join(f"{s.name} ~ {s.distribution.kind}({s.distribution.a:g}, "
                          f"{s.distribution.b:g})" for s in spec.samples)
        title += "\n" + "\n".join(textwrap.wrap(f"{draws}; {spec.n_samples} draws", 50))
    return title


def plot_ratio_sweep(sweep: Any, path: str | os.PathLike[str]) -> None:
    """Loss factor against R (log axis), the paper's coupling and the work of the load."""
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    fig, axes = new_figure()
    ax = axes[0, 0]
    r = sweep.ratios
    ax.plot(r, sweep.loss_factor("paper"), "o-", ms=2.5, color=COLOURS[0],
            label="paper coupling (Eqs 19–23)")
    ax.plot(r, sweep.loss_factor("work"), "s--", ms=2.5, color=COLOURS[1],
            label="work of the load")
    ax.set_xscale("log")
    nice = [t for t in (0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0) if r.min() <= t <= r.max()]
    if len(nice) >= 2:
        ax.set_xticks(nice)
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("Force ratio R = $F_{tip}/F_{centre}$ (–)")
    ax.set_ylabel("Loss factor η (–)")
    ax.set_title(f"planar, U: {sweep.strain_energy_kind}, levels: {sweep.levels}", fontsize=7)
    ax.legend(frameon=False)
    save_figure(fig, path)

