"""Issue 32 item 8: the speed of two bodies in the built-in FE.

The bolted lap of two plates (examples/bolted_lap/bolted_lap.msh, 2.5 mm elements, 9k DOF; a
5 kN bolt with a 10 mm shank, plate A's end held, a lateral tip load past the friction
torque) against
  * a rigid-base part of the same size (the examples' cantilever bar at 48 x 12 x 4, 9.5k
    DOF, 2000 N clamp, 300 N axial): the time of one settled cycle, reference <= 2x;
  * CalculiX node to surface on the same lap file (same law, slopes, increments): reference
    >= 50x faster.
Each solver in this one run, wall time of the model build and of the cycles. Run:
``python benchmarks/assembly_speed.py [--no-ccx]``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from microslip.fe.assembly import Assembly, Contact, Material, Support, bolt, rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.builtin.meshrun import SineCycles, solve_mesh
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import read_mesh
from microslip.fe.meshload import MeshLoad

ROOT = Path(__file__).resolve().parents[1]
INCREMENTS = 40


def lap_assembly(normal: str = "penalty", diameter: float | None = 10.0) -> Assembly:
    pre, shanks = bolt("head", "nut", 5000.0, diameter)
    return Assembly(contacts=(Contact("a_int", "b_int"),), preloads=pre, shanks=shanks,
                    supports=(Support("fix"),), materials=(Material(210000.0, 0.3),),
                    friction=0.3, stick_slope=1e4, normal_contact=normal, normal_slope=1e5)


def builtin(mesh, assembly, loads):  # type: ignore[no-untyped-def]
    t0 = time.perf_counter()
    model = build_mesh_model(mesh, assembly)
    t1 = time.perf_counter()
    r = solve_mesh(model, loads, SineCycles(increments=INCREMENTS))
    t2 = time.perf_counter()
    cycles = len(r.work_per_cycle)
    return {"dof": model.dof, "contact_nodes": int(model.contact_nodes.size),
            "build_s": t1 - t0, "solve_s": t2 - t1, "cycles": cycles,
            "per_cycle_s": (t2 - t1) / cycles, "W_Nmm": r.dissipated_energy,
            "d_mm": float(np.ptp(r.loads[0].loop.displacement)) / 2, "settled": r.settled}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-ccx", action="store_true", help="skip the CalculiX run")
    args = ap.parse_args()
    lap = read_mesh(ROOT / "examples" / "bolted_lap" / "bolted_lap.msh")
    lap_loads = [MeshLoad("tip", (0.0, 1.0, 0.0), 150.0)]
    a = builtin(lap, lap_assembly(), lap_loads)
    bar = cantilever_mesh(48, 12, 4)
    b = builtin(bar, rigid_base(contact_set="contact", clamp_set="clamp", normal_force=2000.0,
                                modulus=70000.0, poisson_ratio=0.33, friction=0.5,
                                stick_slope=1e4, normal_contact="penalty", normal_slope=1e5),
                [MeshLoad("tip", (1.0, 0.0, 0.0), 300.0)])
    print(f"{'case':34s} {'DOF':>6s} {'contact':>7s} {'build s':>8s} {'cycles':>6s} "
          f"{'s/cycle':>8s} {'W N·mm':>10s}")
    for name, r in (("bolted lap, built-in", a), ("rigid-base bar 48x12x4, built-in", b)):
        print(f"{name:34s} {r['dof']:6d} {r['contact_nodes']:7d} {r['build_s']:8.2f} "
              f"{r['cycles']:6d} {r['per_cycle_s']:8.3f} {r['W_Nmm']:10.4g}")
    print(f"lap / rigid-base part, one settled cycle: {a['per_cycle_s'] / b['per_cycle_s']:.2f}x "
          f"(reference: <= 2x); the model build (the preload step): "
          f"{a['build_s'] / b['build_s']:.1f}x")
    if args.no_ccx:
        return
    from microslip.fe.calculix.meshrun import run_mesh_calculix

    # CalculiX's deck has no shank: both solvers on the shank-free lap, axially (no rocking)
    same = lap_assembly(diameter=None)
    lap_loads = [MeshLoad("tip", (1.0, 0.0, 0.0), 500.0)]
    a = builtin(lap, same, lap_loads)
    print(f"bolted lap without a shank, 500 N axial, built-in: build {a['build_s']:.2f} s, "
          f"{a['cycles']} cycles of {a['per_cycle_s']:.3f} s, W = {a['W_Nmm']:.5g} N·mm")
    t0 = time.perf_counter()
    c = run_mesh_calculix(lap, same, loads=lap_loads,
                          increments_per_cycle=INCREMENTS, cycles=2, startup="ramp",
                          formulation="node-to-surface", timeout=3600)
    tc = time.perf_counter() - t0
    s = c.summary()
    per_cycle = tc / 2.25  # the ramp's quarter cycle and two cycles
    print(f"CalculiX node to surface: {tc:.1f} s for 2.25 cycles ({per_cycle:.1f} s/cycle), "
          f"W = {s.get('dissipated_energy_Nmm')} N·mm (built-in {a['W_Nmm']:.5g})")
    built_in = a["build_s"] + a["per_cycle_s"] * a["cycles"]
    print(f"CalculiX / built-in, the whole settled run: {tc / built_in:.0f}x; per cycle: "
          f"{per_cycle / a['per_cycle_s']:.0f}x (reference: >= 50x)")


if __name__ == "__main__":
    main()
