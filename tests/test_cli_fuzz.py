"""A fuzz over every subcommand: bad paths, unwritable outputs, extreme and non-numbers.

Each example is a quick, valid command line of one subcommand with one bad option injected
(hypothesis picks the command, the option and the bad value, and may add valid extreme
options beside it). Whatever it is, the command must fail with an exit code of 1 or 2, say
why on one ``error:`` line without a traceback, and leave the directory as it was. Implausible
values that are still valid only warn (last test).
"""

from __future__ import annotations

import contextlib
import io
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from microslip.cli.main import main

#: Values that are not numbers of any range.
NOT_NUMBERS = ("nan", "inf", "-inf", "1e400", "abc", "", "0x10", "1,5")
#: Paths that cannot be written: under a file, in /proc, a directory, the wrong extension.
BAD_FILES = ("{d}/afile/x{ext}", "/proc/microslip/x{ext}", "{d}/adir", "{d}/out.txt",
             "{d}/afile")
BAD_DIRS = ("{d}/afile/x", "/proc/microslip-x", "{d}/afile")
BAD_CASES = ("{d}/missing.toml", "{d}/adir", "{d}/bad.toml", "{d}/afile")

#: command -> (a quick valid command line, {option: bad values}).
COMMANDS: dict[str, tuple[list[str], dict[str, tuple[str, ...]]]] = {
    "loop": (["loop", "--model", "tip", "--increments", "20"], {
        "--amplitude": ("-1", "0", "356", "1e12", *NOT_NUMBERS),
        "--length": ("-5", "0", *NOT_NUMBERS), "--friction": ("0", "-0.5", *NOT_NUMBERS),
        "--poisson-ratio": ("0.5", "-0.1", "2"), "--modulus": ("0", "-2e5", *NOT_NUMBERS),
        "--increments": ("0", "1", "9", "-3", "1e7", "x", "99999999999"),
        "--plot": BAD_FILES, "--case": BAD_CASES}),
    "planar": (["planar", "--ratio", "1", "--increments", "20", "--samples-per-cycle", "64"], {
        "--ratio": ("0", "-1", "1e9", *NOT_NUMBERS), "--phase": NOT_NUMBERS,
        "--tip-symmetry": ("0", "-1", "x"), "--thickness": ("0", "-1", *NOT_NUMBERS),
        "--samples-per-cycle": ("0", "1", "-5"), "--increments": ("0", "5"),
        "--plot": BAD_FILES, "--mesh": ("tiny",), "--case": BAD_CASES}),
    "fe": (["fe", "--model", "tip", "--mesh", "tiny", "--substeps", "10"], {
        "--amplitude": ("-1", "0", "1e9", *NOT_NUMBERS), "--length": ("0", "-1", "nan"),
        "--thickness": ("0", "-2"), "--substeps": ("0", "7", "-5"),
        "--stick-slope": ("0", "-1", *NOT_NUMBERS), "--timeout": ("0", "-1", "nan"),
        "--out": BAD_DIRS, "--case": BAD_CASES}),
    "sweep": (["sweep", "--model", "tip", "--amplitude-range", "100", "200", "--cases", "3",
               "--increments", "20", "--no-progress"], {
        "--out": (*BAD_FILES, "{d}/x.json"), "--plot": BAD_FILES,
        "--grid": ("mu=-1,2", "colour=1:2:3", "mu=0.4:0.8", "E=nan,1", "mu=", "=1"),
        "--sample": ("mu=gauss:1:2", "mu=normal:-1:0.1", "mu=normal:0.8", "F0=normal:1:1"),
        "--chunk-size": ("0", "-1", "x"), "--retries": ("-1",), "--seed": ("-1", "x"),
        "--case": BAD_CASES}),
    "validate": (["validate", "--model", "tip"], {
        "--out": BAD_DIRS, "--threads": ("0", "1000"), "--timeout": ("0", "-1", "nan"),
        "--length": ("0", "-1", "nan"), "--mesh": ("tiny", "x")}),
    "case": (["case"], {"new": BAD_FILES[:3], "check": BAD_CASES}),
    "fit": (["fit", "--model", "tip", "{d}/loop.csv"], {
        "--fit": ("colour", ""), "--confidence": ("0", "1", "nan"),
        "--friction": ("0", "-1", "nan"), "--stick-slope": ("0", "-1")}),
    "joint": (["joint", "--joint", "jenkins", "--joint-stiffness", "1000", "--slip-force",
               "10", "--amplitude-range", "0.001", "0.1", "--amplitudes", "3",
               "--samples", "64"], {
        "--joint-stiffness": ("0", "-1", *NOT_NUMBERS), "--slip-force": ("0", "-1", "nan"),
        "--amplitudes": ("0", "-1", "x"), "--samples": ("0", "1", "x"),
        "--plot": BAD_FILES}),
}

