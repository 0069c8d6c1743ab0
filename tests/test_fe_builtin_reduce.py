"""The reduced model with every contact node (issue 23, item 3): Craig-Bampton on the
cantilever's own mesh against the full FE's stuck frequencies, the response set's output
rows, the ROM as a structure file that ``modal`` and ``frf`` read (each contact node its own
circular Jenkins element), and its EPMC (softening, damping rising from the stuck values;
against its own time integration)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from microslip.dynamics.assemble import from_matrices
from microslip.dynamics.files import read_structure
from microslip.dynamics.hb import HarmonicBalance
from microslip.dynamics.modal import epmc
from microslip.dynamics.operators import jenkins
from microslip.dynamics.operators2d import CircularIwan
from microslip.dynamics.structure import SI_PER_MM
from microslip.dynamics.timeint import transient
from microslip.errors import ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.reduce import (
    build_rom,
    convergence,
    full_mass,
    rom_structure,
    stuck_frequencies_full,
    write_rom,
)

#: Aluminium cantilever, the issue's values (MPa, -, kg/m^3, -, N, N/mm^3).
E, NU, RHO, MU, FN, LAM, KN = 70000.0, 0.33, 2700.0, 0.5, 2000.0, 1e4, 1e6


def model(nx: int = 24, ny: int = 6, nz: int = 2, normal: str = "fixed"):
    return build_mesh_model(cantilever_mesh(nx, ny, nz), rigid_base(contact_set="contact",
                                                                    clamp_set="clamp",
                                                                    normal_force=FN, modulus=E,
                                                                    poisson_ratio=NU, friction=MU,
                                                                    stick_slope=LAM,
                                                                    normal_contact=normal,
                                                                    normal_slope=KN))


@pytest.fixture(scope="module")
def cantilever():
    m = model()
    return m, full_mass(m, RHO)


@pytest.fixture(scope="module")
def small():
    """The 12x3x1 cantilever's ROM (20 contact nodes, 6 modes): fast enough to integrate."""
    rom = build_rom(model(12, 3, 1), RHO, modes=6, response_set="response")
    return rom, rom_structure(rom)


@pytest.mark.slow
def test_stuck_frequencies_equal_the_full_fe_with_enough_modes(cantilever):
    m, mass = cantilever
    full = stuck_frequencies_full(m, mass, 6)
    rom = build_rom(m, RHO, modes=60, mass=mass)
    assert np.max(np.abs(rom.stuck_frequencies(6) / full - 1.0)) < 1e-6
    assert 480.0 < full[0] < 500.0  # the out-of-plane bending, the lowest


@pytest.mark.slow
def test_error_falls_with_the_number_of_modes(cantilever):
    m, mass = cantilever
    table = convergence(m, RHO, [5, 20, 60], compare=6, mass=mass)
    err = np.abs(np.array(table["relative_error"]))
    worst = err.max(axis=1)
    assert worst[0] > 1e-3 and worst[1] < 1e-5 and worst[2] < 1e-6
    assert np.all(np.diff(worst) < 0.0)
    # CB from above (a constrained Rayleigh-Ritz): never below the full FE (to rounding)
    assert np.all(np.array(table["relative_error"]) > -1e-9)


def test_cutoff_keeps_every_mode_below_it(cantilever):
    m, mass = cantilever
    rom = build_rom(m, RHO, cutoff_hz=60000.0, mass=mass)
    more = build_rom(m, RHO, modes=rom.modes + 1, mass=mass)
    assert rom.interface_frequencies[-1] <= 60000.0 < more.interface_frequencies[-1]
    assert rom.dofs == 2 * m.contact_nodes.size + rom.modes


def test_output_rows_are_exact_for_contact_loads(cantilever):
    """A static load on the contact dofs is reproduced exactly by the constraint modes
    (whatever the modes kept): the response set's mean displacement equals the full FE's."""
    m, mass = cantilever
    rom = build_rom(m, RHO, modes=3, response_set="response", mass=mass)
    springs = rom.contact_springs()
    f_rom = np.zeros(rom.dofs)
    f_rom[1:rom.boundary.size:2] = 1.0  # 1 N along e2 on every contact node
    q = np.linalg.solve(rom.stiffness + np.diag(springs), f_rom)
    s = np.zeros(m.dof)
    s[m.contact_dofs.ravel()] = np.repeat(m.contact_stiffness, 2)
    f = np.zeros(m.dof)
    f[m.contact_dofs[:, 1]] = 1.0
    u = sp.linalg.spsolve((m.stiffness + sp.diags(s)).tocsc(), f)
    nodes = m.mesh.node_sets["response"]
    mean = m.global_vectors(u)[nodes].mean(axis=0)
    assert np.allclose(rom.output @ q, mean, rtol=0.0, atol=1e-9 * np.abs(mean).max())
    assert abs(mean[1]) > 10 * abs(mean[0])


