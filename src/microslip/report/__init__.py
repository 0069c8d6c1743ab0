"""A report of the user's own case: one self-contained HTML page.

:func:`write_report` computes and writes the page atomically: for a case of the user's own
mesh, its part (:mod:`~microslip.report.mesh`: the model built, the loops at the case's
loads, the checks, the structure's modes; the page :mod:`~microslip.report.meshhtml`); for a
bar (:mod:`~microslip.report.compute`: 1-D loops, damping against amplitude, the 1-D versus
FE comparison, the validity indicators of :mod:`microslip.models.validity`, the planar
coupling where the case gives a ratio), drawn by :mod:`~microslip.report.figures` (SVG) on
the page of :mod:`~microslip.report.html`. The page has no script and nothing from the
network: it reads the same offline.
Distinct from :mod:`microslip.reproduce`, which reproduces the paper's figures.
"""

from __future__ import annotations

import os
from typing import Any

from ..case.model import Case
from ..io import atomic_write
from .compute import ReportData, ReportSettings, compute_bar_report
from .compute import report_json as _bar_json
from .html import render as _render_bar
from .mesh import MeshReport, compute_mesh_report, mesh_report_json
from .meshhtml import render_mesh
from .part import is_mesh_case

__all__ = ["MeshReport", "ReportData", "ReportSettings", "compute_report", "render",
           "report_json", "write_report"]


def compute_report(case: Case, settings: ReportSettings | None = None, *,
                   progress: bool = True, structure: bool = True) -> ReportData | MeshReport:
    """Every number of the report of ``case``: a case of the user's own mesh (``[mesh]
    file``) gets its part's report (:func:`~.mesh.compute_mesh_report`, no ``[geometry]``
    needed), a bar the bar's (:func:`~.compute.compute_bar_report`); with ``structure`` the
    section of the structure's mode too, when the case's [mesh] gives a file and a
    density."""
    s = settings or ReportSettings()
    if is_mesh_case(case):
        return compute_mesh_report(case, s, progress=progress, structure=structure)
    return compute_bar_report(case, s, progress=progress, structure=structure)


def render(data: ReportData | MeshReport) -> str:
    """The page of a report: a bar's (:func:`~.html.render`) or a mesh case's
    (:func:`~.meshhtml.render_mesh`)."""
    return render_mesh(data) if isinstance(data, MeshReport) else _render_bar(data)


def report_json(data: ReportData | MeshReport) -> dict[str, Any]:
    """Every number of a report's page as one JSON object: a bar's
    (:func:`~.compute.report_json`) or a mesh case's (:func:`~.mesh.mesh_report_json`)."""
    if isinstance(data, MeshReport):
        return mesh_report_json(data)
    return _bar_json(data)


def write_report(case: Case, path: str | os.PathLike[str],
                 settings: ReportSettings | None = None, *, progress: bool = True,
                 structure: bool = True) -> ReportData | MeshReport:
    """Compute the report of ``case`` and write it to ``path`` (never half-written);
    ``structure``: :func:`compute_report`'s (the section of the structure's mode when the
    case's [mesh] gives a file and a density)."""
    data = compute_report(case, settings, progress=progress, structure=structure)
    page = render(data)
    with atomic_write(path) as fh:
        fh.write(page)
    return data
