"""Clamping pressure laws in the built-in solver and its clamping reactions as a 1-D law
(issue 11, item 2, FE side): the law is the distribution of the box's preload (issue 32,
item 4; its shares: tests/test_fe_preload_distribution.py)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from microslip import preset
from microslip.cli.main import main
from microslip.fe.builtin import box_model, solve_uniaxial
from microslip.fe.builtin.clamping import clamping_pressure
from microslip.fe.builtin.meshgeometry import set_faces
from microslip.fe.builtin.pressure import fe_pressure_law
from microslip.fe.examples import box_hexmesh
from microslip.models.interface import (
    masing_dissipation,
    power_law,
    pressure_law,
    read_pressure_table,
)

P = preset("table1")
PARABOLIC = pressure_law("parabolic")


def test_uniform_law_is_the_paper_s_clamping_load():
    """The named uniform law is no distribution: the consistent shares of F_N / (L w)."""
    model = box_model(P, (8, 2, 1), pressure_law=pressure_law("uniform"))
    assert model.assembly.preloads[0].distribution is None
    assert float(model.clamp_load.sum()) == pytest.approx(-P.normal_force, rel=1e-14)


#: The twin box solver's clamping pressure (line load, N/mm; build_model + clamping_pressure
#: before issue 32 routed the box through the mesh path), section by section.
OLD_LINE_LOAD = {
    ("parabolic", (8, 2, 1)): [2.4370428372090998, 2.0530518223162257, 1.6666196435039782,
                               1.4019117893959867, 1.3355386838545875, 1.4019117893959872,
                               1.6666196435039782, 2.053051822316225, 2.4370428372090993],
    ("power4", "12x2x3"): [3.297490161061631, 2.476216523615961, 1.7940573565441684,
                           1.418393488799261, 1.2943525766186772, 1.2535837464107644,
                           1.2529245022047308, 1.253583746410763, 1.2943525766186728,
                           1.4183934887992626, 1.7940573565441662, 2.476216523615958,
                           3.2974901610616296],
    ("uniform", (8, 2, 1)): [1.7630352447570667, 1.7426477600742845, 1.7586569523751445,
                             1.7465834092637795, 1.7569365433125852, 1.746583409263779,
                             1.7586569523751443, 1.742647760074284, 1.763035244757066],
}


@pytest.mark.parametrize("name, mesh", sorted(OLD_LINE_LOAD, key=str))
def test_the_routed_box_keeps_the_twin_s_clamping_pressure(name, mesh):
    """The box on the mesh path (its pressure law a preload distribution) gives the twin
    solver's clamping pressure table to round-off (measured 1e-14)."""
    law = {"parabolic": PARABOLIC, "power4": power_law(4.0, 3.0), "uniform": None}[name]
    cp = clamping_pressure(box_model(P, mesh, pressure_law=law), P.width)
    old = np.array(OLD_LINE_LOAD[name, mesh])
    np.testing.assert_allclose(cp.x, np.linspace(0.0, P.length, old.size), rtol=1e-15)
    np.testing.assert_allclose(cp.line_load, old, rtol=1e-12)
    assert cp.width == P.width


