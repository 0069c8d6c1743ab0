"""CalculiX runs of the paper's validation (Table 1, 20x2x1 C3D20R mesh): the issue's tolerances
against the closed forms, loop closure, contact status, files, CLI, reuse and dask.

Each ccx case runs once per module (about 15 s each on two cores): the validation fixture
runs tip and centre; the CLI test runs centre once more through ``microslip fe``; the dask
test runs tip once more on a local cluster.
"""

from __future__ import annotations

import csv
import json
import shutil

import numpy as np
import pytest

from microslip import closedform as cf
from microslip import preset
from microslip.cli.main import main
from microslip.energy import damping_from_loop
from microslip.fe import FECase, ResultsError, read_results, run_case
from microslip.fe.calculix.boxrun import box20_mesh
from microslip.fe.calculix.mesh import mesh_spec
from microslip.fe.calculix.meshdeck import load_plan
from microslip.fe.meshload import MeshLoad
from microslip.validate import TOLERANCES, ValidationReport, run_validation

pytestmark = [
    pytest.mark.ccx,
    pytest.mark.slow,
    pytest.mark.skipif(shutil.which("ccx") is None,
                       reason="CalculiX (ccx) is not on PATH; run `bash scripts/setup.sh`"),
]

P = preset("table1")
EA, Q, F0 = P.axial_stiffness, P.friction_per_length, 267.0
EXACT = {
    "tip": (float(cf.tip_displacement(F0, EA, Q)), cf.tip_dissipated_energy(F0, EA, Q)),
    "centre": (float(cf.centre_displacement(F0, EA, Q)), cf.centre_dissipated_energy(F0, EA, Q)),
}


#: The CalculiX mesh of these tests: 20 x 2 x 1 C3D20R (1 076 DOF), the ``coarse`` level before
#: the levels became common to both solvers (``coarse`` is now 24 x 4 x 1, 2 322 DOF, about
#: four times slower in CalculiX; docs/validation.md).
SMALL = "20x2x1"


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> ValidationReport:
    return run_validation(tmp_path_factory.mktemp("validation"), (SMALL,), ("tip", "centre"),
                          progress=False)


@pytest.fixture(scope="module")
def results(report):
    return {r.load_case: r for r in report.results}


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_peak_and_dissipation_within_the_issue_tolerances(results, model):
    r = results[model]
    d0, wd = EXACT[model]
    assert abs(r.damping.peak_displacement / d0 - 1) <= TOLERANCES[model]["peak"]
    assert abs(r.damping.dissipated_energy / wd - 1) <= TOLERANCES[model]["wd"]
    # regression: measured 2026-11 with ccx 2.20 (docs/validation.md); the W_d deficit is
    # mostly the 40-sample trapezoidal rule (-0.41 %), the centre's d0 deficit is the 3-D
    # Poisson constraint at the loaded section. ccx repeats a run to about 1e-5 relative
    # (its printed displacements change in the 7th digit; see the dask test), hence 2e-5.
    expected = {"tip": (3.2552e-4, -6.2471e-3), "centre": (-5.3932e-3, -1.48269e-2)}[model]
    assert r.damping.peak_displacement / d0 - 1 == pytest.approx(expected[0], abs=2e-5)
    assert r.damping.dissipated_energy / wd - 1 == pytest.approx(expected[1], abs=2e-5)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_loop_closes_and_is_a_calculix_loop(results, model):
    r = results[model]
    assert abs(r.closure) <= 1e-3
    d = r.loop.displacement
    # Masing: the second half-cycle is the first one mirrored about the loop's centre
    np.testing.assert_allclose(d[20:] - r.offset, -(d[:21] - r.offset),
                               atol=2e-3 * r.peak_displacement)
    assert r.loop.source == "calculix" and r.loop.force[0] == r.loop.force[-1] == pytest.approx(F0)
    assert r.loop.force.size == 41 and r.converged and r.dof == 1076
    assert r.iterations.shape == (50,) and np.all(r.iterations >= 1)
    assert r.wall_s > 0
    # the FE loop goes through the same energy code as the analytical loops
    again = damping_from_loop(r.loop)
    assert again.dissipated_energy == r.damping.dissipated_energy
    assert r.damping.loss_factor == pytest.approx(4 / (3 * np.pi), rel=0.02)
    # first loading follows the virgin curve d = F^2 / c
    c = 2 * EA * Q if model == "tip" else 8 * EA * Q
    k = slice(3, 11)  # t = 0.075 .. 0.25 s
    np.testing.assert_allclose(r.displacement[k], r.force[k] ** 2 / c, rtol=0.02)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_slip_zones_follow_the_closed_form(results, model):
    """Fig. 8: slip zone F0/q from the tip (F0/(2q) each side of L/2) at the peaks, half of it
    slipping back when the force returns to zero; within one element (12.7 mm)."""
    r = results[model]
    per_domain = F0 / Q if model == "tip" else F0 / (2 * Q)
    for t, share in ((0.25, 1.0), (0.5, 0.5), (0.75, 1.0), (1.0, 0.5), (1.25, 1.0)):
        for length in r.slip_lengths(t).values():
            assert length == pytest.approx(share * per_domain, abs=12.7)
    # locked zone after the reversal: the far end never slips
    k = r.contact.index(0.5)
    x = r.contact.coords[:, 0]
    far = (x < 20.0) | ((x > P.length - 20.0) if model == "centre" else False)
    assert np.all(r.contact.status[k][far] == 1)


