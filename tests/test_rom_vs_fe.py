"""The contact-node ROM against the full FE on the 12x3x1 cantilever (issue 23): the same
quasi-static modal analysis on both (the ROM's own error), and the ROM's EPMC against the
full FE's QSMA (the issue's check; benchmarks/rom_vs_fe.py prints it on 24x6x2)."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.dynamics.modal import quasi_static
from microslip.dynamics.modal_odd import epmc_odd
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.modes import linear_modes
from microslip.meshdynamics.qsma import first_slip_force, qsma
from microslip.meshdynamics.reduce import build_rom, rom_structure

#: The issue's aluminium cantilever (MPa, -, kg/m^3, -, N, N/mm^3).
E, NU, RHO, MU, FN, LAM = 70000.0, 0.33, 2700.0, 0.5, 2000.0, 1e4


@pytest.fixture(scope="module")
def in_plane():
    """The FE's QSMA of the in-plane bending (mode 2) at 1.5 and 2.5 times its first-slip
    force (damping ratio about 1.6 % and 3.5 %), and the ROM (20 fixed-interface modes)
    with the response set's mean motion along the mode as its output."""
    model = build_mesh_model(cantilever_mesh(12, 3, 1), rigid_base(contact_set="contact",
                                                                   clamp_set="clamp",
                                                                   normal_force=FN, modulus=E,
                                                                   poisson_ratio=NU, friction=MU,
                                                                   stick_slope=LAM,
                                                                   normal_contact="fixed"))
    mode = linear_modes(model, RHO, 2, response_set="response").select(2)
    forces = np.array([1.5, 2.5]) * first_slip_force(model, mode)
    fe = qsma(model, mode, forces)
    rom = build_rom(model, RHO, modes=20, response_set="response")
    return fe, forces, rom_structure(rom, mode.direction @ rom.output)


@pytest.mark.slow  # about 15 s
def test_rom_quasi_static_equals_the_full_fe(in_plane):
    """The same quasi-static analysis (the load q sin(2 pi t) M phi, first-harmonic
    frequency, zeta = W / (2 pi a^2 w^2)) on the ROM by harmonic balance at w = 0 (15
    harmonics) and on the full FE by its cyclic incremental solution: the ROM carries the
    FE's contact law node by node, so they agree to the ROM's modal truncation, the
    harmonics and the FE's settling (measured: amplitude within 6e-4, frequency within
    4e-4, damping within 0.5 %). The clamping step's tangential stick forces (up to half
    the friction limit), which the ROM leaves out, shake down in the settled cycle."""
    fe, forces, s = in_plane
    rq = quasi_static(s, forces, 15, samples=256, mode=1)
    assert np.allclose(rq.amplitude, fe.amplitude_mm, rtol=1e-3)
    assert np.allclose(rq.frequency, fe.frequency_Hz, rtol=5e-4)
    assert np.allclose(rq.damping_ratio, fe.damping_ratio, rtol=0.01)
    assert fe.damping_ratio[0] > 0.01 and fe.damping_ratio[1] > 0.03


@pytest.mark.slow
def test_rom_epmc_against_the_full_fe_qsma(in_plane):
    """The issue's check: the ROM's EPMC at the FE's amplitudes against the full FE's QSMA,
    frequency within 0.5 % and damping ratio within 5 %. The gap is the method's (the
    EPMC's dynamics and its harmonic truncation against a quasi-static load: the ROM's own
    QSMA is within 0.5 %, above). Measured on this coarse mesh (20 contact nodes, each
    slipping node 5 % of the area): with 7 harmonics frequency +0.14 % and +0.01 %, damping
    -5.3 % and +2.6 %; with 15 harmonics +0.12 % and -0.03 %, -4.6 % and +3.1 % (on the
    24x6x2 mesh 7 harmonics hold the targets: benchmarks/rom_vs_fe.py)."""
    fe, _forces, s = in_plane
    ep = epmc_odd(s, fe.amplitude_mm, 15, mode=1)
    assert np.all(np.abs(ep.frequency / fe.frequency_Hz - 1.0) < 0.002)
    assert np.all(np.abs(ep.damping_ratio / fe.damping_ratio - 1.0) < 0.05)
