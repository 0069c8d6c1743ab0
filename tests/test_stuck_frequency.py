"""``--stuck-frequency`` on modal and frf: the frequency measured with the joint stuck, from
which the frequency with the joint removed follows; both are printed."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from microslip.cli.main import main
from microslip.dynamics import jenkins
from microslip.dynamics.structure import free_frequency
from microslip.errors import ParameterError

#: A one-mode Jenkins structure: modal mass 0.5 kg, joint 1000 N/mm (1e6 N/m), slider 5 N.
MASS, K_JOINT_SI, STUCK = 0.5, 1.0e6, 300.0
JOINT = ("--modal-mass", "0.5", "--joint", "jenkins", "--joint-stiffness", "1000",
         "--slip-force", "5")


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def hand_free(stuck: float, participation: float = 1.0) -> float:
    """m (2 pi f_s)^2 = m (2 pi f)^2 + p^2 k_J, solved for f by hand."""
    return math.sqrt(stuck**2 - participation**2 * K_JOINT_SI / (MASS * (2 * math.pi) ** 2))


@pytest.mark.parametrize("participation", [1.0, -0.7])
def test_free_frequency_inverts_the_stuck_one(participation):
    f = free_frequency(STUCK, MASS, jenkins(1000.0, 5.0), participation)
    assert f == pytest.approx(hand_free(STUCK, participation), rel=1e-12)
    k_modal = MASS * (2 * math.pi * f) ** 2
    assert f * math.sqrt(1 + participation**2 * K_JOINT_SI / k_modal) == pytest.approx(
        STUCK, rel=1e-12)


def test_modal_takes_the_stuck_frequency_and_prints_both(capsys):
    code, out, err = run(capsys, "modal", "--stuck-frequency", STUCK, *JOINT,
                         "--amplitude-range", "0.001", "1", "--amplitudes", "3", "--json")
    assert code == 0, err
    s = json.loads(out)["structure"]
    assert s["frequency_Hz"] == pytest.approx(hand_free(STUCK), rel=1e-12)
    assert s["stuck_frequency_Hz"] == pytest.approx(STUCK, rel=1e-12)
    code, text, err = run(capsys, "modal", "--stuck-frequency", STUCK, *JOINT,
                          "--amplitude-range", "0.001", "1", "--amplitudes", "3")
    assert code == 0, err
    assert f"mode {hand_free(STUCK):.6g} Hz with the joint removed, 300 Hz stuck" in text


def test_stuck_and_free_give_the_same_curve(capsys):
    args = (*JOINT, "--amplitude-range", "0.001", "1", "--amplitudes", "4", "--json")
    a = json.loads(run(capsys, "modal", "--stuck-frequency", STUCK, *args)[1])
    b = json.loads(run(capsys, "modal", "--frequency", repr(hand_free(STUCK)), *args)[1])
    assert a["frequency_Hz"] == pytest.approx(b["frequency_Hz"], rel=1e-10)
    assert a["damping_ratio"] == pytest.approx(b["damping_ratio"], rel=1e-8, abs=1e-15)


def test_frf_takes_the_stuck_frequency(capsys):
    code, out, err = run(capsys, "frf", "--stuck-frequency", STUCK, *JOINT, "--force", "1",
                         "--harmonics", "3", "--json")
    assert code == 0, err
    s = json.loads(out)["structure"]
    assert s["stuck_frequency_Hz"] == pytest.approx(STUCK, rel=1e-12)
    assert s["frequency_Hz"] == pytest.approx(hand_free(STUCK), rel=1e-12)


def test_both_frequencies_is_a_usage_error(capsys):
    code, out, err = run(capsys, "modal", "--stuck-frequency", "300", "--frequency", "100",
                         *JOINT)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "--frequency" in err and "--stuck-frequency" in err


def test_a_stuck_frequency_below_the_joint_alone_names_the_bound(capsys):
    bound = math.sqrt(K_JOINT_SI / MASS) / (2 * math.pi)
    code, out, err = run(capsys, "frf", "--stuck-frequency", "20", *JOINT, "--force", "1")
    assert code == 1 and out == "" and err.count("\n") == 1
    assert f"> {bound:.6g} Hz" in err and "got 20 Hz" in err
    with pytest.raises(ParameterError, match="stuck frequency must be > 0"):
        free_frequency(-1.0, MASS, jenkins(1000.0, 5.0))


def test_a_structure_file_refuses_the_stuck_frequency(capsys, tmp_path):
    path = tmp_path / "s.npz"
    np.savez(path, M=np.eye(1), K=np.eye(1) * 1e5, joints=np.array([[[0, -1]]]))
    code, out, err = run(capsys, "modal", "--structure", path, "--stuck-frequency", "300",
                         "--joint", "jenkins", "--joint-stiffness", "1000", "--slip-force", "5",
                         "--amplitude-range", "0.01", "1")
    assert code == 1 and out == "" and "--stuck-frequency not used with --structure" in err
