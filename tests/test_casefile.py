"""Case files (microslip.case): the template round trip, validation, presets, unit warnings."""

from __future__ import annotations

import math
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from microslip import preset
from microslip.case import (
    DEFAULT_AMPLITUDE_FRACTION,
    KEYS,
    load_case,
    parse_case,
    plausibility_warnings,
    template,
)
from microslip.case.schema import TABLE_KEYS
from microslip.errors import ParameterError
from microslip.fe.calculix.case import DEFAULT_STICK_SLOPE

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

TITANIUM = {
    "name": "titanium clamp",
    "geometry": {"length": 30, "width": 12, "thickness": 8},
    "material": {"modulus": 114000, "poisson_ratio": 0.34},
    "contact": {"friction": 0.5},
    "clamping": {"normal_force": 12000},
}


def test_template_names_every_key_with_unit_range_and_default():
    text = template()
    for key in KEYS:
        if key.dotted in TABLE_KEYS:  # an assembly's tables: their keys, after [mesh]'s
            assert f"#   [[{key.dotted}]]: {key.meaning}" in text
            for f in TABLE_KEYS[key.dotted]:
                assert f"#     {f.name} (" in text
            continue
        line = next(i for i, s in enumerate(text.splitlines())
                    if s.lstrip("# ").startswith(f"{key.name} ="))
        doc = text.splitlines()[line - 1]
        assert key.range in doc and "default:" in doc
        if key.unit:
            assert key.unit in doc


def test_template_parses_back_to_the_documented_defaults():
    case = parse_case(tomllib.loads(template()))
    assert case.params is not None
    assert case.params.as_dict() == preset("table1").as_dict()
    assert case.get("load.amplitude_fraction") == DEFAULT_AMPLITUDE_FRACTION == 0.5
    assert case.get("contact.stick_slope") == DEFAULT_STICK_SLOPE
    assert case.get("clamping.pressure") == "uniform"
    assert case.get("load.model") == "tip"
    assert case.get("load.planar.phase_deg") == 90.0  # the planar load that planar runs
    assert case.get("load.amplitude") is None
    # the keys it sets: the preset (and the clamp the preset supplies) and the planar load
    assert set(case.values) == {"preset", "geometry.length", "geometry.width",
                                "geometry.thickness", "material.modulus",
                                "material.poisson_ratio", "contact.friction",
                                "clamping.normal_force", "load.planar.tip_amplitude",
                                "load.planar.centre_amplitude", "load.planar.phase_deg"}


def test_template_examples_uncommented_parse_to_the_same_case():
    names = {k.name for k in KEYS}
    lines = []
    for s in template().splitlines():
        key, _, value = s.removeprefix("# ").partition(" = ")
        lines.append(f"{key} = {value}" if key in names and value.strip() else s)
    case = parse_case(tomllib.loads("\n".join(lines)))
    for key in KEYS:
        assert case.get(key.dotted) == parse_case(tomllib.loads(template())).get(key.dotted)
    assert "contact.stick_slope" in case.values and "load.amplitude" not in case.values


def test_default_amplitude_is_half_the_slip_limit_of_the_clamp():
    case = parse_case(TITANIUM)
    assert case.amplitude() == 0.5 * 0.5 * 12000.0
    assert case.amplitude(friction=0.4) == 0.5 * 0.4 * 12000.0
    assert parse_case({**TITANIUM, "load": {"amplitude": 3600}}).amplitude() == 3600.0
    assert parse_case({**TITANIUM, "load": {"amplitude_fraction": 0.25}}).amplitude() == 1500.0
    assert parse_case({}).amplitude() is None


def test_preset_is_a_base_the_file_overrides():
    case = parse_case({"preset": "table2-tip", "contact": {"friction": 0.3},
                       "geometry": {"length": 40.0}})
    assert case.params is not None
    assert case.params.as_dict() == preset("table2-tip").replace(
        friction=0.3, length=40.0).as_dict()


@pytest.mark.parametrize("table, words", [
    ({"geometry": {"lenght": 30}}, ["geometry.lenght", "geometry.length"]),
    ({"geometri": {"length": 30}}, ["[geometri]", "geometry"]),
    ({"friction": 0.5}, ["friction", "contact.friction"]),
    ({"load": {"amplitud": 3}}, ["load.amplitud", "load.amplitude"]),
    ({"load": {"planar": {"phase": 90}}}, ["load.planar.phase", "load.planar.phase_deg"]),
])
def test_unknown_keys_name_the_key_and_the_nearest_valid_one(table, words):
    with pytest.raises(ParameterError) as err:
        parse_case(table, "c.toml")
    message = str(err.value)
    assert "\n" not in message and message.startswith("case c.toml: ")
    for word in words:
        assert word in message


