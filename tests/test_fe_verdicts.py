"""When an FE loop's figures are not damping: stick throughout, shakedown, no convergence, gross
sliding (issue 11, item 5, FE side)."""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest

from microslip import preset
from microslip.cli.main import main
from microslip.energy import dissipated_energy
from microslip.fe.builtin import NewtonOptions, coupling_study, solve_uniaxial
from microslip.fe.builtin import meshmodel as model_module
from microslip.fe.result import (
    SLIP,
    STICK,
    ContactHistory,
    gross_sliding_states,
    idle_loop_reason,
)
from microslip.params import ClampParams

#: The titanium block of issue 11 (30 x 12 x 8 mm, mu 0.5, F_N 12 kN).
TITANIUM = ClampParams(length=30.0, width=12.0, thickness=8.0, modulus=113_800.0,
                       poisson_ratio=0.342, friction=0.5, normal_force=12_000.0)
TITANIUM_ARGS = ["--length", "30", "--width", "12", "--thickness", "8", "--modulus", "113800",
                 "--poisson", "0.342", "--friction", "0.5", "--normal-force", "12000",
                 "--amplitude", "3600"]


def history(status: list[list[int]]) -> ContactHistory:
    s = np.asarray(status, dtype=np.int8)
    k, m = s.shape
    coords = np.zeros((m, 3))
    coords[:, 0] = np.arange(m)
    return ContactHistory(np.arange(m), coords, np.arange(k, dtype=float), s, np.ones(m))


def test_idle_loop_reason_tells_stick_from_shakedown_from_slip():
    stick, slip = STICK, SLIP
    # 5 states, the loop is the last 3 (its increments: the last 2)
    assert "stick throughout" in idle_loop_reason(history([[stick, stick]] * 5), 3)
    shake = [[stick, stick], [slip, stick], [slip, stick], [stick, stick], [stick, stick]]
    assert "shakedown" in idle_loop_reason(history(shake), 3)
    # a slip in the loop's first state belongs to the loading before it
    assert idle_loop_reason(history(shake), 4) is None
    assert idle_loop_reason(history([*shake[:4], [stick, slip]]), 3) is None


def test_gross_sliding_states_are_those_without_a_sticking_point():
    open_ = 0
    h = history([[STICK, STICK], [SLIP, STICK], [SLIP, SLIP], [SLIP, open_], [open_, open_]])
    assert gross_sliding_states(h).tolist() == [2, 3]


def test_stuck_titanium_block_reports_exactly_zero_and_why():
    """Stick slope 1e3 N/mm^3: no point slips; the trapezoidal area is rounding noise, the
    reported W_d and eta are exactly 0."""
    r = solve_uniaxial(TITANIUM, "tip", 3600.0, mesh=(8, 2, 2), stick_slope=1e3)
    assert r.converged
    assert not np.any(r.contact.status == SLIP)
    assert abs(dissipated_energy(r.loop)) < 1e-9 * 3600.0 * r.peak_displacement
    assert r.dissipated_energy == 0.0 and r.damping.loss_factor == 0.0
    assert r.damping.strain_energy > 0.0
    assert "stick throughout" in r.message
    assert r.with_strain_energy("secant").dissipated_energy == 0.0


def test_a_slipping_loop_keeps_its_area():
    r = solve_uniaxial(preset("table1"), "tip", 267.0, mesh=(8, 2, 1))
    assert r.dissipated_energy == dissipated_energy(r.loop) > 0.0
    assert r.message == "converged" and not r.gross_sliding


def test_cli_stuck_block_says_why(capsys):
    assert main(["fe", "--model", "tip", *TITANIUM_ARGS, "--mesh", "tiny", "--stick-slope",
                 "1e3", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dissipated_energy_Nmm"] == 0.0 and data["loss_factor"] == 0.0
    assert "stick throughout" in data["message"]
    assert main(["fe", "--model", "tip", *TITANIUM_ARGS, "--mesh", "tiny", "--stick-slope",
                 "1e3"]) == 0
    text = capsys.readouterr().out
    assert "stick throughout" in text


@pytest.fixture
def one_newton_iteration(monkeypatch):
    """Newton allowed one iteration and no cutting: the clamping (linear) still converges, the
    slipping increments do not."""
    monkeypatch.setattr(model_module, "NewtonOptions",
                        functools.partial(NewtonOptions, max_iterations=1, max_cuts=1))


def test_not_converged_run_has_no_damping_figures(one_newton_iteration):
    r = solve_uniaxial(preset("table1"), "tip", 267.0, mesh=(8, 2, 1))
    assert not r.converged and "did not converge" in r.message
    s = r.summary()
    assert s["converged"] is False
    assert s["dissipated_energy_Nmm"] is None and s["loss_factor"] is None
    assert s["strain_energy_Nmm"] is None


@pytest.mark.parametrize("json_flag", [[], ["--json"]])
def test_cli_not_converged_exits_1_without_damping(capsys, one_newton_iteration, json_flag):
    assert main(["fe", "--model", "tip", "--mesh", "tiny", *json_flag]) == 1
    out = capsys.readouterr().out
    if json_flag:
        data = json.loads(out)
        assert data["dissipated_energy_Nmm"] is None and data["loss_factor"] is None
    else:
        assert "did not converge" in out and "no damping figures" in out
        assert "W_d" not in out and "eta" not in out


def test_planar_full_slip_is_reported_as_gross_sliding():
    """340 N tip + 300 N centre at 90 degrees on the Table 1 bar (issue 11): the peak resultant,
    340 N, is below mu F_N = 356 N, but for most of the cycle no contact point sticks."""
    r = coupling_study(preset("table1"), 340.0, 300.0, 90.0, cycles=3,
                       increments_per_cycle=32, mesh=(8, 2, 1))
    assert r.converged and r.gross_sliding
    s = r.summary()
    assert s["gross_sliding"] is True and "gross sliding" in s["message"]
    assert any(w.startswith("coupled: gross sliding") for w in s["warnings"])
    # the tip alone at 340 N keeps a stuck region: microslip
    assert not r.tip_only.gross_sliding


def test_planar_microslip_is_not_flagged():
    r = coupling_study(preset("table1"), 150.0, 60.0, 90.0, cycles=3,
                       increments_per_cycle=32, mesh=(8, 2, 1))
    assert not r.gross_sliding and r.summary()["warnings"] == []
