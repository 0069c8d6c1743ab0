"""Invariants of the models, loops and energies, for random clamped zones (hypothesis)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from microslip import (
    CENTRE_READINGS,
    POISSON_MODES,
    STRAIN_ENERGY,
    ClampParams,
    ModelOptions,
    damping,
    macroslip_force,
    masing_response,
)

params_st = st.builds(
    ClampParams,
    length=st.floats(5.0, 500.0),
    width=st.floats(1.0, 100.0),
    thickness=st.floats(0.5, 100.0),
    modulus=st.floats(1e3, 3e5),
    poisson_ratio=st.floats(0.0, 0.49),
    friction=st.floats(0.05, 1.5),
    normal_force=st.floats(10.0, 1e5),
)
options_st = st.builds(
    ModelOptions,
    poisson=st.sampled_from([m for m in POISSON_MODES if m != "paper-literal"]),
    length_update=st.booleans(),
    centre=st.sampled_from(CENTRE_READINGS),
)


@settings(max_examples=60, deadline=None)
@given(params_st, options_st, st.sampled_from(["tip", "centre"]), st.floats(0.02, 0.95),
       st.integers(4, 300), st.sampled_from(list(STRAIN_ENERGY)))
def test_loop_invariants(p, opt, model, fraction, n, kind):
    amp = fraction * macroslip_force(model, p, opt)
    assume(amp / p.axial_stiffness < 0.02)  # small strain, as the models assume
    r = damping(model, p, amp, n, opt, kind)
    bb, loop = r.backbone, r.loop
    # monotonic backbone from the origin
    assert bb.displacement[0] == 0.0
    assert np.all(np.diff(bb.displacement) > 0)
    # loop closes and is point-symmetric: descending(F) = -ascending(-F)
    assert loop.force[0] == loop.force[-1] and loop.displacement[0] == loop.displacement[-1]
    m = (loop.force.size - 1) // 2
    np.testing.assert_allclose(loop.force[: m + 1], -loop.force[m:], rtol=1e-12,
                               atol=1e-12 * amp)
    np.testing.assert_allclose(loop.displacement[: m + 1], -loop.displacement[m:],
                               rtol=1e-12, atol=1e-12 * r.peak_displacement)
    # energy positive and loss factor bounded: W_d <= 4 F0 d0 (Masing), so eta_secant <= 4/pi
    assert r.dissipated_energy > 0.0 and r.strain_energy > 0.0
    assert r.dissipated_energy <= 4.0 * r.amplitude * r.peak_displacement
    assert 0.0 < r.loss_factor <= 4.0 / math.pi


@settings(max_examples=40, deadline=None)
@given(params_st, st.floats(0.05, 0.9), st.integers(1, 3))
def test_masing_response_of_sine_retraces_the_loop(p, fraction, cycles):
    """A sinusoidal force history follows the Masing loop and dissipates W_d per cycle."""
    amp = fraction * p.macroslip_force
    assume(amp / p.axial_stiffness < 0.02)  # small strain, as the models assume
    r = damping("tip", p, amp, 400, ModelOptions.uncorrected())
    theta = np.linspace(0.0, 2 * math.pi * (cycles + 0.25), 800 * cycles + 201)
    f = amp * np.sin(theta)
    d = masing_response(r.backbone, f)
    last = theta >= theta[-1] - 2 * math.pi
    w = float(np.sum(0.5 * (f[last][1:] + f[last][:-1]) * np.diff(d[last])))
    assert abs(w / r.dissipated_energy - 1) < 2e-3
    assert d[-1] == np.float64(d[last][0]) or abs(d[-1] - d[last][0]) < 1e-9 * r.peak_displacement
