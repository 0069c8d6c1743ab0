"""W's sensitivity to the normal slope K (issue 33, item 6): the built-in solver on the examples'
cantilever and on the new user's unstructured plate, K = 1e5 (the default), 1e6, 1e7, 1e8
N/mm^3 and ``fixed`` normal contact, on the given mesh and refined x2.

    PYTHONPATH=src .venv/bin/python benchmarks/normal_slope.py

Cases (lambda = 1e4 N/mm^3, mu = 0.5):

* examples/cantilever.inp: aluminium (70000 MPa, 0.33), F_N = 2000 N on ``clamp``, 300 N
  along the bar on ``tip``;
* tests/data/meshes/plate_washer.msh: steel (210000 MPa, 0.3), F_N = 8000 N on the 12 mm
  ``washer``, its ``contact`` patch 25 x 25 mm on the base, 400 N along the plate on ``end``.

Units: N, mm, N·mm.
"""

from __future__ import annotations

import time
from pathlib import Path

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.builtin.meshrun import SineCycles, solve_mesh
from microslip.fe.meshfile import read_mesh
from microslip.fe.meshload import MeshLoad
from microslip.fe.refine import refine_mesh

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "cantilever.inp": (ROOT / "examples" / "cantilever.inp", "contact", "clamp", 2000.0,
                       MeshLoad("tip", (1.0, 0.0, 0.0), 300.0), 70000.0, 0.33),
    "plate_washer.msh": (ROOT / "tests" / "data" / "meshes" / "plate_washer.msh", "contact",
                         "washer", 8000.0, MeshLoad("end", (1.0, 0.0, 0.0), 400.0), 210000.0,
                         0.3),
}
SLOPES = (1e5, 1e6, 1e7, 1e8)


def main() -> None:
    t0 = time.perf_counter()
    for name, (path, contact, clamp, fn, load, e, nu) in CASES.items():
        base = read_mesh(path)
        for level in (1, 2):
            mesh = base if level == 1 else refine_mesh(base, level)
            ws = {}
            for law in (*SLOPES, "fixed"):
                a = rigid_base(contact_set=contact, clamp_set=clamp, normal_force=fn,
                               modulus=e, poisson_ratio=nu, friction=0.5, stick_slope=1e4,
                               normal_contact="fixed" if law == "fixed" else "penalty",
                               normal_slope=1e5 if law == "fixed" else float(law))
                t = time.perf_counter()
                model = build_mesh_model(mesh, a)
                r = solve_mesh(model, [load], SineCycles())
                ws[law] = r.dissipated_energy
                print(f"{name} x{level} ({model.dof} DOF)  K {law!s:>6}: W "
                      f"{r.dissipated_energy:.6g} N mm, {r.cycles} cycles, pressed "
                      f"{r.pressed['nodes']} nodes {r.pressed['area_mm2']:.4g} mm^2, "
                      f"{time.perf_counter() - t:.1f} s",
                      flush=True)
            ref = ws[1e8]
            print(f"{name} x{level}: W / W(1e8) - 1: " + ", ".join(
                f"{k!s}: {w / ref - 1:+.2%}" for k, w in ws.items()), flush=True)
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
