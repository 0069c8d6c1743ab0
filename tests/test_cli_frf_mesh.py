"""``microslip frf --mesh FILE``: the forced response of the user's structure with its clamp
on the contact-node ROM. Exact reference: at a force so small that no node slips the curve
is the stuck ROM's linear response (and the full FE's, to the ROM's truncation); as the force
grows the peak softens and flattens, and it lies on the ROM's EPMC backbone; bad input is
refused in one line."""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from microslip.cli import frfmesh
from microslip.cli.main import main
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import read_mesh, write_inp
from microslip.meshdynamics.frfstudy import FrfMeshSolver, stuck_response
from microslip.meshdynamics.modes import linear_modes, modal_mass, modal_stiffness
from microslip.meshdynamics.reduce import build_rom, rom_structure

BASE = ["--contact-set", "contact", "--clamp-set", "clamp", "--normal-force", "2000",
        "--friction", "0.5", "--stick-slope", "1e4", "--modulus", "70000",
        "--poisson-ratio", "0.33", "--density", "2700", "--mode", "2",
        "--response-set", "response"]
#: Below the softened peak of 0.01 N: every contact node stays stuck.
LOW = ["--force", "0.01", "--frequency-range", "1400", "1600"]


@pytest.fixture(scope="module")
def mesh(tmp_path_factory: pytest.TempPathFactory) -> str:
    """The 12x3x1 cantilever with one more node set, ``mid``: the nodes of the plane
    x = 101.6 mm (two thirds of the length, outside the clamp)."""
    m = cantilever_mesh(12, 3, 1)
    mid = np.flatnonzero(np.isclose(m.nodes[:, 0], 101.6))
    assert mid.size == 8
    m = dataclasses.replace(m, node_sets={**m.node_sets, "mid": mid})
    path = tmp_path_factory.mktemp("frf") / "cantilever_12x3x1.inp"
    return str(write_inp(m, path))


