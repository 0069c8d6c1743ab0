"""``--case FILE.toml`` on every command: the case file becomes the subcommand's defaults.

:func:`parse_args` parses the command line once with every default held back, so that the
namespace holds exactly the options given; it loads the case, turns its keys into values
through the option table (:data:`CASE_OPTIONS`), and fills in what the command line left
out: the case's values, then the defaults. Explicit options win.
A section (or key) the command does not read is ignored, with one note on stderr: a case
file describes one clamp for every command; only unknown or misspelled keys are errors.
"""

from __future__ import annotations

import argparse
import contextlib
import contextvars
import sys
from collections.abc import Collection, Iterator, Sequence
from typing import Any

from ..errors import ParameterError
from ..params import preset
from .model import Case, load_case
from .schema import CLAMP_KEYS
from .table import CASE_DESTS, OPTIONS, add_option
from .units import IMPOSSIBLE, check_impossible, plausibility_warnings

__all__ = ["CASE_OPTIONS", "add_case_option", "annotate_json", "case_output", "parse_args",
           "unread", "warn"]

#: Commands that read the planar load case ([load.planar]); every other command reads [load].
PLANAR_COMMANDS = ("planar",)

#: Commands that read a mesh of the user's own with its loads ([mesh] and its [[mesh.load]]
#: tables): the frictional FE on the mesh.
MESH_COMMANDS = ("fe", "validate")

#: Commands that read the [mesh] section (file, sets, contact, density, mode, response set)
#: but not its loads: the structure of the user's mesh. ``modal`` and ``frf`` read it unless
#: the command line or the case gives another structure (:func:`_structure_given`).
MESH_STRUCTURE_COMMANDS = ("reduce", "modal", "frf")

#: Commands of a structure: they read [structure] and [[joint]], and no load case (their
#: excitation is --force).
STRUCTURE_COMMANDS = ("modal", "frf")

#: Destinations of the joint options of the command line (``--joint``, ``--joint-dof``, the
#: joint's parameters and its clamp): a case with [[joint]] tables gives them instead.
#: From the option table: the options of a ``[[joint]]`` key but the structure's coupling,
#: the stick slope, and the clamp.
JOINT_DESTS = ("joint_dof", *(o.name for o in OPTIONS.values()
                              if o.joint_key is not None and o.name != "coupling"),
               "stick_slope", "preset", *CLAMP_KEYS.values())

#: Case key -> (argparse destination, which load case reads it: "load", "planar" or "all"),
#: from the option table. Keys not listed (name, description, preset) map to no option.
CASE_OPTIONS: dict[str, tuple[str, str]] = CASE_DESTS

#: Destinations checked for plausible units (case values and command-line options alike).
UNIT_DESTS = ("length", "width", "thickness", "modulus", "friction", "normal_force")

_ACTIVE: contextvars.ContextVar[dict[str, Any] | None] = contextvars.ContextVar(
    "microslip_case_output", default=None)


def add_case_option(parser: argparse.ArgumentParser, help: str | None = None) -> None:
    """Add ``--case FILE.toml`` to a subcommand's parser (docs/casefile.md); ``help``: what
    this command reads of the case file, if not the joint and load case."""
    add_option(parser, "case", help=help)


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    raise LookupError("subcommands")  # pragma: no cover - build_parser always has them


@contextlib.contextmanager
def _only_given(parser: argparse.ArgumentParser) -> Iterator[None]:
    """While parsing: every option of every subcommand defaults to nothing (SUPPRESS) and none
    is required, and the subcommands set no defaults, so the namespace holds exactly what the
    command line gives; the defaults come afterwards (:func:`_complete`)."""
    subs = list(_subparsers(parser).values())
    saved = [(a, a.default, a.required) for p in subs for a in p._actions if a.option_strings]
    defaults = [(p, dict(p._defaults)) for p in subs]
    try:
        for a, _, _ in saved:
            a.default, a.required = argparse.SUPPRESS, False
        for p, _ in defaults:
            p._defaults.clear()
        yield
    finally:
        for a, default, required in saved:
            a.default, a.required = default, required
        for p, kept in defaults:
            p._defaults.update(kept)


def _complete(sub: argparse.ArgumentParser, args: argparse.Namespace,
              case_values: dict[str, Any]) -> None:
    """Fill in what the command line left out: the case's values, else the defaults (string
    defaults through the option's type, as argparse does); refuse a required option that
    neither gives."""
    missing = []
    for a in sub._actions:
        if not a.option_strings or a.dest == argparse.SUPPRESS or hasattr(args, a.dest):
            continue
        if a.dest in case_values:
            value = case_values[a.dest]
        elif a.required:
            missing.append(argparse._get_action_name(a))
            continue
        elif a.default is argparse.SUPPRESS:
            continue
        else:
            value = a.default
        if isinstance(value, str) and a.type is not None:
            try:
                value = sub._get_value(a, value)
            except argparse.ArgumentError as exc:
                sub.error(str(exc))
        setattr(args, a.dest, value)
    if missing:
        sub.error(f"the following arguments are required: {', '.join(map(str, missing))}")
    for dest, value in sub._defaults.items():
        if not hasattr(args, dest):
            setattr(args, dest, value)


