"""The contact-node ROM with ``penalty`` normal contact written to a structure file (issue 23,
item 3): 3-D contact joints (joints (n, 3, 2) with k_t, k_n, N_0, mu per joint) read back
give the in-memory structure's stuck frequencies and EPMC points; ``modal`` and ``frf``
take the file without a command-line joint; the new arrays are checked with one line each,
and the files without them read as before."""

from __future__ import annotations

import json

import numpy as np
import pytest

from microslip.dynamics.assemble import from_matrices
from microslip.dynamics.files import read_structure
from microslip.dynamics.modal import epmc
from microslip.dynamics.operators import jenkins
from microslip.dynamics.operators3d import Contact3D
from microslip.errors import ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.reduce import build_rom, rom_arrays, rom_structure, write_rom

#: Aluminium cantilever, the issue's values (MPa, -, kg/m^3, -, N, N/mm^3).
E, NU, RHO, MU, FN, LAM, KN = 70000.0, 0.33, 2700.0, 0.5, 2000.0, 1e4, 1e6


def _rom(normal: str):
    model = build_mesh_model(cantilever_mesh(12, 3, 1), rigid_base(contact_set="contact",
                                                                   clamp_set="clamp",
                                                                   normal_force=FN, modulus=E,
                                                                   poisson_ratio=NU, friction=MU,
                                                                   stick_slope=LAM,
                                                                   normal_contact=normal,
                                                                   normal_slope=KN))
    return model, build_rom(model, RHO, modes=6, response_set="response")


@pytest.fixture(scope="module")
def penalty(tmp_path_factory):
    model, rom = _rom("penalty")
    path = str(tmp_path_factory.mktemp("rom") / "penalty.npz")
    write_rom(path, rom)
    return model, rom, path


def test_file_holds_each_nodes_3d_law(penalty):
    model, _rom, path = penalty
    mf = read_structure(path)
    n = model.contact_nodes.size
    assert mf.joints.shape == (n, 3, 2) and mf.laws is None
    assert np.array_equal(mf.joints[:, :, 0], np.arange(3 * n).reshape(n, 3))
    assert np.all(mf.joints[:, :, 1] == -1)
    assert np.array_equal(mf.contacts[:, 0], model.contact_stiffness)
    assert np.array_equal(mf.contacts[:, 1], model.normal.stiffness)
    assert np.allclose(mf.contacts[:, 2] * MU, model.friction_limit, rtol=1e-15)
    assert np.all(mf.contacts[:, 3] == MU)
    s = from_matrices(mf, mf.joints, None, "circular")
    assert all(isinstance(link.operator, Contact3D) for link in s.joints)


def test_file_structure_equals_the_rom_in_memory(penalty):
    """Stuck frequencies to rounding: the file's matrices are the ROM's (SI), its joints the
    same 3-D elements on the same dofs."""
    _model, rom, path = penalty
    mf = read_structure(path)
    s = from_matrices(mf, mf.joints, None, "circular")
    mem = rom_structure(rom)
    assert np.array_equal(s.mass, mem.mass) and np.array_equal(s.stiffness, mem.stiffness)
    assert np.allclose(s.linear_frequencies(stuck=True), mem.linear_frequencies(stuck=True),
                       rtol=1e-12)
    # the ROM's own eigen-solve (t, N/mm; the stiff normal springs cost a few digits)
    assert np.allclose(s.linear_frequencies(stuck=True)[:4], rom.stuck_frequencies(4),
                       rtol=1e-8)


@pytest.mark.slow  # the 3-D element's kernel compiles on a fresh checkout
def test_file_epmc_points_equal_the_rom_in_memory(penalty):
    _model, rom, path = penalty
    mf = read_structure(path)
    mem = rom_structure(rom)
    s = from_matrices(mf, mf.joints, None, "circular")
    from microslip.dynamics.assemble import with_output

    s = with_output(s, mem.output)
    a = np.geomspace(5e-3, 2e-2, 3)
    c_file, c_mem = epmc(s, a, 3, mode=1), epmc(mem, a, 3, mode=1)
    assert c_mem.damping_ratio[-1] > 0.01  # slipping: the 3-D elements are in play
    assert np.allclose(c_file.frequency, c_mem.frequency, rtol=1e-12)
    assert np.allclose(c_file.damping_ratio, c_mem.damping_ratio, rtol=1e-9, atol=1e-15)


