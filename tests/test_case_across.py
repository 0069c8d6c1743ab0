"""The joint across a two-directional tip or centre joint: ``transverse``, ``pairing`` and
``fe_mesh`` in a case file's ``[[joint]]`` and ``--transverse``, ``--pairing``, ``--fe-mesh``
on ``modal`` and ``frf`` (docs/casefile.md, docs/dynamics.md "The two-directional joint").

The structure: 1 kg in two directions, x stiffened by 4e9 N/m and y by 0.4e9 N/m, one joint
to the ground in both (Table 1 clamp at 200 N, stick slope 1e4 N/mm^3): the tip model
along x and the centre model across it bring the two stuck modes within 12 % of each
other, and a force on both DOFs moves the joint on an ellipse, where the pairing and
which model is across both change the response.
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest
from conftest import run, run_json
from scipy.linalg import eigh

from microslip import preset
from microslip.case import parse_case
from microslip.case.schema import PAIRINGS
from microslip.dynamics.distributions import clamp_joint
from microslip.dynamics.modal import epmc
from microslip.dynamics.operators import IwanOperator
from microslip.dynamics.operators2d import (
    COUPLINGS,
    CircularIwan,
    anisotropic,
    circular,
)
from microslip.dynamics.operators2d import PAIRINGS as OPERATOR_PAIRINGS
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import JointLink, Structure
from microslip.errors import ParameterError
from microslip.meshdynamics.spec import TRANSVERSE, transverse_operator

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

K = np.diag([4.0e9, 0.4e9])  # N/m
W = 2 * np.pi * 11600.0  # rad/s
C = 2 * 0.01 * W * np.eye(2)  # N s/m
CLAMP = preset("table1").replace(normal_force=200.0)
SLOPE = 1e4  # N/mm^3
SERIES = SLOPE * CLAMP.width * CLAMP.length  # N/mm
ELEMENTS = 20
TINY = "8x2x1"

CASE = f"""\
preset = "table1"
[contact]
stick_slope = {SLOPE}
[clamping]
normal_force = 200
[structure]
file = "planar.npz"
[[joint]]
dofs = [[0, -1], [1, -1]]
model = "tip"
elements = {ELEMENTS}
"""

FORCED = ["--force", "3", "--harmonics", "3", "--samples", "64", "--excitation", "0", "1",
          "--frequency-range", "8000", "12000"]
CLI = ["--structure", "planar.npz", "--joint-dof", "0", "--joint-dof", "1", "--joint", "tip",
       "--stick-slope", str(SLOPE), "--normal-force", "200", "--elements", str(ELEMENTS)]


@pytest.fixture
def planar(tmp_path, monkeypatch):
    np.savez(tmp_path / "planar.npz", M=np.eye(2), K=K, C=C)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _case(path, **keys):
    """The case file CASE with the joint's extra keys (and [structure] coupling = ...)."""
    structure = keys.pop("structure_coupling", None)
    text = CASE + "".join(f"{k} = {json.dumps(v)}\n" for k, v in keys.items())
    if structure is not None:
        text = text.replace('[structure]\n', f'[structure]\ncoupling = "{structure}"\n')
    path.write_text(text)
    return path.name


def _by_hand(*links: JointLink) -> Structure:
    """The structure with the given joints and the modal coordinate of its first stuck
    mode as output, built without the couplings."""
    s = Structure(mass=np.eye(2), damping=C, stiffness=K, joints=links, output=np.eye(2)[0])
    _, vecs = eigh(s.stuck_stiffness(), s.mass)
    phi = vecs[:, 0] / vecs[np.argmax(np.abs(vecs[:, 0])), 0]
    return Structure(mass=s.mass, damping=s.damping, stiffness=s.stiffness, joints=links,
                     output=phi / (phi @ phi))


def _curve(structure: Structure):
    return frequency_response(structure, 3.0, np.ones(2), (8000.0, 12000.0), 3, 64)


def _ops() -> tuple[IwanOperator, IwanOperator]:
    return (clamp_joint("tip", CLAMP, SERIES, elements=ELEMENTS),
            clamp_joint("centre", CLAMP, SERIES, elements=ELEMENTS))


