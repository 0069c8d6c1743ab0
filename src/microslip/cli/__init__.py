"""The ``microslip`` command line: one module per subcommand, parsing and delegating only."""

from .main import main

__all__ = ["main"]
