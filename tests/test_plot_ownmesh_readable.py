"""The figures of ``modal --mesh`` read as they should (issue 34 item 9): the log axes' tick
labels never overlap, whatever the span (matplotlib labels the minor ticks of an axis that
spans about a decade or less, and they ran into each other), and the slip-pattern panels draw
a contact node that lifted off as open, not as stick."""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest

from microslip.plot.core import MAX_LOG_LABELS, log_ticks, pyplot
from microslip.plot.ownmesh import compare_figure, node_states


def _study(amplitudes: list[float], zetas: list[float], opened: list[bool] | None = None
           ) -> dict[str, Any]:
    n = len(amplitudes)
    fe = {"amplitude_mm": amplitudes, "frequency_Hz": list(np.linspace(2200, 1800, n)),
          "damping_ratio": zetas, "slip_fraction": [0.1] * n,
          "slip_pattern": {"x_mm": [0.0, 1.0, 2.0, 3.0], "y_mm": [0.0, 0.0, 1.0, 1.0],
                           "slipped": [[False, True, False, False]] * n}}
    if opened is not None:
        fe["slip_pattern"]["open"] = [opened] * n
    rom = {"amplitude_mm": amplitudes, "frequency_Hz": list(np.linspace(2210, 1850, n)),
           "damping_ratio": [z * 1.1 for z in zetas]}
    return {"mode": 2, "label": "bending in the contact plane",
            "linear_frequencies_Hz": [500.0, 2241.6], "solvers": {"fe": fe, "rom": rom}}


def _labels(fig: Any) -> list[list[Any]]:
    """Per axis of every panel: the window extents of its visible, non-empty tick labels."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            boxes = [t.get_window_extent(renderer) for t in axis.get_ticklabels(which="both")
                     if t.get_visible() and t.get_text()]
            out.append(boxes)
    return out


@pytest.mark.parametrize("amplitudes", [
    [0.0112, 0.0163, 0.0281],               # under half a decade: labelled minor ticks before
    [0.011, 0.02, 0.05, 0.09],              # about a decade
    [7.1e-4, 6.2e-3, 0.078],                # two decades
    [1e-7, 1e-5, 1e-3, 0.1, 10.0],          # eight decades
])
def test_no_two_tick_labels_overlap(amplitudes: list[float]) -> None:
    fig = compare_figure(_study(amplitudes, list(np.geomspace(0.011, 0.0151, len(amplitudes)))))
    try:
        for boxes in _labels(fig):
            for a, b in itertools.combinations(boxes, 2):
                assert not a.overlaps(b), (a, b)
        amplitude_axes = [ax.xaxis for ax in fig.axes[:2]]
        for axis in amplitude_axes:  # readable: at least two labels, at most the stated number
            shown = [t for t in axis.get_ticklabels(which="both") if t.get_text()]
            lo, hi = axis.get_view_interval()
            inside = [t for t in shown if lo <= t.get_position()[0] <= hi]
            assert 1 <= len(inside) <= MAX_LOG_LABELS
    finally:
        pyplot().close(fig)


def test_log_ticks_are_plain_numbers_at_a_ladder() -> None:
    plt = pyplot()
    fig, ax = plt.subplots()
    ax.semilogx([0.0105, 0.0298], [1, 2])
    ax.set_xlim(0.0105, 0.0298)
    log_ticks(ax, "x")
    fig.canvas.draw()
    texts = [t.get_text() for t in ax.xaxis.get_ticklabels() if t.get_text()]
    plt.close(fig)
    assert texts == ["0.015", "0.02"]


def test_open_nodes_are_drawn_open_not_stick() -> None:
    """Node 0 open (never slid), node 1 slipped (also open at a state: slipped wins), nodes
    2, 3 stuck: three markers of their own, the open one hollow."""
    fig = compare_figure(_study([0.001, 0.01, 0.1], [0.001, 0.01, 0.05],
                                opened=[True, True, False, False]))
    try:
        panel = fig.axes[2]
        by_label = {c.get_label(): c for c in panel.collections}
        assert set(by_label) == {"stick", "slip", "open (lifted off)"}
        np.testing.assert_array_equal(by_label["open (lifted off)"].get_offsets(), [[0.0, 0.0]])
        np.testing.assert_array_equal(by_label["slip"].get_offsets(), [[1.0, 0.0]])
        np.testing.assert_array_equal(by_label["stick"].get_offsets(),
                                      [[2.0, 1.0], [3.0, 1.0]])
        face = by_label["open (lifted off)"].get_facecolors()  # hollow: no face colour
        assert face.size == 0 or face[:, 3].max() == 0.0
        assert "1 of 4 nodes open" in panel.get_title()
    finally:
        pyplot().close(fig)


def test_a_pattern_without_open_nodes_is_as_before() -> None:
    slipped, opened = node_states({"slipped": [[False, True]]}, 0)
    assert slipped.tolist() == [False, True] and opened.tolist() == [False, False]
