"""Several joints in a case file: ``[structure] file`` and ``[[joint]]`` tables, read by
``microslip modal`` and ``microslip frf`` with ``--case`` (docs/casefile.md)."""

from __future__ import annotations

import sys

import numpy as np
import pytest
from conftest import run, run_json
from scipy.linalg import eigh

from microslip import preset
from microslip.case import parse_case, template
from microslip.case.schema import COUPLINGS, JOINT_KEYS
from microslip.case.template import JOINT_EXAMPLE
from microslip.dynamics.distributions import DEFAULT_ELEMENTS, clamp_joint
from microslip.dynamics.modal import epmc
from microslip.dynamics.operators import jenkins
from microslip.dynamics.operators2d import COUPLINGS as OPERATOR_COUPLINGS
from microslip.dynamics.structure import JointLink, Structure
from microslip.errors import ParameterError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

K0 = (2 * np.pi * 100.0) ** 2  # N/m
CHAIN_K = K0 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]])

TWO_JOINTS = """\
name = "two joints"
preset = "table1"
[structure]
file = "chain.npz"
[[joint]]
dofs = [0]
model = "jenkins"
stiffness = 300
slip_force = 5
[[joint]]
dofs = [1, 2]
model = "tip"
stiffness = 1e5
elements = 40
[joint.clamping]
normal_force = 200
"""


@pytest.fixture
def chain(tmp_path):
    """Three 1 kg masses in a chain fixed at one end (joints at DOF 0 and between 1 and 2)."""
    np.savez(tmp_path / "chain.npz", M=np.eye(3), K=CHAIN_K, C=1e-4 * CHAIN_K)
    (tmp_path / "two.toml").write_text(TWO_JOINTS)
    return tmp_path


@pytest.fixture
def planar(tmp_path):
    """1 kg in two bending planes at 100 and 101.5 Hz, no joint in the file."""
    np.savez(tmp_path / "planar.npz", M=np.eye(2), K=np.diag([K0, 1.03 * K0]),
             C=2 * 0.01 * 2 * np.pi * 100 * np.eye(2))
    return tmp_path


def test_two_joints_parse_with_their_own_models_and_clamps():
    case = parse_case(tomllib.loads(TWO_JOINTS), "cases/two.toml")
    assert case.values["structure.file"] == "cases/chain.npz"  # beside the case file
    first, second = case.joints
    assert (first.number, first.dofs, first.model) == (1, ((0, -1),), "jenkins")
    assert dict(first.values) == {"stiffness": 300.0, "slip_force": 5.0}
    assert first.clamp is None and first.series_stiffness is None
    assert (second.dofs, second.model, second.series_stiffness) == (((1, 2),), "tip", 1e5)
    assert second.clamp == preset("table1").replace(normal_force=200.0)
    assert case.params == preset("table1")  # the case's own clamp is unchanged


def test_a_joint_preset_and_stick_slope_replace_the_case_clamp():
    case = parse_case({"preset": "table1", "contact": {"stick_slope": 1e3}, "joint": [
        {"dofs": [[0, -1], [1, -1]], "model": "centre", "preset": "table2-centre"},
        {"dofs": [2], "model": "tip", "geometry": {"length": 100.0}}]})
    centre, tip = case.joints
    p2 = preset("table2-centre")
    assert centre.clamp == p2 and centre.series_stiffness == 1e3 * p2.width * p2.length
    p1 = preset("table1").replace(length=100.0)
    assert tip.clamp == p1 and tip.series_stiffness == 1e3 * p1.width * 100.0


def test_the_template_example_joints_parse_and_coupling_names_are_the_operators():
    text = template()
    assert all(f"#   {k.name}: " in text for k in JOINT_KEYS)
    case = parse_case(tomllib.loads('preset = "table1"\n' + "\n".join(JOINT_EXAMPLE)))
    assert [j.model for j in case.joints] == ["jenkins", "tip"]
    assert case.joints[1].clamp == preset("table1").replace(normal_force=600.0)
    assert COUPLINGS == tuple(OPERATOR_COUPLINGS)
    assert f"default {DEFAULT_ELEMENTS}," in next(k for k in JOINT_KEYS
                                                  if k.name == "elements").meaning