@pytest.mark.slow  # EPMC with 3-D elements through the CLI (kernel compile on a fresh checkout)
def test_modal_and_frf_take_the_penalty_file_without_a_joint(penalty, capsys):
    from microslip.cli.main import main

    _model, rom, path = penalty
    assert main(["modal", "--structure", path, "--mode", "2", "--amplitude-range", "1e-3",
                 "1e-2", "--amplitudes", "2", "--harmonics", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["energy_method"] is None
    assert any("3-D contact joints" in w for w in out["warnings"])
    assert out["structure"]["joint"]["name"] == "contact3d"
    stuck = rom_structure(rom).linear_frequencies(stuck=True)[1]
    assert abs(out["frequency_Hz"][0] / stuck - 1.0) < 1e-6
    assert main(["frf", "--structure", path, "--mode", "2", "--force", "1",
                 "--frequency-range", "1500", "1800", "--harmonics", "1", "--json"]) == 0
    curve = json.loads(capsys.readouterr().out)["curves"][0]
    assert curve["success"] and curve["points"] > 3


def test_energy_method_refused_on_3d_joints(penalty, capsys):
    from microslip.cli.main import main

    _model, _rom, path = penalty
    assert main(["modal", "--structure", path, "--method", "energy", "--amplitude-range",
                 "1e-3", "1e-2"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) >= 1 and "3-D contact element needs epmc" in err[-1]


def test_fixed_file_reads_as_before_and_needs_no_joint(tmp_path, capsys):
    """The 2-D file's arrays and numbers are unchanged by the 3-D format; the command
    line's joint may now be left out when the file's joints carry their own laws."""
    _model, rom = _rom("fixed")
    arrays = rom_arrays(rom)
    assert sorted(arrays) == ["K", "M", "joint_slip_force", "joint_stiffness", "joints"]
    assert arrays["joints"].shape == (rom.slip_force.size, 2, 2)
    path = str(tmp_path / "fixed.npz")
    write_rom(path, rom)
    mf = read_structure(path)
    assert mf.contacts is None and mf.laws.shape == (rom.slip_force.size, 2)
    from microslip.cli.main import main

    args = ["modal", "--structure", path, "--mode", "2", "--amplitude-range", "1e-3", "1e-2",
            "--amplitudes", "2", "--harmonics", "3", "--json"]
    assert main(args) == 0
    bare = json.loads(capsys.readouterr().out)
    # a command-line joint would change nothing (the file's joints carry their own laws):
    # refused in one line (issue 27), not silently ignored
    assert main([*args, "--joint", "jenkins", "--joint-stiffness", "1", "--slip-force",
                 "1"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: --joint") and err.count("\n") == 1 and "own law" in err
    assert bare["energy_method"] is not None


def _save(path, **extra):
    base = {"M": np.eye(3), "K": np.eye(3), "joints": np.array([[[0, -1], [1, -1], [2, -1]]])}
    np.savez(path, **{**base, **extra})
    return str(path)


LAWS = {"joint_stiffness": np.array([10.0]), "joint_normal_stiffness": np.array([100.0]),
        "joint_preload": np.array([5.0]), "joint_friction": np.array([0.4])}


def test_3d_joint_arrays_checked(tmp_path):
    p = tmp_path / "c.npz"
    mf = read_structure(_save(p, **LAWS))
    assert mf.contacts.tolist() == [[10.0, 100.0, 5.0, 0.4]]
    with pytest.raises(ParameterError, match="missing joint_preload"):
        read_structure(_save(p, **{k: v for k, v in LAWS.items() if k != "joint_preload"}))
    with pytest.raises(ParameterError, match="not joint_slip_force"):
        read_structure(_save(p, **LAWS, joint_slip_force=np.array([2.0])))
    with pytest.raises(ParameterError, match="joint_preload must be finite N"):
        read_structure(_save(p, **{**LAWS, "joint_preload": np.array([np.nan])}))
    # a node the clamping lifted off: preload -k_n x gap (issue 28 item 2)
    assert read_structure(_save(p, **{**LAWS, "joint_preload": np.array([-1.0])})
                          ).contacts.tolist() == [[10.0, 100.0, -1.0, 0.4]]
    with pytest.raises(ParameterError, match="joint_friction must be 1 numbers"):
        read_structure(_save(p, **{**LAWS, "joint_friction": np.array([0.4, 0.4])}))
    with pytest.raises(ParameterError, match="belong to 3-D contact joints"):
        np.savez(p, M=np.eye(2), K=np.eye(2), joints=np.array([[[0, -1], [1, -1]]]),
                 joint_stiffness=[1.0], joint_slip_force=[1.0], joint_preload=[1.0])
        read_structure(str(p))


def test_3d_joints_need_their_laws(tmp_path):
    """A file of 3-D joints without the laws, or another connectivity on a 3-D file with a
    1-D joint, is refused in one line."""
    p = tmp_path / "c.npz"
    np.savez(p, M=np.eye(3), K=np.eye(3), joints=np.array([[[0, -1], [1, -1], [2, -1]]]))
    with pytest.raises(ParameterError, match="need joint_stiffness"):
        read_structure(str(p))
    mf = read_structure(_save(p, **LAWS))
    with pytest.raises(ParameterError, match="carry no laws of their own"):
        from_matrices(mf, np.array([[[0, -1]]]), None, "circular")
    with pytest.raises(ParameterError, match="three directions"):
        from_matrices(mf, mf.joints[:, ::-1], jenkins(1.0, 1.0), "circular")
