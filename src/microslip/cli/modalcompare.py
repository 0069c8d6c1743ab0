"""``microslip modal --mesh FILE --solver all``: every solver of ``modal --mesh`` side by side
on one study (issue 23, item 5).

Each solver of :data:`~microslip.cli.modalmesh.MESH_SOLVERS` runs on the same
:class:`~microslip.cli.modalmesh.MeshStudy` (the clamped model, its modes, the one amplitude
grid), exactly as ``--solver NAME`` alone would; every model is then judged against the full
FE (``fe``, the truth) by :func:`microslip.fe.verdict_modal.modal_verdict`. This module
gathers and prints. Units: Hz, mm, kg/m^3; damping ratios dimensionless.
"""

from __future__ import annotations

import sys
from typing import Any

from ..fe.verdict_modal import DAMPING_CEILING, DAMPING_FLOOR, modal_verdict
from .common import print_json
from .modalmesh import MESH_SOLVERS, MeshCurve, MeshStudy, study_output
from .structure import balance_from_args

__all__ = ["SHARED", "TRUTH", "compare_output", "run_modal_all"]

#: Keys of a solver's JSON that the study gives, the same for every solver: written once.
SHARED = ("mesh", "mode", "label", "density_kg_m3", "linear_frequencies_Hz",
          "free_frequencies_Hz", "modes")
#: The solver every other is judged against.
TRUTH = "fe"


def compare_output(study: MeshStudy, curves: dict[str, MeshCurve]) -> dict[str, Any]:
    """The JSON of every solver's curve on ``study``: the shared keys once, ``solvers``
    (name -> that solver's own keys, as ``--solver NAME --json`` prints them), ``verdicts``
    (name -> :meth:`~microslip.fe.verdict_modal.ModalVerdict.summary`, every solver but the
    full FE) and ``warnings`` (every solver's, each line led by its name)."""
    outputs = {name: study_output(study, name, curve) for name, curve in curves.items()}
    first = next(iter(outputs.values()))
    out: dict[str, Any] = {k: first[k] for k in SHARED}
    out["solvers"] = {name: {k: v for k, v in o.items() if k not in (*SHARED, "solver")}
                      for name, o in outputs.items()}
    truth = out["solvers"].get(TRUTH)
    out["verdicts"] = ({} if truth is None else
                       {name: modal_verdict(name, truth, o).summary()
                        for name, o in out["solvers"].items() if name != TRUTH})
    out["warnings"] = [f"{name}: {w}" for name, o in out["solvers"].items()
                       for w in o["warnings"]]
    return out


def _table(values: dict[str, Any], curve: MeshCurve) -> list[str]:
    """One solver's rows under its own column headers."""
    lines = [" ".join(f"{h:>12}" if f.startswith("{:12") else f"{h:>9}"
                      for h, f in curve.columns.values())]
    for row in zip(*(values[k] for k in curve.columns), strict=True):
        if row[0] is None:
            lines.append(f"{'failed':>12} (see the warnings)")
            continue
        lines.append(" ".join(fmt.format(v) for v, (_, fmt)
                              in zip(row, curve.columns.values(), strict=True)))
    return lines


def run_modal_all(study: MeshStudy) -> int:
    """Run every registered solver on ``study``, print them side by side with the verdicts,
    and draw them (``--plot``)."""
    args = study.args
    balance_from_args(args)  # a bad --harmonics must not wait for the full FE's runs
    curves: dict[str, MeshCurve] = {}
    for k, (name, solver) in enumerate(MESH_SOLVERS.items()):
        if not args.json:
            print(f"solver {k + 1}/{len(MESH_SOLVERS)}: {name}", file=sys.stderr, flush=True)
        curves[name] = solver.run(study)
    out = compare_output(study, curves)
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.plot:
        from ..plot.ownmesh import plot_compare

        plot_compare(out, args.plot)
    if args.json:
        print_json(out)
        return 0
    number = study.number
    print(f"mesh {args.mesh}: mode {number} ({out['label']}), stuck "
          f"{out['linear_frequencies_Hz'][number - 1]:.6g} Hz, free "
          f"{out['free_frequencies_Hz'][number - 1]:.6g} Hz; every solver on the same "
          "amplitude grid")
    for name, curve in curves.items():
        print(f"\n{name}: {curve.label}")
        print("\n".join(_table(out["solvers"][name], curve)))
    if out["verdicts"]:
        print(f"\nagainst the full FE at equal amplitude, where its damping ratio is "
              f"{100 * DAMPING_FLOOR:g}-{100 * DAMPING_CEILING:g} % (microslip):")
        for v in out["verdicts"].values():
            print(f"  {v['verdict']}")
    return 0
