"""Ranges a user can trust (issue 34 item 2): the automatic amplitude grid of ``modal --mesh``
stops at a stated fraction of the part's size or, with a yield strength, where the studied
mode's stress reaches it; a result past the limit or with a damping ratio above 10 % says
so. The part is a new user's: a steel plate 100 x 25 x 4 mm on a washer
(tests/data/meshes/plate.msh, from make_plate_modal.py), whose first mode's grid ran to 54 mm
at the tip before."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from microslip.cli.main import main
from microslip.fe.clamp import MeshClamp
from microslip.meshdynamics.case import StructureCase, prepare_structure
from microslip.meshdynamics.limits import (
    RESULT_MARGIN,
    SIZE_FRACTION,
    GridLimit,
    mode_stress,
    result_warnings,
)
from microslip.meshdynamics.modalstudy import ModalSettings, prepare_modal, run_solvers

ROOT = Path(__file__).resolve().parents[1]
PLATE = ROOT / "tests" / "data" / "meshes" / "plate.msh"
CANTILEVER = ROOT / "examples" / "cantilever.inp"
STEEL = MeshClamp("contact", "washer", normal_force=8000.0, modulus=210000.0,
                  poisson_ratio=0.3, friction=0.5, stick_slope=1e4)
PLATE_CLI = ["--mesh", str(PLATE), "--contact-set", "contact", "--clamp-set", "washer",
             "--normal-force", "8000", "--modulus", "210000", "--poisson-ratio", "0.3",
             "--friction", "0.5", "--density", "7850", "--response-set", "response"]


def plate(mode: int = 1, **kw: float) -> StructureCase:
    return StructureCase(str(PLATE), STEEL, density=7850.0, mode=mode, response_set="response",
                         **kw)


def test_mode_stress_is_the_beam_s_root_stress_at_the_surface() -> None:
    """The cantilever's first mode (101.6 mm overhang, 6.35 mm thick): beam theory's root
    stress per mm of tip deflection is E (t/2) (1.8751 / L)^2 = 75.7 MPa; the recovery at the
    elements' nodes gives 80 (the clamp edge concentrates it). At the Gauss points (inside
    the two elements through the thickness) it would be 55: 27 % low, a yield limit 37 %
    too high."""
    clamp = MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
                      poisson_ratio=0.33, friction=0.5, stick_slope=1e4)
    p = prepare_structure(StructureCase(str(CANTILEVER), clamp, density=2700.0, mode=1,
                                        response_set="response"))
    per_mm = mode_stress(p.model, p.stuck.shapes[0]) / float(
        np.linalg.norm(p.stuck.response_motion[0]))
    beam = 70000.0 * 6.35 / 2 * (1.8751 / 101.6) ** 2
    assert beam <= per_mm <= 1.1 * beam


@pytest.mark.slow
def test_the_plate_s_first_mode_stops_at_a_hundredth_of_its_length() -> None:
    """Before, the grid of mode 1 ran from first slip to 54 mm at the tip of the 4 mm plate;
    now it stops at 1 mm (1 % of 100 mm), says so, and the JSON gives the limit."""
    study = prepare_modal(plate(1), ModalSettings(amplitudes=3))
    lim = study.limit
    assert lim is not None and lim.size_mm == pytest.approx(100.0)
    assert lim.limit_mm == pytest.approx(SIZE_FRACTION * 100.0)
    assert study.amplitudes[-1] == pytest.approx(1.0)
    assert study.amplitudes[0] < 0.1  # still from first slip
    assert len(study.notes) == 1 and "stops at a = 1 mm" in study.notes[0]
    assert "near gross sliding" in study.notes[0]


@pytest.mark.slow
def test_a_yield_strength_stops_the_grid_where_the_mode_s_stress_reaches_it() -> None:
    """With 100 MPa the elastic limit comes first: the top is where the stuck mode's peak
    von Mises stress is 100 MPa, checked against the stress of the mode scaled to it."""
    study = prepare_modal(plate(1, yield_strength=100.0), ModalSettings(amplitudes=2))
    lim = study.limit
    assert lim is not None and lim.yield_limit_mm is not None
    assert lim.limit_mm == lim.yield_limit_mm < lim.size_limit_mm
    p = study.prepared
    r = float(np.linalg.norm(p.stuck.response_motion[0]))
    stress = mode_stress(p.model, p.stuck.shapes[0] * study.amplitudes[-1] / r)
    assert stress == pytest.approx(100.0, rel=1e-9)
    assert "yield strength 100 MPa" in lim.reason and "yield" in study.notes[0]


def test_result_warnings_name_the_amplitudes_past_the_limit_and_a_damping_above_10_percent(
        ) -> None:
    lim = GridLimit(size_mm=100.0, size_limit_mm=1.0)
    assert result_warnings(lim, [0.1, 0.5, RESULT_MARGIN * 0.999], [0.01, 0.05, 0.099]) == []
    w = result_warnings(lim, [0.1, None, 3.0], [0.02, None, 0.176])
    assert len(w) == 2
    assert w[0].startswith("1 amplitude(s) up to a = 3 mm pass the limit of 1 mm")
    assert "small rotations" in w[0]
    assert "17.6 %" in w[1] and "above 10 %" in w[1] and "gross sliding" in w[1]
    assert "no bolt shank" in w[1]
    assert "bolt shank(s) hold" in result_warnings(lim, [0.5], [0.2], shanks=1)[0]


def test_a_range_past_the_limit_is_warned_in_the_json(
        capsys: pytest.CaptureFixture[str]) -> None:
    """--amplitude-range given past the limit: run as asked, each result past it named."""
    code = main(["modal", *PLATE_CLI, "--mode", "1", "--amplitudes", "2",
                 "--amplitude-range", "0.5", "3", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["amplitude_limit"]["limit_mm"] == pytest.approx(1.0)
    assert any("pass the limit of 1 mm" in w for w in out["warnings"])
    assert out["model"]["sets"]["washer"]["area_mm2"] > 0


@pytest.mark.slow
def test_yield_strength_is_a_mesh_option_and_a_case_key(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]
                                                        ) -> None:
    assert main(["modal", "--frequency", "100", "--modal-mass", "1", "--joint", "jenkins",
                 "--joint-stiffness", "1e4", "--slip-force", "1", "--yield-strength",
                 "300"]) == 1
    assert "--yield-strength applies to modal --mesh FILE only" in capsys.readouterr().err
    (tmp_path / "case.toml").write_text(
        f'[material]\nmodulus = 210000\npoisson_ratio = 0.3\nyield_strength = 100\n'
        f'[contact]\nfriction = 0.5\n[clamping]\nnormal_force = 8000\n'
        f'[mesh]\nfile = "{PLATE}"\ncontact_set = "contact"\nclamp_set = "washer"\n'
        f'density = 7850\nresponse_set = "response"\n')
    assert main(["modal", "--case", str(tmp_path / "case.toml"), "--amplitudes", "2",
                 "--json"]) == 0
    lim = json.loads(capsys.readouterr().out)["amplitude_limit"]
    assert lim["yield_strength_MPa"] == 100.0 and lim["limit_mm"] == lim["yield_limit_mm"]


def test_the_fe_curve_carries_the_validity_warnings() -> None:
    """The whole chain on the plate's in-plane mode: a solver's JSON holds the limit's
    warnings next to its own (none past 10 % here)."""
    study = prepare_modal(plate(2), ModalSettings(amplitudes=2))
    curve = run_solvers(study, ("fe",))["fe"]
    from microslip.meshdynamics.modalstudy import study_output

    out = study_output(study, "fe", curve)
    assert out["amplitude_limit"]["size_mm"] == pytest.approx(100.0)
    assert max(z for z in out["damping_ratio"] if z is not None) < 0.10
    assert not any("above 10 %" in w for w in out["warnings"])


def test_a_forced_peak_damped_above_10_percent_is_warned() -> None:
    """frf's peak equivalent damping ratio zeta = F m_f r / (2 omega^2 a) above 10 %: the
    same validity warning as the modal curves'."""
    from types import SimpleNamespace

    from microslip.meshdynamics.frfstudy import curve_warnings, equivalent_damping

    f = np.array([90.0, 100.0, 110.0])
    study = SimpleNamespace(modal_force=1.0, response_motion=1.0,
                            case=SimpleNamespace(clamp=SimpleNamespace(shanks=())))
    omega = 2 * np.pi * 100.0

    def curve(zeta: float) -> SimpleNamespace:
        a = 1.0 / (2 * omega**2 * zeta)  # the peak that zeta gives at F = 1 N
        return SimpleNamespace(force=1.0, frequency=f, amplitude=0.5 * a + 0 * f,
                               peak_frequency=100.0,
                               peak_amplitude=a, success=True, message="")

    assert equivalent_damping(1.0, 1.0, 1.0, 100.0, curve(0.2).peak_amplitude) == (
        pytest.approx(0.2))
    assert curve_warnings([curve(0.05)], study) == []  # type: ignore[arg-type]
    (w,) = curve_warnings([curve(0.2)], study)  # type: ignore[arg-type]
    assert w.startswith("curve at 1 N: damping ratio up to 20 %") and "gross sliding" in w