def test_structure_file_round_trip(cantilever, tmp_path):
    m, mass = cantilever
    rom = build_rom(m, RHO, modes=10, response_set="response", mass=mass)
    path = str(tmp_path / "rom.npz")
    write_rom(path, rom)
    mf = read_structure(path)
    assert mf.joints.shape == (m.contact_nodes.size, 2, 2)
    assert np.array_equal(mf.laws[:, 0], m.contact_stiffness)
    assert np.array_equal(mf.laws[:, 1], m.friction_limit)
    # the command line's joint is not used: every node carries its own law
    s = from_matrices(mf, mf.joints, jenkins(1.0, 1.0), "circular")
    ops = [link.operator for link in s.joints]
    assert all(isinstance(op, CircularIwan) for op in ops)
    assert np.allclose([op.initial_stiffness for op in ops], m.contact_stiffness, rtol=1e-14)
    assert np.allclose([op.slip_force for op in ops], m.friction_limit, rtol=1e-12)
    assert np.allclose(s.linear_frequencies(stuck=True)[:6], rom.stuck_frequencies(6),
                       rtol=1e-9)
    assert np.allclose(rom_structure(rom).linear_frequencies(stuck=True)[:6],
                       rom.stuck_frequencies(6), rtol=1e-9)
    # another connectivity (--joint-dof) takes the command line's joint
    other = from_matrices(mf, mf.joints[::-1], jenkins(5.0, 2.0), "circular")
    assert all(link.operator.initial_stiffness == 5.0 for link in other.joints)


def test_structure_file_laws_checked(tmp_path):
    path = tmp_path / "bad.npz"
    np.savez(path, M=np.eye(2), K=np.eye(2), joints=np.array([[[0, -1], [1, -1]]]),
             joint_stiffness=np.array([1.0]))
    with pytest.raises(ParameterError, match="go together"):
        read_structure(str(path))
    np.savez(path, M=np.eye(2), K=np.eye(2), joints=np.array([[[0, -1], [1, -1]]]),
             joint_stiffness=np.array([1.0]), joint_slip_force=np.array([-1.0]))
    with pytest.raises(ParameterError, match="joint_slip_force must be finite and > 0"):
        read_structure(str(path))
    np.savez(path, M=np.eye(2), K=np.eye(2), joints=np.array([[[0, -1], [1, -1]]]))
    assert read_structure(str(path)).laws is None


def test_bad_input_refused(cantilever):
    m, mass = cantilever
    with pytest.raises(ParameterError, match="one of them"):
        build_rom(m, RHO, modes=5, cutoff_hz=1e4, mass=mass)
    with pytest.raises(ParameterError, match="modes must be an integer"):
        build_rom(m, RHO, modes=0, mass=mass)
    with pytest.raises(ParameterError, match="no node set 'nowhere'"):
        build_rom(m, RHO, modes=5, response_set="nowhere", mass=mass)
    with pytest.raises(ParameterError, match="density"):
        build_rom(m, -1.0, modes=5)


def test_penalty_reduces_to_3d_contact_elements(tmp_path):
    m = model(12, 3, 1, "penalty")
    mass = full_mass(m, RHO)
    rom = build_rom(m, RHO, modes=60, mass=mass)
    assert rom.per_node == 3 and rom.boundary.size == 3 * m.contact_nodes.size
    full = stuck_frequencies_full(m, mass, 4)
    assert np.max(np.abs(rom.stuck_frequencies(4) / full - 1.0)) < 1e-6
    s = rom_structure(rom)
    assert all(link.directions == 3 for link in s.joints)
    assert np.allclose(s.linear_frequencies(stuck=True)[:4], full, rtol=1e-6)
    write_rom(str(tmp_path / "rom.npz"), rom)  # 3-D contact joints (test_fe_builtin_rom_file)
    assert read_structure(str(tmp_path / "rom.npz")).joints.shape == (m.contact_nodes.size, 3, 2)


