"""``microslip case``: write a commented case-file template, or check a case file."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

from ..errors import ParameterError
from .common import print_json

__all__ = ["add_parser", "run_check", "run_new"]


def add_parser(sub: Any) -> None:
    p = sub.add_parser("case", help="case files: write a template, check a file",
                       description="A case file (TOML) describes a joint and its load case; "
                       "every command reads it with --case FILE.toml. See docs/casefile.md.")
    actions = p.add_subparsers(dest="case_command", metavar="ACTION", parser_class=type(p))
    actions.required = True
    new = actions.add_parser("new", help="write a commented template (every key, unit, range, "
                             "default)")
    new.add_argument("file", metavar="FILE.toml")
    new.add_argument("--force", action="store_true", help="overwrite an existing file")
    new.set_defaults(func=run_new)
    check = actions.add_parser("check", help="read a case file and print it resolved, with "
                               "units")
    check.add_argument("file", metavar="FILE.toml")
    check.add_argument("--json", action="store_true", help="print one JSON object")
    check.set_defaults(func=run_check)


def run_new(args: argparse.Namespace) -> int:
    from ..case import template
    from ..io import atomic_write

    if os.path.lexists(args.file) and not args.force:
        raise ParameterError(f"{args.file} exists; give --force to overwrite it")
    if os.path.isdir(args.file):
        raise ParameterError(f"{args.file} is a directory; give a file name")
    try:
        with atomic_write(args.file) as fh:
            fh.write(template())
    except OSError as exc:
        raise ParameterError(f"cannot write {args.file}: {exc.strerror or exc}") from None
    print(f"wrote {args.file} (case-file template; edit it, then run e.g. "
          f"microslip loop --case {args.file})")
    return 0


def run_check(args: argparse.Namespace) -> int:
    from ..case import KEYS, load_case

    case = load_case(args.file)
    for line in case.warnings:
        print(f"warning: {line}", file=sys.stderr)
    amplitude = case.amplitude()
    if args.json:
        print_json({"case_file": args.file, "values": dict(case.values),
                    "params": None if case.params is None else case.params.as_dict(),
                    "amplitude_N": amplitude, "warnings": list(case.warnings)})
        return 0
    print(f"case file {args.file}" + (f" ({case.name})" if case.name else ""))
    for key in KEYS:
        value = case.get(key.dotted)
        if value is None or value == "":
            continue
        given = "" if key.dotted in case.values else "  (default)"
        shown = value if isinstance(value, str) else f"{value:.6g}"
        print(f"  {key.dotted:<30s} {shown} {key.unit}".rstrip() + given)
    if amplitude is not None:
        print(f"  {'resolved amplitude F0':<30s} {amplitude:.6g} N")
    return 0
