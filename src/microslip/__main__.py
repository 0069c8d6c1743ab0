"""``python -m microslip`` runs the command line."""

from .cli.main import entry

entry()