@pytest.mark.slow  # about 1 s, 20 s when the 3-D element's kernel compiles
def test_penalty_epmc_follows_the_fixed_one_in_plane():
    """In-plane bending barely moves the contact normally: the 3-D elements (penalty,
    limit mu N(t)) started from zero tangential force give the 2-D elements' curve (fixed
    normal, where the clamping step's stick forces shake down) to a fraction of a percent.
    (With the stick forces, which do not shake down under a varying N, the penalty ROM is
    checked against the full FE: tests/test_rom_penalty_stick.py.)"""
    import dataclasses

    a = np.geomspace(5e-3, 2e-2, 4)
    curves = []
    for normal in ("penalty", "fixed"):
        rom = build_rom(model(12, 3, 1, normal), RHO, modes=6, response_set="response")
        rom = dataclasses.replace(rom, stick_force=None)
        curves.append(epmc(rom_structure(rom), a, 3, mode=1))
    pen, fix = curves
    assert np.allclose(pen.frequency, fix.frequency, rtol=1e-3)
    assert np.allclose(pen.damping_ratio, fix.damping_ratio, rtol=0.03, atol=1e-4)
    assert pen.damping_ratio[-1] > 0.02


def _in_plane(structure) -> int:
    """The stuck mode that moves the response set most along y (the contact plane)."""
    from scipy.linalg import eigh

    _, vec = eigh(structure.stuck_stiffness(), structure.mass)
    return int(np.argmax(np.abs(structure.output @ vec[:, :4])))


def test_epmc_softens_and_damps_from_the_stuck_values(small):
    _rom, s = small
    mode = _in_plane(s)
    assert mode == 1
    stuck = s.linear_frequencies(stuck=True)[mode]
    a = np.geomspace(2e-3, 4e-2, 8)
    c = epmc(s, a, 5, mode=mode)
    assert abs(c.frequency[0] / stuck - 1.0) < 1e-9 and abs(c.damping_ratio[0]) < 1e-12
    assert np.all(np.diff(c.frequency) <= 1e-9 * stuck)
    assert c.frequency[-1] < 0.95 * stuck
    assert np.all(np.diff(c.damping_ratio) >= -1e-12) and c.damping_ratio[-1] > 0.02


def _epmc_state(s, a: float, harmonics: int, mode: int, samples: int = 128):
    """The EPMC solution at amplitude ``a`` (harmonics (dofs, 2H+1) in the full layout,
    omega, xi) on the odd harmonics (the ROM's joints are odd): Newton along six amplitudes
    up to ``a`` with 7 harmonics, then up the levels 15, 31, 63 below ``harmonics`` and at
    ``harmonics`` (and ``samples``), each from the one before."""
    from microslip.dynamics.harmonics import transfer
    from microslip.dynamics.modal import epmc_point, epmc_start

    low = HarmonicBalance(s, 7, 128, odd=True)
    y, w0 = epmc_start(s, low, mode)
    previous = 1.0
    for ai in np.geomspace(2e-3, a, 6):
        y[:low.size] *= ai / previous
        y, previous = epmc_point(low, float(ai), y, w0), ai
    hb = low
    for h in (*(h for h in (15, 31, 63) if h < harmonics), harmonics):
        if h == 7 and samples == 128:
            break
        up = HarmonicBalance(s, h, samples if h == harmonics else max(128, 16 * (h + 1)),
                             odd=True)
        y = epmc_point(up, a, np.concatenate([transfer(hb, up, y[:hb.size]), y[hb.size:]]),
                       w0)
        hb = up
    n = hb.size
    return hb.expand(y[:n]).reshape(s.dofs, 2 * harmonics + 1), float(y[n]), float(y[n + 1])


