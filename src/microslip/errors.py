"""Exception types of microslip.

Every error a user can cause derives from :class:`MicroslipError`; the command
line turns these into one line on standard error and a non-zero exit code.
"""

from __future__ import annotations

__all__ = ["MacroslipError", "MicroslipError", "ParameterError"]


class MicroslipError(Exception):
    """Base class of every error microslip raises on purpose."""


class ParameterError(MicroslipError, ValueError):
    """A parameter is not finite, out of its physical range, or unknown."""


class MacroslipError(MicroslipError, ValueError):
    """The load reaches the macroslip limit: the microslip model does not apply."""
