"""``sweep --solver fe``: FE amplitude sweeps saved point by point, resumed after Ctrl-C."""

from __future__ import annotations

import numpy as np
import pytest

import microslip.sweep.fe as sweep_fe
from microslip import preset
from microslip.cli.main import main
from microslip.fe import run_loop
from microslip.sweep.fe import FE_COLUMNS, FESweepSpec, read_finished

ARGS = ["sweep", "--solver", "fe", "--model", "tip", "--amplitude-range", "100", "300",
        "--cases", "4", "--mesh", "tiny", "--substeps", "10", "--no-progress"]


@pytest.fixture
def counted(monkeypatch):
    """Counts FE runs; ``counted["stop_after"] = k`` raises KeyboardInterrupt at run k + 1."""
    state = {"runs": 0, "stop_after": None}
    original = sweep_fe._runner

    def runner(spec):
        run = original(spec)

        def counting(amplitude):
            if state["stop_after"] is not None and state["runs"] >= state["stop_after"]:
                raise KeyboardInterrupt
            state["runs"] += 1
            return run(amplitude)

        return counting

    monkeypatch.setattr(sweep_fe, "_runner", runner)
    return state


def _table(path):
    lines = path.read_text().splitlines()
    assert lines[1] == ",".join(FE_COLUMNS)
    return np.array([[float(x) for x in line.split(",")] for line in lines[2:]])


def test_interrupted_sweep_resumes_without_recomputing(tmp_path, capsys, counted):
    out = tmp_path / "fe.csv"
    counted["stop_after"] = 2
    assert main([*ARGS, "--out", str(out)]) == 130
    assert "run the same command again to resume" in capsys.readouterr().err
    assert counted["runs"] == 2 and _table(out).shape == (2, len(FE_COLUMNS))

    counted["stop_after"] = None
    assert main([*ARGS, "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert counted["runs"] == 4  # only the two points left were run
    assert "2 computed now, 2 read from" in text
    assert "estimated time: 2 point(s) x" in text and " s = " in text
    assert "point 3/4: F0 = 233.333 N" in text and "point 4/4: F0 = 300 N" in text
    resumed = _table(out)

    counted["runs"] = 0
    whole = tmp_path / "whole.csv"
    assert main([*ARGS, "--out", str(whole)]) == 0
    assert counted["runs"] == 4
    # every column but the wall time is the same as an uninterrupted run, bit for bit
    np.testing.assert_array_equal(resumed[:, :-1], _table(whole)[:, :-1])


def test_rows_are_the_fe_runs(tmp_path, capsys):
    out = tmp_path / "fe.csv"
    assert main([*ARGS, "--out", str(out)]) == 0
    table = _table(out)
    np.testing.assert_array_equal(table[:, 0], np.linspace(100, 300, 4))
    r, _ = run_loop("tip", preset("table1"), table[2, 0], mesh="tiny", substeps=10)
    assert table[2, 1] == r.peak_displacement
    assert table[2, 4] == r.damping.loss_factor
    assert np.all(table[:, 5] == 1.0)


def test_a_file_of_another_sweep_is_refused(tmp_path, capsys):
    out = tmp_path / "fe.csv"
    assert main([*ARGS, "--out", str(out)]) == 0
    before = out.read_text()
    code = main([*ARGS[:-2], "20", "--no-progress", "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 1 and "holds a different FE sweep" in err and err.count("\n") == 1
    assert out.read_text() == before
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    assert main([*ARGS, "--out", str(other)]) == 1
    assert "is not an FE sweep file" in capsys.readouterr().err


def test_an_incomplete_last_line_is_ignored(tmp_path):
    spec = FESweepSpec("tip", preset("table1"), (100.0, 200.0), mesh="tiny", substeps=10)
    out = tmp_path / "fe.csv"
    sweep_fe.run_fe_sweep(spec, out, progress=False, say=lambda s: None)
    text = out.read_text()
    out.write_text(text[: text.rindex("\n", 0, -1) + 1] + "200.0,0.00")
    assert list(read_finished(out, spec)) == [100.0]


@pytest.mark.parametrize("extra, text, code", [
    (["--grid", "mu=0.4,0.8"], "--grid does not apply to --solver fe", 1),
    # --mesh is checked by the parser, as on every command that takes it (a usage error)
    (["--mesh", "huge"], "unknown mesh 'huge'; choose one of tiny, coarse", 2),
    (["--substeps", "12"], "--substeps must be a positive multiple of 5", 1),
    (["--amplitude-range", "100", "400"], "0 < amplitude < 356 N", 1),
])
def test_bad_options_are_one_line(tmp_path, capsys, extra, text, code):
    out = tmp_path / "fe.csv"
    assert main([*ARGS, *extra, "--out", str(out)]) == code
    err = capsys.readouterr().err
    assert text in err and err.count("\n") == 1
    assert not out.exists()


def test_out_must_be_a_csv(capsys):
    assert main(ARGS) == 1
    assert "--solver fe needs --out FILE.csv" in capsys.readouterr().err
