"""The report page: one HTML file with its style and its figures inside it.

No script, no stylesheet or font from elsewhere: the figures are SVG images embedded as
``data:`` URIs, the style is one ``<style>`` element, so the page reads the same offline.
Every number carries its unit (in the cell or in the column header).
"""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Iterable, Sequence
from typing import Any

from .. import __version__
from ..case.run import MODEL_PORTION, portion_text, tip_portion
from ..case.schema import KEYS
from ..models import MODELS
from .compute import ReportData, comparison
from .figures import damping_figure, loops_figure, planar_figure, structure_figure

__all__ = ["bar_sections", "render"]

STYLE = """
body{font-family:sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;color:#222}
h1{font-size:1.5rem}h2{font-size:1.2rem;margin-top:2rem;border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:.5rem 0}td,th{border:1px solid #ccc;padding:.2rem .5rem}
td.num{text-align:right;font-variant-numeric:tabular-nums}th{background:#f3f3f3}
figure{margin:1rem 0}figure img{max-width:100%;height:auto}figcaption{font-size:.9rem}
.warn{color:#8a4b00}.note{color:#555;font-size:.9rem}
"""


def _e(text: Any) -> str:
    return html.escape(str(text), quote=True)


def _num(x: float, digits: int = 6) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.{digits}g}"


def _table(header: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f'<td class="num">{_e(_num(c))}</td>' if isinstance(c, float)
                         else f"<td>{_e(c)}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def _figure(svg: str, caption: str) -> str:
    uri = "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")
    return (f'<figure><img src="{uri}" alt="{_e(caption)}"><figcaption>{_e(caption)}'
            "</figcaption></figure>")


def _inputs(data: ReportData) -> str:
    case = data.case
    rows: list[Sequence[Any]] = []
    for key in KEYS:
        value = case.get(key.dotted)
        if value is None or (key.dotted not in case.values and key.dotted.startswith("load.")):
            continue
        shown = value if isinstance(value, str) else _num(float(value))
        source = "case file" if key.dotted in case.values else (
            "preset" if key.default == "from preset" else "default")
        rows.append((key.dotted, shown, key.unit or "dimensionless", source, key.meaning))
    s = data.settings
    derived = [
        ("load amplitude F0", _num(data.amplitude), "N", "case", "the case's load"),
        ("macroslip force", _num(data.macroslip), "N", "derived", "mu F_N: the whole "
         "interface slips"),
        ("1-D increments", s.increments, "dimensionless", "report", "force increments of "
         "each first loading"),
        ("FE solver, mesh", f"{s.fe_solver}, {s.mesh}", "", "report", "finite-element runs"),
        ("FE substeps", s.substeps, "dimensionless", "report", "over t = 0..1.25 s"),
    ]
    return (_table(("input", "value", "unit", "from", "meaning"), rows)
            + _table(("setting", "value", "unit", "from", "meaning"), derived))


def _comparison(data: ReportData) -> str:
    rows = comparison(data)
    portion = portion_text(MODEL_PORTION[data.model])
    note = (f'<p class="note">W_d and U of {_e(portion)}, as <code>microslip loop</code> and '
            "<code>microslip fe</code> print them for this case.</p>")
    if data.fe is None:
        return _table(("at the case amplitude", "1-D model"),
                      [(name, x) for name, x, _, _ in rows]) + note
    warn = ("" if data.fe.converged else
            '<p class="warn">The FE run did not converge at every increment.</p>')
    return _table(("at the case amplitude", "1-D model", f"FE ({data.settings.fe_solver})",
                   "1-D / FE - 1 (%)"), rows) + note + warn


def _validity(data: ReportData) -> str:
    r, s = data.validity_rigid, data.validity_layer
    rows = [("slenderness L/t", r.slenderness, s.slenderness),
            ("slip fraction a/L at the peak", r.slip_fraction, s.slip_fraction),
            ("d ln W_d / d ln k_c", r.stiffness_sensitivity, s.stiffness_sensitivity),
            ("shear-lag effect on W_d", r.shear_lag_effect, s.shear_lag_effect)]
    table = _table(("indicator (dimensionless)", "rigid foundation (paper)",
                    f"shear layer, k_c = {data.stick_slope:g} N/mm^3"), rows)
    warnings = [*(f"rigid foundation: {w}" for w in r.warnings),
                *(f"shear layer: {w}" for w in s.warnings)]
    items = "".join(f'<li class="warn">{_e(w)}</li>' for w in warnings)
    return table + (f"<ul>{items}</ul>" if warnings else
                    "<p>No validity warning: the 1-D model applies to this case.</p>")


