"""Quadratic against refined linear hexahedra on the cantilever (issue 29, item 3).

examples/cantilever.inp (24x6x2 C3D8I), sets contact/clamp/tip, F_N 2000 N, mu 0.5, stick
slope 1e4 N/mm^3, E 70000 MPa, nu 0.33, fixed normal contact, one load at a time
(``tip:1,0,0:300`` axial, ``tip:0,1,0:50`` lateral). For each load: hex8 on the mesh refined
x1, x2, x4 (``--refine``), hex20 on the mesh promoted (``--element hex20``) x1 and x2, and
hex20 x1 with the HRZ contact weights instead of CalculiX's; W (N·mm), the peak
displacement (mm), the CPU time (s), the error against the converged estimate and the time
per converged digit, -log10 |W / W* - 1|. W* is Richardson's estimate from the three hex8
levels (observed order) and, as a check, from hex20 x1 -> x2 (order 1 assumed, as for W).
Also the first three stuck frequencies (2700 kg/m^3) of each mesh.

    PYTHONPATH=src python benchmarks/hex20_vs_hex8.py [--quick] [--load SPEC]

``--quick`` leaves out hex8 x4 (about 60k DOF) and hex20 x2 (37k DOF), minutes each on a
loaded machine; W* is then the two-level hex8 estimate (order 1 assumed).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.builtin.meshrun import SineCycles, solve_mesh
from microslip.fe.convergence import richardson
from microslip.fe.meshfile import read_mesh
from microslip.fe.meshload import MeshLoad
from microslip.fe.promote import promote_mesh
from microslip.fe.refine import refine_mesh
from microslip.meshdynamics.modes import linear_modes

CASE = dict(contact_set="contact", clamp_set="clamp", normal_force=2000.0, modulus=70000.0,
            poisson_ratio=0.33, friction=0.5, stick_slope=1e4)
LOADS = ("tip:1,0,0:300", "tip:0,1,0:50")


def run(mesh, load: str, weights: str = "calculix") -> dict:
    t0 = time.process_time()
    model = build_mesh_model(mesh, rigid_base(**CASE), contact_weights=weights)
    result = solve_mesh(model, (MeshLoad.parse(load),), SineCycles(increments=40, tol=1e-3,
                                                                     max_cycles=10))
    s = result.summary()
    cpu = time.process_time() - t0
    freqs = linear_modes(model, 2700.0, 3).frequencies_Hz
    return {"dof": model.dof, "element": model.element, "W": s["dissipated_energy_Nmm"],
            "u": s["peak_displacement_mm"], "cpu": cpu, "f": list(freqs)}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--load", action="append")
    args = ap.parse_args()
    base = read_mesh("examples/cantilever.inp")
    for load in args.load or LOADS:
        rows = []
        for el, r in [("hex8", 1), ("hex8", 2), ("hex8", 4), ("hex20", 1), ("hex20", 2)]:
            if args.quick and (el, r) in (("hex8", 4), ("hex20", 2)):
                continue
            mesh = refine_mesh(base, r)
            rows.append((f"{el} x{r}", run(promote_mesh(mesh) if el == "hex20" else mesh,
                                           load)))
            print(f"  ... {rows[-1][0]}: {rows[-1][1]['cpu']:.1f} s", flush=True)
        rows.append(("hex20 x1 hrz", run(promote_mesh(base), load, "hrz")))
        w = {name: row["W"] for name, row in rows}
        if "hex8 x4" in w:
            est = richardson([w["hex8 x1"], w["hex8 x2"], w["hex8 x4"]], 1.0)
        else:
            est = richardson([w["hex8 x1"], w["hex8 x2"]], 1.0)
        print(f"\nload {load}: W* = {est.value:.6g} N·mm ({est.how}, order {est.order:.2f}, "
              f"uncertainty {100 * est.uncertainty:.1f} %)")
        if "hex20 x2" in w:
            e20 = richardson([w["hex20 x1"], w["hex20 x2"]], 1.0)
            print(f"  from hex20 x1 -> x2: {e20.value:.6g} N·mm ({e20.how})")
        print(f"  {'mesh':<14s} {'element':>7s} {'DOF':>7s} {'W (N·mm)':>11s} {'error':>8s} "
              f"{'u (mm)':>11s} {'CPU (s)':>8s} {'digits':>6s} {'s/digit':>8s}  "
              f"f1..f3 (Hz)")
        for name, row in rows:
            err = row["W"] / est.value - 1.0
            digits = -math.log10(abs(err)) if err else float("inf")
            per = row["cpu"] / digits if digits > 0 else float("inf")
            f = " ".join(f"{x:8.2f}" for x in row["f"])
            print(f"  {name:<14s} {row['element']:>7s} {row['dof']:7d} {row['W']:11.6g} "
                  f"{100 * err:+7.2f}% {row['u']:11.6g} {row['cpu']:8.2f} {digits:6.2f} "
                  f"{per:8.2f}  {f}")
        print(f"  W with HRZ against CalculiX contact weights (hex20 x1): "
              f"{100 * (w['hex20 x1 hrz'] / w['hex20 x1'] - 1):+.2f} %", flush=True)
    _ = np  # numpy is the runtime's


if __name__ == "__main__":
    main()
