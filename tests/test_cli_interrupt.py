"""Ctrl-C on any command (issue 14, item 3): it stops promptly, prints one line
(``error: interrupted``), exits 130 and leaves no partial output behind.
"""

from __future__ import annotations

import os

import pytest
from conftest import listing, run

from microslip.cli.main import main

# --- an interrupted reproduce leaves no partial directory ------------------------------------

@pytest.mark.parametrize("exists", [False, True])
def test_interrupted_reproduce_leaves_no_partial_directory(capsys, tmp_path, monkeypatch,
                                                           exists):
    import microslip.reproduce as rep

    out = tmp_path / "new" / "paper"
    if exists:
        out.mkdir(parents=True)
        (out / "old.txt").write_text("kept")
    before = listing(tmp_path)

    def interrupted(out_dir, **kwargs):
        (out_dir / "fig10.png").write_bytes(b"half")
        raise KeyboardInterrupt

    monkeypatch.setattr(rep, "reproduce", interrupted)
    code, _, err = run(capsys, "reproduce", "--out", out, "--quiet")
    assert code == 130 and err == "error: interrupted\n"
    assert listing(tmp_path) == before


# --- Ctrl-C: prompt, one line, nothing left ---------------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("argv, made", [
    (["sweep", "--model", "tip", "--amplitude-range", "10", "300", "--cases", "2000000",
      "--no-progress", "--out", "{d}/big.csv"], "big.csv"),
    (["reproduce", "--out", "{d}/paper", "--quiet", "--increments", "200000"], "paper"),
], ids=["sweep", "reproduce"])
def test_ctrl_c_stops_promptly_and_leaves_nothing(tmp_path, argv, made):
    """Both runs first warn of their cost: the interrupt comes a second after, in the work."""
    import signal
    import subprocess
    import sys
    import time

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    args = [a.format(d=tmp_path) for a in argv]
    proc = subprocess.Popen([sys.executable, "-m", "microslip", *args], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stderr is not None
    warning = proc.stderr.readline()
    assert warning.startswith("warning: --increments")
    time.sleep(1.0)
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert time.perf_counter() - t0 < 5.0
    assert proc.returncode == 130 and err == "error: interrupted\n", err[-2000:]
    assert not (tmp_path / made).exists() and listing(tmp_path) == []


def test_an_interrupt_wrapped_by_a_library_is_still_an_interrupt(capsys, monkeypatch):
    """numba and others may re-raise Ctrl-C as their own error: still one line, exit 130."""
    import microslip.case.run as computation  # what `loop` runs

    def wrapped(*args, **kwargs):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise RuntimeError("compilation failed") from exc

    monkeypatch.setattr(computation, "damping", wrapped)
    assert main(["loop", "--model", "tip"]) == 130
    assert capsys.readouterr().err == "error: interrupted\n"
