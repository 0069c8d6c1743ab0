"""Start-up time of the command line, against the import of numpy and scipy.sparse.

Run: ``python3 benchmarks/bench_startup.py`` (``--runs N``, default 10).

Each row is a fresh interpreter (a subprocess, as a shell script calling ``microslip`` pays
it), timed wall-clock from start to exit and in CPU time (user + system, of the child; less
sensitive than the wall clock to other work on a busy machine); the median of N runs of
each, the rows interleaved run by run so that a busy machine slows them alike. Targets (issue 21):
``microslip --help`` within 2x and ``microslip loop --model tip --preset table1`` within 3x
of the reference, ``python -c "import numpy, scipy.sparse"``. A single loop runs the models
as plain Python (no numba, issue 27); other numba kernels come from their on-disk cache (one
warm-up run first), as on any call after the first on a machine.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import time

#: (label, argv after the interpreter, target ratio to the reference or None).
ROWS: tuple[tuple[str, list[str], float | None], ...] = (
    ('python -c "import numpy, scipy.sparse"', ["-c", "import numpy, scipy.sparse"], None),
    ("microslip --help", ["-m", "microslip", "--help"], 2.0),
    ("microslip loop --model tip --preset table1",
     ["-m", "microslip", "loop", "--model", "tip", "--preset", "table1"], 3.0),
)


def timed(argv: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds from start to exit of ``python argv`` (output discarded; must
    succeed)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, *argv], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10, help="runs per row (median taken)")
    runs = parser.parse_args(argv).runs
    for _, args, _ in ROWS:  # warm-up: compiled-kernel cache, file system cache
        timed(args)
    runs_ = [[timed(args) for _, args, _ in ROWS] for _ in range(runs)]
    wall = [statistics.median(r[i][0] for r in runs_) for i in range(len(ROWS))]
    cpu = [statistics.median(r[i][1] for r in runs_) for i in range(len(ROWS))]
    print(f"median of {runs} runs, s; ratio to the first row (wall clock, then CPU time)")
    print(f"{'command':<44} {'wall':>7} {'ratio':>6} {'CPU':>7} {'ratio':>6} {'target':>7}")
    met = True
    for i, (label, _, target) in enumerate(ROWS):
        ratio, cpu_ratio = wall[i] / wall[0], cpu[i] / cpu[0]
        mark = "" if target is None else f"{'<=' if ratio <= target else '> '}{target:g}x"
        met &= target is None or ratio <= target
        print(f"{label:<44} {wall[i]:7.3f} {ratio:6.2f} {cpu[i]:7.3f} {cpu_ratio:6.2f} "
              f"{mark:>7}")
    print("targets met (wall clock)" if met else "targets NOT met (wall clock)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
