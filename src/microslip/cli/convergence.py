"""``--refine``, ``--convergence`` and ``--levels`` of ``fe --mesh FILE`` and ``modal --mesh
FILE``: the options, their checks, and the table of a convergence study.

The study is :mod:`microslip.fe.convergence` (Richardson's estimate over the given mesh and
its refinements x2, :mod:`microslip.fe.refine`); this module parses and prints. Units: N·mm,
mm, Hz.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..case.table import MODE_MESH, add_option
from ..errors import ParameterError

__all__ = ["CONVERGENCE_OPTIONS", "add_convergence_options", "check_convergence",
           "frequency_convergence", "mesh_convergence"]

#: The destinations of this module's options (refused without a mesh file).
CONVERGENCE_OPTIONS = ("refine", "convergence", "mesh_levels")


def add_convergence_options(g: Any, refine: bool = True) -> None:
    """``--convergence``, ``--levels`` (and ``--refine``) on the argument group ``g``."""
    if refine:
        add_option(g, "refine", default=None, mode=MODE_MESH)
    add_option(g, "convergence", default=None, mode=MODE_MESH)
    add_option(g, "mesh_levels", default=None, choices=[2, 3], mode=MODE_MESH)


def check_convergence(args: argparse.Namespace, files: tuple[str, ...] = ()) -> None:
    """``--levels`` needs ``--convergence``; with it the options ``files`` (``fe``'s
    ``--out``, ``--plot``: the files of one mesh) are refused."""
    if getattr(args, "mesh_levels", None) is not None and not args.convergence:
        raise ParameterError("--levels applies with --convergence only")
    if getattr(args, "convergence", False):
        bad = [f"--{d}" for d in files if getattr(args, d, None) is not None]
        if bad:
            raise ParameterError(f"{', '.join(bad)} not used with --convergence (it reports "
                                 "the levels); write files from one mesh, e.g. --refine 2")


def _progress(line: str) -> None:
    """A convergence level's start (and, where the study reports it, its finished figures):
    one line on standard error as it happens, also with --json or the output in a file."""
    print(f"convergence: {line}", file=sys.stderr, flush=True)


def mesh_convergence(args: argparse.Namespace, case: Any) -> tuple[dict[str, Any], list[str]]:
    """``fe --mesh FILE --convergence``: the given mesh's summary with ``converged`` and
    ``discretisation_error_estimate`` added, and the lines of the text table."""
    from ..fe.convergence import converge_own_mesh

    study = converge_own_mesh(case, args.mesh_levels or 2, args.solver, progress=_progress)
    out = dict(study.first.summary)
    out["solver_converged"] = all(lv.solver_converged for lv in study.levels)
    out["converged"] = study.summary()  # the estimate (the solver's flag: solver_converged)
    out["discretisation_error_estimate"] = study.error
    out["warnings"] = [*out.get("warnings", []), *study.warnings()]
    w, d = study.dissipated_energy, study.peak_displacement
    lines = ["  mesh convergence (each level subdivides the given mesh's elements; "
             "Richardson's estimate)",
             f"  {'refine':>6s} {'elements':>9s} {'DOF':>8s} {'W (N·mm)':>13s} "
             f"{'peak disp. (mm)':>16s} {'time (s)':>9s}"]
    lines += [f"  {'x' + str(lv.refine):>6s} {lv.elements:9d} {lv.dof:8d} "
              f"{lv.dissipated_energy_Nmm:13.6g} {lv.peak_displacement_mm:16.6g} "
              f"{lv.wall_s:9.3g}" for lv in study.levels]
    for name, unit, est in (("W", "N·mm", w), ("peak displacement", "mm", d)):
        lines.append(f"  converged {name:<17s} {est.value:12.6g} {unit}  ({est.how}; "
                     f"uncertainty {100 * est.uncertainty:.2g} %; the given mesh "
                     f"{100 * est.relative_error:+.2f} % from it)")
    if w.note:
        lines.append(f"  note: {w.note}")
    return out, lines


def frequency_convergence(study: Any, args: argparse.Namespace,
                          out: dict[str, Any]) -> list[str]:
    """``modal --mesh FILE --convergence``: add ``converged_linear_frequencies_Hz`` (and the
    levels) to ``out`` and return the lines of the text table (none without the option).
    ``study``: the modal study (:class:`~microslip.meshdynamics.modalstudy.ModalStudy`)."""
    if not getattr(args, "convergence", False):
        return []
    from ..meshdynamics.convergence import converge_stuck_frequencies

    found = converge_stuck_frequencies(study.prepared.model, study.case.density,
                                       len(out["linear_frequencies_Hz"]), args.mesh_levels or 2)
    out.update(found.summary())
    out["warnings"] = [*out.get("warnings", []), *found.warnings()]
    levels = found.frequencies_Hz
    head = "".join(f" {'x' + str(r) + ' (Hz)':>12s}" for r in found.refine)
    lines = ["", "stuck linear frequencies, mesh convergence (Richardson's estimate):",
             f"  {'mode':>4s}{head} {'converged (Hz)':>15s} {'order':>6s} {'given mesh':>11s}"]
    for k, est in enumerate(found.estimates):
        row = "".join(f" {lv[k]:12.6g}" for lv in levels)
        lines.append(f"  {k + 1:4d}{row} {est.value:15.6g} {est.order:6.3g} "
                     f"{100 * est.relative_error:+10.2f}%")
    lines.append(f"  (order: {', '.join(sorted({e.order_source for e in found.estimates}))}"
                 f"; DOF {', '.join(map(str, found.dof))})")
    return lines
