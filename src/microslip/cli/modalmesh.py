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

from ..case.table import add_option, number
from ..errors import ParameterError
from .common import check_plot, print_json

__all__ = ["MESH_SOLVERS", "add_modal_mesh_options", "run_modal_mesh"]

#: What ``modal --mesh ... --solver`` computes; only ``fe`` is built (issue 23).
MESH_SOLVERS = {
    "fe": "quasi-static modal analysis of the full frictional FE (the truth)",
}
#: Destinations of the one-mode / structure-file / joint options: refused with --mesh.
NOT_WITH_MESH = ("frequency", "stuck_frequency", "modal_mass", "damping_ratio",
                 "participation", "structure", "joint_dof", "coupling", "joint",
                 "joint_stiffness", "slip_force", "chi", "beta", "elements", "preset",
                 "length", "width", "thickness", "method", "harmonics", "transverse",
                 "pairing", "fe_mesh")
#: Options of --mesh only.
MESH_ONLY = ("contact_set", "clamp_set", "normal_contact", "normal_slope", "density",
             "response_set", "solver", "workers")
#: Highest mode number ``--mode`` takes with --mesh (the eigen-solve computes that many).
MAX_MODE = 50
REQUIRED = {"normal_force": "--normal-force N", "friction": "--friction X",
            "modulus": "--modulus MPA", "poisson_ratio": "--poisson-ratio X",
            "density": "--density KG/M3"}


def add_modal_mesh_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("the structure of your own mesh (--mesh FILE; docs/ownmesh.md)")
    g.add_argument("--mesh", metavar="FILE",
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
    g.add_argument("--workers", type=int, default=None, metavar="N",
                   help="local processes for the amplitudes (independent runs; default 1)")
    g.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="a Dask scheduler (tcp://HOST:8786) to run the amplitudes on")


def _given(args: argparse.Namespace, dest: str) -> bool:
    return dest in getattr(args, "given_options", frozenset())


def refuse_mesh_options(args: argparse.Namespace) -> None:
    """Without --mesh, the mesh's options given on the command line are refused."""
    bad = [f"--{d.replace('_', '-')}" for d in (*MESH_ONLY, "scheduler") if _given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} apply to modal --mesh FILE only; remove them")


def _check(args: argparse.Namespace) -> None:
    bad = [f"--{d.replace('_', '-')}" for d in NOT_WITH_MESH if _given(args, d)]
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

    def progress(done: int, total: int, eta: float) -> None:
        if not args.json:
            print(f"\r  amplitude {done}/{total}, about {eta:.0f} s left", end="",
                  file=sys.stderr, flush=True)

    curve = qsma(model, mode, _forces(args, model, stuck, number_), workers=args.workers or 1,
                 scheduler=args.scheduler, progress=progress)
    if not args.json:
        print(file=sys.stderr)
    summary = curve.summary()
    out = {"mesh": args.mesh, "solver": args.solver or "fe", "mode": number_,
           "label": summary["label"], "density_kg_m3": args.density,
           "linear_frequencies_Hz": [float(f) for f in stuck.frequencies_Hz],
           "free_frequencies_Hz": [float(f) for f in free.frequencies_Hz],
           "modes": stuck.summary(),
           "amplitude_mm": summary["amplitude_mm"], "frequency_Hz": summary["frequency_Hz"],
           "secant_frequency_Hz": summary["secant_frequency_Hz"],
           "damping_ratio": summary["damping_ratio"],
           "modal_force": summary["force"],
           "dissipated_energy_Nmm": summary["dissipated_energy_Nmm"],
           "slip_fraction": summary["slip_fraction"], "warnings": summary["warnings"]}
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
        print("{:12.5g} {:12.7g} {:12.7g} {:12.5g} {:9.3f}".format(*row))
    return 0
