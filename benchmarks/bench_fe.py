"""Wall time, DOF and iterations of the CalculiX runs, per mesh level (and stick slope).

Not part of the test suite: the paper-size mesh takes minutes. Prints a markdown table with
the errors against the closed forms, which docs/validation.md quotes.

    python3 benchmarks/bench_fe.py                            # coarse, medium, paper; tip+centre
    python3 benchmarks/bench_fe.py --mesh 10x2x1 --mesh 20x2x1 --mesh 40x2x1 --model tip
    python3 benchmarks/bench_fe.py --mesh coarse --stick-slope 1e3 --stick-slope 1e5

Meshes are level names (coarse, medium, paper) or NXxNYxNZ element counts.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from microslip import preset
from microslip.errors import MicroslipError
from microslip.fe import LEVELS, FECase, MeshSpec, ccx_version, mesh_spec, run_case
from microslip.validate import validation_row


def _mesh(text: str) -> tuple[str, MeshSpec]:
    """A level (its counts on the Table 1 bar, microslip.meshlevels) or NXxNYxNZ."""
    if text in LEVELS:
        return text, mesh_spec(text, preset("table1"))
    try:
        nx, ny, nz = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"mesh must be one of {', '.join(LEVELS)} or NXxNYxNZ, got {text!r}") from None
    return text, MeshSpec(nx, ny, nz)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mesh", action="append", type=_mesh,
                    help="mesh level or NXxNYxNZ (repeat; default coarse, medium, paper)")
    ap.add_argument("--model", action="append", choices=["tip", "centre"],
                    help="load case (repeat; default both)")
    ap.add_argument("--stick-slope", action="append", type=float, metavar="N/MM3",
                    help="stick slope lambda (repeat; default 1e4)")
    ap.add_argument("--element", default="C3D20R", choices=["C3D20R"])
    ap.add_argument("--normal-slope", type=float, default=1e5, metavar="N/MM3")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=None, metavar="S")
    ap.add_argument("--out", metavar="DIR", help="keep the job directories here")
    args = ap.parse_args(argv)
    meshes = args.mesh or [_mesh(k) for k in ("coarse", "medium", "paper")]
    models = args.model or ["tip", "centre"]
    slopes = args.stick_slope or [1e4]
    keep = Path(args.out) if args.out else None
    tmp = tempfile.TemporaryDirectory(prefix="bench-fe-") if keep is None else None
    root = keep if keep is not None else Path(tmp.name)  # type: ignore[union-attr]
    print(f"CalculiX {ccx_version()}, OMP_NUM_THREADS={args.threads}, element {args.element}, "
          f"normal slope {args.normal_slope:g} N/mm^3")
    print("| case | mesh | elements | DOF | lambda (N/mm^3) | wall (s) | iterations "
          "| d0 err | W_d err | W_d err vs sampled | closure | slip length (mm) |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    try:
        for model in models:
            for name, spec in meshes:
                for lam in slopes:
                    case = FECase(model, mesh=spec, stick_slope=lam, element=args.element,
                                  normal_slope=args.normal_slope)
                    job = root / (f"{model}-{spec.label()}-{args.element}-lambda{lam:g}-"
                                  f"k{args.normal_slope:g}")
                    try:
                        r = run_case(case, job, timeout=args.timeout, threads=args.threads)
                    except MicroslipError as exc:
                        print(f"| {model} | {name} | {spec.label()} | {spec.dof} | {lam:g} "
                              f"| failed: {' '.join(str(exc).split())} |||||||")
                        continue
                    row = validation_row(r, name)
                    sampled = r.damping.dissipated_energy / row["wd_closed_sampled_Nmm"] - 1
                    print(f"| {model} | {name} | {spec.label()} | {r.dof} | {lam:g} "
                          f"| {r.wall_s:.1f} | {r.total_iterations} "
                          f"| {100 * row['err_peak_fe_closed']:+.3f} % "
                          f"| {100 * row['err_wd_fe_closed']:+.3f} % "
                          f"| {100 * sampled:+.3f} % | {r.closure:.1e} "
                          f"| {row['slip_length_fe_mm']:.1f} "
                          f"(exact {row['slip_length_closed_mm']:.1f}) |", flush=True)
    finally:
        if tmp is not None:
            tmp.cleanup()
    return 0


if __name__ == "__main__":
    sys.exit(main())
