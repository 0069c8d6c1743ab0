"""The coupled-friction part of ``microslip reproduce``: table, figure and words agree."""

from __future__ import annotations

import pytest

from microslip import preset
from microslip.fe.builtin import coupling_sweep
from microslip.io import write_csv
from microslip.reproduce import coupling_table, figure_coupling, read_csv
from microslip.reproduce.report import _coupling_section

#: the module's fixture runs the built-in FE coupling sweep (about 2.5 s of CPU)
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def table():
    sweep = coupling_sweep(preset("table1"), (0.5, 1.0, 2.0), (0.0, 90.0), mesh="tiny",
                           cycles=3, increments_per_cycle=24)
    return sweep, coupling_table(sweep)


def test_table_matches_the_sweep(table):
    sweep, cols = table
    assert cols["R"] == [0.5, 1.0, 2.0, 0.5, 1.0, 2.0]
    assert cols["phase_deg"] == [0.0] * 3 + [90.0] * 3
    flat = [x for row in sweep.coupling_ratio.tolist() for x in row]
    assert cols["coupling_ratio"] == flat
    for w, wd, c in zip(cols["dissipated_energy_Nmm"], cols["decoupled_dissipated_energy_Nmm"],
                        cols["coupling_ratio"], strict=True):
        assert c == pytest.approx(w / wd, rel=1e-12)


def test_words_follow_the_numbers(table, tmp_path):
    _, cols = table
    write_csv(tmp_path / "c.csv", cols)
    back = read_csv(tmp_path / "c.csv")
    text = _coupling_section(back)
    lo, hi = min(back["coupling_ratio"]), max(back["coupling_ratio"])
    if lo > 1:
        assert "**underestimates**" in text
    elif hi < 1:
        assert "**overestimates**" in text
    else:
        assert "both directions" in text
    for phi in (0.0, 90.0):
        vals = [c for c, p in zip(back["coupling_ratio"], back["phase_deg"], strict=True)
                if p == phi]
        assert f"at φ = {phi:g}° the ratio runs from {min(vals):.3f} to {max(vals):.3f}" in text


def test_figure_is_written(table, tmp_path):
    _, cols = table
    fig12 = {"R": [0.5, 1.0, 2.0], "paper_normalised_loss_factor": [1.0, 1.0, 1.001]}
    figure_coupling(tmp_path / "f.png", fig12, cols)
    assert (tmp_path / "f.png").read_bytes()[:4] == b"\x89PNG"
