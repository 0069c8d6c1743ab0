"""``microslip reduce``: the contact-node ROM of the user's mesh written as a structure file
(issue 23, item 3): ``modal --structure`` reads it back with the ROM's stuck frequency; the
convergence against the full FE is shown; bad input refused in one line; the file is never
half-written."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from microslip.cli.main import main
from microslip.dynamics.files import read_structure
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import write_inp

CLAMP = ["--contact-set", "contact", "--clamp-set", "clamp", "--normal-force", "2000",
         "--friction", "0.5", "--stick-slope", "1e4", "--modulus", "70000",
         "--poisson-ratio", "0.33"]


@pytest.fixture(scope="module")
def mesh(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("reduce") / "cantilever_12x3x1.inp"
    return str(write_inp(cantilever_mesh(12, 3, 1), path))


def _reduce(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(["reduce", *argv, "--json"]) == 0
    out, _ = capsys.readouterr()
    return json.loads(out)


def test_written_rom_read_by_modal_gives_its_stuck_frequency(capsys, mesh, tmp_path):
    out = str(tmp_path / "rom.npz")
    r = _reduce(capsys, "--mesh", mesh, *CLAMP, "--density", "2700", "--rom-modes", "12",
                "--response-set", "response", "--out", out)
    assert os.path.isfile(out) and not os.path.exists(out + ".part")
    assert r["rom"]["fixed_interface_modes"] == 12
    assert r["rom"]["dofs"] == r["rom"]["contact_dofs"] + 12 == 2 * r["contact_nodes"] + 12
    assert r["convergence"]["modes"] == [2, 3, 6, 12]
    worst = [max(abs(e) for e in row) for row in r["convergence"]["relative_error"]]
    assert worst[-1] < worst[0] and worst[-1] < 1e-3 and r["warnings"] == []
    assert r["rom_frequencies_Hz"][1] == pytest.approx(r["full_frequencies_Hz"][1], rel=1e-3)
    # the in-plane bending (mode 2) moves the response set along y
    assert abs(r["response_direction"][1][1]) > 0.99
    assert main(["modal", "--structure", out, "--mode", "2", "--amplitude-range", "1e-4",
                 "1e-2", "--amplitudes", "2", "--harmonics", "3", "--json"]) == 0
    modal = json.loads(capsys.readouterr().out)
    stuck = r["rom_frequencies_Hz"][1]
    assert modal["structure"]["stuck_frequencies_Hz"][1] == pytest.approx(stuck, rel=1e-9)
    assert modal["frequency_Hz"][0] == pytest.approx(stuck, rel=1e-6)
    assert modal["frequency_Hz"][1] < modal["frequency_Hz"][0]  # slipping softens


def test_cutoff_frequency_and_printed_units(capsys, mesh, tmp_path):
    out = str(tmp_path / "cut.npz")
    assert main(["reduce", "--mesh", mesh, *CLAMP, "--density", "2700",
                 "--cutoff-frequency", "60000", "--out", out]) == 0
    text, err = capsys.readouterr()
    assert err == ""
    assert "DOF" in text and "fixed-interface modes (up to" in text and "Hz)" in text
    assert "built in" in text and " s" in text and "kB" in text and "kg/m^3" in text
    assert "full FE (Hz)" in text and "ROM (Hz)" in text
    mf = read_structure(out)
    assert mf.joints.shape[1:] == (2, 2) and mf.laws is not None


def test_penalty_contact_writes_3d_joints(capsys, mesh, tmp_path):
    out = str(tmp_path / "pen.npz")
    r = _reduce(capsys, "--mesh", mesh, *CLAMP, "--density", "2700", "--rom-modes", "8",
                "--normal-contact", "penalty", "--normal-slope", "1e6", "--out", out)
    mf = read_structure(out)
    assert mf.joints.shape == (r["contact_nodes"], 3, 2) and mf.contacts is not None
    assert r["rom"]["contact_dofs"] == 3 * r["contact_nodes"]
    assert np.all(mf.contacts[:, 3] == 0.5)


def test_few_modes_warn(capsys, mesh, tmp_path):
    out = str(tmp_path / "few.npz")
    assert main(["reduce", "--mesh", mesh, *CLAMP, "--density", "2700", "--rom-modes", "1",
                 "--out", out]) == 0
    _, err = capsys.readouterr()
    assert "keep more modes" in err and "%" in err


@pytest.mark.parametrize(("extra", "message"), [
    (["--density", "2700", "--rom-modes", "0"], "--rom-modes must be in [1, 2000], got 0"),
    (["--density", "2700", "--cutoff-frequency", "-5"],
     "--cutoff-frequency must be finite and > 0 Hz, got -5"),
    (["--density", "-1", "--rom-modes", "5"], "--density must be finite and > 0 kg/m^3"),
    (["--density", "2700", "--rom-modes", "5", "--normal-slope", "1e6"],
     "--normal-slope needs --normal-contact penalty"),
    (["--density", "2700", "--rom-modes", "5", "--response-set", "nowhere"],
     "no set named 'nowhere' (the response set)"),
    (["--density", "2700", "--cutoff-frequency", "1"], "no fixed-interface mode below 1"),
])
def test_bad_input_one_line(capsys, mesh, tmp_path, extra, message):
    out = tmp_path / "bad.npz"
    assert main(["reduce", "--mesh", mesh, *CLAMP, *extra, "--out", str(out)]) == 1
    _, err = capsys.readouterr()
    assert err.count("\n") == 1 and err.startswith("error: ") and message in err
    assert not out.exists() and not list(tmp_path.iterdir())


@pytest.mark.parametrize(("extra", "message"), [
    (["--rom-modes", "5"], "the following arguments are required: --density KG/M3"),
    (["--density", "2700", "--rom-modes", "5", "--cutoff-frequency", "1e4"],
     "argument --cutoff-frequency: not allowed with argument --rom-modes"),
])
def test_usage_mistakes_exit_2(capsys, mesh, tmp_path, extra, message):
    """A required option left out, or two that exclude each other: usage mistakes, exit 2
    as argparse's own (issue 27)."""
    out = tmp_path / "bad.npz"
    assert main(["reduce", "--mesh", mesh, *CLAMP, *extra, "--out", str(out)]) == 2
    _, err = capsys.readouterr()
    assert err.count("\n") == 1 and err.startswith("error: ") and message in err
    assert not list(tmp_path.iterdir())


