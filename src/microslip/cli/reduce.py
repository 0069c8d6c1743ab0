"""``microslip reduce``: the reduced model of the user's mesh with every contact node, written
as a structure file that ``modal --structure`` and ``frf --structure`` read.

Craig-Bampton with the contact nodes' dofs kept and fixed-interface modes chosen by count
(``--rom-modes``) or frequency (``--cutoff-frequency``), each contact node its own law
(:mod:`microslip.meshdynamics.reduce`). Before the file is written the ROM's lowest six stuck
frequencies are compared with the full FE's for a few mode counts up to the chosen one, so
that the user sees whether the modes suffice. The file is written to a temporary name and
renamed: never half-written. This module parses and prints. Units: Hz, s, kg/m^3, N, mm.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from typing import Any

import numpy as np

from ..case.options import add_case_option
from ..case.table import DEFAULT_ROM_MODES, MAX_ROM_MODES, add_option
from ..conventions import DEFAULT_STICK_SLOPE
from ..errors import ParameterError
from .common import print_json
from .meshstructure import (
    add_mesh_structure_options,
    check_density,
    density_needed,
    structure_case,
)

__all__ = ["COMPARE", "MAX_ROM_MODES", "WARN_ERROR", "add_parser", "mode_counts", "run"]

#: Stuck frequencies compared with the full FE's.
COMPARE = 6
#: Largest relative error of the compared frequencies before a warning.
WARN_ERROR = 1e-3
#: What the ROM's contact nodes carry, by --normal-contact.
ELEMENTS = {"fixed": "a 2-D circular Jenkins element per contact node at its clamping-step "
                     "normal force",
            "penalty": "a 3-D contact element per contact node (normal penalty with lift-off, "
                       "slip limit mu N(t))"}
#: Response-set motion labels by global axis.
AXES = ("x", "y", "z")


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "reduce", help="reduced model of your mesh with every contact node, for modal and frf",
        description="Craig-Bampton reduced model of the clamped structure of your own mesh "
        "that keeps every contact node's dofs, each with the FE's own contact law, and "
        "fixed-interface modes by count or frequency; shows the convergence of its stuck "
        "frequencies against the full FE and writes it as a structure file (.npz) that "
        "microslip modal --structure and frf --structure read. Units: N, mm, MPa, kg/m^3, Hz.")
    g = p.add_argument_group("the structure (docs/ownmesh.md)")
    add_option(g, "normal_force")
    add_option(g, "friction")
    add_option(g, "stick_slope", default=DEFAULT_STICK_SLOPE)
    add_option(g, "modulus")
    add_option(g, "poisson_ratio")
    add_mesh_structure_options(g, "a set of the mesh: each stuck mode is labelled by the "
                                  "direction (global x, y, z) of its mean displacement")
    r = p.add_argument_group("the reduced model (--rom-modes or --cutoff-frequency)")
    add_option(r, "rom_modes", note=f"default {DEFAULT_ROM_MODES} unless --cutoff-frequency "
               "is given")
    add_option(r, "cutoff_frequency")
    o = p.add_argument_group("output")
    add_option(o, "out", metavar="FILE.npz", help="the structure file to write (.npz; written "
               "to a temporary name and renamed)")
    add_option(o, "json")
    add_case_option(p, "a case file with the clamp ([material], [contact], [clamping]) and "
                    "[mesh] (file, contact_set, clamp_set, normal_contact, normal_slope, "
                    "density, response_set; docs/casefile.md); the ROM's options come from the "
                    "command line; options given here win")
    p.set_defaults(func=run)


def mode_counts(modes: int) -> list[int]:
    """Mode counts of the convergence table: about 1/8, 1/4, 1/2 of ``modes`` and itself."""
    return sorted({max(1, round(modes * f)) for f in (0.125, 0.25, 0.5)} | {modes})


def _check(args: argparse.Namespace) -> None:
    from ..case.assembly import MissingInput, build_assembly
    from .main import UsageError

    missing: list[str] = []
    try:
        build_assembly(vars(args), lambda d: "--" + d.replace("_", "-"))
    except MissingInput as exc:
        missing += exc.missing
    except ParameterError:
        pass  # a bad value: said in one line once the assembly is built (structure_case)
    missing += density_needed(args)
    if args.mesh is None:
        missing.insert(0, "--mesh FILE")
    if args.out is None:
        missing.append("--out FILE.npz")
    if missing:  # a usage mistake, as argparse's own "required" (exit 2)
        raise UsageError("microslip reduce: the following arguments are required: "
                         f"{', '.join(missing)}")
    if args.density is not None:
        check_density(args.density)
    if args.rom_modes is not None and args.cutoff_frequency is not None:
        raise UsageError("microslip reduce: argument --cutoff-frequency: not allowed with "
                         "argument --rom-modes (give one: the modes kept by count or by "
                         "frequency)")
    if args.rom_modes is None and args.cutoff_frequency is None:
        args.rom_modes = DEFAULT_ROM_MODES  # the default the help promises
    if args.rom_modes is not None and not 1 <= args.rom_modes <= MAX_ROM_MODES:
        raise ParameterError(f"--rom-modes must be in [1, {MAX_ROM_MODES}], got "
                             f"{args.rom_modes}")
    f = args.cutoff_frequency
    if f is not None and not (math.isfinite(f) and f > 0.0):
        raise ParameterError(f"--cutoff-frequency must be finite and > 0 Hz, got {f:g}")
    if args.normal_contact != "penalty" and args.normal_slope is not None:
        raise ParameterError("--normal-slope needs --normal-contact penalty")


def run(args: argparse.Namespace) -> int:
    from ..io import check_writable
    from ..meshdynamics.reduce import build_rom, convergence, full_mass, write_rom

    _check(args)
    check_writable(args.out, (".npz",), "--out")
    from ..meshdynamics.case import clamped

    case = structure_case(args)
    model = clamped(case)
    args.density = case.density  # --density, or a material's own (each body's own in M)
    t0 = time.perf_counter()
    mass = full_mass(model, case.density)
    rom = build_rom(model, case.density, modes=args.rom_modes, cutoff_hz=args.cutoff_frequency,
                    response_set=args.response_set, mass=mass)
    build_s = time.perf_counter() - t0
    table = convergence(model, case.density, mode_counts(rom.modes), COMPARE, mass, rom=rom)
    write_rom(args.out, rom)
    out = _summary(args, model, rom, build_s, table)
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.json:
        print_json(out)
        return 0
    _print(out)
    return 0


def _summary(args: argparse.Namespace, model: Any, rom: Any, build_s: float,
             table: dict[str, Any]) -> dict[str, Any]:
    errors = np.asarray(table["relative_error"])
    worst = float(np.max(np.abs(errors[-1])))
    warnings = []
    if worst > WARN_ERROR:
        warnings.append(f"with {rom.modes} fixed-interface modes the ROM's lowest {COMPARE} "
                        f"stuck frequencies are up to {100 * worst:.2g} % off the full FE's; "
                        "keep more modes (--rom-modes, --cutoff-frequency)")
    normal = args.normal_contact or "fixed"
    out: dict[str, Any] = {
        "mesh": args.mesh, "dof": int(model.dof), "contact_nodes": int(rom.slip_force.size),
        "normal_contact": normal, "contact_element": ELEMENTS[normal],
        "density_kg_m3": args.density,
        "rom": {"dofs": rom.dofs, "contact_dofs": int(rom.boundary.size),
                "fixed_interface_modes": rom.modes,
                "highest_interface_frequency_Hz": float(rom.interface_frequencies[-1]),
                "cutoff_frequency_Hz": args.cutoff_frequency, "build_s": build_s},
        "full_frequencies_Hz": [float(f) for f in table["full_Hz"]],
        "rom_frequencies_Hz": [float(f) for f in rom.stuck_frequencies(COMPARE)],
        "convergence": {"modes": list(table["modes"]),
                        "relative_error": errors.tolist()},
        "out": args.out, "file_bytes": os.path.getsize(args.out), "warnings": warnings}
    if args.response_set:
        motion = rom.response_motion(COMPARE)
        out["response_set"] = args.response_set
        out["response_direction"] = motion.tolist()
    return out


def _print(out: dict[str, Any]) -> None:
    rom = out["rom"]
    print(f"mesh {out['mesh']}: {out['dof']} DOF, {out['contact_nodes']} contact nodes, "
          f"{out['normal_contact']} normal contact ({out['contact_element']}); density "
          f"{out['density_kg_m3']:g} kg/m^3")
    print(f"ROM: {rom['dofs']} DOF = {rom['contact_dofs']} contact DOF + "
          f"{rom['fixed_interface_modes']} fixed-interface modes (up to "
          f"{rom['highest_interface_frequency_Hz']:.6g} Hz), built in {rom['build_s']:.2f} s")
    moves = out.get("response_direction")
    head = f"{'mode':>5} {'full FE (Hz)':>14} {'ROM (Hz)':>14} {'rel. error (-)':>15}"
    print(head + (f"  {out['response_set']} moves along" if moves else ""))
    err = out["convergence"]["relative_error"][-1]
    for i, (f, g, e) in enumerate(zip(out["full_frequencies_Hz"], out["rom_frequencies_Hz"],
                                      err, strict=True)):
        along = ""
        if moves:
            m = np.abs(moves[i])
            along = f"  {AXES[int(np.argmax(m))]} ({', '.join(f'{v:.2f}' for v in moves[i])})"
        print(f"{i + 1:>5} {f:>14.7g} {g:>14.7g} {e:>15.2e}{along}")
    print("convergence: largest relative error of the lowest "
          f"{len(out['full_frequencies_Hz'])} stuck frequencies against the full FE (-)")
    for n, row in zip(out["convergence"]["modes"], out["convergence"]["relative_error"],
                      strict=True):
        print(f"{n:>7} modes {max(abs(e) for e in row):>10.2e}")
    print(f"wrote {out['out']} ({out['file_bytes'] / 1024:.0f} kB, {out['contact_nodes']} "
          f"contact joints with their own laws); use it with: microslip modal --structure "
          f"{out['out']} --mode N --amplitude-range MIN MAX")
