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


def _mesh_text(case_file: str, mesh: str) -> str:
    """The template of a case of ``mesh`` (its sets read from the file); the mesh's path is
    written relative to the case file's directory, as the case file reads it."""
    from ..case.template import mesh_template
    from ..fe.meshfile import read_mesh

    m = read_mesh(mesh)
    where = os.path.dirname(os.path.abspath(case_file))
    return mesh_template(os.path.relpath(os.path.abspath(mesh), where),
                         tuple(sorted(m.node_sets)), tuple(sorted(m.surfaces)))


def run_new(args: argparse.Namespace) -> int:
    from ..case import template
    from ..io import atomic_write

    if os.path.lexists(args.file) and not args.overwrite:
        raise ParameterError(f"{args.file} exists; give --force to overwrite it")
    if os.path.isdir(args.file):
        raise ParameterError(f"{args.file} is a directory; give a file name")
    if args.mesh is not None and not os.path.isfile(args.mesh):
        raise ParameterError(f"no mesh file {args.mesh!r} (.inp, .msh, .vtu, ...)")
    text = template() if args.mesh is None else _mesh_text(args.file, args.mesh)
    try:
        with atomic_write(args.file) as fh:
            fh.write(text)
    except OSError as exc:
        raise ParameterError(f"cannot write {args.file}: {exc.strerror or exc}") from None
    run = (f"microslip loop --case {args.file}" if args.mesh is None
           else f"microslip fe --case {args.file} once it has its [[mesh.load]] tables")
    what = "case-file template" if args.mesh is None else f"case of {args.mesh}"
    print(f"wrote {args.file} ({what}; edit it, then run e.g. {run})")
    return 0


def run_check(args: argparse.Namespace) -> int:
    from ..case import load_case

    case = load_case(args.file)
    for line in case.warnings:
        print(f"warning: {line}", file=sys.stderr)
    mesh = "mesh.file" in case.values
    amplitude = None if mesh else case.amplitude()
    if args.json:
        print_json({"case_file": args.file, "values": dict(case.values),
                    "params": None if case.params is None else case.params.as_dict(),
                    "amplitude_N": amplitude, "warnings": list(case.warnings),
                    **({"mesh_loads": [_load_json(ld) for ld in case.mesh_loads]}
                       if mesh else {})})
        return 0
    print(f"case file {args.file}" + (f" ({case.name})" if case.name else ""))
    if mesh:
        print("\n".join(_mesh_lines(case)))
        return 0
    for line in _key_lines(case, ()):
        print(line)
    if amplitude is not None:
        print(f"  {'resolved amplitude F0':<30s} {amplitude:.6g} N")
    return 0


def _key_lines(case: Any, sections: tuple[str, ...]) -> list[str]:
    """One line per key the case sets or defaults (only ``sections`` if given), with its
    unit; a default is marked."""
    from ..case import KEYS

    out = []
    for key in KEYS:
        if sections and key.section not in sections:
            continue
        value = case.get(key.dotted)
        if value is None or value == "":
            continue
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


def _load_json(load: Any) -> dict[str, Any]:
    return {"set": load.set, "direction": list(load.direction), "amplitude_N": load.amplitude,
            "phase_deg": load.phase_deg}