def test_rom_modes_defaults_to_60(capsys, mesh, tmp_path, monkeypatch):
    """Without --rom-modes (and --cutoff-frequency) reduce keeps the 60 modes the help
    promises (issue 27: it refused)."""
    import microslip.meshdynamics.reduce as reduce_module

    seen = {}

    def spy(*a, **k):
        seen.update(k)
        raise KeyboardInterrupt  # stop before the work: the count is what is tested

    monkeypatch.setattr(reduce_module, "build_rom", spy)
    assert main(["reduce", "--mesh", mesh, *CLAMP, "--density", "2700",
                 "--out", str(tmp_path / "a.npz")]) == 130
    assert seen["modes"] == 60 and seen["cutoff_hz"] is None


def test_unknown_set_and_bad_out_refused(capsys, mesh, tmp_path):
    bad = [*CLAMP]
    bad[1] = "nowhere"  # --contact-set
    assert main(["reduce", "--mesh", mesh, *bad, "--density", "2700", "--rom-modes", "5",
                 "--out", str(tmp_path / "a.npz")]) == 1
    assert "nowhere" in capsys.readouterr().err
    assert main(["reduce", "--mesh", mesh, *CLAMP, "--density", "2700", "--rom-modes", "5",
                 "--out", str(tmp_path / "a.txt")]) == 1
    assert "--out must end in .npz" in capsys.readouterr().err
    assert main(["reduce", *CLAMP, "--density", "2700", "--rom-modes", "5"]) == 2
    assert "the following arguments are required: --mesh FILE" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_failed_write_leaves_no_file(capsys, mesh, tmp_path, monkeypatch):
    """A failure while writing (a full disk) leaves neither the file nor its temporary, and
    an older file of that name untouched."""
    out = tmp_path / "rom.npz"
    out.write_bytes(b"older")

    def full_disk(fh, **arrays):
        fh.write(b"PK\x03\x04 partial")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np, "savez", full_disk)
    assert main(["reduce", "--mesh", mesh, *CLAMP, "--density", "2700", "--rom-modes", "5",
                 "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "No space left on device" in err
    assert out.read_bytes() == b"older"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rom.npz"]


def test_case_file_gives_the_clamp_and_the_mesh(capsys, tmp_path, monkeypatch):
    """``reduce --case`` reads [material], [contact], [clamping] and [mesh] (file relative to
    the case file); the same ROM as the command line's, and [[load]] noted as not read."""
    write_inp(cantilever_mesh(12, 3, 1), tmp_path / "beam.inp")
    (tmp_path / "case.toml").write_text(
        "[material]\nmodulus = 70000\npoisson_ratio = 0.33\n[contact]\nfriction = 0.5\n"
        "stick_slope = 1e4\n[clamping]\nnormal_force = 2000\n[mesh]\nfile = \"beam.inp\"\n"
        "contact_set = \"contact\"\nclamp_set = \"clamp\"\n\n[[load]]\nset = \"tip\"\n"
        "direction = [1, 0, 0]\namplitude = 300\n")
    monkeypatch.chdir(tmp_path)
    rom = ["--density", "2700", "--rom-modes", "6", "--json"]
    assert main(["reduce", "--case", "case.toml", *rom, "--out", "a.npz"]) == 0
    out, err = capsys.readouterr()
    by_case = json.loads(out)
    assert "[[load]] not read by reduce" in err
    assert main(["reduce", "--mesh", "beam.inp", *CLAMP, *rom, "--out", "b.npz"]) == 0
    by_flags = json.loads(capsys.readouterr().out)
    # the same model (ARPACK's random start vector moves the modes' last digits)
    assert by_case["full_frequencies_Hz"] == pytest.approx(by_flags["full_frequencies_Hz"],
                                                           rel=1e-9)
    assert by_case["rom_frequencies_Hz"] == pytest.approx(by_flags["rom_frequencies_Hz"],
                                                          rel=1e-9)
    a, b = read_structure("a.npz"), read_structure("b.npz")
    assert np.array_equal(a.laws, b.laws) and np.array_equal(a.joints, b.joints)
