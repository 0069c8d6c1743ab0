"""What the figures show, not only that a PNG was written.

Every figure a command saves is captured at ``savefig``: each panel that holds data must have
both axes labelled with a unit, and no infinite or all-NaN line; the loop figure must draw the
loop that the same command reports in JSON.
"""

from __future__ import annotations

import json
import re

import matplotlib
import numpy as np
import pytest

from microslip.cli.main import main

matplotlib.use("Agg")
from matplotlib.figure import Figure

#: a unit in a label: "(mm)", "[N]", "/ N·mm", or a dimensionless quantity said as such
UNIT = re.compile(r"\([^)]*\)\s*$|\[[^\]]*\]\s*$|/\s*\S+\s*$|\((?:-|–|1|dimensionless)\)")


@pytest.fixture
def saved(monkeypatch):
    figures: list[Figure] = []
    real = Figure.savefig

    def record(self, *args, **kwargs):
        figures.append(self)
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", record)
    return figures


def _panels_with_data(fig: Figure):
    return [ax for ax in fig.axes if ax.lines or ax.collections or ax.patches or ax.images]


def _check_axes(fig: Figure, what: str) -> None:
    panels = _panels_with_data(fig)
    assert panels, f"{what}: no panel holds data"
    for ax in panels:
        for label in (ax.get_xlabel(), ax.get_ylabel()):
            assert label and UNIT.search(label), f"{what}: axis label {label!r} has no unit"
        for line in ax.lines:
            x = np.asarray(line.get_xdata(), dtype=float)
            y = np.asarray(line.get_ydata(), dtype=float)
            # NaN is a gap (a case not computed, said in the output); inf is never drawn
            assert not np.any(np.isinf(x)) and not np.any(np.isinf(y)), f"{what}: inf drawn"
            assert np.any(np.isfinite(x) & np.isfinite(y)) or not x.size, f"{what}: empty line"


COMMANDS = {
    "loop": ["loop", "--model", "tip", "--increments", "200"],
    "planar": ["planar", "--ratio", "2", "--phase", "90", "--increments", "100"],
    "sweep": ["sweep", "--model", "tip", "--preset", "table2-tip", "--amplitude-range", "1000",
              "8000", "--cases", "8", "--increments", "100", "--no-progress"],
    "sweep-planar": ["sweep", "--model", "planar", "--ratio-range", "0.25", "4", "--cases",
                     "6", "--increments", "100", "--no-progress"],
    "joint": ["joint", "--joint", "jenkins", "--joint-stiffness", "100", "--slip-force", "5",
              "--amplitude-range", "0.01", "1"],
}


@pytest.mark.parametrize("name", list(COMMANDS))
def test_every_panel_has_units_and_finite_data(name, saved, tmp_path, capsys):
    argv = COMMANDS[name] + ["--plot", str(tmp_path / "f.png")]
    if name.startswith("sweep"):
        argv += ["--out", str(tmp_path / "s.csv")]
    assert main(argv) == 0, capsys.readouterr().err
    assert saved, f"{name} saved no figure"
    for fig in saved:
        _check_axes(fig, name)


def test_loop_figure_draws_the_reported_loop(saved, tmp_path, capsys):
    assert main(COMMANDS["loop"] + ["--json", "--plot", str(tmp_path / "f.png")]) == 0
    loop = json.loads(capsys.readouterr().out)["loop"]
    force = np.array(loop["force_N"])
    disp = np.array(loop["displacement_mm"])
    (fig,) = saved
    drawn = [(np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float))
             for ax in fig.axes for ln in ax.lines if len(ln.get_xdata()) == force.size]
    assert drawn, "no line with the loop's number of points"
    # the drawn loop is the reported one, up to the axis scale (mm or um, N or kN)
    assert any(np.allclose(x / np.abs(x).max(), disp / np.abs(disp).max(), rtol=0, atol=1e-12)
               and np.allclose(y / np.abs(y).max(), force / np.abs(force).max(), rtol=0,
                               atol=1e-12) for x, y in drawn)


# --- figures ---------------------------------------------------------------------------------

def _figure_of(monkeypatch):
    import microslip.plot.core as core

    saved = []
    monkeypatch.setattr(core, "save_figure", lambda fig, path: saved.append(fig))
    for module in ("microslip.plot.sweep",):
        monkeypatch.setattr(f"{module}.save_figure", lambda fig, path: saved.append(fig))
    return saved


def test_sweep_figure_has_eta_and_wd_panels_without_offsets(monkeypatch, tmp_path):
    from microslip import preset
    from microslip.plot.sweep import plot_sweep
    from microslip.sweep import make_sweep, run_sweep

    saved = _figure_of(monkeypatch)
    spec = make_sweep("tip", preset("table2-tip"), grid=[("amplitude", [1000.0, 1000.5, 1001.0]),
                      ("normal_force", [15000.0, 20000.0])], increments=50)
    plot_sweep(run_sweep(spec, progress=False), tmp_path / "s.png")
    (fig,) = saved
    fig.canvas.draw()
    eta_ax, wd_ax = fig.axes
    assert "Loss factor" in eta_ax.get_ylabel() and "$W_d$ (N·mm)" in wd_ax.get_ylabel()
    for ax in fig.axes:
        assert ax.yaxis.get_major_formatter().get_offset() == ""
    labels = [t.get_text() for t in eta_ax.get_legend().get_texts()]
    assert labels == ["normal force = 15000 N", "normal force = 20000 N"]  # the unit once


def test_sweep_figure_bands_carry_the_series_colour(monkeypatch, tmp_path):
    from matplotlib.colors import to_hex

    from microslip import preset
    from microslip.plot.core import COLOURS
    from microslip.plot.sweep import plot_sweep
    from microslip.sweep import make_sweep, run_sweep
    from microslip.sweep.parameters import Distribution

    saved = _figure_of(monkeypatch)
    spec = make_sweep("tip", preset("table2-tip"), grid=[("amplitude", [1000.0, 4000.0])],
                      samples=[("friction", Distribution("uniform", 0.7, 0.9))], n_samples=20,
                      seed=2, increments=50)
    plot_sweep(run_sweep(spec, progress=False), tmp_path / "s.png")
    legend = saved[0].axes[0].get_legend()
    patches = [h for h in legend.legend_handles if hasattr(h, "get_facecolor")
               and not hasattr(h, "get_xdata")]
    assert patches and {to_hex(p.get_facecolor(), keep_alpha=False) for p in patches} == {
        COLOURS[0].lower()}


def test_small_loops_are_drawn_in_micrometres(monkeypatch, tmp_path):
    import microslip.plot.core as core
    from microslip import damping, preset

    saved = []
    monkeypatch.setattr(core, "save_figure", lambda fig, path: saved.append(fig))
    result = damping("tip", preset("table1"), 267.0, 100)
    core.plot_damping(result, tmp_path / "x.png")
    ax = saved[0].axes[0]
    assert ax.get_xlabel() == "Displacement δ (µm)"
    x = ax.get_lines()[0].get_xdata()
    assert max(abs(x)) == pytest.approx(1000 * max(abs(result.loop.displacement)), rel=1e-15)
    saved[0].canvas.draw()
    assert ax.xaxis.get_major_formatter().get_offset() == ""
