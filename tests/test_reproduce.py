"""``microslip reproduce``: files, CSV contents, claims agree with CSVs."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import pytest

from microslip import planar, reproduce
from microslip.cli.main import main
from microslip.errors import MicroslipError
from microslip.planar import PAPER_RATIOS
from microslip.reproduce import job as reproduce_job
from microslip.reproduce.report import _claim_short

FILES = ("fig01_trajectories.png", "fig10_loops_R_ge_1.png", "fig11_loops_R_le_1.png",
         "fig12_loss_factor_vs_R.png", "fig01_trajectories.csv", "fig10_loops_R_ge_1.csv",
         "fig11_loops_R_le_1.csv", "loss_factor_vs_R.csv", "stiffness_vs_amplitude.csv",
         "loss_factor_vs_R_readings.csv", "report.md")


@pytest.fixture(scope="module")
def job(tmp_path_factory):
    out = tmp_path_factory.mktemp("reproduce")
    code = main(["reproduce", "--out", str(out), "--no-fe", "--quiet"])
    return code, out


@pytest.mark.slow
def test_writes_every_file(job):
    code, out = job
    assert code == 0
    for name in FILES:
        assert (out / name).stat().st_size > 0, name
    assert not (out / "fig09_fe_vs_model.png").exists()
    assert not list(out.glob(".*"))  # no temporary files left behind


@pytest.mark.slow
def test_loss_factor_table_has_the_seven_ratios(job):
    _, out = job
    t = reproduce.read_csv(out / "loss_factor_vs_R.csv")
    assert sorted(t["R"]) == pytest.approx(sorted(PAPER_RATIOS), rel=1e-15)
    for r, e in zip(t["R"], t["eccentricity"], strict=True):
        assert e == pytest.approx(planar.eccentricity(r), rel=1e-15)
    for col in ("paper_loss_factor", "paper_normalised_loss_factor", "work_loss_factor",
                "work_normalised_loss_factor"):
        assert all(math.isfinite(x) and x > 0 for x in t[col]), col
    i1 = t["R"].index(1.0)
    assert t["paper_normalised_loss_factor"][i1] == 1.0
    # the work per cycle does not depend on the phase for the decoupled models
    for w0, w90 in zip(t["work_dissipated_energy_Nmm"], t["work_dissipated_energy_phase90_Nmm"],
                       strict=True):
        assert w90 == pytest.approx(w0, rel=1e-9)


@pytest.mark.slow
def test_report_verdicts_agree_with_the_csv_files(job):
    _, out = job
    comp = reproduce.read_csv(out / "stiffness_vs_amplitude.csv")
    table = reproduce.read_csv(out / "loss_factor_vs_R.csv")
    claims = reproduce.check_claims(comp, table)
    text = (out / "report.md").read_text(encoding="utf-8")
    summary = next(line for line in text.splitlines() if line.startswith("Summary: "))
    for c in claims:
        assert c.verdict in reproduce.VERDICTS
        assert f"{_claim_short(c.key)}: {c.verdict}" in summary
        assert c.evidence in text
    # and independently of check_claims: where is eta lowest, where highest?
    for coupling in ("paper", "work"):
        eta = table[f"{coupling}_loss_factor"]
        order = sorted(range(len(eta)), key=eta.__getitem__)
        holds = (table["R"][order[0]] == 1.0
                 and {round(table["R"][i], 9) for i in order[-2:]} == {0.25, 4.0})
        claim = next(c for c in claims if c.key == f"eta-extremes-{coupling}")
        assert claim.verdict == ("confirmed" if holds else "not confirmed")
    soft = next(c for c in claims if c.key == "softening")
    falls = all(
        a > b for m in ("tip", "centre")
        for a, b in zip(*(lambda k: (k[:-1], k[1:]))(
            [k for mm, k in zip(comp["model"], comp["secant_stiffness_N_per_mm"], strict=True)
             if mm == m]), strict=True))
    assert soft.verdict == ("confirmed" if falls else "not confirmed")
    assert "skipped" in text and "--no-fe" in text


@pytest.mark.slow
def test_loops_csv_holds_the_plotted_loops(job):
    _, out = job
    loops = reproduce.read_csv(out / "fig10_loops_R_ge_1.csv")
    assert set(loops["curve"]) == {"tip", "centre", "resultant"}
    assert sorted(set(loops["R"])) == [1.0, 2.0, 3.0, 4.0]
    tip4 = [f for r, c, f in zip(loops["R"], loops["curve"], loops["force_N"], strict=True)
            if r == 4.0 and c == "tip"]
    assert max(tip4) == pytest.approx(8000.0) and len(tip4) == 2001


def _table(etas):
    """A loss-factor table with the given eta at the paper's R (both couplings)."""
    n = len(PAPER_RATIOS)
    return {"R": list(PAPER_RATIOS), "paper_loss_factor": etas, "work_loss_factor": etas,
            "tip_secant_stiffness_N_per_mm": [1.0] * n,
            "centre_secant_stiffness_N_per_mm": [2.0] * n}


