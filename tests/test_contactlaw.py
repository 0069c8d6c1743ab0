"""The one contact law (:mod:`microslip.contactlaw`): closed forms, and the same numbers
wherever it runs (numpy on every FE node at once, compiled by numba on one 2-D or 3-D
element)."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.contactlaw import CONTACT_LAWS, circular_coulomb, get_contact_law
from microslip.dynamics import kernels2d, operators3d
from microslip.errors import ParameterError
from microslip.fe.builtin.contact import return_map


def _cases(n: int = 400) -> tuple[np.ndarray, ...]:
    """Random nodes, with the edge cases: trial force 0, limit 0, limit infinite (the FE's
    clamping pass), exactly on the circle."""
    rng = np.random.default_rng(7)
    gx, gy, sx, sy = rng.normal(size=(4, n))
    k = rng.uniform(0.1, 10.0, n)
    limit = rng.uniform(0.0, 5.0, n)
    gx[:20], gy[:20] = sx[:20], sy[:20]
    limit[10:30] = 0.0
    limit[30:40] = np.inf
    limit[40:50] = np.hypot(k[40:50] * (gx[40:50] - sx[40:50]), k[40:50] * (gy[40:50] - sy[40:50]))
    return gx, gy, sx, sy, k, limit


def test_stick_returns_the_trial_force_and_the_penalty_stiffness() -> None:
    fx, fy, sx, sy, txx, txy, tyy, _, _, sl = circular_coulomb(0.3, -0.4, 0.1, 0.1, 2.0, 10.0)
    assert (fx, fy, sx, sy) == (2.0 * (0.3 - 0.1), 2.0 * (-0.4 - 0.1), 0.1, 0.1)
    assert (txx, txy, tyy, sl) == (2.0, 0.0, 2.0, 0.0)


def test_slip_is_the_radial_return_onto_the_circle() -> None:
    """Trial force (6, 8) N on the circle of 2 N: f = (1.2, 1.6), s' = g - f / k, tangent
    k (L / |t|) (I - n n^T) with n = (0.6, 0.8)."""
    r = circular_coulomb(3.0, 4.0, 0.0, 0.0, 2.0, 2.0)
    expected = (1.2, 1.6, 3.0 - 0.6, 4.0 - 0.8, 0.4 * 0.64, -0.4 * 0.48, 0.4 * 0.36, 0.6, 0.8,
                1.0)
    np.testing.assert_allclose(r, expected, rtol=1e-15, atol=1e-16)


def test_an_infinite_limit_sticks_and_a_zero_limit_carries_nothing() -> None:
    r = circular_coulomb(np.array([1.0, 0.0]), np.array([2.0, 0.0]), np.zeros(2), np.zeros(2),
                         np.array([3.0, 3.0]), np.array([np.inf, 0.0]))
    assert r[0].tolist() == [3.0, 0.0] and r[1].tolist() == [6.0, 0.0]
    assert r[-1].tolist() == [0.0, 0.0]  # the trial force 0 on a limit 0 sticks
    r = circular_coulomb(1.0, 0.0, 0.0, 0.0, 3.0, 0.0)
    assert (r[0], r[1], r[2], r[-1]) == (0.0, 0.0, 1.0, 1.0)  # slides with no force


def test_force_derivative_along_the_limit_is_the_direction_in_slip() -> None:
    args = (0.7, -1.1, 0.1, 0.2, 3.0)
    h = 1e-6
    r = circular_coulomb(*args, 1.0)
    up, down = circular_coulomb(*args, 1.0 + h), circular_coulomb(*args, 1.0 - h)
    assert r[-1] == 1.0
    np.testing.assert_allclose([(up[0] - down[0]) / (2 * h), (up[1] - down[1]) / (2 * h)],
                               [r[7], r[8]], rtol=1e-8)


def test_the_fe_nodes_are_the_law_bit_for_bit() -> None:
    gx, gy, sx, sy, k, limit = _cases()
    r = return_map(np.column_stack([gx, gy]), np.column_stack([sx, sy]), k, limit)
    law = circular_coulomb(gx, gy, sx, sy, k, limit)
    assert np.array_equal(r.force, np.column_stack(law[:2]))
    assert np.array_equal(r.slip, np.column_stack(law[2:4]))
    assert np.array_equal(r.tangent, np.column_stack(law[4:7]))
    assert np.array_equal(r.slipping, law[-1] > 0.0)


@pytest.mark.parametrize("compiled", [kernels2d._law, operators3d._law],
                         ids=["kernels2d", "operators3d"])
def test_the_compiled_elements_run_the_same_law_bit_for_bit(compiled) -> None:
    """numba's scalar code and numpy's element-by-element code of the one text agree to the
    last bit (also at the edge cases), so an element's law is the FE's."""
    gx, gy, sx, sy, k, limit = _cases()
    law = np.array(circular_coulomb(gx, gy, sx, sy, k, limit))
    one = np.array([compiled(*(float(a[i]) for a in (gx, gy, sx, sy, k, limit)))
                    for i in range(gx.size)]).T
    assert np.array_equal(law, one)


def test_a_law_is_looked_up_by_name() -> None:
    assert get_contact_law("coulomb") is CONTACT_LAWS["coulomb"]
    assert CONTACT_LAWS["coulomb"].return_map is circular_coulomb
    with pytest.raises(ParameterError, match="unknown contact law 'mohr'; choose one of coulomb"):
        get_contact_law("mohr")
