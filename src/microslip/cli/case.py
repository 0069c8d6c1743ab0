"""``microslip case``: write a commented case-file template, or check a case file."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

from ..case.table import add_option
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
    # the file a case action works on: a positional argument, the action's own subject
    new.add_argument("file", metavar="FILE.toml")
    add_option(new, "overwrite")
    add_option(new, "mesh_file", flag="--mesh", dest="mesh",
               help="a mesh of your own part (.inp, .msh, .vtu, ...): the template of its "
                    "case, the [mesh] section with its sets listed from the file, no preset "
                    "bar")
    new.set_defaults(func=run_new)
    check = actions.add_parser("check", help="read a case file and print it resolved, with "
                               "units")
    check.add_argument("file", metavar="FILE.toml")
    add_option(check, "json")
    check.set_defaults(func=run_check)


def _mesh_text(case_file: str, mesh: str) -> Any:
    """The template of a case of ``mesh`` (:class:`~microslip.case.template.MeshTemplate`:
    its sets, bodies and interfaces read from the file); the mesh's path is written relative
    to the case file's directory, as the case file reads it."""
    from ..case.meshroles import offer
    from ..case.template import mesh_template
    from ..fe.meshfile import read_mesh

    m = read_mesh(mesh)
    where = os.path.dirname(os.path.abspath(case_file))
    return mesh_template(os.path.relpath(os.path.abspath(mesh), where), offer(m))


def run_new(args: argparse.Namespace) -> int:
    from ..case import template
    from ..io import atomic_write

    if os.path.lexists(args.file) and not args.overwrite:
        raise ParameterError(f"{args.file} exists; give --force to overwrite it")
    if os.path.isdir(args.file):
        raise ParameterError(f"{args.file} is a directory; give a file name")
    if args.mesh is not None and not os.path.isfile(args.mesh):
        raise ParameterError(f"no mesh file {args.mesh!r} (.inp, .msh, .vtu, ...)")
    made = None if args.mesh is None else _mesh_text(args.file, args.mesh)
    text = template() if made is None else made.text
    try:
        with atomic_write(args.file) as fh:
            fh.write(text)
    except OSError as exc:
        raise ParameterError(f"cannot write {args.file}: {exc.strerror or exc}") from None
    run = (f"microslip loop --case {args.file}" if args.mesh is None
           else f"microslip case check {args.file}, then microslip fe --case {args.file} once "
                "it has its [[mesh.load]] tables")
    what = "case-file template" if args.mesh is None else f"case of {args.mesh}"
    print(f"wrote {args.file} ({what}; edit it, then run e.g. {run})")
    for line in () if made is None else made.unfilled:
        print(f"  to fill: {line}")
    return 0


def run_check(args: argparse.Namespace) -> int:
    from ..case import load_case

    case = load_case(args.file)
    for line in case.warnings:
        print(f"warning: {line}", file=sys.stderr)
    mesh = "mesh.file" in case.values
    amplitude = None if mesh else case.amplitude()
    errors: list[str] = []
    if mesh:
        errors, warnings = _check_mesh_case(case)
        for line in warnings:
            print(f"warning: {line}", file=sys.stderr)
    status = 1 if errors else 0
    if args.json:
        print_json({"case_file": args.file, "values": _json_values(case.values),
                    "params": None if case.params is None else case.params.as_dict(),
                    "amplitude_N": amplitude, "warnings": list(case.warnings),
                    **({"mesh_loads": [_load_json(ld) for ld in case.mesh_loads],
                        "errors": errors} if mesh else {})})
        _print_errors(errors)
        return status
    print(f"case file {args.file}" + (f" ({case.name})" if case.name else ""))
    if mesh:
        print("\n".join(_mesh_lines(case)))
        _print_errors(errors)
        return status
    for line in _key_lines(case, ()):
        print(line)
    if amplitude is not None:
        print(f"  {'resolved amplitude F0':<30s} {amplitude:.6g} N")
    return 0


def _print_errors(errors: list[str]) -> None:
    for line in errors:
        print(f"error: {line}", file=sys.stderr)


def _json_values(values: Any) -> dict[str, Any]:
    """The case's values for JSON: an assembly table as its tables' keys."""
    from dataclasses import asdict, is_dataclass

    return {k: [asdict(x) for x in v] if isinstance(v, tuple) and v and is_dataclass(v[0])
            else v for k, v in values.items()}


def _spell(dest: str) -> str:
    """A destination as the case file names it (``mesh.clamp_set``, ``[[mesh.contact]]``)."""
    from ..case.schema import TABLE_KEYS
    from ..case.table import CASE_DESTS

    for key, (d, _) in CASE_DESTS.items():
        if d == dest:
            return f"[[{key}]]" if key in TABLE_KEYS else key
    return dest


