"""The built-in solver against CalculiX on the user's own mesh, like with like (issue 29).

:func:`compare_on_mesh` is ``microslip validate --mesh FILE``: both solvers on the same mesh,
sets, loads, load history, normal slope and stick slope, with CalculiX's contact formulation
chosen so that both solve the same equations (docs/interpretation.md, "CalculiX against the
built-in solver"):

- the built-in solver's contact is nodal: node i of the contact faces carries a normal spring
  K A_i, a stick spring lambda A_i and the Coulomb limit mu N_i, A_i its consistent share of
  the faces' area; CalculiX's ``node-to-surface`` penalty contact is that law node for node
  (one spring element per slave node of stiffness K A_i and lambda A_i, its friction limit mu
  times the node's own normal force); its ``face-to-face`` contact integrates the tractions
  over the faces instead, a different discretisation of the same continuum that only agrees
  under refinement;
- the built-in solver runs cycles until W per cycle settles; CalculiX then runs as many
  cycles from the same start, and its own cycles' W say whether it settled too (``settled``,
  to :data:`CALCULIX_SETTLE_FACTOR` times the built-in's tolerance; the paper's history is
  one explicit cycle on both sides, settled by definition);
  the W of every cycle of both is in the result, so the comparison is cycle for cycle;
- W's sensitivity to the normal slope: one more built-in run at ten times the slope;
- ``fixed`` normal contact (the built-in solver's default: u_n = 0, the normal forces of the
  clamping step held through the cycles) has no CalculiX counterpart, whose contact pressure
  always follows the overclosure. A ``fixed`` case is compared as a hard contact: both solvers
  run penalty contact at :data:`FIXED_SLOPE_FACTOR` times the case's normal slope (1e7 N/mm^3
  by default, within 0.1 % of the hard-contact limit on the examples, docs/interpretation.md
  section 21), like with like, and the case's own ``fixed`` W and d are reported beside them
  with their difference from the hard contact (``normal_contact``), which is the model's
  (frozen against redistributed normal forces), not either solver's.

Units: N, mm, N·mm.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path
from typing import Any

from ...errors import ParameterError
from ...io import atomic_write
from ...progress import progress_bar
from ..assembly import as_assembly
from ..errors import NonConvergenceError
from ..ownmesh import OwnMeshCase, run_own_mesh
from .meshdeck import check_formulation
from .meshhistory import load_history

__all__ = ["BUILTIN_CONTACT", "CALCULIX_SETTLE_FACTOR", "DEFAULT_FORMULATION",
           "FIXED_SLOPE_FACTOR", "SLOPE_FACTOR", "TOLERANCE", "compare_on_mesh", "settled"]

#: CalculiX's contact formulation that ``validate --mesh`` compares with by default: the one
#: whose equations are the built-in solver's.
DEFAULT_FORMULATION = "node-to-surface"
#: What the built-in solver's contact is, as the comparison names it.
BUILTIN_CONTACT = ("nodal penalty: normal spring K A_i (lift-off allowed), stick spring "
                   "lambda A_i, circular Coulomb limit mu N_i at each contact node")
#: Agreement required where both solve the same equations (issue 29): relative difference of
#: W and of the first load's displacement.
TOLERANCE = {"dissipated_energy_Nmm": 0.01, "peak_displacement_mm": 0.001}
#: The normal slope of the sensitivity run, as a multiple of the case's.
SLOPE_FACTOR = 10.0
#: A ``fixed`` case is compared as penalty contact at this multiple of its normal slope (the
#: default 1e5 N/mm^3 gives 1e7): a hard contact within 0.02-0.09 % of K = 1e8 in W on the
#: examples (docs/interpretation.md section 21), and CalculiX's node-to-surface contact
#: converges there as at 1e5 (the cantilever 12x3x1: the same iterations).
FIXED_SLOPE_FACTOR = 100.0
#: CalculiX counts as settled when its last two cycles' W agree to this multiple of the
#: built-in solver's tolerance: the built-in stops at the first cycle whose change falls below
#: its tolerance, so CalculiX's change at that cycle sits about there too (the cantilever:
#: built-in 9.3e-4, CalculiX 1.05e-3 with W equal to 1e-4).
CALCULIX_SETTLE_FACTOR = 2.0


def settled(works: list[float], tol: float) -> bool:
    """Whether the last two cycles' W agree to ``tol`` (relative; W = 0 twice counts).

    >>> settled([3.0, 2.5, 2.4990], 1e-3), settled([3.0, 2.5], 1e-3), settled([1.0], 1e-3)
    (True, False, False)
    """
    if len(works) < 2:
        return False
    return abs(works[-1] - works[-2]) <= tol * abs(works[-1])


def _rel(a: float, b: float) -> float:
    return a / b - 1.0 if b else math.nan


def _stand_in(case: OwnMeshCase) -> tuple[OwnMeshCase, dict[str, Any]]:
    """The case both solvers run (penalty normal contact) and what was done to its normal
    contact: a ``fixed`` case becomes penalty at :data:`FIXED_SLOPE_FACTOR` times its slope."""
    law = as_assembly(case.clamp)
    if law.normal_contact == "penalty":
        return case, {"case": "penalty", "compared": "penalty",
                      "normal_slope_N_per_mm3": law.normal_slope,
                      "reason": "the case's penalty law on both sides"}
    if law.normal_contact != "fixed":
        raise ParameterError(f"unknown normal contact {law.normal_contact!r}")
    stiff = law.normal_slope * FIXED_SLOPE_FACTOR
    hard = replace(case, clamp=replace(case.clamp, normal_contact="penalty",
                                       normal_slope=stiff))
    return hard, {
        "case": "fixed", "compared": "penalty", "normal_slope_N_per_mm3": stiff,
        "reason": (f"CalculiX has no fixed normal contact (its pressure follows the "
                   f"overclosure): both solvers run a hard contact, penalty "
                   f"K = {stiff:g} N/mm^3 ({FIXED_SLOPE_FACTOR:g} x the case's normal "
                   f"slope); the case's fixed W and d are given beside it")}


def compare_on_mesh(case: OwnMeshCase, out: str | Path | None = None, *,
                    formulation: str = DEFAULT_FORMULATION, progress: bool = True,
                    sensitivity: bool = True) -> dict[str, Any]:
    """Run the built-in solver, then CalculiX, on ``case`` and compare them.

    Parameters
    ----------
    case : OwnMeshCase
        Its clamp a :class:`~microslip.fe.clamp.MeshClamp` or an
        :class:`~microslip.fe.assembly.Assembly`; penalty normal contact, or ``fixed``
        compared as a hard contact (:data:`FIXED_SLOPE_FACTOR`, module docstring);
        ``case.options`` go to CalculiX (``timeout``, ``threads``).
    out : path, optional
        Where ``validation_mesh.json`` is written.
    formulation : str
        CalculiX's contact (:data:`~.meshdeck.CONTACT_FORMULATIONS`; default
        :data:`DEFAULT_FORMULATION`).
    progress : bool
        A progress bar of CalculiX's increments on standard error (tqdm, if installed).
    sensitivity : bool
        One more built-in run at :data:`SLOPE_FACTOR` times the normal slope compared.

    Returns
    -------
    dict
        ``builtin`` and ``calculix`` (the runs' summaries, each with its ``contact``),
        ``relative_difference`` (CalculiX / built-in - 1 of W and d), ``cycle_work_Nmm``
        of both, ``settled`` (both sides' W per cycle within the case's tolerance),
        ``normal_contact`` (the case's and the compared law, the slope, why; for a ``fixed``
        case also its built-in W and d and their difference from the hard contact),
        ``normal_slope_sensitivity``, ``tolerance`` and ``passed`` (settled and within
        :data:`TOLERANCE`).
    """
    form = check_formulation(formulation)
    given = case
    case, normal = _stand_in(case)
    fixed = run_own_mesh(given, "builtin").summary if normal["case"] == "fixed" else None
    builtin = run_own_mesh(case, "builtin").summary
    cycles = int(builtin["cycles"])
    ccx_case = replace(case, cycles=cycles)
    paper = case.history == "paper"  # one explicit cycle after a quarter-cycle rise
    history = load_history(case.loads, case.increments, 1 if paper else cycles,
                           "quarter" if paper else "ramp")
    total = int(history.time.size)  # the clamping increment and those of the load step
    with progress_bar(total, f"CalculiX ({formulation})", enabled=progress,
                      unit="increment") as bar:
        done = [0]

        def watch(n: int) -> None:
            if n > done[0]:
                bar.update(min(n, total) - done[0])
                done[0] = min(n, total)

        ccx_case = replace(ccx_case, options={**case.options, "formulation": formulation,
                                              "progress": watch})
        try:
            ccx = run_own_mesh(ccx_case, "calculix").summary
        except NonConvergenceError as exc:
            raise NonConvergenceError(
                f"{exc.message} ({formulation} contact at {case.increments} increments per "
                f"cycle; smaller increments converge where a reversal flips many nodes "
                f"between stick and slip: try --substeps {2 * case.substeps} or "
                f"{4 * case.substeps}, the built-in solver runs the same)",
                exc.job_dir, exc.log_tail) from None
    slope = float(normal["normal_slope_N_per_mm3"])
    law = f" (normal slope {slope:g} N/mm^3"
    law += (", the hard-contact stand-in for the case's fixed normal contact)"
            if normal["case"] == "fixed" else ")")
    builtin["contact"] = BUILTIN_CONTACT + law
    ccx["contact"] = f"{formulation}: {form.description}{law}"
    works = {"builtin": [float(w) for w in builtin["work_per_cycle_Nmm"]],
             "calculix": [float(w) for w in ccx["cycle_work_Nmm"]]}
    is_settled = {"builtin": bool(builtin["settled"]),
                  "calculix": paper or settled(works["calculix"],
                                               CALCULIX_SETTLE_FACTOR * case.tol)}
    diff = {k: _rel(ccx[k], builtin[k]) for k in TOLERANCE}
    if fixed is not None:
        normal["fixed_builtin"] = {k: fixed[k] for k in (*TOLERANCE, "cycles", "settled",
                                                         "model") if k in fixed}
        normal["fixed_against_hard"] = {k: _rel(fixed[k], builtin[k]) for k in TOLERANCE}
    clamp = as_assembly(case.clamp)
    result: dict[str, Any] = {
        "mesh": str(case.mesh_file), "contact_formulation": formulation,
        "normal_contact": normal,
        "normal_slope_N_per_mm3": clamp.normal_slope,
        "stick_slope_N_per_mm3": clamp.stick_slope,
        "increments_per_cycle": case.increments, "cycles": cycles,
        "builtin": builtin, "calculix": ccx, "cycle_work_Nmm": works,
        "settled": is_settled, "relative_difference": diff,
        "cycle_relative_difference": [_rel(c, b) for b, c in
                                      zip(works["builtin"], works["calculix"], strict=False)],
        "tolerance": dict(TOLERANCE)}
    if sensitivity:
        stiffer = replace(case.clamp, normal_slope=clamp.normal_slope * SLOPE_FACTOR)
        stiff = run_own_mesh(replace(case, clamp=stiffer), "builtin").summary
        w0, w1 = float(builtin["dissipated_energy_Nmm"]), float(stiff["dissipated_energy_Nmm"])
        result["normal_slope_sensitivity"] = {
            "normal_slope_N_per_mm3": clamp.normal_slope * SLOPE_FACTOR,
            "dissipated_energy_Nmm": w1, "relative_change": _rel(w1, w0),
            "dW_dlog10_slope_Nmm": (w1 - w0) / math.log10(SLOPE_FACTOR),
            "peak_displacement_mm": float(stiff["peak_displacement_mm"]),
            "solver": "builtin"}
    result["passed"] = (all(is_settled.values())
                        and all(abs(diff[k]) <= tol for k, tol in TOLERANCE.items()))
    if out is not None:
        with atomic_write(Path(out) / "validation_mesh.json") as fh:
            json.dump(result, fh, indent=2, default=float)
    return result
