"""Typed failures of the finite-element driver.

Every failure of a CalculiX run is a :class:`SolverError` (a
:class:`~microslip.errors.MicroslipError`), so the command line turns it into one line on
standard error. Each carries the job directory and the tail of the solver's log, so that a
failed run can be inspected without running it again. A partial loop is never returned as a
result: any of these errors is raised instead.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import MicroslipError

__all__ = [
    "INSTALL_HINT",
    "NonConvergenceError",
    "ResultsError",
    "SolverError",
    "SolverKilledError",
    "SolverNotFoundError",
    "SolverTimeoutError",
]

#: How to get CalculiX, quoted by every FE command when ``ccx`` is missing.
INSTALL_HINT = "install it with `bash scripts/setup.sh` or `apt-get install calculix-ccx`"


class SolverError(MicroslipError):
    """A CalculiX run failed.

    Parameters
    ----------
    message : str
        One line saying what failed.
    job_dir : path, optional
        The job directory (input deck, solver log, partial results).
    log_tail : str
        The last lines of the solver's output.
    """

    def __init__(self, message: str, job_dir: str | Path | None = None,
                 log_tail: str = "") -> None:
        self.message = message
        self.job_dir = None if job_dir is None else Path(job_dir)
        self.log_tail = log_tail
        where = f" (job directory {self.job_dir})" if self.job_dir is not None else ""
        super().__init__(message + where)

    def __reduce__(self) -> tuple[type[SolverError], tuple[str, Path | None, str]]:
        # keep job_dir and log_tail when the error crosses a process boundary (dask workers)
        return (type(self), (self.message, self.job_dir, self.log_tail))


class SolverNotFoundError(SolverError):
    """The CalculiX executable ``ccx`` is not on PATH."""


class SolverTimeoutError(SolverError):
    """ccx did not finish within the time-out and was stopped."""


class SolverKilledError(SolverError):
    """ccx was ended by a signal (killed from outside, out of memory, crashed)."""


class NonConvergenceError(SolverError):
    """ccx stopped because an increment did not converge (or reported another error)."""


class ResultsError(SolverError):
    """A result file is missing, truncated, or does not hold every substep."""
