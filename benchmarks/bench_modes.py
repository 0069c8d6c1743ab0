"""Speed of the structure's linear modes and of the quasi-static modal analysis (issue 23).

Run: ``python3 benchmarks/bench_modes.py`` (``--quick``: the coarse mesh only;
``--workers N``: the QSMA amplitudes on N local processes, default 1).

The cantilever example (:func:`microslip.fe.examples.cantilever_mesh`): aluminium
(E 70000 MPa, nu 0.33, 2700 kg/m^3), mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3, penalty
normal contact 1e6 N/mm^3. Rows per mesh (24x6x2, about 1.6k dof, and 48x12x4, about 10k):

* modes: the first ten stuck modes (mass, stiffness, shift-invert Lanczos, descriptions),
  target under 1 s on 24x6x2, at most 10 times that on 48x12x4; the model's set-up (assembly
  and clamping step) printed beside it;
* QSMA: the lowest mode at 10 amplitudes from first slip to near gross sliding (the grid
  search included), 40 increments per cycle until W settles to 1e-3, target under 30 s on
  24x6x2, at most 300 s on 48x12x4.

Best of ``--repeat`` for the modes; the QSMA once.
"""

from __future__ import annotations

import argparse
import time

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.modes import linear_modes
from microslip.meshdynamics.qsma import qsma

TARGETS = {(24, 6, 2): (1.0, 30.0), (48, 12, 4): (10.0, 300.0)}


def run(counts: tuple[int, int, int], repeat: int, workers: int) -> dict[str, float]:
    t0 = time.perf_counter()
    model = build_mesh_model(cantilever_mesh(*counts), rigid_base(contact_set="contact",
                                                                  clamp_set="clamp",
                                                                  normal_force=2000.0,
                                                                  modulus=70000.0,
                                                                  poisson_ratio=0.33, friction=0.5,
                                                                  stick_slope=1e4,
                                                                  normal_contact="penalty",
                                                                  normal_slope=1e6))
    setup = time.perf_counter() - t0
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        modes = linear_modes(model, 2700.0, 10, response_set="response")
        best = min(best, time.perf_counter() - t0)
    t0 = time.perf_counter()
    curve = qsma(model, modes.select(1), count=10, workers=workers)
    q_wall = time.perf_counter() - t0
    return {"dof": model.dof, "setup": setup, "modes": best, "f1": modes.frequencies_Hz[0],
            "qsma": q_wall, "f_last": curve.frequency_Hz[-1],
            "zeta_last": curve.damping_ratio[-1], "unsettled": len(curve.warnings)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the 24x6x2 mesh only")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--workers", type=int, default=1)
    args = ap.parse_args()
    meshes = list(TARGETS)[:1] if args.quick else list(TARGETS)
    print(f"{'mesh':>9} {'dof':>6} {'set-up s':>9} {'modes s':>8} {'target':>7} "
          f"{'f1 Hz':>8} {'QSMA s':>8} {'target':>7} {'f Hz at top':>11} {'zeta at top':>11}")
    for counts in meshes:
        r = run(counts, args.repeat, args.workers)
        t_modes, t_qsma = TARGETS[counts]
        name = "x".join(str(c) for c in counts)
        print(f"{name:>9} {r['dof']:>6d} {r['setup']:>9.2f} {r['modes']:>8.2f} "
              f"{t_modes:>7.0f} {r['f1']:>8.1f} {r['qsma']:>8.1f} {t_qsma:>7.0f} "
              f"{r['f_last']:>11.1f} {r['zeta_last']:>11.4f}"
              + (f"  ({r['unsettled']} amplitudes not settled)" if r["unsettled"] else ""))


if __name__ == "__main__":
    main()
