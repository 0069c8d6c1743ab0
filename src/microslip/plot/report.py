"""The figures of ``microslip report``, each returned as the text of a self-contained SVG image.

Drawn in the style of :mod:`microslip.plot.core`; text is drawn as paths
(``svg.fonttype = "path"``), so an SVG needs no font and no network.
:mod:`microslip.report.figures` picks the data of the report; these functions only draw.
Units: N, mm, N·mm.
"""

from __future__ import annotations

import io
import os
import tempfile
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..results import DampingResult
from .core import COLOURS, new_figure, plot_loops, pyplot

if TYPE_CHECKING:
    from ..planar import PlanarResult

__all__ = ["damping_svg", "loops_svg", "mesh_loops_svg", "planar_svg", "structure_svg",
           "svg_text"]


def svg_text(fig: Any) -> str:
    """The SVG of ``fig`` (closed afterwards), from its ``<svg`` element on."""
    plt = pyplot()
    buf = io.StringIO()
    with plt.rc_context({"svg.fonttype": "path"}):
        fig.savefig(buf, format="svg")
    plt.close(fig)
    text = buf.getvalue()
    return text[text.index("<svg"):]


def loops_svg(results: Sequence[DampingResult], fractions: Sequence[float], model: str) -> str:
    """Masing loops and backbones of the 1-D model, each at ``fractions`` of the case
    amplitude."""
    fig, axes = new_figure(width_mm=120.0, height_mm=80.0)
    labels = [f"F0 = {r.amplitude:.4g} N ({f:g} x case): η = {r.loss_factor:.4f}"
              for f, r in zip(fractions, results, strict=True)]
    plot_loops(axes[0, 0], [r.loop for r in results], labels, [r.backbone for r in results])
    axes[0, 0].set_title(f"{model} model (1-D, paper's reading), dashed: first loading",
                         fontsize=8)
    return svg_text(fig)


def damping_svg(amplitude: np.ndarray, loss_factor: np.ndarray, dissipated: np.ndarray,
                fe_points: np.ndarray, fe_label: str, case_amplitude: float,
                macroslip: float) -> str:
    """Loss factor and dissipated energy per cycle against the force amplitude: the 1-D curve
    and the FE points (``fe_points`` rows: amplitude N, loss factor, W_d N·mm; may be empty),
    with the case amplitude (dotted) and the macroslip force (dashed)."""
    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=70.0)
    eta, wd = axes[0, 0], axes[0, 1]
    eta.plot(amplitude, loss_factor, color=COLOURS[0], label="1-D model")
    wd.plot(amplitude, dissipated, color=COLOURS[0], label="1-D model")
    if fe_points.shape[0]:
        a, e, w = fe_points[:, 0], fe_points[:, 1], fe_points[:, 2]
        eta.plot(a, e, "o", color=COLOURS[1], ms=4, label=fe_label)
        wd.plot(a, w, "o", color=COLOURS[1], ms=4, label=fe_label)
    for ax in (eta, wd):
        ax.axvline(case_amplitude, color="0.5", lw=0.6, ls=":")
        ax.axvline(macroslip, color="0.3", lw=0.8, ls="--", label="macroslip μ F_N")
        ax.set_xlabel("Force amplitude $F_0$ (N)")
        ax.legend(loc="best", frameon=False)
    eta.set_ylabel("Loss factor η (dimensionless)")
    wd.set_ylabel("Dissipated energy per cycle $W_d$ (N·mm)")
    return svg_text(fig)


def planar_svg(result: PlanarResult) -> str:
    """The planar case's loops and load path (:func:`microslip.plot.paper.figure_planar`)."""
    from .paper import figure_planar

    with tempfile.TemporaryDirectory(prefix="microslip-report-") as tmp:
        path = os.path.join(tmp, "planar.svg")
        with pyplot().rc_context({"svg.fonttype": "path"}):
            figure_planar(result, path)
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    return text[text.index("<svg"):]


def structure_svg(out: Mapping[str, Any]) -> str:
    """The side-by-side figure of ``modal --mesh ... --solver all``'s JSON object ``out``
    (:func:`microslip.plot.ownmesh.compare_figure`)."""
    from .ownmesh import compare_figure

    return svg_text(compare_figure(out))


def mesh_loops_svg(loops: Sequence[tuple[str, Any, Any]], works: Sequence[float]) -> str:
    """Each load's loop over the settled cycle of a run on the user's mesh
    (:func:`microslip.plot.ownmesh.mesh_loops_figure`)."""
    from .ownmesh import mesh_loops_figure

    return svg_text(mesh_loops_figure(loops, works))