COMP = {"model": ["tip", "tip", "centre", "centre"], "level": [1, 2, 1, 2],
        "amplitude_N": [1.0, 2.0, 1.0, 2.0], "secant_stiffness_N_per_mm": [4.0, 2.0, 8.0, 3.0],
        "loss_factor": [0.2, 0.21, 0.2, 0.2]}


def test_claims_follow_the_numbers_not_the_paper():
    # R order: 1, 2, 3, 4, 1/2, 1/3, 1/4
    paper_shape = [0.1, 0.2, 0.3, 0.5, 0.2, 0.3, 0.4]
    verdicts = {c.key: c.verdict for c in reproduce.check_claims(COMP, _table(paper_shape))}
    assert verdicts["eta-extremes-paper"] == "confirmed"
    assert verdicts["softening"] == "confirmed" and verdicts["centre-stiffer"] == "confirmed"
    flat = reproduce.check_claims(COMP, _table([0.25] * 7))
    assert {c.key: c.verdict for c in flat}["eta-extremes-work"] == "not confirmed"
    missing = [0.1, 0.2, 0.3, 0.5, 0.2, 0.3, math.nan]
    assert reproduce.check_claims(COMP, _table(missing))[2].verdict == "cannot be checked"
    stiff = dict(COMP, secant_stiffness_N_per_mm=[2.0, 4.0, 8.0, 3.0])
    assert reproduce.check_claims(stiff, _table(paper_shape))[0].verdict == "not confirmed"
    weak = dict(_table(paper_shape), centre_secant_stiffness_N_per_mm=[0.5] * 7)
    assert reproduce.check_claims(COMP, weak)[1].verdict == "not confirmed"


def _fake_validation(fail: bool = False):
    def run_validation(out_dir, meshes=("coarse",), models=("tip", "centre"), *,
                       progress=True, timeout=None, scheduler=None):
        if fail:
            raise MicroslipError("ccx failed: no convergence")
        p = Path(out_dir) / "fig09_fe_vs_model.png"
        p.write_bytes(b"png")
        csv = Path(out_dir) / "validation.csv"
        csv.write_text("case,mesh,converged,err_peak_model_fe,err_wd_model_fe,tolerance_peak,"
                       "tolerance_wd\ntip,coarse,True,0.001,0.03,0.01,0.02\n", encoding="utf-8")
        row = {"case": "tip", "mesh": "coarse", "converged": True, "err_peak_model_fe": 0.001,
               "err_wd_model_fe": 0.03, "tolerance_peak": 0.01, "tolerance_wd": 0.02}
        return SimpleNamespace(files=(p, csv), rows=(row,),
                               summary_markdown="| FE | ok |\n|---|---|")
    return run_validation


def _small_coupling_sweep(monkeypatch):
    """The coupled-friction, Table 2 FE and joint-against-FE steps on tiny meshes (their own
    tests: test_reproduce_coupling.py, test_reproduce_table2_fe.py,
    test_reproduce_joint_fe.py)."""
    import microslip.fe.builtin as solver
    import microslip.reproduce.joint_fe as joint_fe
    import microslip.reproduce.table2_fe as table2_fe

    monkeypatch.setattr(table2_fe, "TABLE2_FE_MESH", "tiny")
    monkeypatch.setattr(joint_fe, "JOINT_FE_MESH", (8, 2, 1))
    real = solver.coupling_sweep
    monkeypatch.setattr(solver, "coupling_sweep", lambda params, ratios, phases: real(
        params, ratios[:2], phases, mesh="tiny", cycles=2, increments_per_cycle=16))


@pytest.mark.slow
def test_fe_part_uses_the_validation_when_present(tmp_path, monkeypatch, capsys):
    _small_coupling_sweep(monkeypatch)
    monkeypatch.setattr(reproduce_job, "_fe_module", lambda: (_fake_validation(), ""))
    code = main(["reproduce", "--out", str(tmp_path / "a"), "--fe", "--quiet",
                 "--increments", "20", "--no-structure-study"])
    assert code == 0
    text = (tmp_path / "a" / "report.md").read_text(encoding="utf-8")
    assert "| FE | ok |" in text and "fig09_fe_vs_model.png" in text
    # W_d differs by 3 % against a 2 % tolerance: the FE claim is judged from validation.csv
    assert "models agree with FE: not confirmed" in text
    assert "coupling_ratio_vs_R.csv" in text and (tmp_path / "a" / "coupling_ratio_vs_R.csv"
                                                   ).is_file()
    assert "joint2d_vs_fe.csv" in text and (tmp_path / "a" / "fig13_joint2d_vs_fe.png").is_file()
    monkeypatch.setattr(reproduce_job, "_fe_module", lambda: (_fake_validation(fail=True), ""))
    code = main(["reproduce", "--out", str(tmp_path / "b"), "--quiet", "--increments", "20",
                 "--no-structure-study"])
    _, err = capsys.readouterr()
    assert code == 1 and "ccx failed" in err
    assert "Not run (failed): ccx failed" in (tmp_path / "b" / "report.md").read_text("utf-8")




def test_out_must_be_a_directory(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x", encoding="utf-8")
    code = main(["reproduce", "--out", str(f), "--no-fe", "--quiet"])
    _, err = capsys.readouterr()
    assert code == 1 and "--out must be a directory" in err
