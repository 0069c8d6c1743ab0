"""The 3-D contact element (normal penalty with lift-off, circular Coulomb limit mu N(t)):
its AFT Jacobian against finite differences, its limits (stuck, lifted off, constant normal
force = the 2-D circular Jenkins element)."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.dynamics.operators2d import CircularIwan
from microslip.dynamics.operators3d import Contact3D
from microslip.errors import ParameterError

#: A contact node of the cantilever: lambda A, k_n A (N/mm), N_0 (N), mu.
KT, KN, N0, MU = 1e4 * 8.0, 1e6 * 8.0, 30.0, 0.5
SLIP = MU * N0 / KT  # mm


def basis(n: int, harmonics: int) -> np.ndarray:
    theta = 2 * np.pi * np.arange(n) / n
    cols = [np.ones(n)]
    for k in range(1, harmonics + 1):
        cols += [np.cos(k * theta), np.sin(k * theta)]
    return np.column_stack(cols)


def element() -> Contact3D:
    return Contact3D(KT, KN, N0, MU)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_jacobian_matches_finite_differences(seed):
    """Slip, stick and lift-off in one cycle (the normal swings past N_0 / k_n)."""
    rng = np.random.default_rng(seed)
    b = basis(96, 3)
    c = rng.normal(size=(3, b.shape[1])) * np.array([[4 * SLIP], [4 * SLIP], [0.6 * N0 / KN]])
    c[2, 0], c[2, 1] = 0.2 * N0 / KN, 1.2 * N0 / KN  # a first harmonic that lifts off
    op = element()
    f, jb = op.periodic_force_projected(b @ c.T, b)
    assert np.any(f[:, 2] == N0) and np.any(f[:, 2] < N0)  # lifted off for part of it
    step = 1e-7 * SLIP
    fd = np.zeros_like(jb)
    for i in range(3):
        for j in range(b.shape[1]):
            d = np.zeros_like(c)
            d[i, j] = step
            fd[:, :, i, j] = (op.periodic_force(b @ (c + d).T)
                              - op.periodic_force(b @ (c - d).T)) / (2 * step)
    scale = np.max(np.abs(jb))
    assert np.max(np.abs(jb - fd)) < 1e-5 * scale


def test_stuck_is_linear():
    b = basis(64, 2)
    u = b @ (np.array([[0.0, 0.3, 0.1, 0.0, 0.0]] * 3) * np.array([[SLIP], [SLIP],
                                                                    [0.1 * N0 / KN]])).T
    f = element().periodic_force(u)
    assert np.allclose(f, u @ element().stuck_stiffness, rtol=1e-13, atol=1e-12)


def test_lifted_off_carries_nothing_tangentially():
    u = np.column_stack([np.full(8, 5 * SLIP), np.zeros(8), np.full(8, 2 * N0 / KN)])
    f = element().periodic_force(u)
    assert np.array_equal(f, np.tile([0.0, 0.0, N0], (8, 1)))


def test_constant_normal_is_the_circular_jenkins_element():
    b = basis(128, 3)
    theta = 2 * np.pi * np.arange(128) / 128
    u = np.column_stack([3 * SLIP * np.cos(theta), 1.5 * SLIP * np.sin(theta + 0.3),
                         np.zeros(128)])
    f = element().periodic_force_projected(u, b)[0]
    ref = CircularIwan("node", np.array([KT]), np.array([SLIP])).periodic_force(u[:, :2])
    assert np.allclose(f[:, :2], ref, rtol=0.0, atol=1e-10 * MU * N0)
    assert np.all(f[:, 2] == 0.0)


def test_bad_parameters_refused():
    with pytest.raises(ParameterError, match="preload"):
        Contact3D(KT, KN, float("nan"), MU)
    with pytest.raises(ParameterError, match="friction limit"):  # open: no stick force
        Contact3D(KT, KN, -1.0, MU, stick_force=(1e-3, 0.0))
    with pytest.raises(ParameterError, match=r"shape \(N, 3\)"):
        element().periodic_force(np.zeros((4, 2)))


def test_stick_force_is_counted_from_the_clamped_state() -> None:
    """The clamping step's stick force t0: below slip the element is the same spring (the
    force from the clamped state is k_t u whatever t0); with a constant normal force and a
    cycle that slips both ways the first slip erases t0, so the closed loop is the one from
    zero, shifted by -t0 (the force is counted from the clamped t0)."""
    n = 256
    t = np.arange(n) / n
    small = np.column_stack([1e-4 * np.sin(2 * np.pi * t), np.zeros(n), np.zeros(n)])
    big = np.column_stack([0.02 * np.sin(2 * np.pi * t), 0.01 * np.cos(2 * np.pi * t),
                           np.zeros(n)])
    plain = Contact3D(1e4, 1e5, 100.0, 0.5)
    held = Contact3D(1e4, 1e5, 100.0, 0.5, stick_force=(20.0, -30.0))
    np.testing.assert_allclose(held.periodic_force(small), plain.periodic_force(small),
                               rtol=0, atol=1e-12)
    shifted = plain.periodic_force(big) - [20.0, -30.0, 0.0]
    np.testing.assert_allclose(held.periodic_force(big), shifted, rtol=0, atol=1e-9)
    with pytest.raises(ParameterError, match="exceeds the friction limit"):
        Contact3D(1e4, 1e5, 100.0, 0.5, stick_force=(40.0, 40.0))


#: An open node's gap after clamping, mm: its signed preload is -k_n g0.
GAP = 0.5 * N0 / KN


def test_open_node_carries_nothing_until_its_gap_closes() -> None:
    """Preload -k_n g0 (lifted off by the clamping): no stuck stiffness, no force while the
    normal motion stays above -g0, whatever the tangential motion."""
    op = Contact3D(KT, KN, -KN * GAP, MU)
    assert not op.closed and np.array_equal(op.stuck_stiffness, np.zeros((3, 3)))
    theta = 2 * np.pi * np.arange(64) / 64
    u = np.column_stack([5 * SLIP * np.cos(theta), SLIP * np.sin(theta),
                         -0.9 * GAP * np.sin(theta) ** 2])
    assert np.array_equal(op.periodic_force(u), np.zeros_like(u))


def test_open_node_pressed_shut_is_the_circular_jenkins_element() -> None:
    """Held at u_n = -3 g0 the open node presses with N = 2 k_n g0 (f_n = -N, counted from
    its clamped force 0) and is then the circular Jenkins element of slip force 2 mu k_n g0,
    starting from zero slider force (the clamping left it none)."""
    theta = 2 * np.pi * np.arange(128) / 128
    n = 2 * KN * GAP
    u = np.column_stack([3 * SLIP * np.cos(theta), 1.5 * SLIP * np.sin(theta + 0.3),
                         np.full(128, -3 * GAP)])
    f = Contact3D(KT, KN, -KN * GAP, MU).periodic_force(u)
    ref = CircularIwan("node", np.array([KT]), np.array([MU * n / KT])).periodic_force(
        u[:, :2])
    np.testing.assert_allclose(f[:, :2], ref, rtol=0.0, atol=1e-10 * MU * n)
    np.testing.assert_allclose(f[:, 2], -n, rtol=1e-13)


@pytest.mark.parametrize("seed", [0, 1])
def test_open_node_jacobian_matches_finite_differences(seed: int) -> None:
    """An open node that closes for part of the cycle and slips while closed."""
    rng = np.random.default_rng(seed)
    b = basis(96, 3)
    c = rng.normal(size=(3, b.shape[1])) * np.array([[4 * SLIP], [4 * SLIP], [0.3 * GAP]])
    c[2, 0], c[2, 1] = -GAP, 2.0 * GAP  # closes around the trough of the first harmonic
    op = Contact3D(KT, KN, -KN * GAP, MU)
    f, jb = op.periodic_force_projected(b @ c.T, b)
    assert np.any(f[:, 2] == 0.0) and np.any(f[:, 2] < 0.0)  # open and closed in one cycle
    step = 1e-7 * SLIP
    fd = np.zeros_like(jb)
    for i in range(3):
        for j in range(b.shape[1]):
            d = np.zeros_like(c)
            d[i, j] = step
            fd[:, :, i, j] = (op.periodic_force(b @ (c + d).T)
                              - op.periodic_force(b @ (c - d).T)) / (2 * step)
    assert np.max(np.abs(jb - fd)) < 1e-5 * np.max(np.abs(jb))
