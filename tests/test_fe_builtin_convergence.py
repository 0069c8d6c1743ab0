"""Mesh convergence of the built-in solver: observed order of W_d on three small meshes.

Friction acts at the nodes, so the slip front advances one column of nodes at a time: the
force at which a column starts to slip is off by O(h) and the loop area by O(h^2). With
h, h/2, h/4 (nx = 8, 16, 32 along the Table 1 tip bar) the observed order
log2 (W(h) - W(h/2)) / (W(h/2) - W(h/4)) is 2.13 (C3D8I), converging monotonically; a
mis-weighted contact area (every node of the face given a full element's area) makes the
sequence oscillate (1.6098, 1.6169, 1.6153 N·mm), which the signed ratio catches.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip import preset
from microslip.fe.builtin import solve_uniaxial

P = preset("table1")
F0 = 267.0


@pytest.fixture(scope="module")
def tip_wd() -> np.ndarray:
    return np.array([solve_uniaxial(P, "tip", F0, mesh=(nx, 2, 1)).dissipated_energy
                     for nx in (8, 16, 32)])


def test_observed_order_of_the_tip_loop_area_is_two(tip_wd):
    d = np.diff(tip_wd)
    ratio = d[0] / d[1]  # > 0: monotonic convergence, 2^order
    assert ratio > 0.0, tip_wd
    assert 1.8 <= math.log2(ratio) <= 2.5, math.log2(ratio)