def _check_mesh_case(case: Any) -> tuple[list[str], list[str]]:
    """``case check`` of a mesh case: the assembly its keys describe (every required key
    left out named), then the mesh opened: the sets named, the materials, the bodies, and
    the values against the mesh's scale. Returns (errors, warnings), one line each."""
    from ..case.assembly import MissingInput, build_assembly
    from ..case.meshroles import check_on_mesh
    from ..case.table import CASE_DESTS
    from ..fe.meshfile import read_mesh

    values = {dest: case.values[k] for k, (dest, _) in CASE_DESTS.items()
              if k in case.values}
    values.update({dest: case.get(k) for k, (dest, _) in CASE_DESTS.items()
                   if dest in ("normal_contact",) and dest not in values})
    errors: list[str] = []
    try:
        assembly = build_assembly(values, _spell)
    except MissingInput as exc:
        errors.append(f"case {case.source}: the part needs {', '.join(exc.missing)}")
        assembly = None
    except ParameterError as exc:
        errors.append(f"case {case.source}: {exc}")
        assembly = None
    try:
        mesh = read_mesh(case.values["mesh.file"])
    except ParameterError as exc:
        return [*errors, str(exc)], []
    if assembly is None:
        return errors, []
    sets = tuple((case.values[k], role) for k, role in (
        ("mesh.response_set", "response set"),) if k in case.values)
    found = check_on_mesh(mesh, assembly, case.mesh_loads, sets, spell=_spell)
    return [*errors, *found.errors], list(found.warnings)


def _key_lines(case: Any, sections: tuple[str, ...]) -> list[str]:
    """One line per key the case sets or defaults (only ``sections`` if given), with its
    unit; a default is marked."""
    from ..case import KEYS

    out = []
    for key in KEYS:
        if sections and key.section not in sections:
            continue
        value = case.get(key.dotted)
        if value is None or value == "" or isinstance(value, tuple):
            continue  # unset, or an assembly's tables (listed by _mesh_lines)
        given = "" if key.dotted in case.values else "  (default)"
        shown = value if isinstance(value, str) else f"{value:.6g}"
        out.append(f"  {key.dotted:<30s} {shown} {key.unit}".rstrip() + given)
    return out


#: What a case of the user's own mesh describes, in the order ``case check`` shows it.
MESH_CASE_SECTIONS = ("", "material", "contact", "clamping", "mesh")


def _mesh_lines(case: Any) -> list[str]:
    """``case check`` of a case of the user's own mesh: the part (the clamp's values, the
    [mesh] keys, its loads); the mesh gives the geometry, so no bar and no F0 of a bar."""
    lines = [f"  the part is the mesh {case.values['mesh.file']} (its geometry; "
             "no preset bar)"]
    lines += [line for line in _key_lines(case, MESH_CASE_SECTIONS)
              if not line.lstrip().startswith(("clamping.pressure", "preset"))]
    from ..case.schema import TABLE_KEYS

    for dotted in TABLE_KEYS:
        for k, piece in enumerate(case.values.get(dotted, ()), 1):
            lines.append(f"  [[{dotted}]] {k}: {_piece_text(piece)}")
    if not case.mesh_loads:
        lines.append("  no [[mesh.load]] tables: fe and validate need them (or --load)")
    for k, ld in enumerate(case.mesh_loads, 1):
        d = ", ".join(f"{x:g}" for x in ld.direction)
        lines.append(f"  load {k}: {ld.amplitude:.6g} N on set {ld.set} along ({d}), phase "
                     f"{ld.phase_deg:g} degrees")
    if "mesh.density" not in case.values:
        lines.append("  no density: modal, frf, reduce and the report's structure section "
                     "need [mesh] density (kg/m^3)")
    return lines


def _piece_text(piece: Any) -> str:
    """One assembly table in words, with units."""
    from ..case.assembly import Bolt
    from ..fe.assembly import Contact, Material, Preload, Support

    if isinstance(piece, Bolt):
        shank = ("no shank" if piece.diameter is None else
                 f"a shank of {piece.diameter:.6g} mm" + (
                     "" if piece.modulus is None else f", {piece.modulus:.6g} MPa"))
        return f"{piece.force:.6g} N on {piece.head} and on {piece.nut}, {shank}"
    if isinstance(piece, Contact):
        return (f"{piece.face} on {piece.counter}" if piece.counter is not None
                else f"{piece.face} on the rigid base")
    if isinstance(piece, Preload):
        return f"{piece.force:.6g} N on {piece.face}"
    if isinstance(piece, Support):
        return f"{piece.set} held in {piece.directions}"
    if isinstance(piece, Material):
        rho = "" if piece.density is None else f", density {piece.density:.6g} kg/m^3"
        return (f"{piece.elset}: modulus {piece.modulus:.6g} MPa, Poisson's ratio "
                f"{piece.poisson_ratio:.6g}{rho}")
    return repr(piece)


def _load_json(load: Any) -> dict[str, Any]:
    return {"set": load.set, "direction": list(load.direction), "amplitude_N": load.amplitude,
            "phase_deg": load.phase_deg}
