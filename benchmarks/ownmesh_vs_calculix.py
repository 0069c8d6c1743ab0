"""The cantilever example (issue 22): built-in FE against CalculiX on the same mesh, and the
built-in FE's mesh convergence, printed side by side in one run.

The clamped bar of examples/ (clamped length 50.8, overhang 101.6, width 25.4, thickness
6.35 mm; aluminium E 70000 MPa, nu 0.33; mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3, penalty
normal 1e6 N/mm^3) under an axial end load, a lateral end load in the contact plane, and both
at 90 degrees. Each load case runs on the built-in solver until W per cycle settles (1e-3),
then on CalculiX for the same number of cycles from the same ramp; W is the work of all loads
over the last cycle, d the first load's half peak-to-peak work-conjugate displacement.

Run:  python benchmarks/ownmesh_vs_calculix.py                # 24x6x2 vs CalculiX, ~3 min
      python benchmarks/ownmesh_vs_calculix.py --no-ccx       # convergence only
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
import time
from pathlib import Path

from microslip.fe.clamp import MeshClamp
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import write_inp
from microslip.fe.meshload import MeshLoad
from microslip.fe.ownmesh import OwnMeshCase, run_own_mesh

CASES = {
    "axial 300 N": ("tip:1,0,0:300",),
    "lateral 50 N": ("tip:0,1,0:50",),
    "both, 90 deg": ("tip:1,0,0:300", "tip:0,1,0:50:90"),
}
CLAMP = dict(normal_force=2000.0, friction=0.5, modulus=70000.0, poisson_ratio=0.33,
             stick_slope=1e4, normal_contact="penalty", normal_slope=1e6)


def _case(path: str, loads: tuple[str, ...], cycles: int = 3) -> OwnMeshCase:
    clamp = MeshClamp("contact", "clamp", **CLAMP)  # type: ignore[arg-type]
    return OwnMeshCase(path, clamp, loads=tuple(MeshLoad.parse(s) for s in loads),
                       cycles=cycles)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-ccx", action="store_true", help="skip CalculiX")
    ap.add_argument("--meshes", nargs="+", default=["12x3x1", "24x6x2", "48x12x4"],
                    help="built-in convergence meshes NXxNYxNZ (nx a multiple of 3)")
    ap.add_argument("--ccx-mesh", default="24x6x2")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="ownmesh_"))
    files = {}
    for spec in dict.fromkeys([*args.meshes, args.ccx_mesh]):
        nx, ny, nz = (int(v) for v in spec.split("x"))
        files[spec] = str(write_inp(cantilever_mesh(nx, ny, nz), tmp / f"cant_{spec}.inp"))

    print("Mesh convergence, built-in solver (W N·mm, d mm; last column: vs the finest)")
    print(f"{'load case':<14s}" + "".join(f"{m:>22s}" for m in args.meshes))
    finest: dict[str, tuple[float, float]] = {}
    rows = {}
    for name, loads in CASES.items():
        row = []
        for spec in args.meshes:
            t = time.perf_counter()
            s = run_own_mesh(_case(files[spec], loads)).summary
            row.append((s["dissipated_energy_Nmm"], s["peak_displacement_mm"], s["dof"],
                        time.perf_counter() - t))
        rows[name] = row
        finest[name] = row[-1][:2]
        cells = [f"W {w:.5g} ({w / finest[name][0] - 1:+.1%})" for w, _, _, _ in row]
        print(f"{name:<14s}" + "".join(f"{c:>22s}" for c in cells))
        cells = [f"d {d:.5g} ({d / finest[name][1] - 1:+.2%})" for _, d, _, _ in row]
        print(f"{'':<14s}" + "".join(f"{c:>22s}" for c in cells))
    print("DOF / wall s: " + ", ".join(f"{m}: {r[2]} / {r[3]:.2f}"
                                       for m, r in zip(args.meshes, rows[next(iter(rows))],
                                                       strict=True)))
    if args.no_ccx or shutil.which("ccx") is None:
        print("CalculiX: skipped" + ("" if args.no_ccx else " (ccx not on PATH)"))
        return
    print(f"\nBuilt-in against CalculiX on the same {args.ccx_mesh} mesh (C3D8I), same cycles")
    print(f"{'load case':<14s}{'cycles':>7s}{'W builtin':>12s}{'W ccx':>12s}{'dW':>8s}"
          f"{'d builtin':>12s}{'d ccx':>12s}{'dd':>8s}{'t builtin':>10s}{'t ccx':>8s}"
          "   target")
    for name, loads in CASES.items():
        t = time.perf_counter()
        b = run_own_mesh(_case(files[args.ccx_mesh], loads)).summary
        tb = time.perf_counter() - t
        t = time.perf_counter()
        c = run_own_mesh(_case(files[args.ccx_mesh], loads, b["cycles"]), "calculix").summary
        tc = time.perf_counter() - t
        dw = c["dissipated_energy_Nmm"] / b["dissipated_energy_Nmm"] - 1
        dd = c["peak_displacement_mm"] / b["peak_displacement_mm"] - 1
        ok = "met" if abs(dw) <= 0.03 and abs(dd) <= 0.01 else "NOT met"
        print(f"{name:<14s}{b['cycles']:>7d}{b['dissipated_energy_Nmm']:>12.5g}"
              f"{c['dissipated_energy_Nmm']:>12.5g}{dw:>+8.2%}{b['peak_displacement_mm']:>12.5g}"
              f"{c['peak_displacement_mm']:>12.5g}{dd:>+8.2%}{tb:>9.2f}s{tc:>7.1f}s"
              f"   W 3 %, d 1 %: {ok}")
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
