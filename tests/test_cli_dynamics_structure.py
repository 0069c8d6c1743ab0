"""``--structure`` on ``microslip modal`` and ``microslip frf``: matrices from .npz and
Matrix Market files, linear modes reported, the one-mode structure as a 1-DOF file, bad
files refused with one line, joint orbits of a two-directional joint."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.io
from conftest import run_json

from microslip.cli.main import main

F0, M = 100.0, 2.0  # Hz, kg
K = M * (2 * np.pi * F0) ** 2  # N/m
JOINT = ["--joint", "jenkins", "--joint-stiffness", "300", "--slip-force", "5"]


@pytest.fixture
def one_dof(tmp_path):
    path = tmp_path / "one.npz"
    np.savez(path, M=[[M]], K=[[K]], C=[[2 * 0.01 * M * 2 * np.pi * F0]],
             joints=np.array([[0, -1]]))
    return str(path)


@pytest.fixture
def planar(tmp_path):
    """1 kg in two bending planes at 100 and 101.5 Hz, a 2-D joint to the ground."""
    path = tmp_path / "planar.npz"
    k = (2 * np.pi * F0) ** 2
    np.savez(path, M=np.eye(2), K=np.diag([k, 1.03 * k]), C=2 * 0.01 * 2 * np.pi * F0 * np.eye(2),
             joints=np.array([[[0, -1], [1, -1]]]))
    return str(path)


def test_a_one_dof_file_is_the_one_mode_structure(capsys, one_dof):
    """Same modal curve and forced response as --frequency/--modal-mass, to round-off
    (the modal coordinate's weight M phi / phi^T M phi is 1 to an ulp)."""
    common = ["--amplitude-range", "1e-3", "1", "--amplitudes", "5"]
    a = run_json(capsys, "modal", "--structure", one_dof, *JOINT, *common)
    b = run_json(capsys, "modal", "--frequency", str(F0), "--modal-mass", str(M),
                         "--damping-ratio", "0.01", *JOINT, *common)
    np.testing.assert_allclose(a["frequency_Hz"], b["frequency_Hz"], rtol=1e-14)
    np.testing.assert_allclose(a["damping_ratio"], b["damping_ratio"], rtol=1e-13)
    forced = ["--force", "2", "--harmonics", "3", "--frequency-range", "90", "130"]
    a = run_json(capsys, "frf", "--structure", one_dof, *JOINT, *forced)
    b = run_json(capsys, "frf", "--frequency", str(F0), "--modal-mass", str(M),
                         "--damping-ratio", "0.01", *JOINT, *forced)
    assert a["curves"][0]["peak_amplitude_mm"] == pytest.approx(
        b["curves"][0]["peak_amplitude_mm"], rel=1e-13)
    np.testing.assert_allclose(a["curves"][0]["amplitude_mm"], b["curves"][0]["amplitude_mm"],
                               rtol=1e-13)


def test_linear_modes_are_reported_stuck_and_joint_free(capsys, planar):
    out = run_json(capsys, "modal", "--structure", planar, *JOINT, "--amplitude-range",
                           "1e-3", "1e-3", "--amplitudes", "1", "--mode", "2")
    s = out["structure"]
    free = F0 * np.sqrt([1.0, 1.03])
    np.testing.assert_allclose(s["joint_free_frequencies_Hz"], free, rtol=1e-13)
    # stuck: each plane gains the joint's 300 N/mm = 3e5 N/m
    k = (2 * np.pi * F0) ** 2
    stuck = np.sqrt(np.array([k, 1.03 * k]) + 3e5) / (2 * np.pi)
    np.testing.assert_allclose(s["stuck_frequencies_Hz"], stuck, rtol=1e-13)
    assert s["mode"] == 2 and s["dofs"] == 2
    # small amplitude: mode 2 stuck, damping 1 % of the joint-free frequency's c
    assert out["frequency_Hz"][0] == pytest.approx(stuck[1], rel=1e-10)
    assert out["damping_ratio"][0] == pytest.approx(0.01 * F0 / stuck[1], rel=1e-9)


def test_text_output_lists_the_linear_modes(capsys, planar):
    assert main(["modal", "--structure", planar, *JOINT, "--amplitude-range", "1e-3",
                 "1e-2", "--amplitudes", "2", "--method", "energy"]) == 0
    text = capsys.readouterr().out
    assert "linear modes (Hz), stuck: 132.662, 133.787;" in text
    assert "joints removed: 100, 101.489" in text
    assert "2 DOFs, mode 1: 100 Hz with the joint removed" in text


def test_matrix_market_directory_is_the_npz(capsys, tmp_path, one_dof):
    scipy.io.mmwrite(tmp_path / "M.mtx", np.array([[M]]))
    scipy.io.mmwrite(tmp_path / "K.mtx", np.array([[K]]))
    scipy.io.mmwrite(tmp_path / "C.mtx", np.array([[2 * 0.01 * M * 2 * np.pi * F0]]))
    common = [*JOINT, "--amplitude-range", "1e-3", "1", "--amplitudes", "3"]
    a = run_json(capsys, "modal", "--structure", str(tmp_path), "--joint-dof", "0",
                         *common)
    b = run_json(capsys, "modal", "--structure", one_dof, *common)
    np.testing.assert_allclose(a["frequency_Hz"], b["frequency_Hz"], rtol=1e-15)


def test_two_directional_joint_orbits_and_coupling(capsys, planar):
    """Excited on the diagonal, the two close modes put the joint on an ellipse; the
    circular limit and the decoupled pair give different peaks."""
    forced = ["--structure", planar, "--joint", "jenkins", "--joint-stiffness", "100",
              "--slip-force", "5", "--excitation", "0", "1", "--force", "3",
              "--harmonics", "3", "--samples", "256", "--frequency-range", "85", "135"]
    coupled = run_json(capsys, "frf", *forced, "--coupling", "circular")["curves"][0]
    decoupled = run_json(capsys, "frf", *forced, "--coupling", "decoupled")["curves"][0]
    for curve in (coupled, decoupled):
        (orbit,) = curve["joint_orbits"]
        x, y = np.array(orbit["x_mm"]), np.array(orbit["y_mm"])
        assert x.size == 256 and np.ptp(x) > 0 and np.ptp(y) > 0
        # an ellipse, not a line: the two components are out of phase
        assert abs(np.corrcoef(x, y)[0, 1]) < 0.99
    assert coupled["peak_amplitude_mm"] != pytest.approx(decoupled["peak_amplitude_mm"],
                                                         rel=1e-3)


def test_plot_with_the_joint_orbit_is_written(capsys, planar, tmp_path):
    pytest.importorskip("matplotlib")
    png = tmp_path / "planar.png"
    assert main(["frf", "--structure", planar, "--joint", "jenkins", "--joint-stiffness",
                 "100", "--slip-force", "5", "--excitation", "0", "1", "--force", "3",
                 "--harmonics", "1", "--samples", "64", "--frequency-range", "90", "125",
                 "--plot", str(png)]) == 0
    assert png.stat().st_size > 1000


def write(tmp_path, name, **arrays):
    path = tmp_path / name
    np.savez(path, **arrays)
    return str(path)


def bad_files(tmp_path):
    k = np.array([[2.0, -1.0], [-1.0, 2.0]])
    pickled = tmp_path / "pickled.npz"
    np.savez(pickled, M=np.array([{"a": 1}, None], dtype=object), K=k)
    garbage = tmp_path / "garbage.npz"
    garbage.write_bytes(b"not a zip file")
    return [
        (write(tmp_path, "asym.npz", M=np.eye(2), K=[[2.0, -1.0], [-0.5, 2.0]]),
         "K is not symmetric"),
        (write(tmp_path, "shape.npz", M=np.eye(3), K=k), "K must have the shape of M (3, 3)"),
        (write(tmp_path, "rect.npz", M=np.ones((2, 3)), K=k), "M must be a square numeric"),
        (str(pickled), "holds pickled objects"),
        (write(tmp_path, "nan.npz", M=np.eye(2), K=[[2.0, np.nan], [np.nan, 2.0]]),
         "K has NaN or infinite entries"),
        (write(tmp_path, "neg.npz", M=np.diag([1.0, -1.0]), K=k), "M must be positive definite"),
        (write(tmp_path, "extra.npz", M=np.eye(2), K=k, F=np.ones(2)), "unknown array(s) F"),
        (write(tmp_path, "nok.npz", M=np.eye(2)), "missing array(s) K"),
        (write(tmp_path, "joints.npz", M=np.eye(2), K=k, joints=[[0, 5]]),
         "joint DOF indices must be in [0, 1]"),
        (str(garbage), "is not a readable .npz"),
        (str(tmp_path / "absent.npz"), "does not exist"),
    ]


def test_bad_matrix_files_are_refused_with_one_line(capsys, tmp_path):
    for path, message in bad_files(tmp_path):
        argv = ["modal", "--structure", path, *JOINT, "--joint-dof", "0",
                "--amplitude-range", "0.01", "0.1"]
        assert main(argv) == 1, path
        err = capsys.readouterr().err
        assert message in err, (path, err)
        assert err.count("\n") == 1


@pytest.mark.parametrize(("extra", "message"), [
    (["--frequency", "100"], "--frequency not used with --structure"),
    (["--participation", "0.5"], "--participation not used with --structure"),
    (["--joint-dof", "0", "1", "2"], "--joint-dof takes I or I J"),
    (["--joint-dof", "0", "0"], "a joint connects two different DOFs"),
    (["--joint-dof", "0", "--coupling", "circular"], "--coupling applies to two-directional"),
    (["--joint-dof", "0", "--mode", "3"], "--mode must be in [1, 2]"),
])
def test_bad_structure_options_are_one_line(capsys, planar, extra, message):
    argv = ["modal", "--structure", planar, *JOINT, *extra, "--amplitude-range", "0.01",
            "0.1"]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert message in err
    assert err.count("\n") == 1


def test_structure_options_need_a_structure(capsys):
    assert main(["modal", "--frequency", "100", "--modal-mass", "2", *JOINT, "--mode", "2",
                 "--amplitude-range", "0.01", "0.1"]) == 1
    assert "--mode not used with a one-mode structure" in capsys.readouterr().err