def test_names_match_their_registries_and_couplings_take_x_y_pairing():
    assert tuple(TRANSVERSE) == ("tip", "centre", "fe")
    assert PAIRINGS == tuple(OPERATOR_PAIRINGS)
    tip, centre = _ops()
    (one,) = COUPLINGS["circular"](tip)
    assert isinstance(one, CircularIwan) and one.isotropic
    np.testing.assert_array_equal(one.stiffness, circular(tip).stiffness)
    for pairing in PAIRINGS:
        (two,) = COUPLINGS["circular"](tip, centre, pairing)
        ref = anisotropic(tip, centre, pairing)
        for attr in ("stiffness", "slip", "stiffness_y"):
            np.testing.assert_array_equal(getattr(two, attr), getattr(ref, attr))
    assert COUPLINGS["decoupled"](tip) == (tip, tip)
    assert COUPLINGS["decoupled"](tip, centre) == (tip, centre)
    with pytest.raises(ParameterError, match="does not apply to the decoupled"):
        COUPLINGS["decoupled"](tip, centre, "spatial")


@pytest.mark.slow
def test_transverse_centre_is_the_anisotropic_joint_built_by_hand(capsys, planar):
    """frf and modal of a case with transverse = "centre" against the structure with
    anisotropic(tip, centre, "spatial") built in Python, to 1e-12; the joint across and the
    pairing both change the response (so the comparison sees them)."""
    tip, centre = _ops()
    out = run_json(capsys, "frf", "--case", _case(planar / "a.toml", transverse="centre"),
                   *FORCED)
    ref = _curve(_by_hand(JointLink(anisotropic(tip, centre, "spatial"), np.eye(2))))
    got = out["curves"][0]
    assert got["success"] and ref.success
    np.testing.assert_allclose(got["frequency_Hz"], ref.frequency, rtol=1e-12)
    np.testing.assert_allclose(got["amplitude_mm"], ref.amplitude, rtol=1e-12)
    joint = out["structure"]["case_joints"][0]
    assert joint["transverse"]["model"] == "centre" and joint["pairing"] == "spatial"
    assert joint["transverse"]["initial_stiffness_N_per_mm"] == centre.initial_stiffness
    others = [_curve(_by_hand(JointLink(op, np.eye(2)))) for op in
              (circular(tip), anisotropic(tip, centre, "ordered"))]
    for other in others:  # the isotropic joint and the other pairing: measurably apart
        assert abs(other.peak_amplitude / ref.peak_amplitude - 1.0) > 1e-3
    amps = ["--amplitude-range", "1e-6", "3e-5", "--amplitudes", "4", "--harmonics", "3",
            "--samples", "64"]
    modal = run_json(capsys, "modal", "--case", "a.toml", *amps)
    ref_modal = epmc(_by_hand(JointLink(anisotropic(tip, centre, "spatial"), np.eye(2))),
                     np.geomspace(1e-6, 3e-5, 4), 3, 64, 0)
    np.testing.assert_allclose(modal["frequency_Hz"], ref_modal.frequency, rtol=1e-12)
    np.testing.assert_allclose(modal["damping_ratio"], ref_modal.damping_ratio, rtol=1e-12)
    assert modal["damping_ratio"][-1] > 2 * modal["damping_ratio"][0]  # the joint slips


def test_decoupled_with_transverse_is_tip_along_x_and_centre_along_y(capsys, planar):
    tip, centre = _ops()
    name = _case(planar / "d.toml", transverse="centre", coupling="decoupled")
    out = run_json(capsys, "frf", "--case", name, *FORCED)
    ref = _curve(_by_hand(JointLink(tip, np.eye(2)[0]), JointLink(centre, np.eye(2)[1])))
    got = out["curves"][0]
    np.testing.assert_allclose(got["frequency_Hz"], ref.frequency, rtol=1e-12)
    np.testing.assert_allclose(got["amplitude_mm"], ref.amplitude, rtol=1e-12)
    joint = out["structure"]["case_joints"][0]
    assert joint["coupling"] == "decoupled" and "pairing" not in joint
    # the other way round is another structure
    swapped = _curve(_by_hand(JointLink(centre, np.eye(2)[0]), JointLink(tip, np.eye(2)[1])))
    assert abs(swapped.peak_amplitude / ref.peak_amplitude - 1.0) > 1e-3


