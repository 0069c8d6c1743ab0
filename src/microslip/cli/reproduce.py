"""``microslip reproduce --out DIR``: the paper's figures, tables and a check of its claims."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..case.table import add_option
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
    add_option(p, "out", required=True, metavar="DIR", help="output directory (created)")
    add_option(p, "fe", note="the CalculiX validation for Figs 8-9 (by default when ccx is "
               "available) and the coupled 2-D friction study with the built-in solver (by "
               "default always; --no-fe skips both)")
    add_option(p, "fe_mesh", choices=list(FE_MESHES), default=DEFAULT_MESH, type=None,
               help="mesh of the finite-element validation")
    add_option(p, "increments")
    add_option(p, "levels", choices=list(LEVEL_SCHEMES),
               note="; ".join(f"{k}: {v}" for k, v in LEVEL_SCHEMES.items()))
    add_strain_energy(p, PAPER_STRAIN_ENERGY, ", the paper's Eq. 22; secant is reported beside it")
    add_option(p, "work_energy", choices=list(WORK_STRAIN_ENERGY),
               default=DEFAULT_WORK_STRAIN_ENERGY)
    add_model_options(p, "paper", " here, because the paper's top centre level 16000 N equals "
                                  "mu F_N")
    add_option(p, "structure_study", note="structure/; about a minute; by default with the "
               "finite elements, so --no-fe skips it too")
    add_option(p, "quiet")
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
