"""The figures of a report, each returned as the text of a self-contained SVG image.

This module picks each figure's data from :class:`~microslip.report.compute.ReportData`;
:mod:`microslip.plot.report` draws them.
"""

from __future__ import annotations

from typing import Any

from ..plot.report import damping_svg, loops_svg, planar_svg, structure_svg
from .compute import LOOP_FRACTIONS, ReportData

__all__ = ["damping_figure", "loops_figure", "planar_figure", "structure_figure"]


def loops_figure(data: ReportData) -> str:
    """Masing loops and backbones of the 1-D model at fractions of the case amplitude."""
    return loops_svg(data.loops, LOOP_FRACTIONS, data.model)


def damping_figure(data: ReportData) -> str:
    """Loss factor and dissipated energy per cycle against the force amplitude: 1-D curve and
    the FE points."""
    return damping_svg(data.curve_amplitude, data.curve_loss_factor, data.curve_dissipated,
                       data.fe_curve, f"FE ({data.settings.fe_solver}, mesh {data.settings.mesh})",
                       data.amplitude, data.macroslip)


def planar_figure(data: ReportData) -> str:
    """The planar case's loops and load path."""
    return planar_svg(data.planar)


def structure_figure(data: Any) -> str:
    """Every solver's frequency and damping ratio against amplitude on the case's mesh, and
    the full FE's contact slip pattern."""
    assert data.structure is not None
    return structure_svg(data.structure)