@pytest.mark.parametrize(("joint", "words"), [
    ({"dofs": [0], "model": "jenkins", "stiffness": -1.0, "slip_force": 5},
     ["joint 1 of 1", "joint.stiffness", "> 0", "N/mm"]),
    ({"dofs": [0], "model": "jenkins", "stiffness": 300}, ["needs joint.slip_force"]),
    ({"dofs": [0], "model": "iwan", "stiffness": 3, "slip_force": 1, "chi": 0.5, "beta": 0},
     ["joint.chi", "(-1, 0]"]),
    ({"dofs": [0], "model": "iwan", "stiffness": 3, "slip_force": 1, "chi": -0.5,
      "beta": -1}, ["joint.beta", "[0, inf)"]),
    ({"dofs": [0], "model": "tip", "stiffness": 1e5, "elements": 1},
     ["joint.elements", "[2, 100000]"]),
    ({"dofs": [0, 0], "model": "jenkins"}, ["joint.dofs", "two different DOFs"]),
    ({"dofs": [[0], [1], [2]], "model": "jenkins"}, ["joint.dofs", "[[I, J], [K, L]]"]),
    ({"dofs": [-2], "model": "jenkins"}, ["joint.dofs", ">= 0"]),
    ({"dofs": [0], "model": "bolt"}, ["joint.model", "jenkins, iwan, tip, centre"]),
    ({"model": "jenkins"}, ["joint.dofs is missing"]),
    ({"dofs": [0], "model": "jenkins", "stiffness": 1, "slip_force": 1, "chi": -0.5},
     ["chi not used by model jenkins"]),
    ({"dofs": [0], "model": "tip"}, ["needs joint.stiffness", "contact.stick_slope"]),
    ({"dofs": [0], "model": "tip", "stiffness": 1, "contact": {"stick_slope": 1e4}},
     ["exclude each other"]),
    ({"dofs": [0], "model": "tip", "stiffness": 1, "clamping": {"pressure": "parabolic"}},
     ["uniform pressure"]),
    ({"dofs": [0], "model": "tip", "stiffness": 1, "geometry": {"length": 0}},
     ["joint.geometry.length", "> 0", "mm"]),
    ({"dofs": [0], "model": "jenkins", "stiffness": 1, "slip_force": 1,
      "coupling": "circular"}, ["joint.coupling applies to two-directional"]),
    ({"dofs": [0], "model": "tip", "stifness": 1}, ["unknown case key joint.stifness"]),
])
def test_bad_joint_tables_are_one_line_naming_key_and_range(joint, words):
    with pytest.raises(ParameterError) as exc:
        parse_case({"preset": "table1", "joint": [joint]}, "c.toml")
    message = str(exc.value)
    assert "\n" not in message and message.startswith("case c.toml: ")
    for word in words:
        assert word in message


def test_a_tip_joint_needs_a_clamp():
    with pytest.raises(ParameterError, match="needs a clamp"):
        parse_case({"joint": [{"dofs": [0], "model": "tip", "stiffness": 1e5}]})


def _by_hand(mode: int = 0) -> Structure:
    """The structure TWO_JOINTS describes, built directly from the operators."""
    tip = clamp_joint("tip", preset("table1").replace(normal_force=200.0), 1e5, elements=40)
    w0, w12 = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, -1.0])
    s = Structure(mass=np.eye(3), damping=1e-4 * CHAIN_K, stiffness=CHAIN_K,
                  joints=(JointLink(jenkins(300.0, 5.0), w0), JointLink(tip, w12)),
                  output=np.eye(3)[0])
    k = s.stuck_stiffness()
    _, vecs = eigh(k, s.mass)
    phi = vecs[:, mode] / vecs[np.argmax(np.abs(vecs[:, mode])), mode]
    return Structure(mass=s.mass, damping=s.damping, stiffness=s.stiffness, joints=s.joints,
                     output=phi / (phi @ phi))


def test_two_joints_with_different_models_through_the_cli(capsys, chain, monkeypatch):
    monkeypatch.chdir(chain)
    amps = ["--amplitude-range", "1e-4", "0.3", "--amplitudes", "6", "--harmonics", "3"]
    out = run_json(capsys, "modal", "--case", "two.toml", *amps)
    assert out["case_file"] == "two.toml"
    joints = out["structure"]["case_joints"]
    assert [(j["model"], j["dofs"]) for j in joints] == [("jenkins", [[0, -1]]),
                                                         ("tip", [[1, 2]])]
    assert joints[1]["macroslip_force_N"] == pytest.approx(0.8 * 200.0, rel=1e-12)
    # the stuck limit: K + 300 N/mm e0 e0^T + k_tip (e1 - e2)(e1 - e2)^T, by hand
    k_tip = joints[1]["initial_stiffness_N_per_mm"]
    e0, e12 = np.eye(3)[0], np.array([0.0, 1.0, -1.0])
    k = CHAIN_K + 1e3 * (300.0 * np.outer(e0, e0) + k_tip * np.outer(e12, e12))
    stuck = np.sqrt(eigh(k, np.eye(3), eigvals_only=True)) / (2 * np.pi)
    np.testing.assert_allclose(out["structure"]["stuck_frequencies_Hz"], stuck, rtol=1e-12)
    # (to 1e-4: the tip joint's first elements slip at any amplitude)
    assert out["frequency_Hz"][0] == pytest.approx(stuck[0], rel=1e-4)
    # the whole curve: the structure built by hand from the same operators
    ref = epmc(_by_hand(), np.geomspace(1e-4, 0.3, 6), 3, 128, 0)
    np.testing.assert_allclose(out["frequency_Hz"], ref.frequency, rtol=1e-10)
    np.testing.assert_allclose(out["damping_ratio"], ref.damping_ratio, rtol=1e-8)
    assert max(out["damping_ratio"]) > 3 * out["damping_ratio"][0]  # the joints slip
    forced = run_json(capsys, "frf", "--case", "two.toml", "--force", "5", "--harmonics", "3")
    assert forced["curves"][0]["success"]


