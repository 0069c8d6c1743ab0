"""``microslip joint``: numbers against the Jenkins closed form, errors as one line."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import run_json

from microslip.cli.main import main

JENKINS = ["joint", "--joint", "jenkins", "--joint-stiffness", "100", "--slip-force", "5"]


def test_jenkins_json_against_the_closed_form(capsys):
    out = run_json(capsys, *JENKINS, "--amplitude-range", "0.1", "1", "--amplitudes", "4",
                           "--samples", "4096")
    a = np.array(out["amplitude_mm"])
    np.testing.assert_allclose(a, np.geomspace(0.1, 1.0, 4), rtol=1e-15)
    beta = np.arccos(1.0 - 2.0 * 0.05 / a)
    np.testing.assert_allclose(out["stiffness_N_per_mm"],
                               100.0 / np.pi * (beta - np.sin(2.0 * beta) / 2.0),
                               rtol=0, atol=4.0 * 100.0 / 4096**2)
    np.testing.assert_allclose(out["dissipated_energy_Nmm"], 20.0 * (a - 0.05), rtol=1e-5)
    np.testing.assert_allclose(out["force_N"], 5.0, rtol=1e-15)
    assert out["joint"] == {"name": "jenkins", "elements": 1,
                            "initial_stiffness_N_per_mm": 100.0, "macroslip_force_N": 5.0}


def test_force_range_gives_the_amplitudes_of_those_forces(capsys):
    out = run_json(capsys, "joint", "--joint", "tip", "--stick-slope", "1e4",
                           "--force-range", "10", "300", "--amplitudes", "3")
    np.testing.assert_allclose(out["force_N"], np.geomspace(10.0, 300.0, 3), rtol=1e-12)
    assert out["joint"]["elements"] == 201
    assert out["joint"]["macroslip_force_N"] == pytest.approx(356.0, rel=1e-12)


def test_table_has_units(capsys):
    assert main([*JENKINS, "--amplitude-range", "0.01", "1", "--amplitudes", "3"]) == 0
    text = capsys.readouterr().out
    for unit in ("A (mm)", "F (N)", "K_eq (N/mm)", "D_eq (N/mm)", "W_d (N·mm)", "eta (-)"):
        assert unit in text


def test_plot_is_written(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    path = tmp_path / "dj.png"
    assert main(["joint", "--joint", "iwan", "--joint-stiffness", "1000", "--slip-force", "10",
                 "--chi", "-0.5", "--beta", "0.5", "--amplitude-range", "1e-3", "0.1",
                 "--amplitudes", "5", "--plot", str(path)]) == 0
    assert path.stat().st_size > 1000


@pytest.mark.parametrize(("argv", "message"), [
    (["joint", "--joint", "tip", "--force-range", "10", "300"],
     "needs exactly one of --joint-stiffness"),
    ([*JENKINS, "--chi", "-0.5", "--amplitude-range", "0.1", "1"], "--chi not used by"),
    (["joint", "--joint", "jenkins", "--joint-stiffness", "100", "--amplitude-range", "0.1",
      "1"], "needs --slip-force"),
    ([*JENKINS, "--amplitude-range", "1", "0.1"], "MIN <= MAX"),
    ([*JENKINS, "--amplitude-range", "0", "0.1"], "--amplitude-range must be finite and > 0 mm"),
    ([*JENKINS, "--force-range", "1", "6"], "below the joint's macroslip force 5 N"),
    ([*JENKINS], "exactly one of --amplitude-range"),
    (["joint", "--joint", "iwan", "--joint-stiffness", "1000", "--slip-force", "10", "--chi",
      "0.5", "--beta", "0", "--amplitude-range", "0.1", "1"], "chi must be in (-1, 0]"),
])
def test_bad_input_is_one_line_and_exit_1(capsys, argv, message):
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert message in err
    assert err.count("\n") == 1


def test_unknown_joint_is_a_usage_error(capsys):
    assert main(["joint", "--joint", "bolt", "--amplitude-range", "0.1", "1"]) == 2
    assert "invalid choice" in capsys.readouterr().err
