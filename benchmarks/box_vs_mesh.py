"""The box path against the mesh path on the same box (issue 27, item 8): is the box's own
solver (:mod:`microslip.fe.builtin.solve`, :class:`~microslip.fe.builtin.model.FrictionModel`)
needed for speed, or can the box run through the own-mesh solver
(:mod:`~microslip.fe.builtin.meshmodel`, :mod:`~microslip.fe.builtin.meshrun`)?

Run: ``python3 benchmarks/box_vs_mesh.py`` (``--fine``: also the fine mesh, minutes;
``--quick``: coarse only).

Each case runs in a fresh process (spawned), so its peak resident memory is its own: printed
is the peak RSS of the process after the run, MB, and the growth over the process after its
imports. Cases, Table 1 (445 N, mu 0.8), built-in solver, both paths at their defaults:

* ``loop tip|centre``: the paper's load step (267 N, 50 increments; ``microslip fe --model
  tip|centre --mesh LEVEL``): the box by :func:`~microslip.fe.builtin.solve_uniaxial`, the mesh
  path by :func:`~microslip.fe.examples.box_hexmesh` + ``build_mesh_model`` + ``solve_mesh``
  with the same load factors (``fe --mesh box.inp --history paper``). Time = set-up + loading.
* ``sweep``: ``microslip sweep --solver fe`` on coarse, 5 amplitudes 100 .. 300 N of the tip
  load step; the sweep builds its model at each point (:func:`microslip.fe.run_loop`), so
  both sides do.
* ``planar``: ``microslip planar --solver fe``'s coupled study (tip 150 N, centre 150 N
  across, 90 degrees, 64 increments per cycle, up to 6 cycles, one model for the three runs):
  the box by :func:`~microslip.fe.builtin.coupling_study`; the mesh path replays the box's
  very force samples of each run (coupled, tip alone, centre alone) as ``LoadFactors`` on
  one mesh model, W over the box's last cycle.

W is the box's (the reference), the difference is |W_mesh - W_box| / W_box.

Measured (``--fine``, best of 3, 2 cores shared with other jobs: read the ratios, not the
seconds; mesh = the mesh path at its defaults, full = with ``condensed=False``)::

    case         mesh     dof   W box N·mm  dW mesh  dW full  t box s mesh/box full/box
    loop tip     coarse   625    1.6182804  5.8e-14  5.8e-14     0.06     1.11     1.08
    loop centre  coarse   625   0.40286693  9.6e-16  9.6e-16     0.04     1.17     1.13
    loop tip     medium  1225    1.6162245  1.7e-13  1.7e-13     0.07     1.10     1.12
    loop centre  medium  1225   0.40145896  1.4e-15  1.4e-15     0.06     1.10     1.10
    loop tip     fine    6984    1.6159272  2.0e-12  8.2e-16     0.46    16.90     0.93
    loop centre  fine    6984   0.40121696  1.1e-13  3.2e-15     0.77     7.75     0.58
    sweep tip    coarse   625    2.2960363  1.0e-10  1.0e-10     0.25     1.08     1.09
    planar       coarse   625    1.4626282  8.3e-10  8.3e-10     0.67     1.04     1.01

Peak RSS (MB, growth after the warm-up): box, mesh, full 75-78 (2-5) on coarse and medium;
on fine box 111 (38), mesh 305-308 (232-235), full 116-120 (43-47). The mesh path at its
defaults condenses the fine box onto its 1746 contact dofs (``CONDENSE_MIN_DOF``, and
4 x contact dofs <= free dofs holds exactly at 6984): 8-17x slower, 3x the memory. Un-condensed
it is within 0.6-1.2x of the box everywhere. The decision: docs/interpretation.md, section 24.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import resource
import time
from typing import Any

import numpy as np

from microslip.fe.assembly import rigid_base

TABLE1_AMPLITUDE = 267.0
SWEEP = (100.0, 150.0, 200.0, 250.0, 300.0)
PLANAR = {"tip": 150.0, "centre": 150.0, "phase": 90.0, "increments": 64, "cycles": 6}


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _mesh_model(level: str, full: bool = False) -> Any:
    from microslip import preset
    from microslip.fe.builtin.meshmodel import build_mesh_model
    from microslip.fe.examples import box_hexmesh

    p = preset("table1")
    return build_mesh_model(box_hexmesh(p, level), rigid_base(contact_set="contact",
                                                              clamp_set="clamp",
                                                              normal_force=p.normal_force,
                                                              modulus=p.modulus,
                                                              poisson_ratio=p.poisson_ratio,
                                                              friction=p.friction),
                            **{"condensed": False} if full else {})


def _loop(path: str, case: str, level: str, amplitude: float) -> tuple[float, int]:
    """W (N·mm) and dofs of the paper's load step of one case."""
    from microslip import preset
    from microslip.fe.builtin import solve_uniaxial
    from microslip.fe.builtin.meshrun import LoadFactors, solve_mesh
    from microslip.fe.meshload import MeshLoad
    from microslip.loading import PaperSine

    if path == "box":
        r = solve_uniaxial(preset("table1"), case, amplitude, mesh=level)
        return float(r.dissipated_energy), int(r.dof)
    model = _mesh_model(level, path == "full")
    s = PaperSine.sampled(amplitude, 50)
    m = solve_mesh(model, [MeshLoad(case, (1.0, 0.0, 0.0), amplitude)],
                   LoadFactors(s.force / amplitude, s.quarter, s.time))
    return float(m.dissipated_energy), int(model.dof)


