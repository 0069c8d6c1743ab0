"""Masing's rule with memory for arbitrary histories."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import (
    MacroslipError,
    ModelOptions,
    VirginCurve,
    first_loading,
    masing_response,
    preset,
)
from microslip import closedform as cf

P = preset("table1")
EA, Q = P.axial_stiffness, P.friction_per_length
G = VirginCurve.from_backbone(first_loading("tip", P, 300.0, 3000, ModelOptions.uncorrected()))


def g(f):
    return np.sign(f) * cf.tip_displacement(np.abs(f), EA, Q)


def test_inner_loop_closes_and_outer_branch_resumes():
    """0 -> 250 -> -100 -> 150 -> -100 -> -200: after the inner loop (150, -100) closes at
    -100 the history continues on the branch that started at 250 (return-point memory)."""
    f = np.array([0.0, 250.0, 50.0, -100.0, 150.0, -100.0, -200.0])
    d = masing_response(G, f)
    d250 = g(250.0)
    down = lambda x: d250 + 2 * g((x - 250.0) / 2)  # noqa: E731
    d_m100 = down(-100.0)
    up = lambda x: d_m100 + 2 * g((x + 100.0) / 2)  # noqa: E731
    expected = [0.0, d250, down(50.0), d_m100, up(150.0), d_m100, down(-200.0)]
    np.testing.assert_allclose(d, expected, rtol=1e-6)


def test_first_branch_rejoins_virgin_curve_at_mirror_point():
    f = np.array([0.0, 100.0, -100.0, -250.0])
    d = masing_response(G, f)
    np.testing.assert_allclose(d, g(f), rtol=1e-6)


def test_beyond_backbone_is_macroslip():
    with pytest.raises(MacroslipError):
        masing_response(G, [0.0, 301.0])


def _reference_walk(g, f):
    """The extended Masing rules sample by sample: the specification the fast walk must meet."""
    out = np.empty(len(f))
    stack = [(0.0, 0.0, 0)]
    direction, prev = 0, 0.0
    for k, fk in enumerate(f):
        step = int(np.sign(fk - prev))
        if step != 0 and direction != 0 and step != direction:
            stack.append((prev, out[k - 1] if k else 0.0, step))
        if step != 0:
            direction = step
        while len(stack) > 1:
            fo, _, dr = stack[-1]
            target = -fo if len(stack) == 2 else stack[-2][0]
            if (dr > 0 and fk >= target) or (dr < 0 and fk <= target):
                stack.pop()
                if len(stack) > 1:
                    stack.pop()
            else:
                break
        fo, do, dr = stack[-1]
        out[k] = g(fk) if dr == 0 else do + 2.0 * g((fk - fo) / 2.0)
        prev = fk
    return out


@settings(max_examples=300, deadline=None)
@given(st.lists(st.integers(-6, 6).map(lambda i: 50.0 * i)
                | st.floats(-300.0, 300.0, allow_nan=False), max_size=30))
def test_fast_walk_equals_sample_by_sample_rules(forces):
    """Repeated values, exact hits of closure points and random values alike."""
    f = np.array(forces, dtype=float)
    np.testing.assert_array_equal(masing_response(G, f), _reference_walk(G, f))
