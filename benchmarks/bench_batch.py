"""Throughput of the batch engine, side by side with the other ways to do the same work.

Run: ``python3 benchmarks/bench_batch.py`` (``--quick`` for a smaller run).

Rows (case-increments per second: one increment of one case's first loading, with its
energy accumulation, is one case-increment; all rows run the tip model, Table 2 preset,
amplitudes evenly spaced from 100 N to 8000 N, 1000 increments, consistent Poisson and
length updates, secant U):

* batch engine (numba), 1 and 2 threads;
* the same on a contact (issue 11): shear layer of stick slope 1e5 N/mm^3 with the body's
  shear lag and the parabolic pressure law (``Contact.layer(1e5, "parabolic")``), 1 and 2
  threads, the same cases and the same definition of a case-increment (target: >= 1e9 on 2
  cores with these options on), and the time of one full single loop on that contact
  (``microslip.damping``: backbone, Masing loop and energies, 1000 increments, after
  warm-up; target < 1 ms), tip and centre;
* the single-loop API, ``microslip.damping`` once per case;
* the floor of any model whose slip front solves a transcendental equation: a compiled loop
  over the same cases and increments in the same layout that does nothing but one
  ``math.tanh`` per case-increment (the layer's stuck part, F = Q(a) + q tanh(lambda (L - a))
  / lambda, needs at least one per increment), and, beside it, the same loop with one
  division instead (what SIMD arithmetic alone reaches here). numba vectorises ``tanh`` only
  through Intel SVML, which this llvmlite is not built with; the printout says which;
* a plain-Python loop of the same arithmetic (the kernel's ``py_func`` run by the
  interpreter; it still calls the compiled step function per case-increment);
* a C reference loop (``benchmarks/ref_tip.c``) compiled here with ``gcc -O2``: one case at a
  time, and blocks of cases interleaved; its results are compared with the engine's;
* end to end, ``microslip sweep ... --cases 1000000 --increments 1000 --out x.csv`` in a
  subprocess (start-up, validation, computing and writing the CSV), with the peak memory
  (maximum resident set size) of that process.

The machine may be shared: each timing is the best of a few repeats.
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from numba import config as numba_config
from numba import njit, prange

from microslip import damping, preset
from microslip.batch import batch_damping
from microslip.models import Contact, batch_kernels

HERE = Path(__file__).resolve().parent
PRESET = "table2-tip"
#: The contact of the issue-11 rows: a finite stick slope, shear lag, parabolic pressure.
LAYER = Contact.layer(1e5, "parabolic")


def amplitudes(cases: int) -> np.ndarray:
    return np.linspace(100.0, 8000.0, cases)


def best(fn: Callable[[], object], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def rate_batch(cases: int, n: int, threads: int | None, backend: str, repeats: int,
               model: str = "tip", contact: Contact | None = None) -> float:
    p = preset(PRESET if model == "tip" else "table2-centre")
    a = amplitudes(cases)
    batch_damping(model, p, a[:10], n, backend=backend, threads=threads,
                  contact=contact)  # compile / load
    t = best(lambda: batch_damping(model, p, a, n, backend=backend, threads=threads,
                                   contact=contact), repeats)
    return cases * n / t


def loop_time(model: str, n: int, repeats: int) -> float:
    """Seconds of one ``microslip.damping`` on :data:`LAYER` at 0.8 mu F_N, after warm-up."""
    p = preset(PRESET if model == "tip" else "table2-centre")
    f0 = 0.8 * p.macroslip_force
    damping(model, p, f0, n, contact=LAYER)
    return best(lambda: damping(model, p, f0, n, contact=LAYER), repeats)


@njit(parallel=True, cache=True, fastmath=False)
def _floor_kernel(scale, n, transcendental, out):
    """One ``math.tanh`` (or one division) per case-increment, cases in chunks of CHUNK
    lanes as the engine lays them out; the sum per case keeps the work from being removed."""
    ncase = scale.shape[0]
    chunk = batch_kernels.CHUNK
    for c in prange((ncase + chunk - 1) // chunk):
        lo = c * chunk
        m = min(chunk, ncase - lo)
        acc = np.zeros(m)
        for i in range(1, n + 1):
            fr = i / n
            if transcendental:
                for k in range(m):
                    acc[k] += math.tanh(scale[lo + k] * fr)
            else:
                for k in range(m):
                    acc[k] += 1.0 / (scale[lo + k] + fr)
        for k in range(m):
            out[lo + k] = acc[k]


def rate_floor(cases: int, n: int, threads: int, transcendental: bool, repeats: int) -> float:
    """Case-increments/s of :func:`_floor_kernel` on ``threads`` threads."""
    import numba

    scale = np.linspace(0.1, 20.0, cases)
    out = np.empty(cases)
    before = numba.get_num_threads()
    numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    try:
        _floor_kernel(scale[:10], 2, transcendental, out[:10])
        t = best(lambda: _floor_kernel(scale, n, transcendental, out), repeats)
    finally:
        numba.set_num_threads(before)
    return cases * n / t


def rate_single_loop(cases: int, n: int) -> float:
    p, a = preset(PRESET), amplitudes(cases)
    t0 = time.perf_counter()
    for f0 in a:
        damping("tip", p, float(f0), n)
    return cases * n / (time.perf_counter() - t0)


def rate_python(cases: int, n: int) -> float:
    p, a = preset(PRESET), amplitudes(cases)
    t0 = time.perf_counter()
    batch_damping("tip", p, a, n, backend="python")
    return cases * n / (time.perf_counter() - t0)


def rate_c(workdir: Path, cases: int, n: int, repeats: int) -> dict[str, tuple[float, float]]:
    """{variant: (case-increments/s, largest relative difference to the engine)}."""
    gcc = shutil.which("gcc")
    if gcc is None:
        return {}
    exe = workdir / "ref_tip"
    subprocess.run([gcc, "-O2", "-o", str(exe), str(HERE / "ref_tip.c")], check=True,
                   capture_output=True, timeout=120)
    ref = batch_damping("tip", preset(PRESET), amplitudes(cases), n).loss_factor
    out: dict[str, tuple[float, float]] = {}
    for mode, m in (("sequential", max(cases // 10, 1)), ("interleaved", cases)):
        times = []
        for _ in range(repeats):
            res = subprocess.run([str(exe), str(m), str(n), mode, str(workdir / "eta.bin")],
                                 check=True, capture_output=True, text=True, timeout=600)
            times.append(float(res.stdout))
        eta = np.fromfile(workdir / "eta.bin")
        engine = ref if m == cases else batch_damping("tip", preset(PRESET), amplitudes(m),
                                                      n).loss_factor
        out[mode] = (m * n / min(times), float(np.max(np.abs(eta / engine - 1.0))))
    return out


def end_to_end(workdir: Path, cases: int, n: int) -> tuple[float, float, int]:
    """(wall time s, peak RSS MB, file size bytes) of one `microslip sweep` process."""
    out = workdir / "x.csv"
    cmd = [sys.executable, "-m", "microslip", "sweep", "--model", "tip", "--preset", PRESET,
           "--amplitude-range", "100", "8000", "--cases", str(cases), "--increments", str(n),
           "--out", str(out), "--no-progress"]
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        err = proc.stderr.read().decode() if proc.stderr else ""
        raise SystemExit(f"microslip sweep failed: {err}")
    size = out.stat().st_size
    out.unlink()
    return wall, usage.ru_maxrss / 1024.0, size  # ru_maxrss is in KiB on Linux


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller sizes (a smoke run)")
    ap.add_argument("--increments", type=int, default=1000)
    args = ap.parse_args()
    n = args.increments
    big = 20_000 if args.quick else 400_000
    e2e_cases = 10_000 if args.quick else 1_000_000
    repeats = 1 if args.quick else 3
    print(f"tip model, preset {PRESET}, {n} increments per case; CPU cores: {os.cpu_count()}; "
          f"chunk {batch_kernels.CHUNK} cases; load average at start: "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    rows: list[tuple[str, float, str]] = []
    rows.append(("batch engine, numba, 1 thread", rate_batch(big, n, 1, "numba", repeats),
                 f"{big} cases"))
    rows.append(("batch engine, numba, 2 threads", rate_batch(big, n, 2, "numba", repeats),
                 f"{big} cases"))
    rows.append(("  (centre model, 2 threads)", rate_batch(big, n, 2, "numba", repeats,
                                                       "centre"), f"{big} cases"))
    layer_cases = max(big // 20, 1000)
    layer_rows = [(f"batch engine on layer + parabolic law, {t} thread{'s' * (t > 1)}",
                   rate_batch(layer_cases, n, t, "numba", repeats, contact=LAYER),
                   f"{layer_cases} cases") for t in (1, 2)]
    rows.extend(layer_rows)
    svml = "with SVML" if numba_config.USING_SVML else "no SVML: scalar libm"
    floor_rows = [(f"  floor: one math.tanh per case-increment, {t} thread{'s' * (t > 1)}",
                   rate_floor(big, n, t, True, repeats), f"{big} cases, {svml}")
                  for t in (1, 2)]
    rows.extend(floor_rows)
    rows.append(("  (one division instead, 2 threads)", rate_floor(big, n, 2, False, repeats),
                 f"{big} cases"))
    loops = {m: loop_time(m, n, 20 if args.quick else 100) for m in ("tip", "centre")}
    rows.append(("single-loop API (microslip.damping)", rate_single_loop(20, n), "20 cases"))
    rows.append(("plain-Python loop, same arithmetic", rate_python(10, n), "10 cases"))
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        c = rate_c(work, big, n, repeats)
        for mode, (rate, diff) in c.items():
            m = max(big // 10, 1) if mode == "sequential" else big
            rows.append((f"C reference (gcc -O2), {mode}, 1 core", rate,
                         f"{m} cases, max |eta_C/eta - 1| = {diff:.1e}"))
        if not c:
            rows.append(("C reference", float("nan"), "gcc not found"))
        end_to_end(work, 1000, n)  # warm the numba cache of this interpreter
        wall, rss, size = end_to_end(work, e2e_cases, n)
    rows.append((f"`microslip sweep`, {e2e_cases} cases, end to end", e2e_cases * n / wall,
                 f"{wall:.2f} s wall, peak RSS {rss:.0f} MB, CSV {size / 1e6:.0f} MB"))
    width = max(len(r[0]) for r in rows)
    print(f"{'':{width}}  case-increments/s")
    for name, rate, note in rows:
        print(f"{name:{width}}  {rate:12.3e}   {note}")
    print(f"single loop on layer + parabolic law (microslip.damping, {n} increments, best "
          "after warm-up), target < 1 ms:")
    for m, t in loops.items():
        print(f"  {m:7s} {1e3 * t:8.3f} ms   {'met' if t < 1e-3 else 'NOT met'}")
    layer2 = layer_rows[1][1]
    print(f"batch engine on layer + parabolic law, 2 threads: {layer2:.3e} case-increments/s, "
          f"target >= 1e9: {'met' if layer2 >= 1e9 else 'NOT met'} (rigid tip, 2 threads: "
          f"{rows[1][1]:.3e}; the floor of one tanh per increment, 2 threads: "
          f"{floor_rows[1][1]:.3e})")
    print(f"load average at the end: {', '.join(f'{x:.2f}' for x in os.getloadavg())} "
          "(other processes on the machine slow every row)")
    if args.quick:
        print("targets are judged on the full run (without --quick)")
    else:
        print(f"targets: end to end >= 1e8 case-increments/s (1e6 x 1000 in < 10 s): "
              f"{'met' if e2e_cases * n / wall >= 1e8 else 'NOT met'}; peak memory < 500 MB: "
              f"{'met' if rss < 500 else 'NOT met'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
