"""The report page of a case of the user's own mesh (issue 34 item 3): the part, its loads,
what the solver built, the loops at the case's loads, the checks and the structure's modes;
the 1-D bar's sections only when asked (``report --bar``). The same self-contained page as
the bar's (:mod:`.html`: one style element, SVG figures as ``data:`` URIs, no script)."""

from __future__ import annotations

from typing import Any

from .. import __version__
from ..case.schema import KEYS
from .html import STYLE, _e, _figure, _num, _structure, _table, bar_sections
from .mesh import MeshReport

__all__ = ["render_mesh"]

#: The case-file sections of a part, in the order the inputs table lists them.
PART_SECTIONS = ("", "material", "contact", "clamping", "mesh")


def _loads(data: MeshReport) -> str:
    loads = data.case.mesh_loads
    if not loads:
        return ('<p class="warn">The case gives no loads ([[mesh.load]] tables: set, '
                "direction, amplitude, phase_deg): no loops to report; <code>fe --case</code> "
                "needs them too.</p>")
    rows = [(k, ld.set, ", ".join(f"{x:g}" for x in ld.direction), float(ld.amplitude),
             float(ld.phase_deg)) for k, ld in enumerate(loads, 1)]
    return _table(("load", "set", "direction (global x, y, z)", "amplitude A (N)",
                   "phase (degrees)"), rows)


def _model(data: MeshReport) -> str:
    m = data.model
    head = (f"<p>{_e(m.get('nodes'))} nodes, {_e(m.get('elements'))} elements "
            f"({_e(m.get('element'))}), {_e(m.get('dof'))} DOF, {_e(m.get('bodies'))} "
            f"bod{'y' if m.get('bodies') == 1 else 'ies'}; {_e(m.get('normal_contact'))} "
            f"normal contact; {_e(m.get('contact_nodes'))} contact nodes, "
            f"{_e(m.get('closed_after_preload'))} closed and "
            f"{_e(m.get('open_after_preload'))} open after the preload, contact force "
            f"{_num(float(m.get('contact_force_N', float('nan'))))} N. As "
            "<code>fe --mesh</code> prints it (the JSON's <code>model</code>): check the "
            "areas against the part.</p>")
    rows = []
    for name, s in m.get("sets", {}).items():
        rows.append((name, s.get("role", ""), s.get("faces", "–"),
                     float(s["area_mm2"]) if "area_mm2" in s else "node set",
                     float(s["force_N"]) if "force_N" in s else "–",
                     float(s["pressure_MPa"]) if "pressure_MPa" in s else "–",
                     s.get("directions", "")))
    return head + _table(("set", "role", "faces", "area (mm^2)", "force (N)",
                          "pressure F/A (MPa)", "held directions"), rows)


def _inputs(data: MeshReport) -> str:
    case = data.case
    rows: list[tuple[Any, ...]] = []
    from ..case.template import MESH_UNUSED_KEYS

    for key in KEYS:
        if (key.section not in PART_SECTIONS or key.dotted.startswith("load.")
                or key.dotted in MESH_UNUSED_KEYS or key.dotted == "name"):
            continue
        value = case.get(key.dotted)
        if value is None or value == "" or isinstance(value, tuple):
            continue
        if key.default == "from preset" and key.dotted not in case.values:
            continue
        shown = value if isinstance(value, str) else _num(float(value))
        source = "case file" if key.dotted in case.values else "default"
        rows.append((key.dotted, shown, key.unit or "dimensionless", source, key.meaning))
    from ..case.schema import TABLE_KEYS

    for dotted in TABLE_KEYS:
        for k, piece in enumerate(case.values.get(dotted, ()), 1):
            rows.append((f"[[{dotted}]] {k}", _piece(piece), "", "case file", ""))
    s = data.settings
    settings = [("FE solver", s.fe_solver, "", "report", "the run at the case's loads"),
                ("FE substeps", s.substeps, "dimensionless", "report",
                 "over 1.25 cycles (4/5 of them per cycle)")]
    return (_table(("input", "value", "unit", "from", "meaning"), rows)
            + _table(("setting", "value", "unit", "from", "meaning"), settings))