def test_the_preload_shares_of_a_law_on_the_box():
    """On the box's top, the law's nodal forces are the line integral along x times the
    tributary width across (the twin's clamp_forces)."""
    law = power_law(1.0, 3.0)
    nx = 8
    mesh = box_hexmesh(P, (nx, 1, 1))
    x = np.linspace(0.0, P.length, nx + 1)
    p = law.shape(x / P.length) * P.normal_force / (P.length * P.width)
    h = P.length / nx
    line = np.empty(nx + 1)
    line[1:-1] = h / 6 * (p[:-2] + 4 * p[1:-1] + p[2:])
    line[0] = h / 6 * (2 * p[0] + p[1])
    line[-1] = h / 6 * (2 * p[-1] + p[-2])
    expected = np.repeat(line * P.width / 2, 2)  # two nodes across, half the width each
    model = box_model(P, (nx, 1, 1), pressure_law=law)
    nodes, share = model.assembly.preloads[0].shares(mesh, set_faces(mesh, "clamp", "set"))
    np.testing.assert_array_equal(nodes, mesh.node_sets["clamp"])
    assert np.allclose(P.normal_force * share, expected, rtol=1e-12)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_fe_with_parabolic_pressure_matches_the_1d_law(model):
    """The exact 1-D bar on the same shear layer (stick slope 1e4 N/mm^3 and the body's shear
    lag) with the same pressure law: W_d within 0.5 % on the coarse mesh (measured 0.1 % tip,
    0.2 % centre), while the parabolic law moves W_d by 10-12 % from the uniform one."""
    w1, d1 = masing_dissipation(model, P, 267.0, stick_slope=1e4, law=PARABOLIC)
    w_uniform = masing_dissipation(model, P, 267.0, stick_slope=1e4)[0]
    assert abs(w1 / w_uniform - 1) > 0.09
    r = solve_uniaxial(P, model, 267.0, mesh="coarse", pressure_law=PARABOLIC, increments=100)
    assert r.details.pressure_law == PARABOLIC.name
    assert r.dissipated_energy == pytest.approx(w1, rel=5e-3)
    assert r.peak_displacement == pytest.approx(d1, rel=(2e-3 if model == "tip" else 3e-2))


def test_clamping_reactions_follow_the_law_on_a_thin_bar_and_feed_the_1d_model():
    model = box_model(P, "coarse", pressure_law=PARABOLIC)
    cp = clamping_pressure(model, P.width)
    assert cp.x[0] == 0.0 and cp.x[-1] == P.length
    trib = np.diff(np.concatenate([[0.0], 0.5 * (cp.x[1:] + cp.x[:-1]), [P.length]]))
    assert float(cp.line_load @ trib) == pytest.approx(P.normal_force, rel=1e-12)
    mean = P.normal_force / (P.length * P.width)
    assert np.allclose(cp.pressure / mean, PARABOLIC.shape(cp.x / P.length), rtol=0.03)
    law = fe_pressure_law(P, "coarse", pressure_law=PARABOLIC)
    w_fe = masing_dissipation("tip", P, 267.0, stick_slope=1e4, law=law)[0]
    w_exact = masing_dissipation("tip", P, 267.0, stick_slope=1e4, law=PARABOLIC)[0]
    assert w_fe == pytest.approx(w_exact, rel=5e-3)


def test_clamping_csv_round_trips_to_the_same_law(tmp_path):
    cp = clamping_pressure(box_model(P, (8, 2, 1), pressure_law=PARABOLIC))  # w from the mesh
    law = read_pressure_table(str(cp.write_csv(tmp_path / "p.csv")), P.length)
    xi = np.linspace(0.0, 1.0, 41)
    assert np.array_equal(law.shape(xi), cp.law().shape(xi))
    nodes = np.loadtxt(cp.write_nodes_csv(tmp_path / "n.csv"), delimiter=",", skiprows=1)
    assert nodes.shape == (cp.node_force.size, 3)
    assert nodes[:, 2].sum() == pytest.approx(P.normal_force, rel=1e-12)


def test_cli_pressure_law_and_clamping_csv(capsys, tmp_path):
    csv = tmp_path / "clamp.csv"
    assert main(["fe", "--model", "tip", "--mesh", "tiny", "--pressure-law", "power:2:2",
                 "--clamping-csv", str(csv), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["options"]["pressure_law"] == PARABOLIC.name
    assert str(csv) in data["files"]
    assert main(["loop", "--model", "tip", "--pressure-law", f"table:{csv}", "--json"]) == 0
    capsys.readouterr()


def test_cli_pressure_law_is_builtin_only(capsys):
    assert main(["fe", "--model", "tip", "--solver", "calculix", "--pressure-law",
                 "parabolic"]) == 1
    err = capsys.readouterr().err
    assert "--pressure-law" in err and "calculix" in err