def _json(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(["frf", *argv, "--json"]) == 0
    out, _ = capsys.readouterr()
    return json.loads(out)


def _model(mesh: str, contact: str = "fixed"):  # type: ignore[no-untyped-def]
    return build_mesh_model(read_mesh(mesh), rigid_base(contact_set="contact", clamp_set="clamp",
                                                        normal_force=2000.0, modulus=70000.0,
                                                        poisson_ratio=0.33, friction=0.5,
                                                        stick_slope=1e4, normal_contact=contact))


def _full_fe(mesh: str, load_set: str, direction: np.ndarray, force: float,
             frequencies: np.ndarray, contact: str = "fixed") -> np.ndarray:
    """The full FE's stuck linear response (mm): F spread equally over the load set's nodes
    along ``direction``, the response set's mean displacement along mode 2's direction."""
    model = _model(mesh, contact)
    k = modal_stiffness(model, "stuck").toarray()
    m = modal_mass(model, 2700.0).toarray()
    along = linear_modes(model, 2700.0, 6, "stuck", "response").select(2).direction
    nodes = model.mesh.node_sets[load_set]
    f = np.zeros(model.dof)
    d = model.rotation @ direction
    for node in model.model_nodes(nodes):
        for c in range(3):
            pos = model.index[3 * node + c]
            if pos >= 0:
                f[pos] += force / nodes.size * d[c]
    response = model.mesh.node_sets["response"]
    out = []
    for hz in frequencies:
        u = np.linalg.solve(k - (2 * np.pi * hz) ** 2 * m, f)
        out.append(abs(model.global_vectors(u)[response].mean(axis=0) @ along))
    return np.asarray(out)


@pytest.mark.slow
@pytest.mark.parametrize("contact", ["fixed", "penalty"])
def test_linear_limit_is_the_stuck_rom(capsys: pytest.CaptureFixture[str], mesh: str,
                                       contact: str) -> None:
    """At 0.01 N below the peak no node slips: the harmonic balance equals the stuck ROM's
    linear solve to 1e-9, and the full FE's to the ROM's truncation (1e-4); with either
    normal contact (2-D circular elements, or 3-D elements on their preload)."""
    out = _json(capsys, "--mesh", mesh, *BASE, *LOW, "--normal-contact", contact)
    (curve,) = out["curves"]
    f = np.asarray(curve["frequency_Hz"])
    a = np.asarray(curve["amplitude_mm"])
    assert [f[0], f[-1]] == pytest.approx([1400.0, 1600.0], rel=1e-12)
    model = _model(mesh, contact)
    mode = linear_modes(model, 2700.0, 6, "stuck", "response").select(2)
    rom = build_rom(model, 2700.0, modes=60, response_set="response")
    output = mode.direction @ rom.output
    exact = stuck_response(rom_structure(rom, output), output, 0.01, f)
    assert np.max(np.abs(a - exact) / exact) < 1e-9
    full = _full_fe(mesh, "response", np.asarray(mode.direction), 0.01, f, contact)
    assert np.max(np.abs(a - full) / full) < 1e-4
    assert curve["damping_ratio"] is None  # the largest amplitude is the range's end
    assert any("not a peak" in w for w in out["warnings"])
    assert out["load"] == {"set": "response", "nodes": 8, "direction": mode.direction.tolist()}
    assert out["rom"]["stuck_frequencies_Hz"][1] == pytest.approx(
        out["linear_frequencies_Hz"][1], rel=1e-6)


@pytest.mark.slow
def test_another_load_set_is_the_full_fe(capsys: pytest.CaptureFixture[str],
                                         mesh: str) -> None:
    """A load on the set ``mid`` along y (the ROM built a second time for its rows, the
    modal coordinates' signs aligned): the small-force curve is the full FE's linear
    response to the ROM's truncation."""
    out = _json(capsys, "--mesh", mesh, *BASE, *LOW, "--load-set", "mid",
                "--load-direction", "0,2,0")
    (curve,) = out["curves"]
    f, a = np.asarray(curve["frequency_Hz"]), np.asarray(curve["amplitude_mm"])
    full = _full_fe(mesh, "mid", np.array([0.0, 1.0, 0.0]), 0.01, f)
    assert np.max(np.abs(a - full) / full) < 1e-4
    assert out["load"] == {"set": "mid", "nodes": 8, "direction": [0.0, 1.0, 0.0]}


@pytest.mark.slow
def test_peak_softens_and_lies_on_the_backbone(capsys: pytest.CaptureFixture[str],
                                               mesh: str, tmp_path: Path) -> None:
    """1 N and 3 N (single-harmonic balance, for speed): the peak moves down from the stuck
    frequency, its amplitude grows less than the force (flattens) and the equivalent damping
    ratio rises; each peak is on the ROM's EPMC backbone (frequency within 0.1 %, damping
    ratio within 5 %: the definition takes the stuck mode's shape, the EPMC the slipping
    one's)."""
    table, plot = tmp_path / "frf.csv", tmp_path / "frf.png"
    out = _json(capsys, "--mesh", mesh, *BASE, "--force", "1", "--force", "3",
                "--harmonics", "1", "--csv", str(table), "--plot", str(plot))
    low, high = out["curves"]
    stuck = out["linear_frequencies_Hz"][1]
    assert out["frequency_range_Hz"] == pytest.approx([0.8 * stuck, 1.05 * stuck])
    assert high["peak_frequency_Hz"] < low["peak_frequency_Hz"] < stuck
    assert low["peak_amplitude_mm"] < high["peak_amplitude_mm"] < 3 * low["peak_amplitude_mm"]
    assert 0 < low["damping_ratio"] < high["damping_ratio"]
    assert not out["warnings"]
    backbone = _json_modal(capsys, mesh, low["peak_amplitude_mm"], high["peak_amplitude_mm"])
    for c, f, z in zip(out["curves"], backbone["frequency_Hz"], backbone["damping_ratio"],
                       strict=True):
        assert c["peak_frequency_Hz"] == pytest.approx(f, rel=1e-3)
        assert c["damping_ratio"] == pytest.approx(z, rel=0.05)
    with open(table, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == low["points"] + high["points"]
    assert plot.stat().st_size > 0


def _json_modal(capsys: pytest.CaptureFixture[str], mesh: str, *amplitudes: float) -> dict:
    assert main(["modal", "--mesh", mesh, *BASE, "--solver", "rom", "--harmonics", "1",
                 "--amplitude-range", str(amplitudes[0]), str(amplitudes[1]),
                 "--amplitudes", "2", "--json"]) == 0
    out, _ = capsys.readouterr()
    backbone = json.loads(out)
    assert backbone["amplitude_mm"] == pytest.approx(list(amplitudes), rel=1e-9)
    return backbone


@pytest.mark.slow
def test_text_output(capsys: pytest.CaptureFixture[str], mesh: str) -> None:
    assert main(["frf", "--mesh", mesh, *BASE, *LOW]) == 0
    out, err = capsys.readouterr()
    assert "mode 2 (bending in the contact plane)" in out and "force (N)" in out
    assert "n/a" in out and "not a peak" in err


@pytest.mark.parametrize(("extra", "message"), [
    (["--structure", "x.npz"], "--structure not used with --mesh"),
    (["--excitation", "0"], "--excitation not used with --mesh"),
    (["--frequency", "100"], "--frequency not used with --mesh"),
    (["--load-direction", "0,0,0"], "--load-direction must be three finite numbers"),
    (["--load-direction", "0,0,1"], "does not excite mode 2"),
    (["--load-set", "nosuch"], "nosuch"),
    (["--rom-modes", "0"], "--rom-modes must be >= 1"),
    (["--frequency-range", "1600", "1400"], "--frequency-range must satisfy 0 < MIN < MAX"),
    (["--force", "-1"], "--force must be finite and > 0 N"),
    (["--plot", "frf.foo"], "plot file must end in .png"),
    (["--mode", "51"], "--mode must be in [1, 50]"),
])
def test_bad_input_is_one_line(capsys: pytest.CaptureFixture[str], mesh: str,
                               extra: list[str], message: str) -> None:
    argv = ["frf", "--mesh", mesh, *BASE, *extra]
    if "--force" not in extra:
        argv += ["--force", "1"]
    assert main(argv) in (1, 2)
    _, err = capsys.readouterr()
    assert message in err and len(err.strip().splitlines()) == 1


def test_missing_response_set_is_one_line(capsys: pytest.CaptureFixture[str],
                                          mesh: str) -> None:
    assert main(["frf", "--mesh", mesh, *BASE[:-2], "--force", "1"]) == 2
    _, err = capsys.readouterr()
    assert "needs --response-set NAME" in err and len(err.strip().splitlines()) == 1


def test_solver_options_follow_the_registry(capsys: pytest.CaptureFixture[str], mesh: str,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    """--rom-modes with a solver that does not take it is refused (a stand-in second solver:
    the whole-joint model plugs in the same way)."""
    monkeypatch.setitem(frfmesh.FRF_MESH_SOLVERS, "other",
                        FrfMeshSolver("a stand-in", (), frfmesh.FRF_MESH_SOLVERS["rom"].build))
    assert main(["frf", "--mesh", mesh, *BASE, "--force", "1", "--solver", "other",
                 "--rom-modes", "10"]) == 1
    _, err = capsys.readouterr()
    assert "--rom-modes applies to --solver rom or joint only" in err
    assert main(["frf", "--mesh", mesh, *BASE, "--force", "1", "--backbone", "work"]) == 1
    _, err = capsys.readouterr()
    assert "--backbone applies to --solver joint only" in err


@pytest.mark.slow
def test_whole_joint_linear_limit(capsys: pytest.CaptureFixture[str], mesh: str) -> None:
    """--solver joint at 0.01 N: no joint slips, so the harmonic balance equals the stuck
    whole-joint model's own linear solve to 1e-9 (the load carried through the interface
    reduction, T^T f), and its stuck frequency is the one the model reports."""
    from microslip.meshdynamics.wholejoint import build_whole_joint

    out = _json(capsys, "--mesh", mesh, *BASE, *LOW, "--solver", "joint")
    (curve,) = out["curves"]
    f = np.asarray(curve["frequency_Hz"])
    a = np.asarray(curve["amplitude_mm"])
    model = _model(mesh)
    mode = linear_modes(model, 2700.0, 6, "stuck", "response").select(2)
    rom = build_rom(model, 2700.0, modes=60, response_set="response")
    joint = build_whole_joint(rom, model, mode, mode.direction @ rom.output)
    load = mode.direction @ rom.output @ joint.transform
    exact = stuck_response(joint.structure, load, 0.01, f)
    assert np.max(np.abs(a - exact) / exact) < 1e-9
    assert out["joint"]["stuck_frequency_Hz"] == pytest.approx(
        float(joint.stuck_frequencies()[joint.mode_index(mode.frequency_Hz)]), rel=1e-9)


def test_mesh_options_without_a_mesh_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["frf", "--frequency", "100", "--modal-mass", "1", "--joint", "jenkins",
                 "--joint-stiffness", "100", "--slip-force", "5", "--force", "1",
                 "--load-set", "tip"]) == 1
    _, err = capsys.readouterr()
    assert "--load-set applies to frf --mesh FILE only" in err


def test_peak_comparison_is_relative_to_the_reference() -> None:
    from microslip.meshdynamics.frfstudy import peak_comparison

    ref = {"force_N": 3.0, "peak_amplitude_mm": 0.02, "peak_frequency_Hz": 1600.0,
           "damping_ratio": 0.05}
    other = {"force_N": 3.0, "peak_amplitude_mm": 0.03, "peak_frequency_Hz": 1680.0,
             "damping_ratio": None}
    c = peak_comparison(ref, other)
    assert c["force_N"] == 3.0
    assert c["peak_amplitude_difference"] == pytest.approx(0.5, rel=1e-14)
    assert c["peak_frequency_difference"] == pytest.approx(0.05, rel=1e-12)
    assert c["damping_ratio_difference"] is None


def test_all_refuses_plot_and_csv(capsys: pytest.CaptureFixture[str], mesh: str) -> None:
    assert main(["frf", "--mesh", mesh, *BASE, "--force", "1", "--solver", "all",
                 "--plot", "x.png"]) == 1
    _, err = capsys.readouterr()
    assert "--plot and --csv draw and write one solver's curves" in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.slow
def test_all_runs_both_on_the_same_forces(capsys: pytest.CaptureFixture[str],
                                          mesh: str) -> None:
    """--solver all: the ROM and the whole joint on the same force and range, one harmonic,
    and the joint's peaks against the ROM's computed from the two curves."""
    out = _json(capsys, "--mesh", mesh, *BASE, "--force", "1", "--harmonics", "1",
                "--solver", "all")
    assert set(out["solvers"]) == {"rom", "joint"} and out["reference"] == "rom"
    (rom,), (joint,) = out["solvers"]["rom"]["curves"], out["solvers"]["joint"]["curves"]
    (row,) = out["comparison"]["joint"]
    assert row["peak_amplitude_difference"] == pytest.approx(
        joint["peak_amplitude_mm"] / rom["peak_amplitude_mm"] - 1, rel=1e-12)
    assert rom["frequency_Hz"][0] == joint["frequency_Hz"][0]
    assert "stuck_frequency_Hz" in out["solvers"]["joint"]["joint"]
