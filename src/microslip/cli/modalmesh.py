"""``microslip modal --mesh FILE``: a mode's frequency and damping ratio against amplitude,
on the structure of the user's own mesh.

The study is the library's (:mod:`microslip.meshdynamics.modalstudy`: the solvers of
:data:`~microslip.meshdynamics.modalstudy.MESH_SOLVERS` on one
:class:`~microslip.meshdynamics.case.StructureCase`); this module checks the options, builds
the case (:func:`.meshstructure.structure_case`) and the settings, calls, and prints.
Units: Hz, mm, N, kg/m^3.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..case.table import MODE_MESH, add_option, add_solver, mode_options
from ..conventions import DEFAULT_INTERFACE_MODES
from ..errors import ParameterError
from ..meshdynamics.modalstudy import MESH_SOLVERS, MeshCurve, ModalSettings, ModalStudy
from .common import check_plot, flagged, print_json
from .convergence import add_convergence_options, check_convergence, frequency_convergence
from .meshstructure import (
    add_mesh_structure_options,
    add_reduced_model_options,
    check_mesh_structure,
    structure_case,
)
from .ownmesh import given, verb

__all__ = ["MESH_SOLVERS", "add_modal_mesh_options", "mesh_study", "modal_settings",
           "run_modal_mesh"]

# The mesh structure's options, checks, model and modes: cli.meshstructure (shared with
# frf --mesh). The options of --mesh only are those added with mode=MODE_MESH.
#: ``--solver`` that runs every solver of :data:`MESH_SOLVERS` (:mod:`.modalcompare`).
ALL = "all"


def add_modal_mesh_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("the structure of your own mesh (--mesh FILE; docs/ownmesh.md)")
    add_mesh_structure_options(g)
    add_solver(g, "modal", meaning={**{k: v.help for k, v in MESH_SOLVERS.items()},
                                    ALL: "every one of them side by side, with a verdict on "
                                         "each against the full FE"}, mode=MODE_MESH)
    add_reduced_model_options(g)
    add_option(g, "interface_modes", mode=MODE_MESH,
               note=f"interface; default {DEFAULT_INTERFACE_MODES}")
    add_option(g, "yield_strength", mode=MODE_MESH)
    add_option(g, "workers", note="default 1", mode=MODE_MESH)
    add_option(g, "scheduler", help="a Dask scheduler (tcp://HOST:8786) to run the amplitudes "
                                    "on", mode=MODE_MESH)
    add_convergence_options(g, refine=False)


def refuse_mesh_options(args: argparse.Namespace) -> None:
    """Without --mesh, the mesh's options given on the command line are refused."""
    bad = [f"--{d.replace('_', '-')}" for d in mode_options(args, MODE_MESH) if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to modal --mesh FILE only; remove "
                             "them")


def _check(args: argparse.Namespace) -> None:
    check_mesh_structure(args)
    check_convergence(args)
    solver = args.solver or "fe"
    for dest in dict.fromkeys(o for s in MESH_SOLVERS.values() for o in s.options):
        if given(args, dest) and solver != ALL and dest not in MESH_SOLVERS[solver].options:
            owners = [n for n, s in MESH_SOLVERS.items() if dest in s.options]
            raise ParameterError(f"--{dest.replace('_', '-')} applies to --solver "
                                 f"{' or '.join(owners)} only")


def modal_settings(args: argparse.Namespace) -> ModalSettings:
    """The modal study's settings from the command line, checked (``--harmonics`` defaults
    to :data:`~microslip.dynamics.hb.DEFAULT_HARMONICS`)."""
    from .structure import balance_from_args, harmonic_control

    if args.harmonics == "auto":
        raise ParameterError("--harmonics auto is not available with modal --mesh yet: write "
                             "the ROM with `microslip reduce ... --out rom.npz` and run `modal "
                             "--structure rom.npz --harmonics auto`, or give a number (default "
                             "7)")
    harmonic_control(args)  # refuses --harmonic-tolerance with fixed harmonics
    harmonics, samples = balance_from_args(args)
    with flagged():
        return ModalSettings(amplitudes=args.amplitudes,
                             amplitude_range=(None if args.amplitude_range is None
                                              else tuple(args.amplitude_range)),
                             harmonics=harmonics, samples=samples,
                             workers=args.workers or 1, scheduler=args.scheduler,
                             damping_ratio=args.damping_ratio or 0.0)


