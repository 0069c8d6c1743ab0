"""Run CalculiX (``ccx``) on a job directory, with a time-out, and read the results back.

The solver is started as ``subprocess.run([ccx, "-i", jobname], cwd=job_dir, env={**os.environ,
"OMP_NUM_THREADS": n}, timeout=..., capture_output=True)``: the process environment of the
caller is never modified, the exit code is always checked, and every failure becomes a typed
:class:`~microslip.fe.errors.SolverError` carrying the job directory and the log tail. The
full solver output is kept in ``<job_dir>/ccx.log``.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import signal
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ...errors import ParameterError
from ..errors import (
    INSTALL_HINT,
    NonConvergenceError,
    SolverError,
    SolverKilledError,
    SolverNotFoundError,
    SolverTimeoutError,
)
from .case import FECase

__all__ = [
    "CCX",
    "JOBNAME",
    "SolverRun",
    "ccx_available",
    "ccx_version",
    "default_timeout",
    "find_ccx",
    "run_ccx",
]

#: Name of the CalculiX executable looked up on PATH.
CCX = "ccx"
#: Job name of the deck in a job directory (``job.inp`` -> ``job.dat``, ``job.frd``, ...).
JOBNAME = "job"
_RESULT_SUFFIXES = (".dat", ".frd", ".sta", ".cvg", ".12d")
_RUN_RECORD = "run.json"
#: Lines of solver output kept in an error's ``log_tail``.
LOG_TAIL_LINES = 25
_DIVERGENCE = ("diverge", "too many cutbacks", "increment size smaller", "no convergence",
               "too many iterations", "did not converge")


def ccx_available(executable: str = CCX) -> bool:
    """True when the CalculiX solver can be found on PATH."""
    return shutil.which(executable) is not None


def find_ccx(executable: str | None = None) -> str:
    """Full path of the CalculiX executable, or :class:`SolverNotFoundError` (one line that
    says how to install it)."""
    name = executable or CCX
    path = shutil.which(name)
    if path is None:
        raise SolverNotFoundError(f"the CalculiX solver '{name}' is not on PATH; {INSTALL_HINT}")
    return path


def ccx_version(executable: str | None = None) -> str:
    """The solver's version string (``"2.20"``), or ``"unknown"``."""
    try:
        out = subprocess.run([find_ccx(executable), "-v"], capture_output=True, text=True,
                             timeout=30, check=False).stdout
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    for word in out.split():
        if word[:1].isdigit():
            return word
    return "unknown"


def default_timeout(case: FECase) -> float:
    """A generous time-out for a case, s: 120 s plus 0.15 s per degree of freedom.

    Measured on two shared cores: about 20 s for the coarse mesh (1 100 DOF) and 200 s for the
    paper's (9 600 DOF) at lambda = 1e4 N/mm^3 (docs/validation.md).
    """
    return 120.0 + 0.15 * case.spec.dof


@dataclass(frozen=True)
class SolverRun:
    """What one ccx process did.

    Attributes
    ----------
    job_dir : Path
    jobname : str
    returncode : int
    wall_s : float
        Wall time, s.
    log_tail : str
        The last lines of the solver output (the whole output is in ``job_dir/ccx.log``).
    """

    job_dir: Path
    jobname: str
    returncode: int
    wall_s: float
    log_tail: str


def _tail(text: str, lines: int = LOG_TAIL_LINES) -> str:
    kept = [ln for ln in text.splitlines() if ln.strip()]
    return "\n".join(kept[-lines:])


def _text(data: bytes | str | None) -> str:
    if data is None:
        return ""
    if isinstance(data, bytes):
        return data.decode("latin-1", errors="replace")
    return data


def _error_line(log: str) -> str:
    """The solver's own error message, joined onto one line."""
    lines = log.splitlines()
    for i, ln in enumerate(lines):
        if "*ERROR" in ln:
            msg = [ln.strip()]
            for nxt in lines[i + 1:i + 4]:
                if not nxt.strip() or nxt.strip().startswith("*"):
                    break
                msg.append(nxt.strip())
            return " ".join(msg)
    return ""


def _sta_increments(path: Path) -> int:
    """Converged increments listed so far in a ``.sta`` file (0 while it is missing)."""
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return 0
    rows = (ln.split() for ln in text.splitlines())
    return sum(1 for r in rows if len(r) >= 3 and r[0].isdigit() and r[2].isdigit())


