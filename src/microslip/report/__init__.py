"""A report of the user's own case: one self-contained HTML page.

:func:`write_report` computes (:mod:`~microslip.report.compute`: 1-D loops, damping against
amplitude, the 1-D versus FE comparison, the validity indicators of
:mod:`microslip.models.validity`, the planar coupling where the case gives a ratio), draws
(:mod:`~microslip.report.figures`, SVG) and writes the page (:mod:`~microslip.report.html`)
atomically. The page has no script and nothing from the network: it reads the same offline.
Distinct from :mod:`microslip.reproduce`, which reproduces the paper's figures.
"""

from __future__ import annotations

import os

from ..case.model import Case
from ..io import atomic_write
from .compute import ReportData, ReportSettings, compute_report, report_json
from .html import render

__all__ = ["ReportData", "ReportSettings", "compute_report", "render", "report_json",
           "write_report"]


def write_report(case: Case, path: str | os.PathLike[str],
                 settings: ReportSettings | None = None, *, progress: bool = True,
                 structure: bool = True) -> ReportData:
    """Compute the report of ``case`` and write it to ``path`` (never half-written);
    ``structure``: :func:`~microslip.report.compute.compute_report`'s (the section of the
    structure's mode when the case's [mesh] gives a file and a density)."""
    data = compute_report(case, settings, progress=progress, structure=structure)
    page = render(data)
    with atomic_write(path) as fh:
        fh.write(page)
    return data
