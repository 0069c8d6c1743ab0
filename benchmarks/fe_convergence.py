"""How far each example's mesh is from converged (issue 29): the built-in FE on the example's
mesh and its refinements x2 (microslip.fe.convergence), W and the peak displacement of each
level, Richardson's estimate, the given mesh's discretisation error and the wall time, in one
table; then the time of ``microslip fe --mesh examples/cantilever.inp ... --convergence``
(24x6x2 -> 48x12x4, the issue's target: under 5 s).

Each example runs its documented case (examples/README.md). With ``--ccx`` the last column is
CalculiX's W on the given mesh (x1) with node-to-surface contact, the same slopes and cycles
(:func:`microslip.fe.calculix.compare.compare_on_mesh`, what ``validate --mesh`` runs); the
examples with fixed normal contact have no CalculiX column (CalculiX models penalty only).
The refined levels' CalculiX runs take minutes each: ``benchmarks/ownmesh_vs_calculix.py``
has the per-example comparison in full.

Run:  python benchmarks/fe_convergence.py               # 2 levels each, ~1-3 min
      python benchmarks/fe_convergence.py --levels 3    # 3 levels (the x4 meshes: minutes)
      python benchmarks/fe_convergence.py --only cantilever
      python benchmarks/fe_convergence.py --ccx           # CalculiX's W on the given meshes
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

from microslip.fe.clamp import MeshClamp
from microslip.fe.convergence import converge_own_mesh
from microslip.fe.meshload import MeshLoad
from microslip.fe.ownmesh import OwnMeshCase

ROOT = Path(__file__).resolve().parents[1]
ALUMINIUM = {"normal_force": 2000.0, "friction": 0.5, "modulus": 70000.0,
             "poisson_ratio": 0.33, "stick_slope": 1e4}
PENALTY = {"normal_contact": "penalty", "normal_slope": 1e6}
#: name -> (mesh file, loads, case values): the documented case of examples/README.md.
EXAMPLES: dict[str, tuple[str, tuple[str, ...], dict[str, Any]]] = {
    "cantilever": ("cantilever.inp", ("tip:1,0,0:300",), {**ALUMINIUM, **PENALTY}),
    "bolt_pad": ("bolt_pad.inp", ("end:1,0,0:100", "end:0,1,0:100:90"),
                 {**ALUMINIUM, **PENALTY}),
    "post_on_plate": ("post_on_plate.inp", ("top:1,1,0:50",), ALUMINIUM),
    "box_table1": ("box_table1_24x4x1.inp", ("tip:1,0,0:267",),
                   {"normal_force": 445.0, "friction": 0.8, "modulus": 68947.0,
                    "poisson_ratio": 0.3}),
}

CANTILEVER_CLI = [
    "fe", "--mesh", str(ROOT / "examples" / "cantilever.inp"), "--contact-set", "contact",
    "--clamp-set", "clamp", "--normal-force", "2000", "--load", "tip:1,0,0:300", "--friction",
    "0.5", "--stick-slope", "1e4", "--normal-contact", "penalty", "--normal-slope", "1e6",
    "--modulus", "70000", "--poisson-ratio", "0.33", "--convergence", "--json"]


def _case(name: str) -> OwnMeshCase:
    file, loads, values = EXAMPLES[name]
    clamp = MeshClamp("contact", "clamp", **values)
    return OwnMeshCase(str(ROOT / "examples" / file), clamp,
                       loads=tuple(MeshLoad.parse(s) for s in loads))


def _calculix(case: OwnMeshCase) -> float | None:
    """CalculiX's W (N mm) on the case's own mesh with node-to-surface contact, or None with
    fixed normal contact (CalculiX has penalty only)."""
    from microslip.fe.calculix.compare import compare_on_mesh

    if case.clamp.normal_contact != "penalty":
        return None
    if "post" in case.mesh_file:  # the rocking post: 160 increments a cycle (interpretation)
        case = replace(case, substeps=200)
    r = compare_on_mesh(case, progress=False, sensitivity=False)
    return float(r["calculix"]["dissipated_energy_Nmm"])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", type=int, choices=[2, 3], default=2)
    ap.add_argument("--only", choices=list(EXAMPLES), action="append")
    ap.add_argument("--ccx", action="store_true", help="CalculiX's W on the given meshes")
    args = ap.parse_args()
    head = (f"{'example':<14s} {'load':<34s} {'refine':>6s} {'DOF':>7s} {'W (N mm)':>11s} "
            f"{'d (mm)':>11s} {'time (s)':>8s} {'ccx W (N mm)':>12s}")
    print(head)
    print("-" * len(head))
    summary = []
    for name in args.only or EXAMPLES:
        case = _case(name)
        start = time.perf_counter()
        study = converge_own_mesh(case, args.levels)
        total = time.perf_counter() - start
        load = " + ".join(EXAMPLES[name][1])
        given = _calculix(case) if args.ccx else None
        for lv in study.levels:
            ccx = given if lv.refine == 1 else None
            print(f"{name:<14s} {load:<34s} {'x' + str(lv.refine):>6s} {lv.dof:7d} "
                  f"{lv.dissipated_energy_Nmm:11.5g} {lv.peak_displacement_mm:11.5g} "
                  f"{lv.wall_s:8.2f} {'-' if ccx is None else f'{ccx:.5g}':>12s}")
        summary.append((name, study, total))
    print()
    print(f"{'example':<14s} {'W converged (N mm)':>18s} {'order':>12s} {'uncert.':>8s} "
          f"{'given mesh W':>12s} {'given mesh d':>12s} {'total (s)':>9s}")
    for name, study, total in summary:
        w, d = study.dissipated_energy, study.peak_displacement
        print(f"{name:<14s} {w.value:18.5g} {w.order:5.2g} {w.order_source:>6s} "
              f"{100 * w.uncertainty:7.1f}% {100 * w.relative_error:+11.1f}% "
              f"{100 * d.relative_error:+11.2f}% {total:9.1f}")
        if w.note:
            print(f"{'':<14s} ({w.note})")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "microslip", *CANTILEVER_CLI],
                          capture_output=True, text=True, check=False)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    print(f"\nmicroslip fe --mesh examples/cantilever.inp ... --convergence (24x6x2 -> "
          f"48x12x4): {wall:.2f} s wall, {cpu:.2f} s CPU, exit {done.returncode} (target "
          "< 5 s; on a shared machine the CPU time is the figure)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
