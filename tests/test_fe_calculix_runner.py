"""The solver driver's failure modes, with stand-in executables (no CalculiX needed): every
failure is a typed error that carries the job directory and the log tail."""

from __future__ import annotations

import os
import pickle
import stat
from pathlib import Path

import pytest

from microslip.errors import MicroslipError
from microslip.fe import (
    FECase,
    MeshSpec,
    NonConvergenceError,
    ResultsError,
    SolverError,
    SolverKilledError,
    SolverNotFoundError,
    SolverTimeoutError,
    ccx_available,
    find_ccx,
    run_case,
    run_ccx,
)


def fake_ccx(tmp_path: Path, body: str, name: str = "fakeccx") -> str:
    """An executable shell script standing in for ccx."""
    path = tmp_path / "bin" / name
    path.parent.mkdir(exist_ok=True)
    path.write_text("#!/bin/sh\n" + body + "\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    return str(path)


@pytest.fixture
def job(tmp_path: Path) -> Path:
    d = tmp_path / "job"
    d.mkdir()
    (d / "job.inp").write_text("*HEADING\nstand-in\n")
    return d


def test_environment_working_directory_and_arguments(tmp_path, job):
    exe = fake_ccx(tmp_path, 'echo "$OMP_NUM_THREADS $(pwd) $@" > seen.txt; echo done')
    before = dict(os.environ)
    run = run_ccx(job, timeout=30, threads=3, executable=exe)
    assert os.environ == before  # the caller's environment is never touched
    threads, cwd, *argv = (job / "seen.txt").read_text().split()
    assert threads == "3" and Path(cwd).resolve() == job.resolve() and argv == ["-i", "job"]
    assert run.returncode == 0 and run.log_tail == "done"
    assert (job / "ccx.log").read_text() == "done\n"


def test_time_out_stops_the_solver(tmp_path, job):
    exe = fake_ccx(tmp_path, "echo increment 1; exec sleep 30")
    with pytest.raises(SolverTimeoutError) as err:
        run_ccx(job, timeout=0.5, executable=exe)
    assert err.value.job_dir == job and "0.5 s" in str(err.value)
    assert "increment 1" in err.value.log_tail


def test_killed_solver(tmp_path, job):
    exe = fake_ccx(tmp_path, "echo starting; kill -9 $$")
    with pytest.raises(SolverKilledError, match="SIGKILL") as err:
        run_ccx(job, timeout=30, executable=exe)
    assert err.value.log_tail == "starting" and err.value.job_dir == job


def test_divergence_is_non_convergence(tmp_path, job):
    exe = fake_ccx(tmp_path, "echo ' *ERROR: solution seems to diverge; please try '; "
                             "echo ' automatic incrementation; program stops'; exit 201")
    with pytest.raises(NonConvergenceError, match="diverge; please try automatic") as err:
        run_ccx(job, timeout=30, executable=exe)
    assert "program stops" in err.value.log_tail
    # the error survives a trip through pickle (dask workers) with its attributes
    back = pickle.loads(pickle.dumps(err.value))
    assert type(back) is NonConvergenceError and back.job_dir == job
    assert back.log_tail == err.value.log_tail and str(back) == str(err.value)


def test_other_errors_and_nonzero_exit(tmp_path, job):
    exe = fake_ccx(tmp_path, "echo '*ERROR reading *MATERIAL'; exit 0")
    with pytest.raises(SolverError, match=r"\*ERROR reading \*MATERIAL") as err:
        run_ccx(job, timeout=30, executable=exe)
    assert type(err.value) is SolverError
    with pytest.raises(SolverError, match="exit code 3"):
        run_ccx(job, timeout=30, executable=fake_ccx(tmp_path, "exit 3", "other"))


def test_missing_deck(tmp_path):
    with pytest.raises(SolverError, match="no input deck"):
        run_ccx(tmp_path, timeout=30, executable=fake_ccx(tmp_path, "exit 0"))


def test_solver_that_writes_nothing_gives_missing_results(tmp_path):
    exe = fake_ccx(tmp_path, "echo finished")
    case = FECase("tip", mesh=MeshSpec(2, 2, 1))
    with pytest.raises(ResultsError, match="missing") as err:
        run_case(case, tmp_path / "run", executable=exe, timeout=30)
    assert err.value.log_tail == "finished"
    assert (tmp_path / "run" / "job.inp").read_text().startswith("*HEADING")
    assert not (tmp_path / "run" / "run.json").exists()  # no record of a successful run


def test_stale_results_are_removed_before_a_run(tmp_path):
    out = tmp_path / "run"
    out.mkdir()
    for suffix in (".dat", ".frd", ".sta"):
        (out / f"job{suffix}").write_text("old\n")
    exe = fake_ccx(tmp_path, "exit 0")
    with pytest.raises(ResultsError, match="missing"):
        run_case(FECase("tip", mesh=MeshSpec(2, 2, 1)), out, executable=exe, timeout=30)
    assert not (out / "job.dat").exists()


def test_missing_solver_says_how_to_install(monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))
    assert not ccx_available()
    with pytest.raises(SolverNotFoundError) as err:
        find_ccx()
    msg = str(err.value)
    assert "\n" not in msg and "bash scripts/setup.sh" in msg and "calculix-ccx" in msg
    assert isinstance(err.value, MicroslipError)
    with pytest.raises(SolverNotFoundError):
        run_case(FECase("tip"), tmp_path / "never")
    assert not (tmp_path / "never").exists()


def test_invalid_run_options(tmp_path, job):
    exe = fake_ccx(tmp_path, "exit 0")
    with pytest.raises(MicroslipError, match="timeout"):
        run_ccx(job, timeout=-1, executable=exe)
    with pytest.raises(MicroslipError, match="threads"):
        run_ccx(job, timeout=10, threads=0, executable=exe)