def _reads(command: str, scope: str) -> bool:
    """True if ``command`` reads keys of ``scope`` ("all", "load", "planar" or "mesh")."""
    if scope == "all":
        return True
    if scope == "mesh":
        return command in MESH_COMMANDS or command in MESH_STRUCTURE_COMMANDS
    if scope == "planar":
        return command in PLANAR_COMMANDS
    return command not in PLANAR_COMMANDS and command not in STRUCTURE_COMMANDS


#: Destinations of a structure that is not the case's mesh (``modal``, ``frf``): given on the
#: command line, they leave the [mesh] section unread.
OTHER_STRUCTURE = ("structure", "frequency", "stuck_frequency", "modal_mass")


def _structure_given(case: Case, command: str, explicit: Collection[str]) -> bool:
    """True if ``modal`` or ``frf`` studies another structure than the case's mesh: a
    structure file or one mode given on the command line, or a [structure] file in the case."""
    return command in STRUCTURE_COMMANDS and (
        any(d in explicit for d in OTHER_STRUCTURE) or "structure.file" in case.values)


def _case_reads(case: Case, command: str, scope: str, explicit: Collection[str]) -> bool:
    """:func:`_reads`, and [mesh] not read by a structure command given another structure."""
    if scope == "mesh" and _structure_given(case, command, explicit):
        return False
    return _reads(command, scope)


def _section(dotted: str) -> str:
    return dotted.rsplit(".", 1)[0] if "." in dotted else ""


def unread(case: Case, command: str, dests: Collection[str],
           explicit: Collection[str] = ()) -> tuple[str, ...]:
    """What of ``case`` the command does not read: ``[section]`` when it reads none of the
    section's keys the file sets, else the dotted keys; ``[[joint]]`` for joint tables off
    modal and frf. A case file describes one clamp for every command, so these are ignored.
    """
    skipped = [k for k, (dest, scope) in CASE_OPTIONS.items()
               if k in case.values and (not _case_reads(case, command, scope, explicit)
                                        or dest not in dests)]
    out: list[str] = []
    for key in skipped:
        section = _section(key)
        whole = all(k in skipped for k in CASE_OPTIONS
                    if k in case.values and _section(k) == section)
        name = f"[{section}]" if section and whole else key
        if name not in out:
            out.append(name)
    if case.joints and command not in STRUCTURE_COMMANDS:
        out.append("[[joint]]")
    if case.mesh_loads and command not in MESH_COMMANDS:
        out.append(case.loads_as)
    return tuple(out)


def _structure_case(case: Case, command: str, explicit: dict[str, Any]) -> dict[str, Any]:
    """The checks and defaults of [[joint]] tables (modal and frf)."""
    if not case.joints or command not in STRUCTURE_COMMANDS:
        return {}
    given = [d for d in JOINT_DESTS if d in explicit]
    if given:
        flags = ", ".join("--" + d.replace("_", "-") for d in given)
        raise ParameterError(f"{flags} conflict{'s' if len(given) == 1 else ''} with the "
                             f"[[joint]] tables of case {case.source}; set the joints in the "
                             "case file, or leave them out of it")
    return {"joint": None}


def _amplitude_swept(explicit: dict[str, Any]) -> bool:
    """True if the command line varies the amplitude itself (sweep) or takes none."""
    if "amplitude_range" in explicit or explicit.get("model") == "planar":
        return True
    specs = [*explicit.get("grid", []), *explicit.get("sample", [])]
    if not specs:
        return False
    from ..sweep import ALIASES

    names = (s.split("=", 1)[0].strip().lower() for s in specs)
    return any(ALIASES.get(n, n) == "amplitude" for n in names)


def case_defaults(case: Case, command: str, dests: dict[str, argparse.Action],
                  explicit: dict[str, Any]) -> dict[str, Any]:
    """The subcommand defaults a case gives; keys the command does not read are skipped
    (:func:`unread` names them)."""
    out: dict[str, Any] = _structure_case(case, command, explicit)
    if case.mesh_loads and command in MESH_COMMANDS and "load" not in explicit:
        out["load"] = [ld.spec() for ld in case.mesh_loads]
    for key, (dest, scope) in CASE_OPTIONS.items():
        if (key not in case.values or not _case_reads(case, command, scope, explicit)
                or dest not in dests):
            continue
        if dest in explicit or dest == "amplitude":
            continue  # the command line wins; the amplitude is resolved after the parse
        value = case.values[key]
        if isinstance(dests[dest], argparse._AppendAction):  # a repeatable option
            value = list(value) if isinstance(value, tuple) else [value]  # tables: a tuple
        out[dest] = value
    for key, (dest, scope) in CASE_OPTIONS.items():
        # a required option the file leaves out takes the default the case file documents
        # (``load.model``: tip), as the file's comment promises
        if (dest in dests and dests[dest].required and dest not in explicit
                and dest not in out and _case_reads(case, command, scope, explicit)
                and case.get(key) is not None):
            out[dest] = case.get(key)
    if case.params is not None and "preset" in dests:
        if "preset" in explicit:
            raise ParameterError(f"--preset {explicit['preset']} conflicts with the clamp of "
                                 f"case {case.source}; override single values (--length ...) "
                                 "instead")
        out["preset"] = None
    return out


