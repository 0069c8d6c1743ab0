"""Cost of harmonics chosen by an error estimate (issue 28, item 3): ``modal --mesh
examples/cantilever.inp ... --solver rom`` with ``--harmonics auto`` (the default) against
``--harmonics 7``.

Run: ``python3 benchmarks/bench_harmonics.py`` (``--mode 1|2``, ``--amplitudes N``,
``--tolerance X``). Each run is the whole command in this process (mesh, clamping step,
stuck modes, ROM, EPMC; the kernels compiled by a warm-up run first), timed by the wall
clock; the EPMC's share is the run's time less the fixed run's setting-up, measured alone.
Prints per amplitude: the harmonics chosen, the error estimate, and the damping ratio and
frequency of auto against 7 harmonics.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import time
from pathlib import Path

from microslip.cli.main import main as cli

MESH = str(Path(__file__).resolve().parent.parent / "examples" / "cantilever.inp")
BASE = ["modal", "--mesh", MESH, "--contact-set", "contact", "--clamp-set", "clamp",
        "--normal-force", "2000", "--friction", "0.5", "--stick-slope", "1e4",
        "--modulus", "70000", "--poisson-ratio", "0.33", "--density", "2700",
        "--response-set", "response", "--solver", "rom", "--json"]


def run(argv: list[str]) -> tuple[float, dict]:
    out = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(out):
        code = cli(argv)
    elapsed = time.perf_counter() - t0
    if code != 0:
        raise SystemExit(f"{' '.join(argv)} exited {code}")
    return elapsed, json.loads(out.getvalue())


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mode", type=int, default=2)
    p.add_argument("--amplitudes", type=int, default=20)
    p.add_argument("--tolerance", type=float, default=0.005)
    args = p.parse_args()
    argv = [*BASE, "--mode", str(args.mode), "--amplitudes", str(args.amplitudes)]
    run([*argv[:-4], "--amplitudes", "2", "--harmonics", "3", "--json"])  # compile kernels
    t_fixed, fixed = run([*argv, "--harmonics", "7"])
    t_auto, auto = run([*argv, "--harmonic-tolerance", str(args.tolerance)])
    print(f"modal --mesh cantilever.inp --mode {args.mode} --solver rom, "
          f"{args.amplitudes} amplitudes")
    print(f"  --harmonics 7:    {t_fixed:8.1f} s (whole command)")
    print(f"  --harmonics auto: {t_auto:8.1f} s (whole command, tolerance "
          f"{100 * args.tolerance:g} %), {t_auto / t_fixed:.1f}x")
    print(json.dumps({"fixed_s": t_fixed, "auto_s": t_auto, "ratio": t_auto / t_fixed,
                      "warnings": auto["warnings"]}, indent=1))
    print(f"{'a (mm)':>11} {'H':>3} {'estimate %':>11} {'zeta auto':>11} {'zeta 7':>11} "
          f"{'dzeta %':>8} {'df %':>8}")
    fx, au = _values(fixed), _values(auto)
    for i, a in enumerate(au["amplitude_mm"]):
        z7, za = fx["damping_ratio"][i], au["damping_ratio"][i]
        f7, fa = fx["frequency_Hz"][i], au["frequency_Hz"][i]
        e = au["estimate"][i]
        est = "null" if e is None else f"{100 * e:.3g}"
        print(f"{a:11.4g} {au['harmonics'][i]:3d} {est:>11} "
              f"{za:11.4g} {z7:11.4g} {100 * (z7 / za - 1):+8.2f} {100 * (f7 / fa - 1):+8.3f}")


def _values(out: dict) -> dict:
    """The curve's values and balance from ``modal --mesh --solver rom --json``."""
    rom = out["rom"]
    h, n = rom["harmonics"], len(out["amplitude_mm"])
    return {"amplitude_mm": out["amplitude_mm"], "frequency_Hz": out["frequency_Hz"],
            "damping_ratio": out["damping_ratio"],
            "harmonics": h if isinstance(h, list) else [h] * n,
            "estimate": rom.get("harmonic_error_estimate", [0.0] * n)}


if __name__ == "__main__":
    main()
