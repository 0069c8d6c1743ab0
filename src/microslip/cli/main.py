"""Entry point: ``microslip <command> ...``.

Each subcommand lives in its own module ``microslip.cli.<name>`` that defines
``add_parser(subparsers)``; the parser it adds sets ``func`` to a callable
``(args) -> int``. The command line parses and delegates; no physics here.

Only the module of the command that runs is imported (:func:`build_parser` with ``argv``):
the others appear in ``microslip --help`` by their one-line summary in :data:`COMMANDS`, so
that a small call does not pay for importing every command's physics (FE, harmonic balance,
fitting, plotting).
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence
from types import MappingProxyType
from typing import NoReturn

from .. import __version__
from ..case.options import case_output, parse_args
from ..case.runflags import EXIT_STATUS, EXIT_UNSETTLED
from ..errors import MicroslipError

__all__ = ["COMMANDS", "EXIT_STATUS", "EXIT_UNSETTLED", "SUBCOMMANDS", "UsageError",
           "build_parser", "entry", "main"]


#: Subcommand -> its one-line summary in ``microslip --help``, in the order listed there; the
#: module ``microslip.cli.<name>`` is imported only when the command runs.
COMMANDS = MappingProxyType({
    "loop": "hysteresis loop and damping of the tip or centre model",
    "planar": "circular/elliptical loading: paper's coupling and work-based damping",
    "reproduce": "regenerate the paper's figures and tables and check its claims",
    "fe": "finite-element run (built-in solver or CalculiX) of the tip or centre case",
    "validate": "run the FE validation (CalculiX) and write Figs 8 and 9",
    "sweep": "parameter study: damping over grids and random samples",
    "fit": "identify friction and contact stiffness from measured loops",
    "case": "case files: write a template, check a file",
    "joint": "describing function of a joint: stiffness, damping, loss factor",
    "modal": "nonlinear modal analysis: frequency and damping ratio vs amplitude",
    "frf": "forced response: frequency-response curves through the resonance",
    "reduce": "reduced model of your mesh with every contact node, for modal and frf",
    "report": "HTML report of a case: loops, damping, FE comparison, validity",
})

#: Subcommand modules, in the order ``--help`` lists them.
SUBCOMMANDS = tuple(COMMANDS)


class UsageError(Exception):
    """A command-line mistake (unknown option, bad value syntax)."""


class Parser(argparse.ArgumentParser):
    """An ArgumentParser that raises instead of printing usage and exiting."""

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def build_parser(argv: Sequence[str] | None = None) -> Parser:
    """The parser of the command line ``argv``: the full parser of the command it names (the
    first argument that is not an option), the others by their summary only; without
    ``argv`` every command's full parser."""
    chosen = _command(argv) if argv is not None else None
    parser = Parser(
        prog="microslip",
        description="Microslip friction damping in clamped joints (Lord & Rongong 2016). "
        "Units: N, mm, MPa, N·mm.", epilog=EXIT_STATUS,
    )
    parser.add_argument("--version", action="version", version=f"microslip {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    for name, summary in COMMANDS.items():
        if argv is None or name == chosen:
            importlib.import_module(f"{__package__}.{name}").add_parser(sub)
        else:
            sub.add_parser(name, help=summary)
    return parser


def _command(argv: Sequence[str]) -> str | None:
    """The command that ``argv`` names (its first argument not an option), or None."""
    return next((a for a in argv if not a.startswith("-")), None)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code (0 success, 1 failure, 2 usage, 3 a result
    that did not settle (:data:`EXIT_UNSETTLED`), 130 interrupted: Ctrl-C at any moment is
    one line, never a traceback)."""
    try:
        return _main(argv)
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # Ctrl-C wrapped by a library (e.g. while numba compiles)
        if not _interrupted(exc):
            raise
        print("error: interrupted", file=sys.stderr)
        return 130


def _interrupted(exc: BaseException) -> bool:
    """True if a KeyboardInterrupt is in the cause or context chain of ``exc``."""
    seen: set[int] = set()
    e: BaseException | None = exc
    while e is not None and id(e) not in seen:
        if isinstance(e, KeyboardInterrupt):
            return True
        seen.add(id(e))
        e = e.__cause__ or e.__context__
    return False


def _main(argv: Sequence[str] | None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(argv)
    try:
        args = parse_args(parser, argv)  # with --case FILE.toml: the file's keys as defaults
    except UsageError as exc:
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except SystemExit as exc:  # --help and --version
        return exc.code if isinstance(exc.code, int) else 0
    except MicroslipError as exc:  # an unreadable or invalid case file
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 1
    try:
        with case_output(args):
            return int(args.func(args))
    except MicroslipError as exc:
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 1
    except UsageError as exc:  # conflicting options found by the command itself
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into head & co.
        return 0
    except OSError as exc:  # a file system failure the checks before the work could not see
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"error: {where}{_one_line(exc.strerror or str(exc))}", file=sys.stderr)
        return 1


def _one_line(text: str) -> str:
    return " ".join(text.split())


def entry() -> None:
    """Console-script entry point."""
    sys.exit(main())