def _self_excitation(s, x, w: float, xi: float) -> np.ndarray:
    """The EPMC's self-excitation xi M q'(t) of the orbit ``x`` (dofs, 2H + 1) as harmonic
    coefficients (N): q' has c_k' = k w s_k, s_k' = -k w c_k."""
    k = np.arange(1, x.shape[1] // 2 + 1)
    dq = np.zeros_like(x)
    dq[:, 1::2] = w * k * x[:, 2::2]
    dq[:, 2::2] = -w * k * x[:, 1::2]
    return SI_PER_MM * xi * (s.mass @ dq)


def _forced_orbit(s, x, w: float, xi: float, periods: int = 20) -> tuple[float, float, float]:
    """The ROM under the EPMC's whole self-excitation xi M q'(t) (no negative damping),
    integrated in time from the EPMC orbit's state at t = 0 (the sliders at zero) at the
    EPMC's frequency; from the settled last period (max(15, H) harmonics of every dof, X_k):
    the first-harmonic natural frequency (Hz), the damping ratio from the load's work
    W per cycle and the output's first-harmonic amplitude (mm)."""
    load = _self_excitation(s, x, w, xi)
    k = np.arange(1, x.shape[1] // 2 + 1)
    x0 = x[:, 0] + x[:, 1::2].sum(axis=1)
    v0 = w * (x[:, 2::2] @ k)
    run = transient(s, load, w / (2 * np.pi), periods, initial=(x0, v0))
    assert run.change < 1e-3
    n = run.steps
    kk = np.arange(1, max(15, x.shape[1] // 2) + 1)
    basis = (2.0 / n) * np.exp(-2j * np.pi * np.outer(kk, np.arange(1, n + 1)) / n)
    xk = basis @ run.displacement  # (15, dofs): x(t) = Re sum X_k e^{i k w t}
    pk = load[:, 1::2] - 1j * load[:, 2::2]  # (dofs, H): p(t) = Re sum P_k e^{i k w t}
    x1 = xk[0]
    mass = SI_PER_MM * float(np.real(x1.conj() @ s.mass @ x1))
    w_ti = np.sqrt(w**2 + float(np.real(x1.conj() @ pk[:, 0])) / mass)
    work = np.pi / w * sum(float(np.real(pk[:, j].conj() @ (1j * (j + 1) * w * xk[j])))
                           for j in range(pk.shape[1]))  # N mm per cycle
    kinetic = SI_PER_MM * float(np.sum(kk**2 * np.real(
        np.einsum("ki,ij,kj->k", xk.conj(), s.mass, xk))))
    return w_ti / (2 * np.pi), work / (2 * np.pi * w**2 * kinetic), abs(s.output @ x1)


def _gaps(s, amplitude: float, harmonics: int, samples: int = 128
          ) -> tuple[float, float, float]:
    """Relative gaps time integration / EPMC: frequency, damping ratio, amplitude."""
    x, w, xi = _epmc_state(s, amplitude, harmonics, 1, samples)
    f, zeta, a = _forced_orbit(s, x, w, xi)
    return f / (w / (2 * np.pi)) - 1.0, zeta / (xi / (2 * w)) - 1.0, a / amplitude - 1.0


@pytest.mark.slow  # 80 s on a quiet machine (63 harmonics on 46 DOF; 29 min at load 15)
def test_epmc_against_time_integration(small):
    """The EPMC orbit q(t) (H harmonics, frequency w, negative damping xi) solves
    ``M q'' + K q + f(q) = xi M q'(t)`` once the right-hand side is taken as a given periodic
    load: the same equation with the artificial damping moved to the load. So the ROM
    loaded by the EPMC's whole self-excitation p(t) = xi M q'(t) (every harmonic kept) and
    integrated in time at w until settled reproduces the orbit, exactly as H grows and the
    time step shrinks. From the settled period (X_k, P_k the k-th harmonics of q and p):

    * frequency: ``w_t^2 = w^2 + Re(X_1^H P_1) / (X_1^H M X_1)``, the first-harmonic
      natural frequency (the first harmonic's balance with the in-phase part of the load
      moved to the stiffness side); w_t = w exactly when the load is in quadrature with the
      response (phase resonance), as it is on the EPMC orbit;
    * damping ratio: ``zeta_t = W / (2 pi w^2 sum_k k^2 X_k^H M X_k)``, W the load's work
      per cycle; on the EPMC orbit W = xi pi w sum_k k^2 X_k^H M X_k, so zeta_t = xi / (2 w),
      the EPMC's;
    * amplitude: the output's first harmonic, against the EPMC's a.

    The residual is the harmonic truncation (the time step is below 2e-4 of each gap:
    halving it moved the damping gap at a = 1.2e-2 mm from +1.69 % to +1.67 %). Measured on
    this ROM (odd harmonics; samples 128 up to 15 harmonics, then 16 (H + 1)):

    ==========  =================  =================  =================  ==================
    a (mm)      H = 7              H = 15             H = 31 (512)       H = 63 (1024)
    ==========  =================  =================  =================  ==================
    9e-3        f +0.01 %, z +0.4  f +0.02 %, z +0.8  f +0.01 %, z +0.2  f -0.000 %, z -0.01
    1.2e-2      f +0.03 %, z +1.7  f +0.01 %, z +0.9  f -0.00 %, z +0.2  f +0.001 %, z +0.02
    2e-2        f +0.10 %, z +2.4  f +0.06 %, z +1.6  f -0.01 %, z -0.3  see the test
    ==========  =================  =================  =================  ==================

    (z: the damping ratio's gap, %; damping ratios 1.2 %, 2.3 % and 4.8 %). The gap does not
    fall like 1/H: the contact nodes' own modes (the ROM with its joints slipping has modes
    at 1.7, 2.1, 3.0, 5.2, 7.7, 17 and 28 times the mode's 1.73 kHz) are reached by the
    stick-slip harmonics, and the orbit keeps their response: the damping ratio moves 1.5 %
    from 7 to 15 harmonics and 3 % from 15 to 31 at a = 2e-2 mm. The harmonics chosen by
    the error estimate (:mod:`microslip.dynamics.harmonics`, tolerance 0.5 %) climb to 63
    here (the 46-DOF ROM's balance fits the size limit) and meet the issue's 1 % in
    frequency and damping ratio at the three amplitudes, up to zeta 4.8 %; 7 harmonics do
    not (2.4 % at 2e-2 mm)."""
    from microslip.dynamics.harmonics import HarmonicControl, adaptive_epmc

    _rom, s = small
    amplitudes = (9e-3, 1.2e-2, 2e-2)
    auto = adaptive_epmc(s, amplitudes, mode=1, odd=True)
    assert auto.damping_ratio[-1] > 0.045
    for i, amplitude in enumerate(amplitudes):
        h = int(auto.point_harmonics[i])
        df, dz, da = _gaps(s, amplitude, h, HarmonicControl.samples(h))
        assert abs(df) < 1e-2 and abs(dz) < 1e-2 and abs(da) < 1e-2, (amplitude, h, df, dz)
    # 7 harmonics miss the 1 % at the top of the microslip range
    assert abs(_gaps(s, 2e-2, 7)[1]) > 0.02


def test_modal_and_frf_read_the_rom(small, tmp_path, capsys):
    """``microslip modal --structure rom.npz`` and ``frf`` take the ROM like any structure
    file; the file's per-node laws are its joints (a joint on the command line would change
    nothing and is refused: tests/test_cli_issue27_options.py)."""
    import json

    from microslip.cli.main import main

    rom, s = small
    path = str(tmp_path / "rom.npz")
    write_rom(path, rom)
    joint: list[str] = []
    assert main(["modal", "--structure", path, "--mode", "2", *joint, "--amplitude-range",
                 "1e-3", "1e-2", "--amplitudes", "2", "--harmonics", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    text = json.dumps(out)
    assert str(round(float(s.linear_frequencies(stuck=True)[1]), 3))[:7] in text
    assert main(["frf", "--structure", path, "--mode", "2", *joint, "--force", "1",
                 "--frequency-range", "1500", "1800", "--harmonics", "1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)


def test_odd_harmonic_epmc_is_the_same_curve(small):
    """Circular Jenkins elements to the ground are odd: the balance on the odd harmonics
    alone gives the EPMC's curve to rounding (at a fraction of the cost)."""
    from microslip.dynamics.modal_odd import epmc_odd

    _rom, s = small
    a = np.geomspace(5e-3, 3e-2, 5)
    full, odd = epmc(s, a, 5, mode=1), epmc_odd(s, a, 5, mode=1)
    assert odd.damping_ratio[-1] > 0.02
    assert np.allclose(odd.frequency, full.frequency, rtol=1e-10)
    assert np.allclose(odd.damping_ratio, full.damping_ratio, rtol=1e-8, atol=1e-14)
    pen = rom_structure(build_rom(model(12, 3, 1, "penalty"), RHO, modes=4))
    with pytest.raises(ParameterError, match="odd joint forces"):
        epmc_odd(pen, a, 3, mode=1)
