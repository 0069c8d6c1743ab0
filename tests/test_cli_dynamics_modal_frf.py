"""``microslip modal`` and ``microslip frf`` with a Jenkins joint: the JSON keys of the
issue's command line against the closed forms (single-harmonic balance, stuck linear
limit), errors as one line."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import run, run_json

from microslip.cli.main import main

M, F0, KJ, FS = 2.0, 100.0, 300.0, 5.0  # kg, Hz, N/mm, N
MODE = ["--frequency", str(F0), "--modal-mass", str(M)]
JOINT = ["--joint", "jenkins", "--joint-stiffness", str(KJ), "--slip-force", str(FS)]
K = M * (2 * np.pi * F0) ** 2 * 1e-3  # structure's stiffness, N/mm
MASS = M * 1e-3  # N s^2/mm


def jenkins_df(a):
    """K_eq, D_eq (N/mm) of the Jenkins joint (REFERENCES.md)."""
    ds = FS / KJ
    beta = np.arccos(np.clip(1 - 2 * ds / a, -1, 1))
    k_eq = np.where(a > ds, KJ / np.pi * (beta - np.sin(2 * beta) / 2), KJ)
    d_eq = np.where(a > ds, 4 * FS * (a - ds) / (np.pi * a**2), 0.0)
    return k_eq, d_eq


def test_modal_single_harmonic_is_the_closed_form_backbone(capsys):
    """w^2 = (k + K_eq) / m, zeta = (c w + D_eq) / (2 m w^2); the quadrature of the
    describing function errs by at most 4 k_J / N^2 on K_eq and D_eq. The energy method
    reported beside it uses 512 samples."""
    n = 512
    out = run_json(capsys, "modal", *MODE, "--damping-ratio", "0.01", *JOINT,
                           "--harmonics", "1", "--samples", str(n),
                           "--amplitude-range", "1e-3", "1", "--amplitudes", "13")
    a = np.array(out["amplitude_mm"])
    np.testing.assert_allclose(a, np.geomspace(1e-3, 1.0, 13), rtol=1e-15)
    k_eq, d_eq = jenkins_df(a)
    w = np.sqrt((K + k_eq) / MASS)
    c = 2 * 0.01 * MASS * 2 * np.pi * F0
    bound = 4 * KJ / n**2
    np.testing.assert_allclose(out["frequency_Hz"], w / (2 * np.pi), rtol=bound / (2 * K))
    np.testing.assert_allclose(out["damping_ratio"], (c * w + d_eq) / (2 * MASS * w**2),
                               rtol=0, atol=bound / (2 * MASS * w.min() ** 2))
    assert out["harmonics"] == 1 and out["samples"] == n
    # the energy method reported beside it is the same balance, to solver tolerance
    np.testing.assert_allclose(out["energy_method"]["frequency_Hz"], out["frequency_Hz"],
                               rtol=1e-12)


def test_modal_stuck_limit_includes_the_linear_damping(capsys):
    """Below the slip amplitude the joint is a spring: f = stuck frequency and
    zeta = zeta_lin f_free / f_stuck (c fixed by --frequency), with 7 harmonics (the
    default), and with the harmonics chosen (auto): 1 and 3 agree to rounding, 3 are kept."""
    stuck = F0 * np.sqrt((K + KJ) / K)
    for extra in (["--harmonics", "7"], ["--harmonics", "auto"]):
        out = run_json(capsys, "modal", *MODE, "--damping-ratio", "0.02", *JOINT,
                       "--amplitude-range", "1e-4", "1e-2", "--amplitudes", "3", *extra)
        assert out["structure"]["stuck_frequency_Hz"] == pytest.approx(stuck, rel=1e-14)
        np.testing.assert_allclose(out["frequency_Hz"], stuck, rtol=1e-12)
        np.testing.assert_allclose(out["damping_ratio"], 0.02 * F0 / stuck, rtol=1e-10)
    assert out["harmonics"] == [3, 3, 3] and out["samples"] == [64, 64, 64]
    assert max(out["harmonic_error_estimate"]) < 1e-9
    assert out["harmonic_tolerance"] == 0.005


def test_modal_auto_reports_harmonics_per_amplitude(capsys):
    """``--harmonics auto``: per amplitude the harmonics taken, their samples
    and the error estimate, under the tolerance; the answer is the fixed balance's at those
    harmonics and samples. Fixed harmonics keep their keys as numbers."""
    argv = ["modal", *MODE, *JOINT, "--amplitude-range", "0.02", "0.2", "--amplitudes", "3"]
    out = run_json(capsys, *argv, "--harmonics", "auto", "--harmonic-tolerance", "0.001")
    assert all(e < 1e-3 for e in out["harmonic_error_estimate"])
    assert out["harmonic_tolerance"] == 0.001
    for i, (h, n) in enumerate(zip(out["harmonics"], out["samples"], strict=True)):
        assert h in (3, 7, 15, 31, 63) and n == max(32, 1 << (16 * (h + 1) - 1).bit_length())
        fixed = run_json(capsys, *argv, "--harmonics", str(h), "--samples", str(n))
        assert fixed["damping_ratio"][i] == pytest.approx(out["damping_ratio"][i], rel=1e-9)
        assert fixed["harmonics"] == h and "harmonic_error_estimate" not in fixed
    assert main([*argv, "--harmonics", "auto"]) == 0
    assert "harmonics auto:" in capsys.readouterr().out


def test_frf_auto_reports_harmonics_per_curve(capsys):
    out = run_json(capsys, "frf", *MODE, "--damping-ratio", "0.01", *JOINT, "--force", "1",
                   "--force", "3", "--harmonics", "auto")
    assert len(out["harmonics"]) == 2 and len(out["harmonic_error_estimate"]) == 2
    assert all(e < 5e-3 for e in out["harmonic_error_estimate"])
    assert out["harmonic_tolerance"] == 0.005


def test_frf_single_harmonic_peak_is_the_closed_form(capsys):
    """Without linear damping the peak of the single-harmonic balance is at phase
    resonance: D_eq(A) A = F gives A = d_s / (1 - pi F / (4 f_s)), and m w^2 = k + K_eq(A).
    The AFT quadrature errs by O(N^-2) on the amplitude (bound (2 pi / N)^2 / 2,
    test_dynamics_response). The sampled joint force is not invariant under a phase shift
    of the motion, and the phase turns fast through the resonance, so the peak frequency
    converges like N^-1 (measured 0.13 / N for N = 256 to 2048)."""
    n = 1024
    forces = (1.0, 2.0)
    out = run_json(capsys, "frf", *MODE, *JOINT, "--harmonics", "1", "--samples", str(n),
                           "--force", str(forces[0]), "--force", str(forces[1]))
    assert [c["force_N"] for c in out["curves"]] == list(forces)
    tol = 0.5 * (2 * np.pi / n) ** 2
    for c, force in zip(out["curves"], forces, strict=True):
        a = FS / KJ / (1 - np.pi * force / (4 * FS))
        w = np.sqrt((K + jenkins_df(np.array(a))[0]) / MASS)
        assert c["peak_amplitude_mm"] == pytest.approx(a, rel=tol)
        assert c["peak_frequency_Hz"] == pytest.approx(w / (2 * np.pi), rel=0.25 / n)
        assert c["success"]
        f, amp = np.array(c["frequency_Hz"]), np.array(c["amplitude_mm"])
        assert f.shape == amp.shape and f.size == c["points"] > 20
        assert f[0] == out["frequency_range_Hz"][0] and f[-1] == out["frequency_range_Hz"][1]
        # the located peak is above every continuation point, and near the largest one
        assert c["peak_amplitude_mm"] >= amp.max()
        assert c["peak_amplitude_mm"] < 1.01 * amp.max()


def test_frf_stuck_limit_is_the_linear_peak(capsys):
    """A force too small to slip the joint: the linear oscillator's peak,
    w^2 = K/m - c^2/(2 m^2), A = F / (c sqrt(K/m - c^2/(4 m^2))), with 7 harmonics."""
    force, zeta = 0.01, 0.01
    out = run_json(capsys, "frf", *MODE, "--damping-ratio", str(zeta), *JOINT,
                           "--force", str(force), "--frequency-range", "110", "125")
    c = 2 * zeta * MASS * 2 * np.pi * F0
    kk = K + KJ
    curve = out["curves"][0]
    assert curve["peak_amplitude_mm"] < FS / KJ  # stuck
    assert curve["peak_frequency_Hz"] == pytest.approx(
        np.sqrt(kk / MASS - c**2 / (2 * MASS**2)) / (2 * np.pi), rel=1e-9)
    assert curve["peak_amplitude_mm"] == pytest.approx(
        force / (c * np.sqrt(kk / MASS - c**2 / (4 * MASS**2))), rel=1e-10)


def test_text_output_has_units(capsys):
    assert main(["frf", *MODE, "--damping-ratio", "0.01", *JOINT, "--harmonics", "1",
                 "--force", "1"]) == 0
    text = capsys.readouterr().out
    for unit in ("force (N)", "peak a (mm)", "peak f (Hz)", " Hz"):
        assert unit in text
    assert main(["modal", *MODE, *JOINT, "--amplitude-range", "0.01", "0.1",
                 "--amplitudes", "2", "--method", "energy"]) == 0
    text = capsys.readouterr().out
    for unit in ("q (mm)", "f (Hz)", "zeta (-)"):  # q: the modal coordinate
        assert unit in text


def test_csv_and_plot_are_written(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    csv, png = tmp_path / "frf.csv", tmp_path / "frf.png"
    assert main(["frf", *MODE, "--damping-ratio", "0.01", *JOINT, "--harmonics", "1",
                 "--force", "1", "--csv", str(csv), "--plot", str(png)]) == 0
    header = csv.read_text().splitlines()[0]
    assert header == "force_N,frequency_Hz,amplitude_mm"
    assert png.stat().st_size > 1000


MODAL = ["modal", *MODE, *JOINT, "--amplitude-range", "0.01", "0.1"]
FRF = ["frf", *MODE, *JOINT]


@pytest.mark.parametrize(("argv", "message"), [
    ([*FRF, "--force", "0"], "--force must be finite and > 0 N"),
    ([*FRF, "--force", "1", "--force", "-2"], "--force must be finite and > 0 N"),
    ([*FRF, "--force", "1", "--harmonics", "0"], "--harmonics must be in [1, 256]"),
    ([*FRF, "--force", "1", "--harmonics", "7", "--samples", "15"],
     "--samples must be in [16, 65536]"),
    ([*FRF, "--force", "1", "--harmonics", "auto", "--samples", "256"],
     "--samples is not used with --harmonics auto"),
    ([*MODAL, "--harmonics", "auto", "--samples", "256"], "--samples is not used with"),
    ([*MODAL, "--harmonics", "7", "--harmonic-tolerance", "0.01"],
     "--harmonic-tolerance is used by --harmonics auto only"),
    ([*MODAL, "--harmonics", "auto", "--harmonic-tolerance", "0.5"],
     "--harmonic-tolerance must be in (0, 0.5)"),
    ([*MODAL, "--harmonics", "auto", "--harmonic-tolerance", "0"],
     "--harmonic-tolerance must be in (0, 0.5)"),
    ([*MODAL, "--harmonic-tolerance", "0.01"],
     "--harmonic-tolerance is used by --harmonics auto only"),
    ([*MODAL, "--method", "energy", "--harmonic-tolerance", "0.01"],
     "--harmonic-tolerance is not used by --method energy"),
    ([*FRF, "--force", "1", "--frequency-range", "120", "80"], "0 < MIN < MAX (Hz)"),
    ([*FRF, "--force", "1", "--step", "2"], "--step must be in (0, 1]"),
    (["modal", *MODE, *JOINT, "--amplitude-range", "0.1", "0.01"], "0 < MIN <= MAX (mm)"),
    ([*MODAL, "--amplitudes", "0"], "--amplitudes must be in [1, 100000]"),
    ([*MODAL, "--damping-ratio", "1"], "damping ratio must be in [0, 1)"),
    ([*MODAL, "--participation", "0"], "participation must be finite and != 0"),
    ([*MODAL, "--modal-mass", "0"], "modal mass must be > 0 (kg), got 0"),
    # options that would do nothing are refused
    ([*MODAL, "--method", "energy", "--harmonics", "3"], "--harmonics is not used by"),
    ([*MODAL, "--length", "50"], "--length not used by --joint jenkins"),
    ([*FRF, "--force", "1", "--no-corrections"], "--no-corrections not used by"),
    ([*FRF, "--force", "1", "--chi", "-0.5"], "--chi not used by --joint jenkins"),
])
def test_bad_input_is_one_line_and_exit_1(capsys, argv, message):
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert message in err
    assert err.count("\n") == 1


def test_harmonics_neither_auto_nor_a_number_is_a_usage_error(capsys):
    assert main([*MODAL, "--harmonics", "many"]) == 2
    assert "not auto or a whole number: 'many'" in capsys.readouterr().err


def test_missing_force_is_a_usage_error(capsys):
    assert main(FRF) == 2
    assert "--force" in capsys.readouterr().err


def test_mesh_commands_refuse_auto_harmonics_in_one_line(capsys):
    """modal --mesh and frf --mesh take a fixed number of harmonics: ``auto`` is refused with
    the way to get it (modal --structure on the written ROM), not silently replaced."""
    from pathlib import Path

    mesh = str(Path(__file__).resolve().parents[1] / "examples" / "cantilever.inp")
    clamp = ["--mesh", mesh, "--contact-set", "contact", "--clamp-set", "clamp",
             "--normal-force", "2000", "--friction", "0.5", "--modulus", "70000",
             "--poisson-ratio", "0.33", "--density", "2700", "--response-set", "response"]
    code, _, err = run(capsys, "modal", *clamp, "--solver", "rom", "--harmonics", "auto")
    assert code == 1 and err.count("\n") == 1 and "modal --structure rom.npz" in err
    code, _, err = run(capsys, "frf", *clamp, "--force", "1", "--harmonics", "auto")
    assert code == 1 and err.count("\n") == 1 and "not available with frf --mesh" in err
