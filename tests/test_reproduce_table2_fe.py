"""The Table 2 zones in the built-in FE solver beside the 1-D models (reproduce step)."""

from __future__ import annotations

import math

import pytest

from microslip import ModelOptions, damping, macroslip_force, preset
from microslip.planar import CENTRE_LEVEL_FORCE, TIP_LEVEL_FORCE
from microslip.reproduce.report import _table2_fe_section
from microslip.reproduce.table2_fe import table2_fe_table


@pytest.fixture(scope="module")
def cols():
    return table2_fe_table(mesh="tiny", increments=200)


def test_every_level_below_macroslip_is_run(cols):
    expected = [("tip", lv) for lv in (1, 2, 3, 4)
                if lv * TIP_LEVEL_FORCE < macroslip_force("tip", preset("table2-tip"))]
    expected += [("centre", lv) for lv in (1, 2, 3, 4)
                 if lv * CENTRE_LEVEL_FORCE < macroslip_force("centre", preset("table2-centre"))]
    assert list(zip(cols["model"], cols["level"], strict=True)) == expected
    assert ("centre", 4) not in expected  # 16000 N is mu F_N: gross sliding


def test_columns_are_what_they_say(cols):
    for i, model in enumerate(cols["model"]):
        p = preset(f"table2-{model}")
        a = cols["amplitude_N"][i]
        rigid = damping(model, p, a, 200, ModelOptions()).dissipated_energy
        assert cols["rigid_dissipated_energy_Nmm"][i] == rigid
        w = cols["fe_dissipated_energy_Nmm"][i]
        assert w >= 0 and cols["fe_converged"][i] is True
        if w == 0:  # the FE sticks throughout (tiny mesh, low level): no ratio
            assert math.isnan(cols["rigid_over_fe"][i])
            assert "W_d = 0" in cols["fe_message"][i] or "stick" in cols["fe_message"][i]
            continue
        assert cols["rigid_over_fe"][i] == pytest.approx(rigid / w, rel=1e-15)
        assert cols["layer_over_fe"][i] == pytest.approx(
            cols["layer_dissipated_energy_Nmm"][i] / w, rel=1e-15)
        # the layer is softer than the rigid foundation: it slips later and dissipates less
        assert cols["layer_dissipated_energy_Nmm"][i] < rigid


def test_report_states_the_range_of_the_ratios(cols):
    text = _table2_fe_section(cols)
    ratios = [r for r in cols["rigid_over_fe"] if math.isfinite(r)]
    assert f"{min(ratios):.3g} to {max(ratios):.3g} times the FE's W_d" in text
    assert text.count("\n| ") == len(cols["model"]) + 1