def test_files_and_table(report):
    assert report.passed
    names = sorted(f.name for f in report.files)
    assert names == ["fig08_contact_status.png", "fig09_fe_vs_model.png", "validation.csv"]
    assert all(f.stat().st_size > 1000 for f in report.files)
    with open(report.out_dir / "validation.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["case"], r["mesh"], r["verdict"]) for r in rows] == [
        ("tip", SMALL, "pass"), ("centre", SMALL, "pass")]
    for row, mem in zip(rows, report.rows, strict=True):
        assert float(row["err_wd_fe_closed"]) == mem["err_wd_fe_closed"]
        assert float(row["peak_closed_mm"]) == pytest.approx(EXACT[row["case"]][0], rel=1e-12)
        # the uncorrected model is the closed form; the default reading differs slightly
        assert float(row["peak_uncorrected_mm"]) == pytest.approx(
            float(row["peak_closed_mm"]), rel=1e-9)
        assert abs(float(row["err_peak_model_fe"])) < 0.02
    assert "| tip | 20x2x1 (20x2x1) | 1076 |" in report.summary_markdown
    assert "**tip**: pass" in report.summary_markdown
    assert "**centre**: pass" in report.summary_markdown


def test_vtu_export(results, tmp_path):
    meshio = pytest.importorskip("meshio")
    from microslip.fe import SOLVERS
    from microslip.fe.vtu import write_vtu_series

    r = results["tip"]
    files = write_vtu_series(r, SOLVERS["calculix"].fields(r), tmp_path)
    assert [f.name for f in files][-1] == "fe_tip.pvd" and len(files) == 52
    m = meshio.read(files[10])  # t = 0.25 s
    assert {"displacement", "contact_status", "contact_slip", "contact_pressure"} <= set(
        m.point_data)
    status = m.point_data["contact_status"]
    assert set(np.unique(status)) == {-1, 1, 2}
    plan = load_plan(box20_mesh(P, mesh_spec(SMALL, P)), [MeshLoad("tip", (1.0, 0.0, 0.0), F0)])
    u = plan.conjugate(m.point_data["displacement"][None, plan.loaded])[0, 0]
    assert u - r.details.clamp_displacement == pytest.approx(
        results["tip"].displacement[10], rel=1e-3)


