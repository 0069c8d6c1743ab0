"""Clamping pressure laws in the built-in solver and its clamping reactions as a 1-D law
(issue 11, item 2, FE side)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from microslip import preset
from microslip.cli.main import main
from microslip.fe.builtin import build_model, solve_uniaxial
from microslip.fe.builtin.clamping import clamp_forces, clamping_pressure
from microslip.fe.builtin.mesh import box_mesh
from microslip.fe.builtin.pressure import fe_pressure_law
from microslip.models.interface import (
    masing_dissipation,
    power_law,
    pressure_law,
    read_pressure_table,
)

P = preset("table1")
PARABOLIC = pressure_law("parabolic")


def test_uniform_law_is_the_paper_s_clamping_load():
    mesh = box_mesh(P.length, P.width, P.thickness, 24, 4, 1)
    paper = clamp_forces(mesh, P, None)
    assert np.allclose(clamp_forces(mesh, P, pressure_law("uniform")), paper, rtol=1e-13)
    assert paper.sum() == pytest.approx(P.normal_force, rel=1e-14)


def test_consistent_forces_of_a_piecewise_linear_law_are_exact():
    """n = 1: p is linear on each half, with its kink on the mid node; the consistent nodal
    force of a linear traction on hat functions is h/6 (p_(i-1) + 4 p_i + p_(i+1)) inside and
    h/6 (2 p_0 + p_1) at the ends, times the tributary width."""
    law = power_law(1.0, 3.0)
    nx = 8
    mesh = box_mesh(P.length, P.width, P.thickness, nx, 1, 1)
    x = np.linspace(0.0, P.length, nx + 1)
    p = law.shape(x / P.length) * P.normal_force / (P.length * P.width)
    h = P.length / nx
    line = np.empty(nx + 1)
    line[1:-1] = h / 6 * (p[:-2] + 4 * p[1:-1] + p[2:])
    line[0] = h / 6 * (2 * p[0] + p[1])
    line[-1] = h / 6 * (2 * p[-1] + p[-2])
    expected = np.repeat(line * P.width / 2, 2)  # two nodes across, half the width each
    assert np.allclose(clamp_forces(mesh, P, law), expected, rtol=1e-12)


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
    model = build_model(P, "coarse", pressure_law=PARABOLIC)
    cp = clamping_pressure(model)
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
    cp = clamping_pressure(build_model(P, (8, 2, 1), pressure_law=PARABOLIC))
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
