"""``microslip modal --mesh FILE``: a mode's frequency and damping ratio against amplitude,
on the structure of the user's own mesh.

``--solver fe`` is the truth: quasi-static modal analysis of the full frictional FE
(:func:`microslip.fe.builtin.qsma.qsma`, Lacayo and Allen 2019); the stuck and free linear
modes come first (:func:`microslip.fe.builtin.modes.linear_modes`). This module parses and
prints. Units: Hz, mm, N, kg/m^3.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from ..case.table import add_option, mesh_file, number
from ..errors import ParameterError
from .common import check_plot, print_json
from .ownmesh import REQUIRED as MESH_REQUIRED
from .ownmesh import given, verb

__all__ = ["MESH_SOLVERS", "add_modal_mesh_options", "run_modal_mesh"]

#: What ``modal --mesh ... --solver`` computes; only ``fe`` is built (issue 23).
MESH_SOLVERS = {
    "fe": "quasi-static modal analysis of the full frictional FE (the truth)",
    "rom": "EPMC by harmonic balance on a Craig-Bampton model that keeps every contact node "
           "with the FE's own contact law (--rom-modes fixed-interface modes)",
}
#: Destinations of the one-mode / structure-file / joint options: refused with --mesh.
NOT_WITH_MESH = ("frequency", "stuck_frequency", "modal_mass", "damping_ratio",
                 "participation", "structure", "joint_dof", "coupling", "joint",
                 "joint_stiffness", "slip_force", "chi", "beta", "elements", "preset",
                 "length", "width", "thickness", "method", "transverse", "pairing",
                 "fe_mesh")
#: Options of --mesh only.
MESH_ONLY = ("contact_set", "clamp_set", "normal_contact", "normal_slope", "density",
             "response_set", "solver", "workers", "rom_modes")
#: Highest mode number ``--mode`` takes with --mesh (the eigen-solve computes that many).
MAX_MODE = 50
REQUIRED = {**MESH_REQUIRED, "density": "--density KG/M3"}


def add_modal_mesh_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("the structure of your own mesh (--mesh FILE; docs/ownmesh.md)")
    g.add_argument("--mesh", metavar="FILE", type=mesh_file,
                   help="a hexahedral mesh of your structure with its clamp (.inp, .msh, "
                        ".vtu, ...): its modes and the damping its clamp gives them")
    add_option(g, "contact_set")
    add_option(g, "clamp_set")
    g.add_argument("--normal-contact", choices=["fixed", "penalty"], default=None,
                   help="fixed: the clamping step's normal forces; penalty: --normal-slope, "
                        "lift-off allowed (default fixed)")
    g.add_argument("--normal-slope", type=number, default=None, metavar="N/MM3",
                   help="penalty normal stiffness per area, N/mm^3 (default 1e5)")
    g.add_argument("--density", type=number, default=None, metavar="KG/M3",
                   help="density of the body, kg/m^3 (aluminium 2700, steel 7850)")
    g.add_argument("--response-set", metavar="NAME", default=None,
                   help="set whose mean displacement along the mode is the amplitude "
                        "(amplitude_mm)")
    g.add_argument("--solver", choices=list(MESH_SOLVERS), default=None,
                   help="; ".join(f"{k}: {v}" for k, v in MESH_SOLVERS.items())
                   + " (default fe)")
    g.add_argument("--rom-modes", type=int, default=None, metavar="N",
                   help="rom: fixed-interface modes kept (default 60; the ROM's stuck "
                        "frequencies then equal the full FE's to about 1e-6)")
    g.add_argument("--workers", type=int, default=None, metavar="N",
                   help="local processes for the amplitudes (independent runs; default 1)")
    g.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="a Dask scheduler (tcp://HOST:8786) to run the amplitudes on")


def _nulls(values: Any) -> list[float | None]:
    """A column for JSON: NaN (an amplitude that failed; its reason is in ``warnings``) as
    null."""
    return [None if v is None or math.isnan(v) else float(v) for v in values]



def refuse_mesh_options(args: argparse.Namespace) -> None:
    """Without --mesh, the mesh's options given on the command line are refused."""
    bad = [f"--{d.replace('_', '-')}" for d in (*MESH_ONLY, "scheduler") if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to modal --mesh FILE only; remove "
                             "them")


