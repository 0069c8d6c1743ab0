"""Every figure lives in :mod:`microslip.plot` (issue 21, item 5): no other module imports
matplotlib, ``import microslip.plot`` does not import it, and each figure moved there draws
with a unit on every labelled axis."""

from __future__ import annotations

import ast
import functools
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import microslip

SRC = Path(microslip.__file__).parent


@functools.cache
def imports_outside_plot(src: Path = SRC) -> list[tuple[str, str, list[str]]]:
    """(module:line, imported module, names) of every import outside microslip/plot, those
    inside functions included (``ast.walk`` visits every node); ``import a.b`` gives
    ("a.b", []), ``from ..a import b`` ("a", ["b"])."""
    found = []
    for path in sorted(src.rglob("*.py")):
        rel = path.relative_to(src)
        if rel.parts[0] == "plot":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            where = f"{rel.as_posix()}:{getattr(node, 'lineno', 0)}"
            if isinstance(node, ast.Import):
                found += [(where, a.name, []) for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                found.append((where, node.module or "", [a.name for a in node.names]))
    return found


def matplotlib_importers(src: Path = SRC) -> list[str]:
    """Modules outside microslip/plot that import matplotlib, anywhere in their body."""
    return [where for where, module, _ in imports_outside_plot(src)
            if module == "matplotlib" or module.startswith("matplotlib.")]


#: The drawing primitives of microslip.plot.core: only the plot package draws with them.
DRAWING = {"new_figure", "save_figure", "plot_loops", "COLOURS", "displacement_scale"}


def drawing_importers(src: Path = SRC) -> list[str]:
    """Modules outside microslip/plot that import a drawing primitive of the plot package."""
    return [where for where, module, names in imports_outside_plot(src)
            if module.split(".")[-1] in ("plot", "core") and "plot" in module.split(".")
            and DRAWING & set(names)]


def test_only_the_plot_package_imports_matplotlib():
    assert matplotlib_importers() == []


def test_only_the_plot_package_draws():
    assert drawing_importers() == []


def test_the_scan_sees_an_import_inside_a_function(tmp_path):
    """The scan finds a function-level ``from matplotlib.x import y`` (as validate.py had)
    and a drawing primitive imported from the plot package outside it."""
    fake = tmp_path / "microslip"
    (fake / "plot").mkdir(parents=True)
    (fake / "plot" / "ok.py").write_text("import matplotlib.pyplot as plt\n")
    (fake / "bad.py").write_text("def f():\n    from matplotlib.colors import X\n")
    (fake / "cli").mkdir()
    (fake / "cli" / "x.py").write_text("def g():\n    from ..plot import COLOURS, pyplot\n"
                                       "    import matplotlib\n")
    assert matplotlib_importers(fake) == ["bad.py:2", "cli/x.py:3"]
    assert drawing_importers(fake) == ["cli/x.py:2"]


def test_importing_the_plot_package_does_not_import_matplotlib():
    code = ("import sys, microslip.plot, microslip.plot.dynamics, microslip.plot.validation, "
            "microslip.plot.report; print('matplotlib' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    assert done.stdout.strip() == "False"


# -- every moved figure draws, with a unit on each labelled axis ------------------------------
#: A unit in parentheses or brackets, "(-)" and "(dimensionless)" included.
UNIT = re.compile(r"\([^()]+\)|\[[^\[\]]+\]")


@pytest.fixture
def drawn(monkeypatch):
    """Every figure saved while the test runs (matplotlib's Agg backend)."""
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    from microslip.plot import pyplot

    pyplot()  # the package's style and the Agg backend
    figures: list[Figure] = []
    save = Figure.savefig

    def record(self, *args, **kwargs):
        figures.append(self)
        return save(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", record)
    return figures


def labels(fig) -> tuple[list[str], list[str]]:
    """The non-empty x and y labels of the figure's visible axes."""
    axes = [ax for ax in fig.axes if ax.get_visible()]
    return ([ax.get_xlabel() for ax in axes if ax.get_xlabel()],
            [ax.get_ylabel() for ax in axes if ax.get_ylabel()])


def assert_units(figures, n: int = 1) -> None:
    assert len(figures) == n
    for fig in figures:
        xs, ys = labels(fig)
        assert xs and ys, "a figure without axis labels"
        for text in xs + ys:
            assert UNIT.search(text), f"no unit in the axis label {text!r}"


def test_the_unit_check_can_fail(drawn, tmp_path):
    from microslip.plot.core import new_figure, save_figure

    fig, axes = new_figure()
    axes[0, 0].set_xlabel("force")
    axes[0, 0].set_ylabel("displacement (mm)")
    save_figure(fig, tmp_path / "bad.png")
    with pytest.raises(AssertionError, match="no unit in the axis label 'force'"):
        assert_units(drawn)


A = np.geomspace(1e-3, 0.1, 6)


def test_describing_function(drawn, tmp_path):
    from microslip.dynamics.describing import DescribingFunction
    from microslip.plot.dynamics import plot_describing_function

    k = 1000.0 / (1.0 + A / 0.01)
    result = DescribingFunction("iwan", A, k * A, k, 0.1 * k, np.pi * 0.1 * k * A**2,
                                np.full(A.size, 0.1), 64)
    plot_describing_function(result, tmp_path / "joint.png")
    assert (tmp_path / "joint.png").stat().st_size > 1000
    assert_units(drawn)


def modal_curve(method: str, shift: float = 0.0):
    from microslip.dynamics.modal import ModalCurve

    return ModalCurve(method, A, 100.0 - 5.0 * A / A[-1] + shift, 0.01 + 0.02 * A / A[-1],
                      1, 64)


@pytest.mark.parametrize("same", [True, False])
def test_modal(drawn, tmp_path, same):
    from microslip.plot.dynamics import plot_modal

    curve = modal_curve("epmc")
    plot_modal(curve, curve if same else modal_curve("energy", 0.1), tmp_path / "modal.png")
    assert_units(drawn)


@pytest.mark.parametrize("orbit", [False, True])
def test_frequency_response(drawn, tmp_path, orbit):
    from microslip.dynamics.response import FrequencyResponse
    from microslip.plot.dynamics import plot_frequency_response

    f = np.linspace(90.0, 110.0, 30)
    a = 0.1 / (1.0 + ((f - 100.0) / 2.0) ** 2)
    curve = FrequencyResponse(2.0, f, a, np.zeros((f.size, 3)), float(a.max()), 100.0, 1, 64,
                              True, "")
    theta = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    orbits = [[{"joint": 0, "frequency_Hz": 100.0, "x_mm": 0.1 * np.cos(theta),
                "y_mm": 0.05 * np.sin(theta)}]] if orbit else [[]]
    plot_frequency_response([curve], modal_curve("epmc"), orbits, tmp_path / "frf.png")
    assert_units(drawn)
    assert len(drawn[0].axes) == (2 if orbit else 1)


def test_joint_against_fe(drawn, tmp_path):
    from microslip.plot.dynamics import figure_joint_fe

    theta = np.linspace(0.0, 2 * np.pi, 32, endpoint=False)
    orbit = np.column_stack([1e-3 * np.cos(theta), 2e-3 * np.sin(theta)])
    force = np.column_stack([50 * np.cos(theta + 0.2), 80 * np.sin(theta + 0.2)])
    joints = {"circular": "isotropic circular", "decoupled": "decoupled sum"}
    run = SimpleNamespace(orbit=orbit, fe_force=force,
                          joint_force={k: 1.1 * force for k in joints})
    figure_joint_fe(tmp_path / "fig13.png", [1.0, 4.0], joints,
                    {"circular": [1.1, 1.2], "decoupled": [0.9, 0.8]}, run, 1.0)
    assert_units(drawn)


def test_contact_status(drawn, tmp_path):
    from microslip.plot.validation import StatusPanel, figure_contact_status

    status = np.ones((5, 3), dtype=np.int64)
    status[3:] = 2
    panels = [[StatusPanel(case, t, 100.0 * t, np.linspace(0, 100, 6), np.linspace(0, 20, 4),
                           status, 100.0, 20.0, 50.0 if case == "centre" else None, (60.0,))
               for t in (0.25, 0.5)] for case in ("tip", "centre")]
    figure_contact_status(panels, tmp_path / "fig08.png")
    assert_units(drawn)


def masing_loop(amplitude: float):
    """A Masing loop of the quadratic backbone delta = F^2 / c (N, mm)."""
    from microslip.results import HysteresisLoop

    f = amplitude * np.cos(np.linspace(0.0, 2 * np.pi, 41))
    c = 2e6
    d = np.where(np.arange(f.size) <= 20, amplitude**2 / c - 2 * ((amplitude - f) / 2) ** 2 / c,
                 -(amplitude**2) / c + 2 * ((amplitude + f) / 2) ** 2 / c)
    return HysteresisLoop(f, d)


def test_fe_against_model(drawn, tmp_path):
    from microslip.plot.validation import LoopPanel, figure_fe_vs_model

    loop = masing_loop(100.0)
    figure_fe_vs_model([LoopPanel("tip", 100.0, loop, loop, (("coarse", loop),))],
                       tmp_path / "fig09.png")
    assert_units(drawn)


def test_report_figures(drawn):
    from microslip.plot.report import damping_svg, loops_svg
    from microslip.results import DampingResult

    results = [DampingResult(0.1, 1.0, "secant", 0.016, f, f * f / 2e6, masing_loop(f))
               for f in (50.0, 100.0)]
    svg = loops_svg(results, (0.5, 1.0), "tip")
    amplitude = np.linspace(10.0, 250.0, 5)
    svg2 = damping_svg(amplitude, 0.01 * amplitude / 250, 1e-4 * amplitude**3 / 250**2,
                       np.array([[100.0, 0.004, 0.3]]), "FE (builtin, mesh tiny)", 100.0, 267.0)
    assert svg.startswith("<svg") and svg2.startswith("<svg")
    assert_units(drawn, 2)


def test_report_planar_figure(drawn):
    from microslip import preset
    from microslip.planar import planar_damping
    from microslip.plot.report import planar_svg

    result = planar_damping(preset("table2-tip"), preset("table2-centre"), 400.0, 300.0,
                            increments=100, samples_per_cycle=256)
    assert planar_svg(result).startswith("<svg")
    assert_units(drawn)