def mesh_study(args: argparse.Namespace) -> ModalStudy:
    """Check the command line, build the case and the settings, and prepare the study
    (:func:`microslip.meshdynamics.modalstudy.prepare_modal`: the clamped model, its stuck
    and free modes, the amplitude grid)."""
    from ..meshdynamics.modalstudy import prepare_modal

    _check(args)
    check_plot(args.plot)
    case = structure_case(args)
    settings = modal_settings(args)
    with flagged():
        return prepare_modal(case, settings)


def progress_printer(args: argparse.Namespace) -> Any:
    """The full FE's progress on stderr, also with --json or the output in a file: on a
    terminal one line rewritten in place, ended by a newline; otherwise a line per
    amplitude."""
    live = sys.stderr.isatty()

    def progress(done: int, total: int, eta: float) -> None:
        text = f"  amplitude {done}/{total}, about {eta:.0f} s left"
        if not live:
            print(text.strip(), file=sys.stderr, flush=True)
            return
        print(f"\r{text}", end="", file=sys.stderr, flush=True)
        if done == total:
            print(file=sys.stderr)

    return progress


def run_modal_mesh(args: argparse.Namespace) -> int:
    """One solver's curve (``--solver all``: :func:`.modalcompare.run_modal_all`, which
    :mod:`.modal` dispatches to)."""
    from ..meshdynamics.modalstudy import run_solvers, study_output

    study = mesh_study(args)
    solver = args.solver or "fe"
    curve = run_solvers(study, (solver,), progress_printer(args))[solver]
    out = study_output(study, solver, curve)
    table = frequency_convergence(study, args, out)  # --convergence: the stuck frequencies
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.plot:
        from ..plot.ownmesh import plot_qsma

        plot_qsma(out, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(headline(study, out, curve.label))
    print_study_model(out)
    print("\n".join(curve_table(out, curve) + table))
    return 0


def print_study_model(out: dict[str, Any]) -> None:
    """What the study built (:func:`.ownmesh.print_model`) and where its amplitudes stop."""
    from .ownmesh import print_model

    print_model(out["model"])
    lim = out.get("amplitude_limit")
    if lim is not None:
        print(f"  amplitude limit        {lim['limit_mm']:.4g} mm ({lim['reason']})")


def headline(study: ModalStudy, out: dict[str, Any], what: str) -> str:
    """The first line of the text output: the mesh, the mode, its stuck and free
    frequencies (Hz) and ``what`` was computed."""
    number = study.number
    return (f"mesh {study.case.mesh_name}: mode {number} ({out['label']}), stuck "
            f"{out['linear_frequencies_Hz'][number - 1]:.6g} Hz, free "
            f"{out['free_frequencies_Hz'][number - 1]:.6g} Hz; {what}")


def curve_table(values: dict[str, Any], curve: MeshCurve) -> list[str]:
    """One solver's rows under its own column headers (units in the headers)."""
    lines = [" ".join(f"{h:>12}" if f.startswith("{:12") else f"{h:>9}"
                      for h, f in curve.columns.values())]
    for row in zip(*(values[k] for k in curve.columns), strict=True):
        if row[0] is None:
            lines.append(f"{'failed':>12} (see the warnings)")
            continue
        lines.append(" ".join(fmt.format(v) for v, (_, fmt)
                              in zip(row, curve.columns.values(), strict=True)))
    return lines
