"""Start-up time of the command line, against the import of numpy and scipy.sparse.

Run: ``python3 benchmarks/bench_startup.py`` (``--runs N``, default 7).

Each row is a fresh interpreter (a subprocess, as a shell script calling ``microslip`` pays
it), timed wall-clock from start to exit; the best of N runs, the rows interleaved run by
run so that a busy machine slows them alike. Targets (issue 21): ``microslip --help`` within
2x and ``microslip loop --model tip --preset table1`` within 3x of the reference, ``python
-c "import numpy, scipy.sparse"``. The numba kernels come from their on-disk cache (one
warm-up run first), as on any call after the first on a machine.
"""

from __future__ import annotations

import argparse
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


def wall(argv: list[str]) -> float:
    """Seconds from start to exit of ``python argv`` (output discarded; must succeed)."""
    start = time.perf_counter()
    subprocess.run([sys.executable, *argv], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7, help="runs per row (best taken)")
    runs = parser.parse_args(argv).runs
    for _, args, _ in ROWS:  # warm-up: compiled-kernel cache, file system cache
        wall(args)
    best = [min(t) for t in zip(*([wall(args) for _, args, _ in ROWS] for _ in range(runs)),
                                strict=True)]
    reference = best[0]
    print(f"best of {runs} runs, s; ratio to the first row")
    print(f"{'command':<46} {'time (s)':>9} {'ratio':>7} {'target':>7}")
    met = True
    for (label, _, target), t in zip(ROWS, best, strict=True):
        ratio = t / reference
        mark = "" if target is None else f"{'<=' if ratio <= target else '> '}{target:g}x"
        met &= target is None or ratio <= target
        print(f"{label:<46} {t:9.3f} {ratio:7.2f} {mark:>7}")
    print("targets met" if met else "targets NOT met")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