def test_one_case_joint_equals_the_joint_dof_options(capsys, planar, monkeypatch):
    """A two-directional tip joint: the case file and --joint-dof/--joint/--stick-slope give
    the same frequency-response curve, bit for bit."""
    monkeypatch.chdir(planar)
    (planar / "one.toml").write_text(
        'preset = "table1"\n[contact]\nstick_slope = 1e4\n[structure]\nfile = "planar.npz"\n'
        'coupling = "decoupled"\n[[joint]]\ndofs = [[0, -1], [1, -1]]\nmodel = "tip"\n'
        "elements = 30\n")
    forced = ["--force", "20", "--harmonics", "3", "--samples", "64",
              "--frequency-range", "90", "160"]
    a = run_json(capsys, "frf", "--case", "one.toml", *forced)
    b = run_json(capsys, "frf", "--structure", "planar.npz", "--joint-dof", "0",
                 "--joint-dof", "1", "--joint", "tip", "--stick-slope", "1e4", "--elements",
                 "30", "--coupling", "decoupled", *forced)
    assert a.pop("case_file") == "one.toml"
    # a tip joint that is its own model across: warned, naming each path's way out
    wa, wb = a.pop("warnings"), b.pop("warnings")
    assert len(wa) == len(wb) == 1
    assert wa[0].startswith("joint 1: the tip model is also the joint across")
    assert 'transverse = "fe"' in wa[0] and "--transverse fe" in wb[0]
    assert wa[0].split(";", 1)[1].split(":")[0] == wb[0].split(";", 1)[1].split(":")[0]
    sa, sb = a.pop("structure"), b.pop("structure")
    case_joint = sa.pop("case_joints")[0]
    assert case_joint.pop("coupling") == "decoupled"
    assert {k: v for k, v in case_joint.items() if k not in ("number", "model", "dofs")} \
        == sb.pop("joint")
    assert sa == sb and a == b
    # the joint's own coupling wins over [structure] coupling
    (planar / "own.toml").write_text((planar / "one.toml").read_text().replace(
        'model = "tip"', 'model = "tip"\ncoupling = "circular"'))
    c = run_json(capsys, "frf", "--case", "own.toml", *forced)
    d = run_json(capsys, "frf", "--case", "one.toml", "--coupling", "circular", *forced)
    assert c["curves"][0]["amplitude_mm"] == d["curves"][0]["amplitude_mm"]
    assert c["curves"][0]["amplitude_mm"] != a["curves"][0]["amplitude_mm"]


@pytest.mark.parametrize(("extra", "words"), [
    (["--joint", "jenkins"], ["--joint conflicts with the [[joint]] tables"]),
    (["--joint-dof", "0"], ["--joint-dof conflicts"]),
    (["--length", "100"], ["--length conflicts"]),
    (["--elements", "10", "--slip-force", "3"], ["--slip-force, --elements conflict"]),
])
def test_command_line_joint_options_conflict_with_case_joints(capsys, chain, monkeypatch,
                                                              extra, words):
    monkeypatch.chdir(chain)
    code, out, err = run(capsys, "modal", "--case", "two.toml", "--amplitude-range", "0.01",
                         "0.1", *extra)
    assert code == 1 and out == "" and err.count("\n") == 1 and err.startswith("error: ")
    for word in words:
        assert word in err


def test_joints_and_structures_go_where_they_belong(capsys, chain, monkeypatch):
    monkeypatch.chdir(chain)
    code, _, err = run(capsys, "loop", "--case", "two.toml", "--model", "tip", "--increments",
                       "100")
    assert code == 0 and err == "case: [structure], [[joint]] not read by loop\n"
    (chain / "nostructure.toml").write_text(TWO_JOINTS.replace('file = "chain.npz"', ""))
    code, _, err = run(capsys, "frf", "--case", "nostructure.toml", "--force", "1")
    assert code == 1 and "no structure" in err
    (chain / "far.toml").write_text(TWO_JOINTS.replace("dofs = [1, 2]", "dofs = [1, 3]"))
    code, _, err = run(capsys, "frf", "--case", "far.toml", "--force", "1")
    assert code == 1 and "joint 2: dofs" in err and "[0, 2]" in err
    code, _, err = run(capsys, "modal", "--case", "two.toml", "--coupling", "circular",
                       "--amplitude-range", "0.01", "0.1")
    assert code == 1 and "two-directional joints only" in err