@pytest.mark.parametrize(("keys", "flags"), [
    ({"transverse": "centre", "pairing": "ordered"},
     ["--transverse", "centre", "--pairing", "ordered"]),
    ({"transverse": "tip", "coupling": "decoupled"},
     ["--transverse", "tip", "--coupling", "decoupled"]),
    ({"transverse": "fe", "fe_mesh": TINY}, ["--transverse", "fe", "--fe-mesh", TINY]),
])
def test_the_flags_give_the_json_of_the_case_file(capsys, planar, keys, flags):
    a = run_json(capsys, "frf", "--case", _case(planar / "f.toml", **keys), *FORCED)
    b = run_json(capsys, "frf", *CLI, *flags, *FORCED)
    assert a.pop("case_file") == "f.toml"
    sa, sb = a.pop("structure"), b.pop("structure")
    joint = sa.pop("case_joints")[0]
    assert joint.pop("coupling") == keys.get("coupling", "circular")
    assert {k: v for k, v in joint.items() if k not in ("number", "model", "dofs")} \
        == sb.pop("joint")
    assert sa == sb and a == b
    assert a["curves"][0]["success"]


@pytest.mark.slow
def test_the_fe_joint_across_is_the_fe_first_loading(capsys, planar):
    """transverse = "fe": the operator across is fe_backbone(clamp, "centre", mesh,
    stick_slope) as a joint (meshdynamics.febackbone), and the structure runs end to end."""
    from microslip.fe.builtin import fe_backbone
    from microslip.meshdynamics.febackbone import backbone_operator

    name = _case(planar / "fe.toml", transverse="fe", fe_mesh=TINY)
    (spec,) = parse_case(tomllib.loads((planar / name).read_text()), name).joints
    assert (spec.transverse, spec.fe_mesh, spec.stick_slope) == ("fe", TINY, SLOPE)
    across = transverse_operator(spec)
    ref = backbone_operator(fe_backbone(CLAMP, "centre", mesh=TINY, stick_slope=SLOPE))
    assert across is not None and across.name == ref.name
    np.testing.assert_array_equal(across.stiffness, ref.stiffness)
    np.testing.assert_array_equal(across.slip, ref.slip)
    out = run_json(capsys, "frf", "--case", name, *FORCED)
    joint = out["structure"]["case_joints"][0]
    assert joint["transverse"]["fe_mesh"] == TINY and joint["pairing"] == "spatial"
    tip, _ = _ops()
    got = out["curves"][0]
    ref_curve = _curve(_by_hand(JointLink(anisotropic(tip, ref, "spatial"), np.eye(2))))
    np.testing.assert_allclose(got["amplitude_mm"], ref_curve.amplitude, rtol=1e-12)


@pytest.mark.parametrize(("keys", "words"), [
    ({"transverse": "centre", "dofs": [0]},
     ["joint.transverse", "tip | centre | fe", "two-directional joints only"]),
    ({"transverse": "centre", "model": "jenkins", "stiffness": 1, "slip_force": 1,
      "elements": None}, ["joint.transverse", "tip | centre | fe", "not to model jenkins"]),
    ({"transverse": "lateral"}, ["joint.transverse", "tip, centre, fe", "'lateral'"]),
    ({"pairing": "ordered"}, ["joint.pairing", "ordered | spatial", "needs joint.transverse"]),
    ({"transverse": "centre", "pairing": "ordered", "coupling": "decoupled"},
     ["joint.pairing", "ordered | spatial", "coupling circular only"]),
    ({"transverse": "centre", "fe_mesh": TINY},
     ["joint.fe_mesh", "NXxNYxNZ", 'needs joint.transverse = "fe"']),
    ({"transverse": "fe", "fe_mesh": "huge"}, ["joint.fe_mesh", "NXxNYxNZ", "'huge'"]),
    ({"transverse": "fe", "stiffness": 1e5}, ['joint.transverse = "fe"',
                                              "contact.stick_slope", "not joint.stiffness"]),
])
def test_bad_keys_across_are_one_line_naming_joint_key_and_values(keys, words):
    joint = {"dofs": [[0, -1], [1, -1]], "model": "tip", "elements": ELEMENTS, **keys}
    joint = {k: v for k, v in joint.items() if v is not None}
    with pytest.raises(ParameterError) as exc:
        parse_case({"preset": "table1", "contact": {"stick_slope": SLOPE}, "joint": [joint]},
                   "c.toml")
    message = str(exc.value)
    assert "\n" not in message and message.startswith("case c.toml: joint 1 of 1: ")
    for word in words:
        assert word in message