def run_ccx(job_dir: str | Path, jobname: str = JOBNAME, *, timeout: float,
            threads: int = 1, executable: str | None = None,
            watch: Callable[[int], None] | None = None) -> SolverRun:
    """Run ``ccx -i jobname`` in ``job_dir`` and check how it ended.

    Parameters
    ----------
    job_dir : path
        Directory holding ``<jobname>.inp``; the results are written beside it.
    jobname : str
    timeout : float
        Seconds after which the solver is stopped (ccx can hang after a cut-back).
    threads : int
        ``OMP_NUM_THREADS`` for the solver (passed in its environment only).
    executable : str, optional
        Solver name or path (default ``ccx`` on PATH).
    watch : callable, optional
        Called about once a second while ccx runs with the number of increments (of all
        steps) it has finished, from its ``.sta`` file: a progress display.

    Raises
    ------
    SolverNotFoundError, SolverTimeoutError, SolverKilledError, NonConvergenceError,
    SolverError
    """
    exe = find_ccx(executable)
    job_dir = Path(job_dir)
    if not (job_dir / f"{jobname}.inp").is_file():
        raise SolverError(f"no input deck {jobname}.inp", job_dir)
    if not (isinstance(timeout, (int, float)) and math.isfinite(timeout) and timeout > 0):
        raise ParameterError(f"timeout must be > 0 s, got {timeout!r}")
    if not (isinstance(threads, int) and 1 <= threads <= 256):
        raise ParameterError(f"threads must be an integer in [1, 256], got {threads!r}")
    env = {**os.environ, "OMP_NUM_THREADS": str(threads)}
    log_path = job_dir / "ccx.log"
    start = time.perf_counter()
    try:
        proc = subprocess.Popen([exe, "-i", jobname], cwd=job_dir, env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    except OSError as exc:
        raise SolverError(f"could not start {exe}: {exc.strerror or exc}", job_dir) from None
    try:
        while True:
            left = timeout - (time.perf_counter() - start)
            try:
                out, err = proc.communicate(timeout=max(min(1.0, left), 1e-3))
                break
            except subprocess.TimeoutExpired:
                if time.perf_counter() - start >= timeout:
                    proc.kill()
                    out, err = proc.communicate()
                    log = _text(out) + _text(err)
                    log_path.write_text(log, encoding="utf-8")
                    raise SolverTimeoutError(
                        f"ccx did not finish within {timeout:g} s and was stopped; a partial "
                        "loop is not a result", job_dir, _tail(log)) from None
                if watch is not None:
                    watch(_sta_increments(job_dir / f"{jobname}.sta"))
    except BaseException:
        if proc.poll() is None:  # interrupted: leave no ccx behind
            proc.kill()
            proc.wait()
        raise
    wall = time.perf_counter() - start
    if watch is not None:
        watch(_sta_increments(job_dir / f"{jobname}.sta"))
    log = _text(out) + _text(err)
    log_path.write_text(log, encoding="utf-8")
    tail = _tail(log)
    rc = proc.returncode
    if rc < 0:
        try:
            name = signal.Signals(-rc).name
        except ValueError:
            name = f"signal {-rc}"
        raise SolverKilledError(f"ccx was ended by {name} after {wall:.1f} s; no result",
                                job_dir, tail)
    error = _error_line(log)
    if rc != 0 or error:
        what = error or f"ccx exited with code {rc}"
        if any(k in log.lower() for k in _DIVERGENCE):
            raise NonConvergenceError(f"ccx did not converge: {what}", job_dir, tail)
        raise SolverError(f"ccx failed (exit code {rc}): {what}", job_dir, tail)
    return SolverRun(job_dir, jobname, rc, wall, tail)


def _sha256(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _reusable(job_dir: Path, jobname: str, digest: str) -> float | None:
    """Wall time of a previous complete run of the same deck in ``job_dir``, else None."""
    record = job_dir / _RUN_RECORD
    if not record.is_file():
        return None
    try:
        data = json.loads(record.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if data.get("deck_sha256") != digest or data.get("returncode") != 0:
        return None
    if not all((job_dir / f"{jobname}{s}").is_file() for s in (".dat", ".frd", ".sta")):
        return None
    wall = data.get("wall_s")
    return float(wall) if isinstance(wall, (int, float)) else math.nan
