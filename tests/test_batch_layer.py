"""The batch engine on a contact (shear layer + pressure law) and the compiled slip front.

Exact references first: Menq's shear-layer bar (parametric in the slip length, shared/
REFERENCES.md) and the rigid foundation as the stick slope grows, both through the batch
engine; then an independent NumPy bisection of F(a) = f (the method the library used before
the compiled front), and the physical front (the first crossing) where F(a) is not monotone;
then the batch engine against the single loop, bit for bit, and sweeps that use it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import ModelOptions, ParameterError, damping, preset
from microslip.batch import batch_damping
from microslip.models import Contact
from microslip.models.interface import (
    layer_stiffness,
    power_law,
    table_law,
    tip_domain,
    virgin_curve,
)
from microslip.sweep import make_sweep, run_sweep

P = preset("table1")
EA = P.axial_stiffness
Q = P.friction_per_length
ASYMMETRIC = table_law([0.0, 100.0, P.length], [1.0, 2.0, 3.0], P.length)
CONTACTS = [pytest.param(Contact.layer(1e5), marks=pytest.mark.slow),  # 4-10 s a model
            Contact.layer(1e4, "parabolic"),
            Contact.layer(2e3, power_law(0.7, 3.0)), Contact(math.inf, False, ASYMMETRIC),
            Contact.layer(1e3, ASYMMETRIC)]
AMPS = np.array([40.0, 150.0, 213.0, 300.0])


@pytest.mark.parametrize("front", [0.05, 0.3, 0.7, 0.95])
def test_batch_menq_closed_form(front: float) -> None:
    """Menq: F = q a + (q/lambda) tanh(lambda (L - a)), d = q/k + (F a - q a^2/2)/(E A)."""
    slope = 2e3
    k = slope * P.width
    lam = math.sqrt(k / EA)
    a = front * P.length
    f = Q * a + Q / lam * math.tanh(lam * (P.length - a))
    d = Q / k + (f * a - Q * a * a / 2) / EA
    r = batch_damping("tip", P, np.array([f]), 200, ModelOptions.uncorrected(),
                      contact=Contact(slope, shear_lag=False))
    assert r.peak_displacement[0] == pytest.approx(d, rel=1e-13)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_batch_rigid_limit_is_the_rigid_engine(model: str) -> None:
    rigid = batch_damping(model, P, AMPS, 400)
    stiff = batch_damping(model, P, AMPS, 400, contact=Contact(1e300, shear_lag=False))
    np.testing.assert_allclose(stiff.loss_factor, rigid.loss_factor, rtol=1e-9)
    np.testing.assert_allclose(stiff.dissipated_energy, rigid.dissipated_energy, rtol=1e-9)


def _bisection_d(slope: float, law, forces: np.ndarray) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Tip bar: the slip front by 64 bisections of F(a) = f in NumPy, then d(a)."""
    k = layer_stiffness(P, slope, shear_lag=True)
    lam = math.sqrt(k / EA)
    limit, length = P.macroslip_force, P.length

    def xi(s: np.ndarray) -> np.ndarray:
        return 1.0 - s / length

    def big_q(s: np.ndarray) -> np.ndarray:
        return -limit * (law.cumulative(xi(s)) - 1.0)

    def q(s: np.ndarray) -> np.ndarray:
        return limit / length * law.shape(xi(s))

    def force(s: np.ndarray) -> np.ndarray:
        return big_q(s) + q(s) / lam * np.tanh(lam * (length - s))

    lo, hi = np.zeros_like(forces), np.full_like(forces, length)
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        below = force(mid) < forces
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    a = 0.5 * (lo + hi)
    r = limit * length * (law.second(xi(a)) - law.second(np.ones_like(a)) - (xi(a) - 1.0))
    return q(a) / k + (forces * a - r) / EA


@pytest.mark.parametrize("law", [power_law(1.0, 1.0), power_law(2.0, 3.0),
                                 power_law(3.5, 2.0), ASYMMETRIC], ids=lambda law: law.name)
def test_compiled_front_is_the_bisection_root(law) -> None:  # type: ignore[no-untyped-def]
    for slope in (1e3, 1e5):
        onset = tip_domain(P, layer_stiffness(P, slope), law).onset
        forces = np.linspace(1.001 * onset, 0.95 * P.macroslip_force, 60)
        d = virgin_curve("tip", P, forces, stick_slope=slope, law=law)[1]
        np.testing.assert_allclose(d, _bisection_d(slope, law, forces), rtol=1e-12)


