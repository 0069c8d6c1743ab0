"""``microslip modal --mesh FILE --solver all``: every solver of ``modal --mesh`` side by side
on one study (issue 23, item 5).

The study is the library's (:func:`microslip.meshdynamics.modalstudy.run_solvers` and
:func:`~microslip.meshdynamics.modalstudy.compare_output`: every model judged against the
full FE by :func:`microslip.meshdynamics.verdict_modal.modal_verdict`); this module prints.
Units: Hz, mm, kg/m^3; damping ratios dimensionless.
"""

from __future__ import annotations

import sys
from typing import Any

from ..meshdynamics.modalstudy import ModalStudy, compare_all
from ..meshdynamics.verdict_modal import DAMPING_CEILING, DAMPING_FLOOR
from .common import print_json
from .convergence import frequency_convergence
from .modalmesh import curve_table, headline, print_study_model, progress_printer

__all__ = ["run_modal_all"]


def run_modal_all(study: ModalStudy, args: Any) -> int:
    """Run every registered solver on ``study``, print them side by side with the verdicts,
    and draw them (``--plot``)."""
    def echo(line: str) -> None:
        if not args.json:
            print(line, file=sys.stderr, flush=True)

    curves, out = compare_all(study, progress_printer(args), echo)
    table = frequency_convergence(study, args, out)  # --convergence: the stuck frequencies
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.plot:
        from ..plot.ownmesh import plot_compare

        plot_compare(out, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(headline(study, out, "every solver on the same amplitude grid"))
    print_study_model(out)
    for name, curve in curves.items():
        print(f"\n{name}: {curve.label}")
        print("\n".join(curve_table(out["solvers"][name], curve)))
    if out["verdicts"]:
        print(f"\nagainst the full FE at equal amplitude, where its damping ratio is "
              f"{100 * DAMPING_FLOOR:g}-{100 * DAMPING_CEILING:g} % (microslip):")
        for v in out["verdicts"].values():
            print(f"  {v['verdict']}")
    if table:
        print("\n".join(table))
    return 0