def _piece(piece: Any) -> str:
    """One assembly table in words, with units."""
    from ..case.assembly import Bolt
    from ..fe.assembly import Contact, Material, Preload, Support

    if isinstance(piece, Bolt):
        shank = ("no shank" if piece.diameter is None else
                 f"a shank of {piece.diameter:.6g} mm")
        return f"{piece.force:.6g} N on {piece.head} and on {piece.nut}, {shank}"
    if isinstance(piece, Contact):
        return (f"{piece.face} on {piece.counter}" if piece.counter is not None
                else f"{piece.face} on the rigid base")
    if isinstance(piece, Preload):
        return f"{piece.force:.6g} N on {piece.face}"
    if isinstance(piece, Support):
        return f"{piece.set} held in {piece.directions}"
    if isinstance(piece, Material):
        rho = "" if piece.density is None else f", {piece.density:.6g} kg/m^3"
        return f"{piece.elset}: {piece.modulus:.6g} MPa, nu {piece.poisson_ratio:.6g}{rho}"
    return repr(piece)


def _loops(data: MeshReport) -> str:
    if not data.case.mesh_loads:
        return ""
    if data.fe is None:
        why = (data.fe_error if data.fe_error is not None else
               "the report ran without FE runs (--no-fe)")
        return f'<p class="warn">No loops: {_e(why)}.</p>'
    fe = data.fe
    tol = fe.get("work_tolerance_Nmm")
    rows = [(k, ld["set"], float(ld["amplitude_N"]), float(ld["work_Nmm"]),
             float(ld["peak_displacement_mm"])) for k, ld in enumerate(fe["loads"], 1)]
    settled = "settled" if fe.get("settled", True) else "did NOT settle"
    intro = (f"<p>The case's loads on its mesh {_e(data.mesh_file)}, as "
             f"<code>fe --case</code> runs them ({_e(fe.get('solver', ''))} solver, "
             f"{_e(fe.get('element', ''))}): dissipated energy W = "
             f"{_num(float(fe['dissipated_energy_Nmm']))} N·mm per cycle (the whole "
             f"interface), first load's peak displacement "
             f"{_num(float(fe['peak_displacement_mm']))} mm; W per cycle {settled} after "
             f"{_e(fe.get('cycles'))} cycles"
             + (f" (W below {_num(float(tol), 2)} N·mm is the solver's rounding)"
                if tol is not None else "") + ".</p>")
    table = _table(("load", "set", "amplitude A (N)", "work over the cycle (N·mm)",
                    "peak displacement (mm)"), rows)
    figure = ""
    if data.loops:
        from ..plot.report import mesh_loops_svg

        figure = _figure(mesh_loops_svg(data.loops, [r[3] for r in rows]),
                         "Each load's force (N) against its work-conjugate displacement "
                         "over the settled cycle (mm, or µm for small loops).")
    return intro + table + figure


def _checks(data: MeshReport) -> str:
    items = "".join(f'<li class="warn">{_e(w)}</li>' for w in data.checks)
    if not items:
        return ("<p>No check raised a warning: the sets, the materials, the bodies and the "
                "values against the part's size passed, and every run settled.</p>")
    return (f"<p>{len(data.checks)} warning(s) on the part (an error would have stopped the "
            "report):</p><ul>" + items + "</ul>")


def render_mesh(data: MeshReport) -> str:
    """The whole page of a mesh case's report."""
    case = data.case
    title = case.name or (case.source or "microslip case")
    loads = "; ".join(f"{ld.amplitude:g} N on {ld.set} along "
                      f"({', '.join(f'{x:g}' for x in ld.direction)})"
                      for ld in case.mesh_loads) or "no loads"
    warnings = "".join(f'<li class="warn">{_e(w)}</li>' for w in case.warnings)
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{_e(title)}: microslip report</title><style>{STYLE}</style></head><body>",
        f"<h1>{_e(title)}</h1>",
        f"<p>{_e(case.get('description') or '')}</p>",
        f'<p class="note">Case file {_e(case.source)}; mesh {_e(data.mesh_file)}; loads: '
        f"{_e(loads)}; microslip {_e(__version__)}. Units: N, mm, MPa, N·mm, kg/m^3.</p>",
        f"<ul>{warnings}</ul>" if warnings else "",
        "<h2>The part and its loads</h2>", _loads(data),
        "<h2>What the solver built</h2>", _model(data),
        "<h2>Inputs</h2>", _inputs(data),
        "<h2>Loops at the case's loads</h2>", _loops(data) or _loads(data),
        "<h2>Checks</h2>", _checks(data),
        "<h2>Damping of the structure's mode</h2>", _structure(data),
    ]
    if data.bar is not None:
        parts += ['<h2>The 1-D bar of the case\'s [geometry] (asked: --bar)</h2>',
                  '<p class="note">The sections below describe the bar of the case\'s preset '
                  "and [geometry], not the mesh above: the paper's 1-D models and the box FE "
                  "on that bar.</p>", *bar_sections(data.bar)]
    parts.append("</body></html>")
    return "\n".join(p for p in parts if p) + "\n"