def _resolve_amplitude(args: argparse.Namespace, case: Case, explicit: dict[str, Any]) -> None:
    if args.command in MESH_COMMANDS and case.mesh_loads:
        return  # the [[load]] tables are the loads of the mesh
    if (not hasattr(args, "amplitude") or "amplitude" in explicit
            or args.command in STRUCTURE_COMMANDS
            or "displacement_amplitude" in explicit or _amplitude_swept(explicit)):
        return
    base = preset(args.preset) if getattr(args, "preset", None) else None
    mu = args.friction if args.friction is not None else getattr(base, "friction", None)
    fn = (args.normal_force if args.normal_force is not None
          else getattr(base, "normal_force", None))
    amplitude = case.amplitude(mu, fn)
    if amplitude is None and "load.amplitude_fraction" in case.values:
        raise ParameterError(f"case {case.source}: load.amplitude_fraction needs the "
                             "friction and normal force of the clamp")
    if amplitude is not None:
        args.amplitude = amplitude
        if "load.amplitude" not in case.values:
            fraction = case.get("load.amplitude_fraction")
            args.amplitude_rule = (f"F0 = {fraction:g} x the slip limit mu F_N = {fraction:g} "
                                   f"x {mu:g} x {fn:g} N = {amplitude:g} N "
                                   "(load.amplitude_fraction)")


def parse_args(parser: argparse.ArgumentParser, argv: Sequence[str] | None
               ) -> argparse.Namespace:
    """Parse ``argv``; with ``--case`` the file's keys are defaults that options override.

    Prints one ``warning:`` line on stderr per implausible unit and keeps the sentences in
    ``args.input_warnings``; the destinations given on the command line are
    ``args.given_options`` (for options that apply to some modes only).
    """
    argv = None if argv is None else list(argv)
    with _only_given(parser):
        args = parser.parse_args(argv)
    sub = _subparsers(parser)[args.command]
    explicit = {a.dest: getattr(args, a.dest) for a in sub._actions
                if a.option_strings and hasattr(args, a.dest)}
    case_path = explicit.get("case")
    defaults: dict[str, Any] = {}
    if case_path is not None:
        case = load_case(case_path)
        dests = {a.dest: a for a in sub._actions}
        defaults = case_defaults(case, args.command, dests, explicit)
        skipped = unread(case, args.command, dests, explicit)
        if skipped:
            print(f"case: {', '.join(skipped)} not read by {args.command}", file=sys.stderr)
    _complete(sub, args, defaults)
    args.given_options = frozenset(explicit)
    if case_path is not None:
        _resolve_amplitude(args, case, explicit)
        args.case_name = case.name
        args.case_joints = case.joints if args.command in STRUCTURE_COMMANDS else ()
    check_impossible({d: getattr(args, d, None) for d in IMPOSSIBLE},
                     names={d: "--" + d.replace("_", "-") for d in IMPOSSIBLE})
    warnings = plausibility_warnings({d: getattr(args, d, None) for d in UNIT_DESTS})
    for line in warnings:
        print(f"warning: {line}", file=sys.stderr)
    args.input_warnings = warnings
    return args


@contextlib.contextmanager
def case_output(args: argparse.Namespace) -> Iterator[None]:
    """While a command runs: its text output starts with the case file, its JSON names it."""
    case_file = getattr(args, "case", None)
    rule = getattr(args, "amplitude_rule", None)
    notes = {"case_file": case_file, "warnings": list(getattr(args, "input_warnings", [])),
             "amplitude_rule": rule}
    if case_file is not None and not getattr(args, "json", False):
        name = getattr(args, "case_name", "")
        print(f"case file {case_file}" + (f" ({name})" if name else ""))
        if rule is not None:
            print(f"  amplitude {rule}")
    token = _ACTIVE.set(notes)
    try:
        yield
    finally:
        _ACTIVE.reset(token)


def warn(message: str) -> None:
    """One ``warning:`` line on standard error, also listed under ``warnings`` in the JSON
    output of the running command."""
    print(f"warning: {message}", file=sys.stderr)
    notes = _ACTIVE.get()
    if notes is not None:
        notes["warnings"].append(message)


def annotate_json(obj: Any) -> Any:
    """``obj`` with ``case_file`` and the unit warnings added, while a case output is active."""
    notes = _ACTIVE.get()
    if notes is None or not isinstance(obj, dict):
        return obj
    out = dict(obj)
    if notes["case_file"] is not None:
        out["case_file"] = notes["case_file"]
    if notes["amplitude_rule"] is not None:
        out["amplitude_rule"] = notes["amplitude_rule"]
    if notes["warnings"]:
        out["warnings"] = [*out.get("warnings", []), *notes["warnings"]]
    return out