#: Valid but extreme or implausible options a command may get beside the bad one.
EXTRAS = {
    "loop": (["--modulus", "2.1e11"], ["--length", "0.03"], ["--json"]),
    "planar": (["--json"], ["--phase", "360"], ["--modulus", "1e9"]),
    "fe": (["--json"], ["--normal-force", "1e6"]),
    "sweep": (["--grid", "E=1e9,2e9"], ["--threads", "1"]),
    "validate": (["--json"],),
    "case": ((),),
    "fit": (["--json"],),
    "joint": (["--json"],),
}


def _scratch() -> Path:
    d = Path(tempfile.mkdtemp(prefix="microslip-fuzz-"))
    (d / "afile").write_text("not a directory\n")
    (d / "adir").mkdir()
    (d / "bad.toml").write_text("[geometry]\nlenght = 30\n")
    (d / "loop.csv").write_text("force_N,displacement_mm\n0,0\n1,0.001\n0,0.0005\n-1,-0.001\n")
    return d


def _listing(d: Path) -> list[tuple[str, int]]:
    return sorted((str(p.relative_to(d)), p.stat().st_size if p.is_file() else -1)
                  for p in d.rglob("*"))


@st.composite
def bad_command_lines(draw: st.DrawFn) -> tuple[list[str], str]:
    command = draw(st.sampled_from(sorted(COMMANDS)))
    base, bad = COMMANDS[command]
    option = draw(st.sampled_from(sorted(bad)))
    value = draw(st.sampled_from(bad[option]))
    ext = draw(st.sampled_from([".png", ".csv", ".svg", ""]))
    extra = draw(st.sampled_from(EXTRAS[command]))
    if command == "case":
        argv = ["case", option, value]
    else:
        argv = [*base, *extra, option, value]
    return [a.replace("{ext}", ext) for a in argv], command


def _run(argv: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def _check_fails_cleanly(template: list[str]) -> None:
    d = _scratch()
    argv = [a.replace("{d}", str(d)) for a in template]
    before = _listing(d)
    code, _, err = _run(argv)
    assert code in (1, 2), (argv, code, err)
    assert "Traceback" not in err, (argv, err)
    errors = [line for line in err.splitlines() if not line.startswith("warning: ")]
    assert len(errors) == 1 and errors[0].startswith("error: "), (argv, err)
    assert _listing(d) == before, argv


ALL_BAD = [(command, option, value) for command, (_, bad) in sorted(COMMANDS.items())
           for option, values in sorted(bad.items()) for value in values]


@pytest.mark.parametrize("command, option, value", ALL_BAD)
def test_each_bad_option_alone_fails_cleanly(command, option, value):
    base = COMMANDS[command][0]
    argv = ["case", option, value] if command == "case" else [*base, option, value]
    _check_fails_cleanly([a.replace("{ext}", ".png") for a in argv])


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(bad_command_lines())
def test_bad_options_with_extreme_extras_fail_cleanly(case):
    _check_fails_cleanly(case[0])


@settings(max_examples=12, deadline=None, derandomize=True)
@given(st.sampled_from([
    (["loop", "--model", "tip", "--increments", "20", "--modulus", "80"], "GPa given as MPa"),
    (["loop", "--model", "centre", "--increments", "20", "--length", "0.254", "--width",
      "0.0254"], "metres"),
    (["planar", "--ratio", "1", "--increments", "20", "--samples-per-cycle", "64",
      "--modulus", "90"], "GPa given as MPa"),
    (["sweep", "--model", "tip", "--amplitude-range", "50", "100", "--cases", "2",
      "--increments", "20", "--no-progress", "--grid", "t=0.001,0.002"], "metres"),
    (["fe", "--model", "tip", "--mesh", "tiny", "--substeps", "10", "--friction", "3"],
     "friction coefficient above 2"),
]))
def test_implausible_units_warn_and_still_run(case):
    """A borderline value warns and runs; a value that cannot be meant (a modulus in
    pascals) is an error: :func:`test_impossible_units_fail_in_one_line`."""
    argv, words = case
    code, out, err = _run(argv)
    assert code == 0, err
    assert err.startswith("warning: ") and words in err and "Traceback" not in err
    assert out


@pytest.mark.parametrize(("argv", "words"), [
    (["loop", "--model", "tip", "--increments", "20", "--modulus", "6.9e10"],
     ["--modulus 6.9e+10 MPa", "pascals"]),
    (["planar", "--ratio", "1", "--increments", "20", "--samples-per-cycle", "64",
      "--modulus", "1e10"], ["--modulus 1e+10 MPa", "pascals"]),
])
def test_impossible_units_fail_in_one_line(argv, words):
    """A modulus above any solid's is a unit mistake: exit 1, one line, nothing printed."""
    code, out, err = _run(argv)
    assert code == 1 and out == "" and err.count("\n") == 1 and err.startswith("error: ")
    assert all(w in err for w in words) and "Traceback" not in err