def test_truncated_or_partial_results_are_errors(results, tmp_path):
    src = results["tip"].job_dir
    case = results["tip"].details.case
    cut = tmp_path / "frd"
    shutil.copytree(src, cut)
    text = (cut / "job.frd").read_text()
    (cut / "job.frd").write_text(text[: len(text) * 2 // 3])
    with pytest.raises(ResultsError, match="truncated"):
        read_results(case, cut)
    short = tmp_path / "dat"
    shutil.copytree(src, short)
    text = (short / "job.dat").read_text()
    (short / "job.dat").write_text(text[: text.rindex(" displacements")])
    with pytest.raises(ResultsError, match="stopped early"):
        read_results(case, short)


def test_reuse_reads_a_finished_run_without_the_solver(results, tmp_path, monkeypatch):
    job = tmp_path / "again"
    shutil.copytree(results["centre"].job_dir, job)
    monkeypatch.setenv("PATH", str(tmp_path))  # no ccx from here on
    r = run_case(FECase("centre", mesh=SMALL), job, reuse=True)
    np.testing.assert_array_equal(r.loop.displacement, results["centre"].loop.displacement)
    assert r.wall_s == pytest.approx(results["centre"].wall_s)
    # another deck (other stick slope) in the same directory is not reused
    with pytest.raises(Exception, match="not on PATH"):
        run_case(FECase("centre", mesh=SMALL, stick_slope=2e4), job, reuse=True)


def test_cli_fe_json_has_the_loop_keys(tmp_path, capsys):
    out = tmp_path / "centre"
    code = main(["fe", "--model", "centre", "--solver", "calculix", "--mesh", SMALL, "--out",
                 str(out), "--json"])
    text, err = capsys.readouterr()
    assert code == 0, err
    data = json.loads(text)
    assert main(["loop", "--model", "centre", "--json", "--increments", "50"]) == 0
    loop_keys = set(json.loads(capsys.readouterr()[0]))
    # the keys of `microslip loop --json` (but the 1-D model's contact and validity warnings),
    # plus FE ones
    assert loop_keys - {"contact", "warnings"} <= set(data)
    assert data["dof"] == 1076 and data["converged"] is True and data["wall_s"] > 0
    assert len(data["loop"]["force_N"]) == len(data["loop"]["displacement_mm"]) == 41
    d0, wd = EXACT["centre"]
    assert abs(data["peak_displacement_mm"] / d0 - 1) <= 0.02
    assert abs(data["dissipated_energy_Nmm"] / wd - 1) <= 0.03
    assert set(data["slip_length_by_domain_mm"]) == {"tension", "compression"}
    assert (out / "job.inp").is_file() and (out / "fe_centre.pvd").is_file()
    assert (out / "result.json").is_file()
    assert sum(1 for f in out.glob("fe_centre_*.vtu")) == 51


def test_cli_validate_reuses_finished_jobs(report, capsys, monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))  # nothing is solved again
    code = main(["validate", "--out", str(report.out_dir), "--mesh", SMALL, "--reuse",
                 "--no-progress"])
    text, err = capsys.readouterr()
    assert code == 0, err
    assert "**tip**: pass" in text and "wrote" in text


def test_dask_scheduler_gives_identical_results(report, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        remote = run_validation(tmp_path, (SMALL,), ("tip",), progress=False,
                                scheduler=cluster.scheduler_address)
    local = next(r for r in report.results if r.load_case == "tip")
    # ccx 2.20 itself is not bit-reproducible from run to run (the 7th printed digit of a
    # displacement can change between two runs of one deck on one machine), so "identical"
    # means identical to the solver's round-off
    np.testing.assert_allclose(remote.results[0].loop.displacement, local.loop.displacement,
                               rtol=1e-5, atol=1e-11)
    assert remote.rows[0]["wd_fe_Nmm"] == pytest.approx(report.rows[0]["wd_fe_Nmm"], rel=1e-5)
    assert remote.rows[0]["verdict"] == "pass"
