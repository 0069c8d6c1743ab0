"""The direction of the FE centre load (``centre_direction``), against hand-derived facts.

A unit load vector p of the centre case is a uniform traction of total 1 N on the
mid-length section x = L/2 (the split between the tension and compression domains of
Section 2.2): its nodal forces add up to 1 N along the chosen axis (x for ``axial``, y for
``transverse``) and to 0 N along the other two, every loaded node lies at x = L/2, and a
uniform traction on the rectangle w x t has no moment about the section's centre. In the
all-stick regime the response is linear, so doubling the force doubles the work-conjugate
displacement p . u, which lies along the load.
"""

from __future__ import annotations

import numpy as np
import pytest

from microslip import ParameterError, preset
from microslip.fe.builtin import CENTRE_DIRECTIONS, BoxLoading, box_model

P = preset("table1")
AXIS = {"axial": 0, "transverse": 1}


@pytest.fixture(scope="module")
def model():
    return box_model(P, (8, 2, 1))


def nodal_forces(model, direction: str) -> np.ndarray:
    """The centre's unit load vector on every mesh node, (n_nodes, 3), N."""
    full = np.zeros(model.index.size)
    full[model.free] = BoxLoading(P, model, direction).run.vectors[1]
    out = np.zeros((len(model.mesh.nodes), 3))
    out[model.order] = full.reshape(-1, 3)
    return out


@pytest.mark.parametrize("direction", sorted(CENTRE_DIRECTIONS))
def test_centre_load_is_a_unit_traction_on_the_mid_section(model, direction):
    f = nodal_forces(model, direction)
    expected = np.zeros(3)
    expected[AXIS[direction]] = 1.0
    np.testing.assert_allclose(f.sum(axis=0), expected, rtol=0, atol=1e-14)
    loaded = np.flatnonzero(np.any(f != 0.0, axis=1))
    x = model.mesh.nodes[loaded, 0]
    np.testing.assert_allclose(x, 0.5 * P.length, rtol=0, atol=1e-12 * P.length)
    # no moment about the centre of the section (y = w/2, z = t/2)
    arm = model.mesh.nodes[loaded] - np.array([0.5 * P.length, 0.5 * P.width,
                                               0.5 * P.thickness])
    moment = np.cross(arm, f[loaded]).sum(axis=0)
    np.testing.assert_allclose(moment, 0.0, atol=1e-12 * P.width)


def test_axial_and_transverse_differ_and_respond_linearly_while_stuck(model):
    small = 1e-3 * P.macroslip_force  # far below first slip: linear response
    d = {}
    for direction in CENTRE_DIRECTIONS:
        h = BoxLoading(P, model, direction).advance([0.0, 0.0], [small, 2 * small])
        assert h.converged
        d[direction] = np.asarray(h.centre_displacement)
        assert d[direction][1] == pytest.approx(2 * d[direction][0], rel=1e-9)
        assert d[direction][0] > 0.0  # the load does positive work
    assert d["axial"][0] != pytest.approx(d["transverse"][0], rel=1e-3)


def test_unknown_direction_is_named(model):
    with pytest.raises(ParameterError, match="unknown centre direction 'vertical'"):
        BoxLoading(P, model, "vertical")
