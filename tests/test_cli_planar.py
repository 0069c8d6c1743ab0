"""``microslip planar`` (the analytical solver): JSON, units, one-line mistakes, and the clamp
options that change the Table 2 zones."""

from __future__ import annotations

import json
import math
import re

import pytest
from conftest import run

from microslip import ModelOptions, planar, preset
from microslip.cli.main import main


def test_planar_json(capsys, tmp_path):
    png = tmp_path / "p.png"
    code = main(["planar", "--ratio", "2", "--phase", "90", "--centre-reading", "paper",
                 "--increments", "200", "--samples-per-cycle", "256", "--json",
                 "--plot", str(png)])
    out, err = capsys.readouterr()
    assert code == 0 and png.stat().st_size > 0
    d = json.loads(out)
    # the paper's Table 2 zones are squat (L/t 2 and 1): said on stderr and in the JSON
    assert err.splitlines() == [f"warning: {w}" for w in d["warnings"]]
    assert any("tip model: the clamped zone is squat" in w for w in d["warnings"])
    assert (d["tip_amplitude_N"], d["centre_amplitude_N"], d["ratio"]) == (4000.0, 4000.0, 2.0)
    assert d["eccentricity"] == pytest.approx(math.sqrt(3) / 2)
    for key in ("dissipated_energy_Nmm", "paper_dissipated_energy_Nmm", "paper_loss_factor",
                "work_dissipated_energy_Nmm", "work_loss_factor", "tip_share_of_dissipation",
                "centre_share_of_dissipation"):
        assert isinstance(d[key], float) and d[key] > 0, key
    ref = planar.planar_damping(preset("table2-tip"), preset("table2-centre"), 4000.0, 4000.0,
                                increments=200, options=ModelOptions(centre="paper"),
                                phase_deg=90.0, samples_per_cycle=256)
    assert d["work_loss_factor"] == ref.work_loss_factor
    assert d["paper_loss_factor"] == ref.paper.loss_factor


@pytest.mark.parametrize("argv, message", [
    (["--ratio", "2", "--tip-amplitude", "100"], "either --ratio"),
    (["--tip-amplitude", "100"], "give --tip-amplitude N and --centre-amplitude N"),
    (["--ratio", "0.25"], "macroslip limit of the centre model"),
    (["--ratio", "-1"], "R must be finite and > 0"),
    (["--ratio", "1.7", "--levels", "top"], "not a ratio of two whole levels"),
])
def test_planar_mistakes_are_one_line(capsys, argv, message):
    code = main(["planar", "--increments", "50", *argv])
    out, err = capsys.readouterr()
    assert code == 1 and out == ""
    assert message in err and len(err.strip().splitlines()) == 1


def test_planar_text_states_units(capsys):
    code = main(["planar", "--tip-amplitude", "3000", "--centre-amplitude", "5000",
                 "--increments", "100", "--samples-per-cycle", "128"])
    out, _ = capsys.readouterr()
    assert code == 0
    assert re.search(r"W_d \(N·mm\)", out) and "R = 1.2" in out


# --- custom geometry everywhere --------------------------------------------------------------

def test_planar_clamp_flags_change_the_zones(capsys):
    base = run(capsys, "planar", "--ratio", "1", "--increments", "100", "--json")
    longer = run(capsys, "planar", "--ratio", "1", "--increments", "100", "--json",
                 "--length", "100")
    a, b = (json.loads(r[1]) for r in (base, longer))
    assert "tip_params" not in a
    assert b["tip_params"]["length"] == b["centre_params"]["length"] == 100.0
    # Table 2's reading (interpretation.md §6): the tip zone is half the contact width
    assert b["tip_params"]["width"] == 25.0 and b["centre_params"]["width"] == 50.0
    assert b["tip_params"]["thickness"] == b["centre_params"]["thickness"] == 10.0
    # the rigid-foundation d0 ~ F0^2 / (E A q) with q = mu F_N / L: proportional to L
    ratio = b["tip"]["peak_displacement_mm"] / a["tip"]["peak_displacement_mm"]
    assert ratio == pytest.approx(2.0, rel=0.05)