def _check(args: argparse.Namespace) -> None:
    bad = [f"--{d.replace('_', '-')}" for d in NOT_WITH_MESH if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} not used with --mesh (the mesh gives the "
                             "structure, its contact the joint)")
    missing = [flag for dest, flag in REQUIRED.items() if getattr(args, dest, None) is None]
    for dest in ("contact_set", "clamp_set"):
        if getattr(args, dest, None) is None:
            missing.insert(0, f"--{dest.replace('_', '-')} NAME")
    if missing:
        raise ParameterError(f"--mesh {args.mesh} needs {', '.join(missing)}")
    if args.normal_contact != "penalty" and args.normal_slope is not None:
        raise ParameterError("--normal-slope needs --normal-contact penalty")
    solver = args.solver or "fe"
    if solver == "fe":
        bad = [flag for dest, flag in (("harmonics", "--harmonics"), ("rom_modes",
               "--rom-modes")) if given(args, dest)]
        if bad:
            raise ParameterError(f"{', '.join(bad)} {verb(bad)} to --solver rom only")
    elif given(args, "workers") or given(args, "scheduler"):
        raise ParameterError("--workers and --scheduler apply to --solver fe only")
    if not 1 <= args.amplitudes <= 200:
        raise ParameterError(f"--amplitudes must be in [1, 200] with --mesh, got "
                             f"{args.amplitudes}")


def _forces(args: argparse.Namespace, model: Any, modes: Any, number: int) -> Any:
    """The modal force levels: the grid from first slip to near gross sliding, or
    --amplitude-range mapped through the stuck mode (linear: the response set's amplitude is
    q r / omega^2 at modal force q, r its motion per unit modal coordinate)."""
    import numpy as np

    from ..fe.builtin.qsma import qsma_amplitudes

    mode = modes.select(number)
    if args.amplitude_range is None:
        return qsma_amplitudes(model, mode, args.amplitudes)
    lo, hi = args.amplitude_range
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ParameterError(f"--amplitude-range must satisfy 0 < MIN <= MAX (mm), got "
                             f"{lo:g} {hi:g}")
    r = float(np.linalg.norm(modes.response_motion[number - 1]))
    omega2 = (2 * math.pi * mode.frequency_Hz) ** 2
    return np.geomspace(lo, hi, args.amplitudes) * omega2 / r