def _study(level: str) -> Any:
    from microslip import preset
    from microslip.fe.builtin import coupling_study

    return coupling_study(preset("table1"), PLANAR["tip"], PLANAR["centre"], PLANAR["phase"],
                          cycles=PLANAR["cycles"], increments_per_cycle=PLANAR["increments"],
                          mesh=level)


def _planar(level: str) -> tuple[float, int]:
    """The coupled W of the box's planar study (N·mm) and its dofs."""
    r = _study(level)
    return float(r.dissipated_energy), int(r.coupled.stats.dof)


def _replay(r: Any, level: str, full: bool) -> float:
    """The coupled W of the box study ``r`` replayed on the mesh path (N·mm)."""
    from microslip.fe.builtin.meshrun import LoadFactors, solve_mesh
    from microslip.fe.meshload import MeshLoad

    model = _mesh_model(level, full)
    w = []
    for run in (r.coupled, r.tip_only, r.centre_only):
        loads, cols = [], []
        for name, f, d in (("tip", run.f_tip, (1.0, 0.0, 0.0)),
                           ("centre", run.f_centre, (0.0, 1.0, 0.0))):
            a = float(np.max(np.abs(f)))
            if a > 0.0:
                loads.append(MeshLoad(name, d, a))
                cols.append(f / a)
        n, k0 = run.samples_per_cycle, run.cycle_start
        start = k0 + (len(run.f_tip) - 1 - k0) // n * n - n
        m = solve_mesh(model, loads, LoadFactors(np.stack(cols, axis=1), start))
        w.append(float(m.dissipated_energy))
    return w[0]


def _warm_up() -> None:
    """One tiny run of each path, so that no timed run pays a first call's one-off costs."""
    from microslip import preset
    from microslip.fe.builtin import solve_uniaxial
    from microslip.fe.builtin.meshmodel import build_mesh_model
    from microslip.fe.builtin.meshrun import LoadFactors, solve_mesh
    from microslip.fe.examples import box_hexmesh
    from microslip.fe.meshload import MeshLoad

    p = preset("table1")
    solve_uniaxial(p, "tip", 200.0, mesh=(4, 2, 1), increments=10)
    m = build_mesh_model(box_hexmesh(p, (4, 2, 1)), rigid_base(contact_set="contact",
                                                               clamp_set="clamp",
                                                               normal_force=p.normal_force,
                                                               modulus=p.modulus,
                                                               poisson_ratio=p.poisson_ratio,
                                                               friction=p.friction))
    solve_mesh(m, [MeshLoad("tip", (1.0, 0.0, 0.0), 200.0)],
               LoadFactors(np.array([0.0, 1.0, 0.0, -1.0, 0.0])))


def _job(kind: str, path: str, level: str, case: str, repeat: int) -> dict[str, float]:
    """One case on one path in this (fresh) process: best wall time of ``repeat`` runs."""
    _warm_up()
    base = _rss_mb()
    study = _study(level) if kind == "planar" and path != "box" else None
    walls = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        if kind == "loop":
            w, dof = _loop(path, case, level, TABLE1_AMPLITUDE)
        elif kind == "sweep":
            ws = [_loop(path, "tip", level, a) for a in SWEEP]
            w, dof = ws[-1][0], ws[-1][1]
        elif study is None:
            w, dof = _planar(level)
        else:  # the replay only, not the box study it replays (run above, untimed)
            w, dof = _replay(study, level, path == "full"), -1
        walls.append(time.perf_counter() - t0)
    return {"W": w, "dof": dof, "wall": min(walls), "peak": _rss_mb(),
            "grow": _rss_mb() - base}


def _spawn(fn: Any, *args: Any) -> dict[str, float]:
    with mp.get_context("spawn").Pool(1) as pool:
        return dict(pool.apply(fn, args))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="coarse only, no sweep")
    ap.add_argument("--fine", action="store_true", help="also the fine mesh (minutes)")
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs")
    args = ap.parse_args()
    levels = ["coarse"] if args.quick else ["coarse", "medium"] + (["fine"] if args.fine
                                                                   else [])
    rows = [("loop", lv, c) for lv in levels for c in ("tip", "centre")]
    if not args.quick:
        rows += [("sweep", "coarse", "tip"), ("planar", "coarse", "")]
    print("box path (reference) vs mesh path on the same box, built-in solver, Table 1; "
          f"best of {args.repeat}; mesh = its defaults (condensed from "
          "CONDENSE_MIN_DOF), full = condensed=False (the box's full banded factor); "
          "MB = peak RSS of the process / its growth after the warm-up")
    print(f"{'case':<13}{'mesh':<7}{'dof':>5}  {'W box N·mm':>11} {'dW mesh':>8} "
          f"{'dW full':>8}  {'t box s':>7} {'mesh/box':>8} {'full/box':>8}  "
          f"{'MB box':>8} {'MB mesh':>8} {'MB full':>8}")
    for kind, level, case in rows:
        res = {path: _spawn(_job, kind, path, level, case, args.repeat)
               for path in ("box", "mesh", "full")}
        box = res["box"]
        dw = {k: abs(v["W"] - box["W"]) / box["W"] for k, v in res.items()}
        mb = "".join(f" {res[k]['peak']:>4.0f}/{res[k]['grow']:<3.0f}" for k in res)
        print(f"{f'{kind} {case}'.strip():<13}{level:<7}{int(box['dof']):>5}  "
              f"{box['W']:>11.8g} {dw['mesh']:>8.1e} {dw['full']:>8.1e}  "
              f"{box['wall']:>7.2f} {res['mesh']['wall'] / box['wall']:>8.2f} "
              f"{res['full']['wall'] / box['wall']:>8.2f} {mb}", flush=True)


if __name__ == "__main__":
    main()