@pytest.mark.parametrize("table, words", [
    ({"geometry": {"length": -3}}, ["geometry.length", "> 0", "mm", "-3"]),
    ({"geometry": {"length": "30"}}, ["geometry.length", "number"]),
    ({"geometry": {"length": True}}, ["geometry.length", "number"]),
    ({"material": {"poisson_ratio": 0.5}}, ["material.poisson_ratio", "[0, 0.5)"]),
    ({"load": {"amplitude_fraction": 1.2}}, ["amplitude_fraction", "(0, 1)"]),
    ({"load": {"model": "planar"}}, ["load.model", "tip, centre"]),
    ({"load": {"amplitude": 3, "amplitude_fraction": 0.5}}, ["exclude"]),
    ({"clamping": {"pressure": "power:"}}, ["clamping.pressure", "power:N[:EDGE]"]),
    ({"clamping": {"pressure": "cosine"}}, ["clamping.pressure", "uniform"]),
    ({"preset": "table9"}, ["preset", "table1"]),
    ({"contact": {"friction": 0.5}}, ["not", "geometry.length", "preset"]),
    ({**TITANIUM, "clamping": {"normal_force": -5}}, ["normal_force", "> 0"]),
])
def test_bad_values_are_one_line_with_the_range(table, words):
    with pytest.raises(ParameterError) as err:
        parse_case(table)
    assert "\n" not in str(err.value)
    for word in words:
        assert word in str(err.value)


@pytest.mark.parametrize("values, words", [
    ({"modulus": 2.1e11}, ["modulus", "pascals"]),
    ({"modulus": 114.0 / 1000}, ["modulus", "GPa"]),
    ({"length": 0.03}, ["length", "metres"]),
    ({"thickness": 8000.0 * 1000}, ["thickness", "micrometres"]),
    ({"friction": 2.5}, ["friction", "above 2"]),
])
def test_implausible_units_warn(values, words):
    (line,) = plausibility_warnings(values)
    for word in words:
        assert word in line


def test_plausible_values_do_not_warn_and_bad_force_is_an_error():
    assert plausibility_warnings({"modulus": 1e2, "length": 0.05, "width": 1e4,
                                  "friction": 2.0, "normal_force": 1e-3}) == []
    with pytest.raises(ParameterError, match="normal_force"):
        plausibility_warnings({"normal_force": 0.0})


def test_a_case_in_metres_carries_warnings_and_in_pascals_is_an_error():
    table = {**TITANIUM, "geometry": {"length": 0.03, "width": 0.012, "thickness": 0.008}}
    case = parse_case(table, "si.toml")
    assert len(case.warnings) == 3
    assert all(w.startswith("case si.toml: ") for w in case.warnings)
    table["material"] = {"modulus": 114e9, "poisson_ratio": 0.34}
    with pytest.raises(ParameterError, match=r"^case si.toml: material.modulus 1.14e\+11 MPa "
                       r"is above 1e\+09 MPa, far stiffer than any solid: pascals given as MPa"):
        parse_case(table, "si.toml")


@given(st.floats(1e-6, 1e12), st.floats(1e-6, 1e12))
def test_warnings_exactly_outside_the_bands(length, modulus):
    lines = plausibility_warnings({"length": length, "modulus": modulus})
    expected = (not 0.05 <= length <= 1e4) + (not 1e2 <= modulus <= 1e7)
    assert len(lines) == expected


def test_case_is_immutable():
    case = parse_case(TITANIUM)
    with pytest.raises(AttributeError):
        case.source = "x"  # type: ignore[misc]
    with pytest.raises(TypeError):
        case.values["contact.friction"] = 1.0  # type: ignore[index]
    assert "Case(" in repr(case)


def test_load_case_errors_are_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[geometry\nlength = 3\n")
    binary = tmp_path / "bin.toml"
    binary.write_bytes(b"\xff\xfe\x00")
    for path, word in ((bad, "not valid TOML"), (binary, "UTF-8"),
                       (tmp_path / "missing.toml", "cannot read"), (tmp_path, "cannot read")):
        with pytest.raises(ParameterError) as err:
            load_case(path)
        assert word in str(err.value) and str(path) in str(err.value)


def test_load_case_reads_a_file(tmp_path):
    path = tmp_path / "ti.toml"
    path.write_text('[geometry]\nlength = 30\nwidth = 12\nthickness = 8\n'
                    '[material]\nmodulus = 114000\npoisson_ratio = 0.34\n'
                    '[contact]\nfriction = 0.5\n[clamping]\nnormal_force = 12000\n'
                    '[load.planar]\nphase_deg = 90\n')
    case = load_case(path)
    assert case.source == str(path)
    assert case.params is not None and case.params.macroslip_force == 6000.0
    assert case.get("load.planar.phase_deg") == 90.0
    assert math.isclose(case.amplitude() or 0.0, 3000.0)
