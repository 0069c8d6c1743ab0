"""The FE's first loading as a joint backbone (microslip.fe.builtin.backbone).

Exact properties first (the concave majorant, the operator's virgin curve through the FE's
nodes), then the physics check that makes the backbone useful: a Masing joint built from
the FE's first loading reproduces the FE's own settled cycle in that direction.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import preset
from microslip.errors import ParameterError
from microslip.fe.builtin.backbone import HULL_TOLERANCE, concave_majorant, fe_backbone
from microslip.fe.builtin.study import coupling_study, model_for
from microslip.fe.constants import DEFAULT_STICK_SLOPE
from microslip.meshdynamics.fe_check import cycle_work
from microslip.meshdynamics.febackbone import backbone_operator

MESH = (8, 2, 1)


@pytest.fixture(scope="module")
def fem():
    return model_for(preset("table1"), MESH, DEFAULT_STICK_SLOPE, "C3D8I", "banded", None)


@pytest.fixture(scope="module")
def centre(fem):
    return fe_backbone(preset("table1"), "centre", mesh=fem, increments=128)


def test_a_concave_curve_keeps_every_node():
    d = np.linspace(0.0, 2.0, 41)
    f = np.sqrt(d)
    assert concave_majorant(d, f).tolist() == list(range(41))


def test_a_small_dent_is_bridged_and_a_large_one_refused():
    d = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    f = np.array([0.0, 2.0, 2.999, 4.0, 4.5])  # node 2 a hair below the chord 1-3
    assert concave_majorant(d, f, tolerance=1e-3).tolist() == [0, 1, 3, 4]
    with pytest.raises(ParameterError, match="not concave"):
        concave_majorant(d, np.array([0.0, 2.0, 2.5, 4.0, 4.5]), tolerance=1e-3)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.01, 1.0), min_size=3, max_size=30),
       st.lists(st.floats(1e-3, 1.0), min_size=3, max_size=30))
def test_the_majorant_is_concave_above_every_node_and_keeps_the_ends(steps, rises):
    n = min(len(steps), len(rises))
    d = np.concatenate([[0.0], np.cumsum(steps[:n])])
    f = np.concatenate([[0.0], np.cumsum(rises[:n])])
    keep = concave_majorant(d, f, tolerance=1e9)
    assert keep[0] == 0 and keep[-1] == n
    hull = np.interp(d, d[keep], f[keep])
    assert np.all(hull >= f - 1e-12 * (1.0 + abs(f[-1])))
    slopes = np.diff(f[keep]) / np.diff(d[keep])
    assert np.all(np.diff(slopes) <= 1e-9 * (1.0 + np.max(np.abs(slopes))))


def test_the_operator_passes_through_the_fe_nodes(centre):
    op = backbone_operator(centre)
    assert op.slip_force == pytest.approx(preset("table1").macroslip_force, rel=1e-12)
    keep = concave_majorant(centre.displacement, centre.force)
    d = centre.displacement[keep][1:]
    # virgin curve of parallel Jenkins elements: F(a) = sum k_i min(a, phi_i)
    virgin = np.minimum(d[:, None], op.slip[None, :]) @ op.stiffness
    np.testing.assert_allclose(virgin, centre.force[keep][1:], rtol=1e-10)
    gap = np.interp(centre.displacement, centre.displacement[keep], centre.force[keep])
    assert np.max(gap - centre.force) <= HULL_TOLERANCE * centre.force[-1]


def test_across_the_bar_the_fe_is_about_ten_times_softer_than_along_it(fem):
    p = preset("table1")
    tip = fe_backbone(p, "tip", mesh=fem, increments=64)
    across = fe_backbone(p, "centre", mesh=fem, increments=64)
    ratio = np.interp(267.0, across.force, across.displacement) / np.interp(
        267.0, tip.force, tip.displacement)
    assert 5.0 < ratio < 20.0  # in-plane bending on the friction foundation (docs/dynamics.md)


def test_a_masing_joint_from_the_fe_backbone_reproduces_the_fe_cycle(fem, centre):
    """The FE's centre-only settled cycle at 0.75 mu F_N against the joint built from the
    FE's own first loading, driven by the same motion: within 1.5 % on this mesh (the
    FE's loop is Masing but for the slips its load makes along the bar)."""
    p = preset("table1")
    study = coupling_study(p, 267.0, 267.0, 90.0, mesh=fem, increments_per_cycle=128)
    run = study.centre_only
    d = np.ascontiguousarray(run.centre_displacement[run.last_cycle()][:-1])
    w = cycle_work(backbone_operator(centre).periodic_force(d)[0], d)
    assert w == pytest.approx(run.dissipated_energy, rel=0.015)
    assert w != pytest.approx(run.dissipated_energy, rel=1e-4)  # a real comparison


@pytest.mark.parametrize("kwargs, message", [
    ({"load": "side"}, "unknown backbone load"),
    ({"increments": 1}, "increments must be"),
    ({"top": 1.0}, "top must be"),
    ({"centre_direction": "up"}, "unknown centre direction"),
])
def test_bad_arguments_are_refused_in_one_line(fem, kwargs, message):
    with pytest.raises(ParameterError, match=message):
        fe_backbone(preset("table1"), mesh=fem, **kwargs)
