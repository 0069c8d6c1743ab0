"""The side-by-side figure's damping axis (plot.ownmesh.compare_figure): it starts a few
decades below the full FE's smallest damping ratio, and a model far below it (a whole joint
that hardly slips) is named as off the axis instead of squeezing the comparable curves."""

from __future__ import annotations

import pytest

pytest.importorskip("matplotlib")


def test_a_model_far_below_the_truth_is_named_off_the_axis() -> None:
    from microslip.plot.ownmesh import DAMPING_AXIS_DECADES, compare_figure

    a = [0.01, 0.02, 0.04]
    out = {"mode": 1, "label": "bending out of plane", "linear_frequencies_Hz": [500.0],
           "solvers": {
               "fe": {"amplitude_mm": a, "frequency_Hz": [499.0, 495.0, 490.0],
                      "damping_ratio": [2e-4, 1e-3, 3e-3]},
               "rom": {"amplitude_mm": a, "frequency_Hz": [499.0, 495.1, 490.2],
                       "damping_ratio": [2.1e-4, 1e-3, 3.1e-3]},
               "joint": {"amplitude_mm": a, "frequency_Hz": [505.0, 505.0, 505.0],
                         "damping_ratio": [1e-27, None, 2e-26]}}}
    fig = compare_figure(out)
    damp = fig.axes[1]
    assert damp.get_ylim()[0] == pytest.approx(2e-4 / DAMPING_AXIS_DECADES, rel=1e-12)
    notes = [t.get_text() for t in damp.texts]
    assert any("below the axis" in t and "joint" in t and "rom" not in t for t in notes)
