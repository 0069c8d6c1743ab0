"""The examples (issues 22, 29): the built-in FE's mesh convergence on the cantilever, then the
built-in FE against CalculiX on each example's mesh, in one table.

The clamped bar of examples/ (clamped length 50.8, overhang 101.6, width 25.4, thickness
6.35 mm; aluminium E 70000 MPa, nu 0.33; mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3, penalty
normal 1e6 N/mm^3) under an axial end load, a lateral end load in the contact plane, and both
at 90 degrees. Each load case runs on the built-in solver until W per cycle settles (1e-3),
then on CalculiX for the same number of cycles from the same ramp; W is the work of all loads
over the last cycle, d the first load's half peak-to-peak work-conjugate displacement.

The CalculiX table (:data:`EXAMPLES`) runs validate --mesh's comparison on
examples/cantilever.inp, post_on_plate.inp and bolt_pad.inp: CalculiX's node-to-surface
contact (the built-in solver's nodal law) for as many cycles as the built-in needs to settle.

Run:  python benchmarks/ownmesh_vs_calculix.py                 # ~20 min with CalculiX
      python benchmarks/ownmesh_vs_calculix.py --face-to-face  # also face-to-face, ~40 min
      python benchmarks/ownmesh_vs_calculix.py --no-ccx        # convergence only
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


#: The examples of issue 29 on their committed meshes: (file, loads, substeps). The post's
#: reversal flips most of its contact between stick and slip: CalculiX's node-to-surface
#: contact needs 160 increments per cycle there to converge (40 diverge).
EXAMPLES = {
    "cantilever, axial 300 N": ("examples/cantilever.inp", ("tip:1,0,0:300",), 50),
    "post, 500 N at 45 deg": ("examples/post_on_plate.inp", ("top:1,1,0:500",), 200),
    "bolt pad, axial 100 N": ("examples/bolt_pad.inp", ("end:1,0,0:100",), 50),
}
#: validate --mesh's contact values on every example (its default normal slope).
VALIDATE = dict(normal_force=2000.0, friction=0.5, modulus=70000.0, poisson_ratio=0.33,
                stick_slope=1e4, normal_contact="penalty", normal_slope=1e5)


def _examples(face_to_face: bool) -> None:
    """Built-in against CalculiX's node-to-surface contact (validate --mesh's default) on each
    example, same increments and cycles, and the built-in W at 10x the normal slope."""

    from microslip.fe.calculix.compare import compare_on_mesh

    root = Path(__file__).resolve().parent.parent
    print("\nBuilt-in against CalculiX on the same mesh, increments, cycles and slopes "
          "(normal 1e5, stick 1e4 N/mm^3)")
    head = (f"{'example':<24s}{'CalculiX contact':<17s}{'cyc':>4s}{'W builtin':>11s}"
            f"{'W ccx':>11s}{'dW':>9s}{'d builtin':>11s}{'d ccx':>11s}{'dd':>9s}"
            f"{'W@10K':>8s}{'t ccx':>8s}  settled")
    print(head)
    forms = ("node-to-surface", "face-to-face") if face_to_face else ("node-to-surface",)
    for name, (path, loads, substeps) in EXAMPLES.items():
        clamp = MeshClamp("contact", "clamp", **VALIDATE)  # type: ignore[arg-type]
        case = OwnMeshCase(str(root / path), clamp,
                           loads=tuple(MeshLoad.parse(s) for s in loads), substeps=substeps)
        for form in forms:
            t = time.perf_counter()
            r = compare_on_mesh(case, formulation=form, progress=False,
                                sensitivity=form == forms[0])
            tc = time.perf_counter() - t
            b, c, d = r["builtin"], r["calculix"], r["relative_difference"]
            sens = r.get("normal_slope_sensitivity", {}).get("relative_change")
            ok = "/".join("yes" if v else "NO" for v in r["settled"].values())
            print(f"{name:<24s}{form:<17s}{r['cycles']:>4d}{b['dissipated_energy_Nmm']:>11.5g}"
                  f"{c['dissipated_energy_Nmm']:>11.5g}{d['dissipated_energy_Nmm']:>+9.3%}"
                  f"{b['peak_displacement_mm']:>11.5g}{c['peak_displacement_mm']:>11.5g}"
                  f"{d['peak_displacement_mm']:>+9.4%}"
                  f"{'' if sens is None else f'{sens:+.1%}':>8s}{tc:>7.0f}s  {ok}")
    print("W@10K: the built-in W at 10x the normal slope, relative; settled: built-in/CalculiX")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-ccx", action="store_true", help="skip CalculiX")
    ap.add_argument("--meshes", nargs="+", default=["12x3x1", "24x6x2", "48x12x4"],
                    help="built-in convergence meshes NXxNYxNZ (nx a multiple of 3)")
    ap.add_argument("--face-to-face", action="store_true",
                    help="also CalculiX's face-to-face contact on each example")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="ownmesh_"))
    files = {}
    for spec in dict.fromkeys(args.meshes):
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
    _examples(args.face_to_face)
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
