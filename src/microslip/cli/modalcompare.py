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

from ..case.model import Case
from ..case.table import CASE_DESTS, OPTIONS
from ..fe.verdict_modal import DAMPING_CEILING, DAMPING_FLOOR, modal_verdict
from .common import print_json
from .modalmesh import (
    ALL,
    MESH_SOLVERS,
    MeshCurve,
    MeshStudy,
    curve_table,
    headline,
    mesh_study,
    study_output,
)
from .structure import balance_from_args, harmonic_control

__all__ = ["REPORT_AMPLITUDES", "SHARED", "TRUTH", "case_argv", "case_comparison",
           "compare_output", "run_all", "run_modal_all"]

#: Keys of a solver's JSON that the study gives, the same for every solver: written once.
SHARED = ("mesh", "mode", "label", "density_kg_m3", "linear_frequencies_Hz",
          "free_frequencies_Hz", "modes")
#: The solver every other is judged against.
TRUTH = "fe"
#: Amplitudes of the structure section of ``microslip report`` (first slip to near gross
#: sliding).
REPORT_AMPLITUDES = 6


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


def run_all(study: MeshStudy) -> tuple[dict[str, MeshCurve], dict[str, Any]]:
    """Every registered solver's curve on ``study``, and :func:`compare_output` of them."""
    args = study.args
    if harmonic_control(args) is None:  # a bad --harmonics must not wait for the full FE
        balance_from_args(args)
    curves: dict[str, MeshCurve] = {}
    for k, (name, solver) in enumerate(MESH_SOLVERS.items()):
        if not args.json:
            print(f"solver {k + 1}/{len(MESH_SOLVERS)}: {name}", file=sys.stderr, flush=True)
        curves[name] = solver.run(study)
    return curves, compare_output(study, curves)


def case_argv(case: Case, amplitudes: int = REPORT_AMPLITUDES) -> list[str] | None:
    """The command line ``modal --mesh ... --solver all --json`` of a case file's structure
    ([mesh] file, sets, density, mode, response set; the material, contact and clamping
    values), or None when the case has no mesh file or no density."""
    v = case.values
    if "mesh.file" not in v or "mesh.density" not in v:
        return None
    argv = ["modal", "--mesh", str(v["mesh.file"]), "--solver", ALL, "--json",
            "--amplitudes", str(amplitudes), "--mode", str(case.get("mesh.mode"))]
    for key in ("mesh.contact_set", "mesh.clamp_set", "mesh.density", "mesh.response_set",
                "material.modulus", "material.poisson_ratio", "contact.friction",
                "contact.stick_slope", "clamping.normal_force"):
        value = case.get(key)
        if value is not None:
            argv += [OPTIONS[CASE_DESTS[key][0]].flag,
                     str(value)]  # a float's shortest repr: the same number back
    return argv


def case_comparison(case: Case, amplitudes: int = REPORT_AMPLITUDES) -> dict[str, Any] | None:
    """:func:`compare_output` of every solver on the structure of a case file
    (:func:`case_argv`; None without one): what ``microslip report`` shows in its section
    "Damping of the structure's mode"."""
    from .main import build_parser

    argv = case_argv(case, amplitudes)
    if argv is None:
        return None
    return run_all(mesh_study(build_parser(argv).parse_args(argv)))[1]


def run_modal_all(study: MeshStudy) -> int:
    """Run every registered solver on ``study``, print them side by side with the verdicts,
    and draw them (``--plot``)."""
    args = study.args
    curves, out = run_all(study)
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.plot:
        from ..plot.ownmesh import plot_compare

        plot_compare(out, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(headline(study, out, "every solver on the same amplitude grid"))
    for name, curve in curves.items():
        print(f"\n{name}: {curve.label}")
        print("\n".join(curve_table(out["solvers"][name], curve)))
    if out["verdicts"]:
        print(f"\nagainst the full FE at equal amplitude, where its damping ratio is "
              f"{100 * DAMPING_FLOOR:g}-{100 * DAMPING_CEILING:g} % (microslip):")
        for v in out["verdicts"].values():
            print(f"  {v['verdict']}")
    return 0
