"""The quasi-static modal analysis's amplitude grid on a mode that hardly slips (its top must
run cyclically, not only on the first loading) and the per-node slip pattern of a point
(meshdynamics.qsma, issue 23)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import MeshModel, build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.modes import Modes, linear_modes
from microslip.meshdynamics.qsma import (
    GROSS_STICK,
    _failed,
    _first_loading_top,
    _point,
    cyclic_ok,
    first_slip_force,
    qsma,
    qsma_amplitudes,
    qsma_point,
)


@pytest.fixture(scope="module")
def cantilever() -> tuple[MeshModel, Modes]:
    """The 12x3x1 cantilever, ``fixed`` normal contact: mode 1 bends out of the contact
    plane (hardly slips: a first loading carries it far past what a cycle does), mode 2 in
    it."""
    model = build_mesh_model(cantilever_mesh(12, 3, 1), rigid_base(contact_set="contact",
                                                                   clamp_set="clamp",
                                                                   normal_force=2000.0,
                                                                   modulus=70000.0,
                                                                   poisson_ratio=0.33, friction=0.5,
                                                                   stick_slope=1e4,
                                                                   normal_contact="fixed"))
    return model, linear_modes(model, 2700.0, 2, response_set="response")


@pytest.mark.slow  # about 10 s
def test_grid_top_runs_cyclically_on_a_mode_that_hardly_slips(
        cantilever: tuple[MeshModel, Modes]) -> None:
    """Out-of-plane bending: the first loading keeps a tenth of the contact stuck far beyond
    what the reversing cycle does (there 96 % of the area slips). The grid's top is lowered
    until its cyclic run converges and keeps GROSS_STICK stuck, so every point of the grid
    runs with finite figures."""
    model, modes = cantilever
    mode = modes.select(1)
    assert mode.label == "bending out of plane"
    q1 = first_slip_force(model, mode)
    first = _first_loading_top(model, mode, q1, 1.25, 80)
    assert not cyclic_ok(_point(model, mode, first, None))  # the old top: past the cycle's
    grid = qsma_amplitudes(model, mode, 3)
    assert grid[-1] < first / 1.25
    curve = qsma(model, mode, grid)
    assert np.all(np.isfinite(curve.damping_ratio)) and np.all(curve.damping_ratio > 0)
    assert np.all(curve.slip_fraction <= 1.0 - GROSS_STICK)


def test_slip_pattern_per_contact_node(cantilever: tuple[MeshModel, Modes]) -> None:
    """``node_slipped`` flags each contact node that slipped over the settled cycle: its area
    is the point's slip fraction, the pattern grows with the amplitude and is in the contact
    nodes' order, none slips below first slip, and a failed run flags none."""
    model, modes = cantilever
    mode = modes.select(2)
    q1 = first_slip_force(model, mode)
    n_c = model.contact_nodes.size
    area = model.contact_area
    quiet = qsma_point(model, mode, 0.5 * q1)
    assert quiet.node_slipped.shape == (n_c,) and quiet.node_slipped.dtype == bool
    assert not quiet.node_slipped.any()
    small, large = (qsma_point(model, mode, f * q1) for f in (1.5, 4.0))
    for p in (small, large):
        assert p.node_slipped.shape == (n_c,)
        assert float(area[p.node_slipped].sum() / area.sum()) == pytest.approx(
            p.slip_fraction, rel=1e-12)
    assert 0 < small.node_slipped.sum() < large.node_slipped.sum() < n_c
    assert np.all(large.node_slipped[small.node_slipped])  # the slip zone only grows
    # the flags follow the contact nodes' order: the pattern of the in-plane bending is
    # mirror-symmetric about the beam's mid-plane y = const (a shuffled order is not)
    xyz = model.mesh.nodes[model.contact_nodes]
    mirror = xyz.copy()
    mirror[:, 1] = xyz[:, 1].min() + xyz[:, 1].max() - xyz[:, 1]
    pairs = np.array([np.argmin(np.linalg.norm(xyz - p, axis=1)) for p in mirror])
    assert np.allclose(xyz[pairs], mirror, atol=1e-9)
    for p in (small, large):
        assert np.array_equal(p.node_slipped, p.node_slipped[pairs])
        assert not np.array_equal(p.node_slipped, np.roll(p.node_slipped, 1)[pairs])
    bad = _failed(1.0, "test", n_c)
    assert bad.node_slipped.shape == (n_c,) and not bad.node_slipped.any()
    assert math.isnan(bad.slip_fraction)
    # not in the JSON summary
    curve = qsma(model, mode, [1.5 * q1])
    assert "node_slipped" not in curve.summary()
