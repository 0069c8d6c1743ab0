"""Output files of every command (issue 14, item 3): an output that cannot be written, or has
the wrong extension, is one ``error:`` line before the work; a write that fails after the
checks is one line too; directories are published whole (``staged_directory``) or not at all.
"""

from __future__ import annotations

import os

import pytest
from conftest import listing, one_line_error, run

from microslip.errors import ParameterError
from microslip.io import check_writable, staged_directory

# --- unwritable outputs: refused before the work, nothing left behind -----------------------

UNWRITABLE = [
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--cases", "3",
     "--no-progress", "--out", "{bad}.csv"),
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--cases", "3",
     "--no-progress", "--plot", "{bad}.png"),
    ("sweep", "--model", "planar", "--ratio-range", "1", "2", "--cases", "2",
     "--no-progress", "--out", "{bad}.csv"),
    ("loop", "--model", "tip", "--increments", "100", "--plot", "{bad}.png"),
    ("planar", "--ratio", "1", "--increments", "100", "--plot", "{bad}.png"),
    ("validate", "--out", "{bad}"),
    ("reproduce", "--out", "{bad}"),
    ("fe", "--model", "tip", "--out", "{bad}"),
]


@pytest.mark.parametrize("argv", UNWRITABLE, ids=lambda a: " ".join(a[:2]))
@pytest.mark.parametrize("where", ["under_a_file", "proc"])
def test_unwritable_outputs_are_one_line_before_the_work(capsys, tmp_path, argv, where):
    (tmp_path / "afile").write_text("x")
    bad = str(tmp_path / "afile" / "x") if where == "under_a_file" else "/proc/microslip-x"
    before = listing(tmp_path)
    one_line_error(run(capsys, *(a.format(bad=bad) for a in argv)), "cannot write")
    assert listing(tmp_path) == before


@pytest.mark.parametrize("argv", [
    ("loop", "--model", "tip", "--plot", "{d}/out.txt"),
    ("planar", "--ratio", "1", "--plot", "{d}/out.txt"),
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--plot", "{d}/out.txt"),
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--out", "{d}/out.txt"),
], ids=lambda a: " ".join(a[:2]))
def test_unknown_output_formats_are_refused_before_the_work(capsys, tmp_path, argv):
    allowed = ".csv" if argv[-2] == "--out" else ".png"
    one_line_error(run(capsys, *(a.format(d=tmp_path) for a in argv)), "out.txt", allowed)
    assert listing(tmp_path) == []


def test_a_plot_path_that_is_a_directory_is_refused(capsys, tmp_path):
    (tmp_path / "fig.png").mkdir()
    one_line_error(run(capsys, "loop", "--model", "tip", "--plot", tmp_path / "fig.png"),
                   "must be a file, got the directory")


def test_check_writable_names_the_reason():
    with pytest.raises(ParameterError, match="must be a directory, got the file"):
        check_writable(__file__, directory=True)
    with pytest.raises(ParameterError, match=r"must end in \.csv"):
        check_writable("x.txt", (".csv",))


def test_check_writable_creates_nothing(tmp_path):
    target = tmp_path / "a" / "b" / "c.csv"
    assert check_writable(target, (".csv",)) == target
    assert listing(tmp_path) == []


def test_write_failures_after_the_checks_are_one_line(capsys, tmp_path, monkeypatch):
    def full_disk(*args, **kwargs):
        raise OSError(28, "No space left on device", str(tmp_path / "x.png"))

    monkeypatch.setattr("microslip.plot.plot_damping", full_disk)
    one_line_error(run(capsys, "loop", "--model", "tip", "--increments", "50", "--plot",
                       tmp_path / "x.png"), "No space left on device", "x.png")


def test_staged_directory_publishes_on_success_only(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    (target / "keep.txt").write_text("old")
    (target / "sub").mkdir()
    (target / "sub" / "stale.txt").write_text("old")
    with staged_directory(target) as stage:
        (stage / "sub").mkdir()
        (stage / "sub" / "new.txt").write_text("new")
        (stage / "keep.txt").write_text("new")
    assert listing(tmp_path) == ["out", "out/keep.txt", "out/sub", "out/sub/new.txt"]
    assert (target / "keep.txt").read_text() == "new"


def test_staged_directory_gives_a_new_directory_the_usual_permissions(tmp_path):
    (tmp_path / "reference").mkdir()
    with staged_directory(tmp_path / "out") as stage:
        (stage / "a.txt").write_text("a")
    mode = os.stat(tmp_path / "out").st_mode
    assert mode == os.stat(tmp_path / "reference").st_mode
    assert (tmp_path / "out" / "a.txt").read_text() == "a"