@pytest.mark.slow
def test_front_is_the_first_crossing_where_f_of_a_is_not_monotone() -> None:
    """A sharp pressure minimum in the middle (n = 0.5) on a soft layer makes F(a) fall
    somewhere: the loaded front then jumps to the next point where F reaches the load, the
    smallest a with F(a) >= f (a bisection of [0, L] may find a later root)."""
    law = power_law(0.5, 3.0)
    bar = tip_domain(P, layer_stiffness(P, 1e3), law)
    grid = np.linspace(0.0, P.length, 400001)
    values = bar.force(grid)
    assert np.any(np.diff(values) < 0.0)  # the case is what it says
    forces = np.linspace(bar.onset, 0.98 * P.macroslip_force, 301)[1:]
    slip = virgin_curve("tip", P, forces, stick_slope=1e3, law=law)[0][0]
    first = grid[np.argmax(values[None, :] >= forces[:, None], axis=1)]
    np.testing.assert_allclose(slip, first, atol=2 * (grid[1] - grid[0]))


@pytest.mark.parametrize("contact", CONTACTS, ids=lambda c: f"{c.law_name}-{c.stick_slope:g}")
@pytest.mark.parametrize("model", ["tip", "centre"])
def test_batch_is_the_single_loop_bit_for_bit(model: str, contact: Contact) -> None:
    for kind in ("secant", "backbone", "branch"):
        for opt in (ModelOptions(), ModelOptions(poisson="paper-literal", length_update=False)):
            r = batch_damping(model, P, AMPS, 300, opt, kind, contact=contact)
            for i, f0 in enumerate(AMPS):
                s = damping(model, P, float(f0), 300, opt, kind, contact=contact)
                assert r.peak_displacement[i] == s.peak_displacement
                assert r.dissipated_energy[i] == s.dissipated_energy
                assert r.strain_energy[i] == s.strain_energy
                assert r.loss_factor[i] == s.loss_factor
    py = batch_damping(model, P, AMPS[:2], 30, contact=contact, backend="python")
    assert py.loss_factor.tolist() == [
        damping(model, P, float(f), 30, contact=contact).loss_factor for f in AMPS[:2]]


@settings(max_examples=15, deadline=None)
@given(thickness=st.floats(2.0, 40.0), slope=st.floats(1e3, 1e6),
       fraction=st.floats(0.05, 0.9), threads=st.sampled_from([1, 2]))
def test_batch_of_varied_cases_matches_each_loop(thickness: float, slope: float,
                                                 fraction: float, threads: int) -> None:
    thick = np.array([thickness, 0.5 * thickness, 2.0 * thickness])
    amp = fraction * P.macroslip_force
    c = Contact.layer(slope, "parabolic")
    r = batch_damping("tip", {**P.as_dict(), "thickness": thick}, amp, 200, contact=c,
                      threads=threads)
    for t, w in zip(thick, r.dissipated_energy, strict=True):
        p = P.__class__(**{**P.as_dict(), "thickness": float(t)})
        assert w == damping("tip", p, amp, 200, contact=c).dissipated_energy


def test_batch_refusals_on_a_contact() -> None:
    c = Contact.layer(1e4)
    with pytest.raises(ParameterError, match="'stored'"):
        batch_damping("tip", P, AMPS, 100, strain_energy="stored", contact=c)
    with pytest.raises(ParameterError, match="physical centre reading"):
        batch_damping("centre", P, AMPS, 100, ModelOptions(centre="paper"), contact=c)
    with pytest.raises(ParameterError, match="contact must be a Contact"):
        batch_damping("tip", P, AMPS, 100, contact=1e4)  # type: ignore[arg-type]


def test_sweep_on_a_contact_runs_the_batch_engine() -> None:
    c = Contact.layer(1e4, power_law(2.0, 3.0))
    spec = make_sweep("centre", P, grid=[("amplitude", AMPS), ("thickness", [3.18, 6.0])],
                      increments=200, contact=c)
    r = run_sweep(spec, progress=False, chunk_size=3, threads=2)
    assert r.backend == "numba"
    for i in range(spec.size):
        p = P.__class__(**{**P.as_dict(), "thickness": float(spec.column("thickness")[i])})
        s = damping("centre", p, float(spec.column("amplitude")[i]), 200, contact=c)
        assert r.loss_factor[i] == s.loss_factor
        assert r.dissipated_energy[i] == s.dissipated_energy
