"""Harmonic balance against time integration to steady state, in the same run.

Targets (issue 12):
1. A frequency-response curve of a 1-DOF oscillator with a microslip (tip) joint, 7
   harmonics, 128 samples, about 200 continuation points: under 0.5 s after warm-up and at
   least 100 times faster than the time integration it is checked against.
2. A damping-versus-amplitude backbone over three decades (100 amplitudes): under 0.5 s.
3. (issue 13) A 10-DOF structure with two joints, 7 harmonics, about 200 continuation
   points: under 2 s, at least 100 times faster than time integration to steady state.

The time integration (from rest, exact return mapping) runs to steady state at
``--ti-points`` frequencies spread along the curve, each for the fewest periods of 25, 50,
100, ... after which the first harmonic changes by less than 1e-8 over the last period;
only that last, sufficient run is timed (generous to the time integration: in practice the
settling time is not known in advance). Its cost for the whole curve is that per-point cost
times the curve's points (printed as such). Its amplitude is compared with the harmonic
balance's at the same frequencies (the issue's 0.5 %).

Run:  python3 benchmarks/bench_dynamics.py [--repeat 3] [--ti-points 8]

Times are wall-clock seconds (time.perf_counter), best of ``--repeat``.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from microslip import preset
from microslip.dynamics import clamp_joint
from microslip.dynamics.assemble import from_matrices, modal_output, mode_load, with_output
from microslip.dynamics.files import MatrixFile
from microslip.dynamics.modal import energy_method, epmc
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import Structure, one_mode
from microslip.dynamics.timeint import steady_state, transient
from microslip.named import readonly

#: The 1-DOF system: 1 kg, 1000 Hz with the joint removed, 0.2 % linear damping; the Table 1
#: clamp's tip model in series with a 1e5 N/mm spring (stuck: 1872 Hz).
FORCE = 50.0  # N
HARMONICS, SAMPLES = 7, 128
STEPS = 256  # time steps per period of the time integration
SETTLED = 1e-8  # relative change of the first harmonic over the last period
#: Continuation step of the 10-DOF curve: its norm scales the joints' harmonics (the balance
#: is condensed onto them), about 230 points.
STEP_10 = 0.022


def one_dof() -> Structure:
    return one_mode(1000.0, 1.0, 0.002, clamp_joint("tip", preset("table1"), 1e5))


def best(fn: Callable[[], Any], repeat: int) -> tuple[Any, float]:
    out, seconds = None, np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        seconds = min(seconds, time.perf_counter() - t0)
    return out, seconds


def settled(integrate: Callable[[int], Any]) -> tuple[Any, float, int]:
    """The first run of 25, 50, 100, ... periods that has settled, its seconds, periods."""
    periods = 25
    while True:
        t0 = time.perf_counter()
        out = integrate(periods)
        seconds = time.perf_counter() - t0
        if out.change < SETTLED or periods >= 12_800:
            return out, seconds, periods
        periods *= 2


def compare(r: Any, ti_points: int, integrate: Callable[[float, int], Any]
            ) -> tuple[float, float, int]:
    """Per-point seconds of the settled time integration, worst amplitude gap, periods."""
    picks = np.unique(np.linspace(0, r.frequency.size - 1, ti_points).round().astype(int))
    picks = np.unique(np.append(picks, np.argmax(r.amplitude)))
    total, worst, most = 0.0, 0.0, 0
    for i in picks:
        f = float(r.frequency[i])
        ti, seconds, periods = settled(lambda p, f=f: integrate(f, p))
        total += seconds
        worst = max(worst, abs(r.amplitude[i] / ti.amplitude - 1.0))
        most = max(most, periods)
    return total / picks.size, worst, most


def race(title: str, run: Callable[[], Any], integrate: Callable[[float, int], Any],
         target: float, scheme: str, repeat: int, ti_points: int) -> None:
    """Time a frequency response ``run`` against the settled time integration
    ``integrate(frequency_Hz, periods)`` at points of its curve, and print them side by side."""
    run()  # warm-up (numba compilation)
    r, t_hb = best(run, repeat)
    integrate(float(r.frequency[0]), 2)  # compile
    per_point, worst, most = compare(r, ti_points, integrate)
    t_ti = per_point * r.frequency.size
    print(f"{title}, {r.frequency.size} points")
    print(f"   peak {r.peak_amplitude:.6g} mm at {r.peak_frequency:.6g} Hz; "
          f"success {r.success}")
    print(f"   harmonic balance      {t_hb:8.3f} s   (target < {target:g} s)")
    print(f"   time integration      {t_ti:8.3f} s   ({per_point:.4f} s per point x "
          f"{r.frequency.size} points, measured at {ti_points}+1; {scheme}, {STEPS} steps "
          f"per period, up to {most} periods to settle below {SETTLED:g})")
    print(f"   speed-up              {t_ti / t_hb:8.0f} x   (target >= 100 x)")
    print(f"   amplitude HB vs TI    {100 * worst:8.3f} %   (target <= 0.5 %, worst of "
          f"the measured frequencies incl. the peak)")


def bench_frf(repeat: int, ti_points: int) -> None:
    s = one_dof()
    lo = 0.8 * float(s.linear_frequencies(stuck=False)[0])
    hi = float(s.linear_frequencies(stuck=True)[0]) / 0.8
    race(f"1. FRF, 1 DOF, tip joint (201 elements), {HARMONICS} harmonics, {SAMPLES} "
         f"samples, F = {FORCE:g} N",
         lambda: frequency_response(s, FORCE, np.ones(1), (lo, hi), HARMONICS, SAMPLES),
         lambda f, p: steady_state(s, FORCE, f, periods=p, steps=STEPS),
         0.5, "Newmark", repeat, ti_points)


def bench_backbone(repeat: int) -> None:
    s = one_dof()
    amps = np.geomspace(1e-4, 1e-1, 100)  # mm, three decades
    epmc(s, amps[:2], HARMONICS, SAMPLES)
    energy_method(s, amps[:2])
    e, t_epmc = best(lambda: epmc(s, amps, HARMONICS, SAMPLES), repeat)
    en, t_energy = best(lambda: energy_method(s, amps), repeat)
    print(f"2. backbone, 100 amplitudes {amps[0]:g} to {amps[-1]:g} mm")
    print(f"   EPMC, {HARMONICS} harmonics      {t_epmc:8.3f} s   (target < 0.5 s)")
    print(f"   energy method        {t_energy:8.3f} s   (target < 0.5 s)")
    print(f"   damping ratio {e.damping_ratio.min():.4g} to {e.damping_ratio.max():.4g}; "
          f"largest EPMC/energy difference "
          f"{np.max(np.abs(e.damping_ratio / en.damping_ratio - 1)) * 100:.2f} %")


def ten_dof() -> Structure:
    """A fixed-free chain of 10 masses of 0.1 kg and springs of 4e7 N/m, stiffness-
    proportional damping 1e-5 s; tip joints (1e5 N/mm series spring) from DOF 3 to the
    ground and between DOFs 9 and 8; reported: the first stuck mode's coordinate."""
    n, k = 10, 4e7
    kk = (np.diag(np.full(n, 2 * k)) - np.diag(np.full(n - 1, k), 1)
          - np.diag(np.full(n - 1, k), -1))
    kk[-1, -1] = k
    matrices = MatrixFile(mass=readonly(0.1 * np.eye(n)), stiffness=readonly(kk),
                          damping=readonly(1e-5 * kk),
                          joints=readonly(np.array([[[3, -1]], [[9, 8]]])), path="chain")
    s = from_matrices(matrices, matrices.joints, clamp_joint("tip", preset("table1"), 1e5),
                      "circular")
    return with_output(s, modal_output(s, 0))


def bench_ten_dof(repeat: int, ti_points: int) -> None:
    s = ten_dof()
    load = 20.0 * mode_load(s, 0)  # a modal force of 20 N on the first mode
    lo = 0.9 * float(s.linear_frequencies(stuck=False)[0])
    hi = float(s.linear_frequencies(stuck=True)[0]) / 0.9
    race(f"3. FRF, 10 DOF, two tip joints, {HARMONICS} harmonics, {SAMPLES} samples",
         lambda: frequency_response(s, 1.0, load, (lo, hi), HARMONICS, SAMPLES, step=STEP_10),
         lambda f, p: transient(s, load, f, periods=p, steps=STEPS),
         2.0, "central differences", repeat, ti_points)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--ti-points", type=int, default=8)
    args = parser.parse_args()
    bench_frf(args.repeat, args.ti_points)
    bench_backbone(args.repeat)
    bench_ten_dof(args.repeat, args.ti_points)


if __name__ == "__main__":
    main()
