"""Iwan operators: closed forms, Masing's rules on any history, the analytic Jacobian."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import microslip
from microslip.dynamics.distributions import clamp_joint, from_backbone, iwan4, iwan4_segalman
from microslip.dynamics.operators import HystereticOperator, IwanOperator, jenkins
from microslip.errors import ParameterError

P = microslip.preset("table1")
#: Series spring of the tip joint: Table 1's width x length x a stick slope of 1e4 N/mm^3.
K_SERIES = 1.0e4 * P.width * P.length


def masing_stack(op: IwanOperator, xs: np.ndarray) -> np.ndarray:
    """Force along a displacement path by Masing's extended rules (an independent stack).

    Virgin curve F_bb (odd); after a reversal at (x_r, F_r): F = F_r + 2 F_bb((x - x_r)/2).
    A branch closes when x passes the start of the branch beneath it (the mirror point -x_r
    on the virgin curve for the first one); both are forgotten.
    """
    def bb(a: float) -> float:
        return float(op.backbone_force(np.array([a]))[0])

    stack: list[tuple[float, float]] = []
    x_prev, direction, force = 0.0, 0.0, 0.0
    out = []
    for x in xs:
        s = float(np.sign(x - x_prev))
        if s != 0.0:
            if direction not in (0.0, s):
                stack.append((x_prev, force))
            direction = s
            while stack:
                start_beneath = stack[-2][0] if len(stack) >= 2 else -stack[0][0]
                if (x - start_beneath) * s < 0.0:
                    break
                del stack[-2:]
            force = bb(x) if not stack else stack[-1][1] + 2.0 * bb((x - stack[-1][0]) / 2.0)
        out.append(force)
        x_prev = x
    return np.array(out)


def tip_joint(elements: int = 200) -> IwanOperator:
    return clamp_joint("tip", P, K_SERIES, elements=elements)


OPERATORS = {
    "jenkins": lambda: jenkins(100.0, 5.0),
    "iwan": lambda: iwan4_segalman(1000.0, 10.0, -0.5, 0.5, elements=50),
    "tip": lambda: tip_joint(50),
}


def test_every_operator_is_a_hysteretic_operator():
    for make in OPERATORS.values():
        assert isinstance(make(), HystereticOperator)


def test_jenkins_loop_closed_form():
    """A Jenkins element on a cosine: the stick and slip pieces of its loop, exactly."""
    k, fs, a = 100.0, 5.0, 0.13
    theta = 2.0 * np.pi * np.arange(64) / 64
    x = a * np.cos(theta)
    f, _ = jenkins(k, fs).periodic_force(x)
    down = theta <= np.pi
    expected = np.where(down, np.maximum(fs - k * (a - x), -fs), np.minimum(-fs + k * (x + a), fs))
    np.testing.assert_allclose(f, expected, rtol=0, atol=1e-13 * fs)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_clamp_operator_reproduces_the_models_masing_loop_at_its_nodes(model):
    """The model's own loop (first loading + Masing's rule, behind the series spring)."""
    n, m = 200, 150
    op = clamp_joint(model, P, K_SERIES, elements=n)
    f_ms = microslip.macroslip_force(model, P)
    bb = microslip.first_loading(model, P, f_ms * m / (n + 1), m)
    f_j, d_j = bb.force, bb.displacement + bb.force / K_SERIES
    f0, d0 = f_j[-1], d_j[-1]
    x = np.concatenate([d_j, d0 - 2.0 * d_j[1:], -d0 + 2.0 * d_j[1:]])
    expected = np.concatenate([f_j, f0 - 2.0 * f_j[1:], -f0 + 2.0 * f_j[1:]])
    got = op.force_history(x).force
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-9 * f0)
    loop = x[m:]  # the closed loop from (d0, F0)
    f_periodic, _ = op.periodic_force(loop[:-1])
    np.testing.assert_allclose(f_periodic, expected[m:-1], rtol=0, atol=1e-9 * f0)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_clamp_operator_virgin_curve_is_the_models_backbone(model):
    n = 200
    op = clamp_joint(model, P, K_SERIES, elements=n)
    f_ms = microslip.macroslip_force(model, P)
    bb = microslip.first_loading(model, P, f_ms * n / (n + 1), n)
    d = bb.displacement + bb.force / K_SERIES
    np.testing.assert_allclose(op.backbone_force(d), bb.force, rtol=1e-12, atol=0)
    assert op.slip_force == pytest.approx(f_ms, rel=1e-12)


def test_nested_inner_loops_on_a_non_symmetric_history():
    """Return-point memory: an inner loop closes where it began and the outer branch goes on
    as if it had not happened; past the virgin extremum the virgin curve is rejoined."""
    op = tip_joint(200)
    d1 = 0.004
    turns = [d1, -0.3 * d1, 0.6 * d1, 0.1 * d1, 0.6 * d1, 0.9 * d1, -0.6 * d1, 1.4 * d1]
    xs = np.concatenate([np.linspace(a, b, 41)[1:] for a, b in zip([0.0, *turns], turns,
                                                                    strict=False)])
    f = op.force_history(xs).force
    np.testing.assert_allclose(f, masing_stack(op, xs), rtol=0, atol=1e-9 * op.slip_force)
    def bb(a: float) -> float:
        return float(op.backbone_force(np.array([a]))[0])

    end = [40 * (k + 1) - 1 for k in range(len(turns))]  # sample index of each turn
    assert f[end[0]] == pytest.approx(bb(d1), rel=1e-12)  # the virgin curve up to d1
    # the inner loop 0.6 d1 -> 0.1 d1 -> 0.6 d1 closes at its start
    assert f[end[4]] == pytest.approx(f[end[2]], rel=1e-12)
    # then 0.9 d1 lies on the branch from -0.3 d1 as if the inner loop had not happened
    x_r, f_r = -0.3 * d1, f[end[1]]
    assert f[end[5]] == pytest.approx(f_r + 2.0 * bb((0.9 * d1 - x_r) / 2.0), rel=1e-12)
    # and -0.6 d1 on the branch from d1 (the branch from 0.9 d1 closed at -0.3 d1)
    assert f[end[6]] == pytest.approx(bb(d1) - 2.0 * bb((d1 + 0.6 * d1) / 2.0), rel=1e-12)
    # beyond d1 the virgin curve again
    assert f[-1] == pytest.approx(bb(1.4 * d1), rel=1e-12)


turning_points = st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=1, max_size=8)


@pytest.mark.parametrize("name", list(OPERATORS))
@settings(max_examples=40, deadline=None)
@given(turns=turning_points, scale=st.floats(0.1, 3.0))
def test_any_history_follows_the_extended_masing_rules(name, turns, scale):
    op = OPERATORS[name]()
    reach = 2.0 * float(op.slip.max()) * scale
    pts = [0.0, *(reach * t for t in turns)]
    xs = np.concatenate([np.linspace(a, b, 13)[1:] for a, b in itertools.pairwise(pts)])
    got = op.force_history(xs).force
    np.testing.assert_allclose(got, masing_stack(op, xs), rtol=0, atol=1e-9 * op.slip_force)


@pytest.mark.parametrize("name", list(OPERATORS))
@settings(max_examples=40, deadline=None)
@given(coef=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=6, max_size=6),
       scale=st.floats(0.05, 3.0), samples=st.sampled_from([16, 33, 64]))
def test_periodic_force_is_the_settled_history(name, coef, scale, samples):
    """The closed periodic force equals the third period of the history from rest."""
    op = OPERATORS[name]()
    x = _signal(coef, samples) * float(op.slip.max()) * scale
    f, _ = op.periodic_force(x)
    settled = op.force_history(np.tile(x, 3)).force[2 * samples:]
    np.testing.assert_allclose(f, settled, rtol=0, atol=1e-12 * op.slip_force)


@pytest.mark.parametrize("name", list(OPERATORS))
@settings(max_examples=40, deadline=None)
@given(coef=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=6, max_size=6),
       direction=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=32, max_size=32),
       scale=st.floats(0.05, 3.0))
def test_analytic_jacobian_matches_finite_differences(name, coef, direction, scale):
    op = OPERATORS[name]()
    reach = float(op.slip.max()) * scale
    x = _signal(coef, 32) * reach
    dx = np.asarray(direction)
    f0, jac = op.periodic_force(x)
    h = 1e-8 * reach
    fwd = (op.periodic_force(x + h * dx)[0] - f0) / h
    bwd = (f0 - op.periodic_force(x - h * dx)[0]) / h
    # the force is piecewise linear in x: one-sided differences are exact up to round-off
    # (f / h ~ 1e-8 relative) unless the step crosses a switching point; where the two sides
    # disagree the force has a kink in this direction and no derivative to compare with
    tol = 1e-6 * op.initial_stiffness
    assume(np.allclose(fwd, bwd, rtol=0, atol=tol))
    np.testing.assert_allclose(jac @ dx, 0.5 * (fwd + bwd), rtol=0, atol=tol)


def _signal(coef: list[float], samples: int) -> np.ndarray:
    theta = 2.0 * np.pi * np.arange(samples) / samples + 0.1234567  # no symmetric ties
    h = np.arange(1, 4)
    c = np.asarray(coef)
    return c[:3] @ np.cos(np.outer(h, theta)) + c[3:] @ np.sin(np.outer(h, theta))


def test_segalman_parameters_give_stiffness_and_slip_force():
    op = iwan4_segalman(1000.0, 10.0, -0.4, 0.3, elements=100)
    assert op.initial_stiffness == pytest.approx(1000.0, rel=1e-12)
    assert op.slip_force == pytest.approx(10.0, rel=1e-12)


def test_iwan4_virgin_curve_exact_at_the_bin_edges():
    chi, pm, r, s, n = -0.5, 0.02, 1e5, 300.0, 64
    op = iwan4(chi, pm, r, s, n)
    a = pm * (np.arange(1, n) / n) ** (2.0 / (1.0 + chi))
    exact = (r * a ** (chi + 2.0) / (chi + 2.0)
             + a * (r * (pm ** (chi + 1.0) - a ** (chi + 1.0)) / (chi + 1.0) + s))
    np.testing.assert_allclose(op.backbone_force(a), exact, rtol=1e-12)


@pytest.mark.parametrize(("n", "rtol"), [(100, 5e-3), (1000, 2e-5)])
def test_iwan4_dissipation_converges_to_segalmans_closed_form(n, rtol):
    """W_d = 4 R A^(3+chi)/((chi+2)(chi+3)) below macroslip, from the loop of the operator;
    the discretisation error falls like n^-2 (bins keep the 0th and 1st moments only)."""
    from microslip.dynamics.describing import describing_function

    chi, pm, r, s = -0.5, 0.02, 1e5, 300.0
    a = np.array([0.001, 0.005, 0.0123, 0.0199])
    w = describing_function(iwan4(chi, pm, r, s, n), a, samples=4096).dissipated_energy
    exact = 4.0 * r * a ** (3.0 + chi) / ((chi + 2.0) * (chi + 3.0))
    np.testing.assert_allclose(w, exact, rtol=rtol)


def test_from_backbone_refuses_a_convex_curve():
    with pytest.raises(ParameterError, match="not concave at 1 mm"):
        from_backbone("x", [0.0, 1.0, 2.0], [0.0, 1.0, 3.0])


def test_rigid_bar_needs_a_finite_series_stiffness():
    with pytest.raises(ParameterError, match="series stiffness must be finite"):
        clamp_joint("tip", P, float("inf"))


@pytest.mark.parametrize(("stiffness", "slip"), [(0.0, 1.0), (-1.0, 1.0), (1.0, float("nan"))])
def test_jenkins_refuses_bad_parameters(stiffness, slip):
    with pytest.raises(ParameterError):
        jenkins(stiffness, slip)


@pytest.mark.parametrize("name", list(OPERATORS))
@settings(max_examples=40, deadline=None)
@given(coef=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=6, max_size=6),
       basis=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=96, max_size=96),
       scale=st.floats(0.05, 3.0))
def test_projected_jacobian_is_the_jacobian_times_the_basis(name, coef, basis, scale):
    """The kernel that never forms J gives the same force (bit for bit: same sums in the
    same order) and J @ E to round-off."""
    op = OPERATORS[name]()
    x = _signal(coef, 32) * float(op.slip.max()) * scale
    e = np.asarray(basis).reshape(32, 3)
    f, jac = op.periodic_force(x)
    f_p, je = op.periodic_force_projected(x, e)
    np.testing.assert_array_equal(f_p, f)
    np.testing.assert_allclose(je, jac @ e, rtol=0, atol=1e-13 * op.initial_stiffness)


@pytest.mark.parametrize("name", list(OPERATORS))
@settings(max_examples=20, deadline=None)
@given(coef=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=7, max_size=7),
       scale=st.floats(0.05, 3.0))
def test_periodic_harmonics_is_the_aft_of_the_periodic_force(name, coef, scale):
    """The compiled AFT step: coefficients -> samples -> closed periodic force and J ->
    coefficients, as the FFT transforms and the time-domain Jacobian give it."""
    from microslip.dynamics.hb import from_time, to_time

    op = OPERATORS[name]()
    u = np.asarray(coef) * float(op.slip.max()) * scale
    synth = np.ascontiguousarray(to_time(np.eye(7), 32).T)
    analysis = np.ascontiguousarray(from_time(np.eye(32), 3).T)
    # the samples as the compiled step makes them (an FFT's round-off differs, and where a
    # sample ties with a slip sample that decides which one-sided derivative J is)
    f, jac = op.periodic_force(synth @ u)
    force, dforce = op.periodic_harmonics(u, synth, analysis)
    np.testing.assert_allclose(force, from_time(f, 3), rtol=0, atol=1e-12 * op.slip_force)
    np.testing.assert_allclose(dforce, analysis @ jac @ synth, rtol=0,
                               atol=1e-12 * op.initial_stiffness)