def run_modal_mesh(args: argparse.Namespace) -> int:
    from ..fe.builtin.meshmodel import build_mesh_model
    from ..fe.builtin.modes import linear_modes
    from ..fe.builtin.qsma import qsma
    from ..fe.constants import DEFAULT_NORMAL_SLOPE
    from ..fe.meshcheck import check_roles
    from ..fe.meshfile import read_mesh

    _check(args)
    check_plot(args.plot)
    mesh = read_mesh(args.mesh)
    check_roles(mesh, args.contact_set, args.clamp_set,
                [args.response_set] if args.response_set else [])
    model = build_mesh_model(
        mesh, contact_set=args.contact_set, clamp_set=args.clamp_set,
        normal_force=float(args.normal_force), modulus=float(args.modulus),
        poisson_ratio=float(args.poisson_ratio), friction=float(args.friction),
        stick_slope=float(args.stick_slope),
        normal_contact=args.normal_contact or "fixed",
        normal_slope=DEFAULT_NORMAL_SLOPE if args.normal_slope is None else args.normal_slope)
    number_ = 1 if args.mode is None else args.mode
    if not 1 <= number_ <= MAX_MODE:
        raise ParameterError(f"--mode must be in [1, {MAX_MODE}] with --mesh, got {number_}")
    n = max(6, number_)
    stuck = linear_modes(model, args.density, n, "stuck", args.response_set)
    free = linear_modes(model, args.density, n, "free", args.response_set)
    mode = stuck.select(number_)

    forces = _forces(args, model, stuck, number_)
    if (args.solver or "fe") == "rom":
        return _rom(args, model, stuck, number_, forces, free)

    def progress(done: int, total: int, eta: float) -> None:
        if not args.json:
            print(f"\r  amplitude {done}/{total}, about {eta:.0f} s left", end="",
                  file=sys.stderr, flush=True)

    curve = qsma(model, mode, forces, workers=args.workers or 1,
                 scheduler=args.scheduler, progress=progress)
    if not args.json:
        print(file=sys.stderr)
    summary = curve.summary()
    out = {"mesh": args.mesh, "solver": args.solver or "fe", "mode": number_,
           "label": summary["label"], "density_kg_m3": args.density,
           "linear_frequencies_Hz": [float(f) for f in stuck.frequencies_Hz],
           "free_frequencies_Hz": [float(f) for f in free.frequencies_Hz],
           "modes": stuck.summary(),
           "amplitude_mm": _nulls(summary["amplitude_mm"]),
           "frequency_Hz": _nulls(summary["frequency_Hz"]),
           "secant_frequency_Hz": _nulls(summary["secant_frequency_Hz"]),
           "damping_ratio": _nulls(summary["damping_ratio"]),
           "modal_force": summary["force"],
           "dissipated_energy_Nmm": _nulls(summary["dissipated_energy_Nmm"]),
           "slip_fraction": _nulls(summary["slip_fraction"]), "warnings": summary["warnings"]}
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.plot:
        from ..plot.ownmesh import plot_qsma

        plot_qsma(out, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(f"mesh {args.mesh}: mode {number_} ({out['label']}), stuck "
          f"{out['linear_frequencies_Hz'][number_ - 1]:.6g} Hz, free "
          f"{out['free_frequencies_Hz'][number_ - 1]:.6g} Hz; quasi-static modal analysis "
          "of the full FE")
    print(f"{'a (mm)':>12} {'f (Hz)':>12} {'f_sec (Hz)':>12} {'zeta (-)':>12} "
          f"{'slip (-)':>9}")
    for row in zip(out["amplitude_mm"], out["frequency_Hz"], out["secant_frequency_Hz"],
                   out["damping_ratio"], out["slip_fraction"], strict=True):
        if row[0] is None:
            print(f"{'failed':>12} (see the warnings)")
            continue
        print("{:12.5g} {:12.7g} {:12.7g} {:12.5g} {:9.3f}".format(*row))
    return 0


def _rom(args: argparse.Namespace, model: Any, stuck: Any, number: int, forces: Any,
         free: Any) -> int:
    """``--solver rom``: EPMC on the contact-node ROM over the amplitudes of the force grid
    (through the stuck mode: a = q r / omega^2, the response set's amplitude)."""
    import numpy as np

    from ..dynamics.modal import epmc
    from ..dynamics.modal_odd import epmc_odd
    from ..fe.builtin.reduce import build_rom, rom_structure
    from .structure import balance_from_args

    mode = stuck.select(number)
    r = float(np.linalg.norm(stuck.response_motion[number - 1]))
    omega2 = (2 * math.pi * mode.frequency_Hz) ** 2
    if args.amplitude_range is not None:
        lo, hi = args.amplitude_range
        amps = np.geomspace(lo, hi, args.amplitudes)
    else:
        amps = np.asarray(forces) * r / omega2
    harmonics, samples = balance_from_args(args)
    rom = build_rom(model, args.density, modes=args.rom_modes or 60,
                    response_set=args.response_set)
    structure = rom_structure(rom, mode.direction @ rom.output)
    method = epmc if rom.per_node == 3 else epmc_odd  # odd joint forces: odd harmonics only
    curve = method(structure, amps, harmonics, samples, number - 1)
    out = {"mesh": args.mesh, "solver": "rom", "mode": number, "label": mode.label,
           "density_kg_m3": args.density,
           "linear_frequencies_Hz": [float(f) for f in stuck.frequencies_Hz],
           "free_frequencies_Hz": [float(f) for f in free.frequencies_Hz],
           "rom_frequencies_Hz": [float(f) for f in rom.stuck_frequencies(len(
               stuck.frequencies_Hz))],
           "rom": {"dofs": rom.dofs, "fixed_interface_modes": args.rom_modes or 60,
                   "contact_nodes": len(rom.slip_force),
                   "harmonics": curve.harmonics, "samples": curve.samples},
           "amplitude_mm": [float(a) for a in curve.amplitude],
           "frequency_Hz": [float(f) for f in curve.frequency],
           "damping_ratio": [float(z) for z in curve.damping_ratio], "warnings": []}
    if args.json:
        print_json(out)
        return 0
    print(f"mesh {args.mesh}: mode {number} ({mode.label}), stuck "
          f"{out['linear_frequencies_Hz'][number - 1]:.6g} Hz; EPMC on the contact-node ROM "
          f"({rom.dofs} DOF, {curve.harmonics} harmonics)")
    print(f"{'a (mm)':>12} {'f (Hz)':>12} {'zeta (-)':>12}")
    for row in zip(out["amplitude_mm"], out["frequency_Hz"], out["damping_ratio"],
                   strict=True):
        print("{:12.5g} {:12.7g} {:12.5g}".format(*row))
    return 0
