"""One case file describes one clamp for every command: a section a command does not read is
ignored with one note on stderr; only unknown or misspelled keys are errors. The template of
``microslip case new`` runs on every command that takes ``--case``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from microslip import preset
from microslip.cli.main import main

ONE_MODE = ("--frequency", "100", "--modal-mass", "0.5", "--joint", "jenkins",
            "--joint-stiffness", "1000", "--slip-force", "5")


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def template(tmp_path, monkeypatch, capsys):
    """``microslip case new c.toml`` in a fresh directory."""
    monkeypatch.chdir(tmp_path)
    assert main(["case", "new", "c.toml"]) == 0
    capsys.readouterr()
    return tmp_path / "c.toml"


def test_modal_ignores_the_load_case_of_a_case_file(capsys, template):
    text = template.read_text().replace("# amplitude = \n", "amplitude = 100.0\n")
    assert "\namplitude = 100.0\n" in text
    template.write_text(text)
    code, out, err = run(capsys, "modal", "--case", template.name, *ONE_MODE,
                         "--amplitude-range", "0.001", "1", "--amplitudes", "3", "--json")
    assert code == 0, err
    assert err == "case: [load], [load.planar] not read by modal\n"
    code, plain, err = run(capsys, "modal", *ONE_MODE, "--amplitude-range", "0.001", "1",
                           "--amplitudes", "3", "--json")
    assert code == 0, err
    with_case = json.loads(out)
    assert with_case.pop("case_file") == template.name
    assert with_case == json.loads(plain)


def test_a_misspelled_key_is_still_an_error(capsys, template):
    template.write_text(template.read_text() + "\n[load]\namplitud = 3\n")
    code, out, err = run(capsys, "modal", "--case", template.name, *ONE_MODE)
    assert code == 1 and out == "" and err.count("\n") == 1
    template.write_text(template.read_text().replace("\n[load]\namplitud = 3\n", "")
                        .replace('# model = "tip"', 'modle = "tip"'))
    code, out, err = run(capsys, "modal", "--case", template.name, *ONE_MODE)
    assert code == 1 and out == "" and "unknown case key load.modle" in err
    assert "did you mean load.model?" in err


def test_a_key_the_command_lacks_in_a_read_section_is_named(capsys, template):
    text = template.read_text().replace('# pressure = "uniform"', 'pressure = "parabolic"')
    template.write_text(text)
    code, _, err = run(capsys, "modal", "--case", template.name, *ONE_MODE,
                       "--amplitude-range", "0.001", "1", "--amplitudes", "3")
    assert code == 0, err
    assert err == "case: clamping.pressure, [load.planar] not read by modal\n"


def test_loop_notes_the_planar_load_it_does_not_read(capsys, template):
    code, out, err = run(capsys, "loop", "--case", template.name, "--model", "tip",
                         "--increments", "100", "--json")
    assert code == 0 and err == "case: [load.planar] not read by loop\n"
    assert json.loads(out)["amplitude_N"] == 178.0  # 0.5 mu F_N of table1


def test_planar_runs_on_the_template_the_circular_case(capsys, template):
    code, out, err = run(capsys, "planar", "--case", template.name, "--increments", "200",
                         "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["ratio"] == pytest.approx(1.0, abs=1e-12)
    assert data["phase_deg"] == 90.0
    # R = 1 at 90 degrees is the circle: eccentricity 0
    assert data["eccentricity"] == pytest.approx(0.0, abs=1e-12)
    assert data["tip_amplitude_N"] == 100.0 and data["centre_amplitude_N"] == 200.0
    assert data["centre_params"] == preset("table1").as_dict()  # the template's clamp
    assert np.isfinite(data["work_dissipated_energy_Nmm"])
    assert data["work_dissipated_energy_Nmm"] > 0