def test_a_pairing_with_the_structure_decoupled_is_refused(capsys, planar):
    name = _case(planar / "s.toml", transverse="centre", pairing="spatial",
                 structure_coupling="decoupled")
    code, _, err = run(capsys, "frf", "--case", name, *FORCED)
    assert code == 1 and err.count("\n") == 1 and err.startswith("error: case s.toml: ")
    assert "joint 1: joint.pairing (ordered | spatial)" in err and "decoupled" in err


@pytest.mark.parametrize(("flags", "words"), [
    (["--pairing", "ordered"], ["--pairing (ordered | spatial) needs --transverse"]),
    (["--transverse", "centre", "--pairing", "spatial", "--coupling", "decoupled"],
     ["--pairing", "--coupling circular only"]),
    (["--transverse", "centre", "--fe-mesh", TINY], ["--fe-mesh LEVEL needs --transverse fe"]),
    (["--fe-mesh", TINY], ["--fe-mesh LEVEL needs --transverse fe"]),
    (["--transverse", "fe", "--stick-slope", None, "--joint-stiffness", "1e5"],
     ["--transverse fe needs --stick-slope"]),
    (["--transverse", "centre", "--joint-dof", None], ["two-directional joints only"]),
    (["--transverse", "centre", "--joint", "jenkins", "--stick-slope", None,
      "--slip-force", "5", "--joint-stiffness", "300", "--elements", None],
     ["--transverse (tip | centre | fe) applies to --joint tip or centre"]),
    (["--transverse", "lateral"], ["--transverse", "invalid choice"]),
    (["--fe-mesh", "huge"], ["--fe-mesh", "unknown mesh 'huge'"]),
])
def test_bad_flags_are_usage_errors_of_one_line(capsys, planar, flags, words):
    argv = list(CLI)
    for flag, value in zip(flags[::2], flags[1::2], strict=True):
        if value is None:  # drop the option from CLI: (its second occurrence, for joint-dof)
            i = len(argv) - 1 - argv[::-1].index(flag)
            del argv[i:i + 2]
        elif flag in argv and flag != "--joint-dof":
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    code, out, err = run(capsys, "frf", *argv, *FORCED)
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith("error: ")
    for word in words:
        assert word in err


def test_one_mode_and_case_joints_refuse_the_flags(capsys, planar):
    code, _, err = run(capsys, "modal", "--frequency", "100", "--modal-mass", "1", "--joint",
                       "tip", "--stick-slope", "1e4", "--transverse", "centre",
                       "--amplitude-range", "1e-6", "1e-5")
    assert code == 2 and err.count("\n") == 1 and "two-directional joints only" in err
    name = _case(planar / "c.toml", transverse="centre")
    code, _, err = run(capsys, "frf", "--case", name, "--pairing", "ordered", *FORCED)
    assert code == 1 and err.count("\n") == 1 and "--pairing conflicts with the [[joint]]" in err


def test_a_tip_joint_that_is_its_own_model_across_is_warned_once(capsys, planar):
    """Without a joint across the warning goes to stderr (one line) and into the JSON's
    ``warnings``, naming the way out; with one, or for a one-directional joint, nothing."""
    amps = ["--amplitude-range", "1e-6", "3e-6", "--amplitudes", "2", "--harmonics", "1",
            "--samples", "32"]
    code, out, err = run(capsys, "modal", *CLI, *amps, "--json")
    assert code == 0
    (line,) = err.strip().splitlines()
    assert line.startswith("warning: --joint tip: the tip model is also the joint across")
    assert "--transverse fe" in line and json.loads(out)["warnings"] == [line[9:]]
    code, out, err = run(capsys, "modal", "--case", _case(planar / "w.toml"), *amps, "--json")
    assert code == 0 and json.loads(out)["warnings"] == [err.strip()[9:]]
    assert 'joint 1: the tip model' in err and 'transverse = "fe"' in err
    for argv in (["modal", *CLI, "--transverse", "centre", *amps, "--json"],
                 ["modal", "--structure", "planar.npz", "--joint-dof", "0", "--joint", "tip",
                  "--stick-slope", str(SLOPE), *amps, "--json"]):
        code, out, err = run(capsys, *argv)
        assert code == 0 and err == "" and json.loads(out)["warnings"] == []
