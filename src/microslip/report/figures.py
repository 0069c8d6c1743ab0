"""The figures of a report, each returned as the text of a self-contained SVG image.

Drawn with :mod:`microslip.plot.core` (journal style, :data:`~microslip.plot.core.COLOURS`);
text is drawn as paths (``svg.fonttype = "path"``), so an SVG needs no font and no network.
"""

from __future__ import annotations

import io
import os
import tempfile
from typing import Any

from ..plot.core import COLOURS, new_figure, plot_loops, pyplot
from .compute import LOOP_FRACTIONS, ReportData

__all__ = ["damping_figure", "loops_figure", "planar_figure", "svg_text"]


def svg_text(fig: Any) -> str:
    """The SVG of ``fig`` (closed afterwards), from its ``<svg`` element on."""
    plt = pyplot()
    buf = io.StringIO()
    with plt.rc_context({"svg.fonttype": "path"}):
        fig.savefig(buf, format="svg")
    plt.close(fig)
    text = buf.getvalue()
    return text[text.index("<svg"):]


def loops_figure(data: ReportData) -> str:
    """Masing loops and backbones of the 1-D model at fractions of the case amplitude."""
    fig, axes = new_figure(width_mm=120.0, height_mm=80.0)
    labels = [f"F0 = {r.amplitude:.4g} N ({f:g} x case): η = {r.loss_factor:.4f}"
              for f, r in zip(LOOP_FRACTIONS, data.loops, strict=True)]
    plot_loops(axes[0, 0], [r.loop for r in data.loops], labels,
               [r.backbone for r in data.loops])
    axes[0, 0].set_title(f"{data.model} model (1-D, paper's reading), dashed: first loading",
                         fontsize=8)
    return svg_text(fig)


def damping_figure(data: ReportData) -> str:
    """Loss factor and dissipated energy per cycle against the force amplitude: 1-D curve and
    the FE points."""
    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=70.0)
    eta, wd = axes[0, 0], axes[0, 1]
    eta.plot(data.curve_amplitude, data.curve_loss_factor, color=COLOURS[0], label="1-D model")
    wd.plot(data.curve_amplitude, data.curve_dissipated, color=COLOURS[0], label="1-D model")
    if data.fe_curve.shape[0]:
        a, e, w = data.fe_curve[:, 0], data.fe_curve[:, 1], data.fe_curve[:, 2]
        label = f"FE ({data.settings.fe_solver}, mesh {data.settings.mesh})"
        eta.plot(a, e, "o", color=COLOURS[1], ms=4, label=label)
        wd.plot(a, w, "o", color=COLOURS[1], ms=4, label=label)
    for ax in (eta, wd):
        ax.axvline(data.amplitude, color="0.5", lw=0.6, ls=":")
        ax.axvline(data.macroslip, color="0.3", lw=0.8, ls="--", label="macroslip μ F_N")
        ax.set_xlabel("Force amplitude $F_0$ (N)")
        ax.legend(loc="best", frameon=False)
    eta.set_ylabel("Loss factor η (dimensionless)")
    wd.set_ylabel("Dissipated energy per cycle $W_d$ (N·mm)")
    return svg_text(fig)


def planar_figure(data: ReportData) -> str:
    """The planar case's loops and load path (:func:`microslip.plot.paper.figure_planar`)."""
    from ..plot.paper import figure_planar

    with tempfile.TemporaryDirectory(prefix="microslip-report-") as tmp:
        path = os.path.join(tmp, "planar.svg")
        with pyplot().rc_context({"svg.fonttype": "path"}):
            figure_planar(data.planar, path)
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    return text[text.index("<svg"):]