def _planar(data: ReportData) -> str:
    p = data.planar_run
    if data.planar_error is not None:
        return (f'<p class="warn">The planar load of the case cannot be computed: '
                f"{_e(data.planar_error)}</p>")
    if p is None:
        return ('<p class="note">The case gives no planar load (load.planar.ratio or both '
                "planar amplitudes): no coupling to report.</p>")
    r, k = p.result, p.inputs.tip_symmetry
    w = r.work
    rows = [(name, x.dissipated_energy, x.strain_energy, x.loss_factor, portion_text(part))
            for name, x, part in (("tip model", r.tip, tip_portion(k)),
                                  ("centre model", r.centre, MODEL_PORTION["centre"]),
                                  ("paper's resultant (Eqs 19-23)", r.paper, "mixed"))]
    rows.append(("work of the load", w.dissipated_energy, w.strain_energy, w.loss_factor,
                 portion_text("whole")))
    intro = (f"<p>Force ratio R = {_num(r.ratio)} (dimensionless), eccentricity "
             f"{_num(r.eccentricity, 4)} (dimensionless), tip {_num(r.tip_amplitude)} N, centre "
             f"{_num(r.centre_amplitude)} N, phase {_num(r.phase_deg)} degrees; the case's "
             f"clamp, its tip zone one of {k} symmetric parts of the width "
             f"(w = {_num(p.inputs.tip_params.width)} mm), as "
             "<code>microslip planar --case</code>.</p>")
    return (intro + _table(("", "W_d (N·mm)", "U (N·mm)", "η (dimensionless)", "W_d of"),
                           rows)
            + _figure(planar_figure(data), "Planar case: loops of the tip, centre and "
                      "resultant models; load path in the force plane (N)."))


def _structure(data: Any) -> str:
    """The damping of the structure's mode on the case's mesh: every solver side by side, the
    verdicts, the figure; or what the case lacks for it (``data``: a bar's
    :class:`ReportData` or a mesh case's :class:`~.mesh.MeshReport`, their ``structure``
    and ``case``)."""
    out = data.structure
    if out is None and "mesh.file" in data.case.values:
        return (f'<p class="note">The case\'s mesh {_e(str(data.case.values["mesh.file"]))} '
                "has no density ([mesh] density, kg/m^3, or one in every [[mesh.material]]): "
                "its modes and their damping are not reported.</p>")
    if out is None:
        return ('<p class="note">The case gives no mesh of the structure with its density '
                "([mesh] file, density; mode and response_set optional): no structure to "
                "report.</p>")
    n = out["mode"]
    intro = (f"<p>Mesh {_e(out['mesh'])}, mode {n} ({_e(out['label'])}): stuck "
             f"{_num(out['linear_frequencies_Hz'][n - 1])} Hz, free "
             f"{_num(out['free_frequencies_Hz'][n - 1])} Hz, density "
             f"{_num(float(out['density_kg_m3']))} kg/m^3; every solver on one amplitude grid, "
             "as <code>microslip modal --mesh FILE --solver all</code>.</p>")
    lim = out.get("amplitude_limit")
    if lim:
        intro += (f"<p>Amplitude limit {_num(float(lim['limit_mm']), 4)} mm "
                  f"({_e(lim['reason'])}): the automatic grid runs from first slip to it or "
                  "to near gross sliding, whichever comes first.</p>")
    if out.get("structural_damping_ratio"):
        intro += (f"<p>Every model carries a structural damping ratio of "
                  f"{_num(float(out['structural_damping_ratio']))} (dimensionless) on every "
                  "mode.</p>")
    rows = [(name, v["verdict"]) for name, v in out["verdicts"].items()]
    table = _table(("model", "against the full FE at equal amplitude (microslip range)"),
                   rows) if rows else ""
    warnings = "".join(f'<li class="warn">{_e(w)}</li>' for w in out["warnings"])
    return (intro + table + (f"<ul>{warnings}</ul>" if warnings else "")
            + _figure(structure_figure(data), "Natural frequency (Hz) and damping ratio "
                      "(dimensionless) against the response set's amplitude (mm) for every "
                      "solver; below, the full FE's contact nodes in the contact plane (mm), "
                      "stick, slip or open over the settled cycle, at three amplitudes."))


def bar_sections(data: ReportData) -> list[str]:
    """The 1-D bar's sections of a page: its inputs, the 1-D model against the FE, the
    validity, the loops, the damping against amplitude and the planar coupling."""
    return [
        "<h2>Inputs</h2>", _inputs(data),
        "<h2>1-D model against finite elements</h2>", _comparison(data),
        "<h2>Validity of the 1-D model</h2>", _validity(data),
        "<h2>Hysteresis loops</h2>",
        _figure(loops_figure(data), "Force against displacement of the loaded section: Masing "
                "loops (solid) and first loadings (dashed), force in N, displacement in mm."),
        "<h2>Damping against amplitude</h2>",
        _figure(damping_figure(data), "Loss factor (dimensionless) and dissipated energy per "
                "cycle (N·mm) against the force amplitude (N); dotted: the case amplitude."),
        "<h2>Planar coupling</h2>", _planar(data),
    ]


def render(data: ReportData) -> str:
    """The whole page of a bar's report (a mesh case's: :func:`~.meshhtml.render_mesh`)."""
    case = data.case
    title = case.name or (case.source or "microslip case")
    spec = MODELS[data.model]
    warnings = "".join(f'<li class="warn">{_e(w)}</li>' for w in case.warnings)
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{_e(title)}: microslip report</title><style>{STYLE}</style></head><body>",
        f"<h1>{_e(title)}</h1>",
        f"<p>{_e(case.get('description') or '')}</p>",
        f'<p class="note">Case file {_e(case.source)}; microslip {_e(__version__)}; '
        f"{_e(spec.label)} ({_e(spec.equations)}). Units: N, mm, MPa, N·mm.</p>",
        f"<ul>{warnings}</ul>" if warnings else "",
        *bar_sections(data),
        "<h2>Damping of the structure's mode</h2>", _structure(data),
        "</body></html>",
    ]
    return "\n".join(p for p in parts if p) + "\n"
