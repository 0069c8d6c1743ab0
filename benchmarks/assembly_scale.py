"""Issue 35 item 5: an assembly of about 100k DOF, the structure study's stages measured in one
run: the model (the preload step on two bodies), the stuck modes, the interface reduction
on the relative interface dofs and the EPMC of mode 2 over 20 amplitudes (7 harmonics), each
stage's wall and CPU time and resident peak. Target: modes, reduction and EPMC under 120 s
and 4 GB together.

The part: the examples' cantilever bar at 96 x 24 x 12 (93,750 DOF) standing on a steel base
block under its clamped length (a conforming interface: ``microslip.fe.examples.on_block``),
the block held at its bottom, 2000 N on the clamp face, fixed normal contact. Run:
``python benchmarks/assembly_scale.py [--counts 96 24 12]``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from bench_structure import _interface_row, _reset_peak, _stage_peak_mb

from microslip.fe.assembly import Assembly, Contact, Material, Preload, Support
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh, on_block


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--counts", type=int, nargs=3, default=(96, 24, 12))
    args = ap.parse_args()
    bar = cantilever_mesh(*args.counts)
    mesh = on_block(bar, layers=2)
    a = Assembly(contacts=(Contact("bar_int", "base_int"),), preloads=(Preload("clamp", 2000.0),),
                 supports=(Support("base_fix"),),
                 materials=(Material(70000.0, 0.33, 2700.0, "BAR"),
                            Material(210000.0, 0.3, 7850.0, "BASE")),
                 friction=0.5, stick_slope=1e4)
    _reset_peak()
    t0, c0 = time.perf_counter(), time.process_time()
    model = build_mesh_model(mesh, a)
    out = {"row": "assembly", "dof": model.dof, "contact_nodes": int(model.contact_nodes.size),
           "model_s": round(time.perf_counter() - t0, 1),
           "model_cpu_s": round(time.process_time() - c0, 1),
           "model_MB": round(_stage_peak_mb() or 0.0)}
    print(json.dumps(out), flush=True)
    out = _interface_row(model, out)
    print(f"assembly of {model.dof} DOF ({model.contact_nodes.size} contact nodes on the "
          f"interface of two bodies): model {out['model_s']} s; modes + reduction + EPMC "
          f"{out['seconds']:.1f} s (target 120 s), peak {out['peak_MB']:.0f} MB (target "
          f"4096 MB); {out['note']}; load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
