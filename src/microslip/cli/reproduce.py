"""``microslip reproduce --out DIR``: the paper's figures, tables and a check of its claims."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..conventions import DEFAULT_MESH
from ..planar import LEVEL_SCHEMES, PAPER_STRAIN_ENERGY, WORK_STRAIN_ENERGY
from ..planar.loadpath import DEFAULT_WORK_STRAIN_ENERGY
from .common import (
    add_model_options,
    add_strain_energy,
    check_output_dir,
    increments_option,
    model_options,
)

__all__ = ["add_parser", "run"]

#: First loadings of one reproduce run, roughly (the seven R twice, readings, tables), for the
#: cost estimate of --increments.
REPRODUCE_LOADINGS = 40


def add_parser(sub: Any) -> None:
    from ..reproduce import FE_MESHES

    p = sub.add_parser(
        "reproduce", help="regenerate the paper's figures and tables and check its claims",
        description="Write Figs 1, 10, 11, 12 (and 8-9 with the finite-element validation), "
        "the data behind them as CSV, and report.md with the readings in force, the results "
        "and a point-by-point check of the paper's claims. Units: N, mm, N·mm.")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (created)")
    p.add_argument("--fe", action=argparse.BooleanOptionalAction, default=None,
                   help="run the finite elements: the CalculiX validation for Figs 8-9 (by "
                        "default when ccx is available) and the coupled 2-D friction study "
                        "with the built-in solver (by default always; --no-fe skips both)")
    p.add_argument("--fe-mesh", choices=list(FE_MESHES), default=DEFAULT_MESH,
                   help="mesh of the finite-element validation (default coarse)")
    p.add_argument("--increments", type=int, default=1000, metavar="N",
                   help="force increments of each first loading (default 1000)")
    p.add_argument("--levels", choices=list(LEVEL_SCHEMES), default="base",
                   help="how R maps onto the paper's amplitude levels: "
                        + "; ".join(f"{k}: {v}" for k, v in LEVEL_SCHEMES.items())
                        + " (default base)")
    add_strain_energy(p, PAPER_STRAIN_ENERGY, ", the paper's Eq. 22; secant is reported beside it")
    p.add_argument("--work-energy", choices=list(WORK_STRAIN_ENERGY),
                   default=DEFAULT_WORK_STRAIN_ENERGY,
                   help="U of the combined motion in the work-based eta "
                        f"(default {DEFAULT_WORK_STRAIN_ENERGY})")
    add_model_options(p, "paper", " here, because the paper's top centre level 16000 N equals "
                                  "mu F_N")
    p.add_argument("--structure-study", action=argparse.BooleanOptionalAction, default=None,
                   help="the damping of the cantilever example's two bending modes from its "
                        "mesh: full FE, contact-node ROM and whole joint side by side "
                        "(structure/; about a minute; by default with the finite elements, "
                        "so --no-fe skips it too)")
    p.add_argument("--quiet", action="store_true", help="no progress display")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..io import staged_directory
    from ..reproduce import reproduce

    def echo(msg: str) -> None:
        print(msg, file=sys.stderr)

    increments = increments_option(args.increments, loops=REPRODUCE_LOADINGS)
    check_output_dir(args.out)
    with staged_directory(args.out) as stage:  # an interrupted run leaves no partial DIR
        res = reproduce(stage, increments=increments,
                        options=model_options(args), strain_energy=args.strain_energy,
                        levels=args.levels, work_energy=args.work_energy, fe=args.fe,
                        fe_mesh=args.fe_mesh, progress=not args.quiet, echo=echo)
        structure: list[Path] = []
        if args.structure_study or (args.structure_study is None and args.fe is not False):
            from ..reproduce.structurejob import structure_study

            structure, lines = structure_study(stage, None if args.quiet else echo)
            with open(stage / "report.md", "a", encoding="utf-8") as fh:
                fh.write("\n" + "\n".join(lines))
    out = Path(args.out)
    files = [*res.files, *structure]
    print(f"microslip reproduce: {len(files)} files in {out} ({res.elapsed_s:.1f} s for the "
          "paper)")
    for f in files:
        print(f"  {out / f.relative_to(stage)}")
    t = res.table
    print(f"  {'R':>6s} {'eps':>6s} {'paper eta':>11s} {'norm.':>9s} {'work eta':>11s} "
          f"{'norm.':>9s}   (dimensionless, U {res.sweep.strain_energy_kind})")
    for i in range(len(t["R"])):
        print(f"  {t['R'][i]:6.3g} {t['eccentricity'][i]:6.3f} {t['paper_loss_factor'][i]:11.6g} "
              f"{t['paper_normalised_loss_factor'][i]:9.6f} {t['work_loss_factor'][i]:11.6g} "
              f"{t['work_normalised_loss_factor'][i]:9.6f}")
    print("  claims of the paper (details in report.md):")
    for c in res.claims:
        print(f"    {c.key}: {c.verdict}")
    if res.fe_status != "done":
        print(f"  finite elements {res.fe_status}: {res.fe_message}; Fig. 9 not produced")
    return 1 if res.fe_status == "failed" else 0
