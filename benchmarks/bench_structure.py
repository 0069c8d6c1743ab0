"""The issue-23 targets side by side: modes, ROM build, ROM EPMC and full-FE QSMA on the
cantilever example, and the peak memory of a 50k-DOF mesh, measured in one run.

Run: ``python3 benchmarks/bench_structure.py`` (``--quick``: the 24x6x2 mesh only;
``--large``: adds the 96x24x6 mesh's memory row, ``--large-only``: that row alone;
``--penalty``: adds the penalty ROM's EPMC; ``--timeout S``: the longest a timed row may
run before it is stopped and reported as over, default 10 times its target plus 60 s).

The cantilever example (:func:`microslip.fe.examples.cantilever_mesh`, C3D8I): aluminium
E 70000 MPa, nu 0.33, 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3, ``fixed``
normal contact (``modal --mesh``'s default: the 2-D circular element per contact node).
Rows (each in its own process, so that a row's time and peak memory are its own; the
model's set-up, the assembly and the clamping step, is timed apart and not counted):

* modes: the ten lowest stuck modes with their descriptions (target 1 s on 24x6x2);
* ROM build: consistent mass, 20 fixed-interface modes, constraint modes (5 s);
* ROM EPMC: the in-plane bending mode (mode 2), 20 amplitudes 2e-3 to 3e-2 mm, 7
  harmonics, the odd-harmonic balance ``modal --mesh --solver rom`` uses (5 s; the
  kernels are compiled before the clock starts);
* full-FE QSMA: the same mode, 10 amplitudes from first slip to near gross sliding, the
  grid search included, one process (30 s);
* on 48x12x4 (about 10k DOF) each target is ten times that;
* ``--penalty``, beyond the targets, on 24x6x2: the ROM's EPMC with ``penalty`` normal
  contact (a 3-D contact element per node, normal slope 1e6 N/mm^3), on every harmonic
  (the odd-harmonic balance refuses it: the normal preload makes its force not odd);
* interface model (issue 28, item 5): the ten stuck modes, the interface model built on the
  full FE directly (20 fixed-interface modes, 10 characteristic constraint modes plus mode
  2's first-loading shapes; no contact-node ROM) and the EPMC of mode 2 over 20
  amplitudes, 7 harmonics, one row (target 15 s on 48x12x4, 1.5 s on 24x6x2), each stage's
  time and resident peak in the note;
* ``--large``: the interface model's row on the 96x24x12 mesh (93,750 DOF; 120 s, 4 GB;
  stopped after 30 min, with the stages it finished; measured 43 s and 2.0 GB at load 6-7);
* ``--large``: the 96x24x6 mesh (about 50k DOF): modes, ROM build and one QSMA amplitude
  in one process, its peak resident memory (target 2 GB) and the peak of each stage (the
  model's set-up, modes, ROM build, QSMA; Linux's VmHWM, reset between stages).

The machine's load average is printed with the table (a shared machine slows every row).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from typing import Any

import numpy as np

RHO = 2700.0
#: Targets on 24x6x2, s; 48x12x4 gets ten times them.
TARGETS = {"modes": 1.0, "build": 5.0, "epmc": 5.0, "qsma": 30.0, "interface": 1.5}
LABELS = {"modes": "modes (10 stuck)", "build": "ROM build (20 modes)",
          "epmc": "ROM EPMC 20 x H7", "qsma": "full-FE QSMA 10 amplitudes",
          "epmc3d": "ROM EPMC 20 x H7, penalty",
          "interface": "interface: modes+red.+EPMC"}
#: Rows beyond the targets' (24x6x2 only): the penalty ROM's EPMC, against the same 5 s.
EXTRA = {"epmc3d": 5.0}
MESHES = {"24x6x2": (24, 6, 2), "48x12x4": (48, 12, 4)}
LARGE = (96, 24, 6)
#: Peak memory target of the 50k-DOF mesh, MB.
MEMORY_MB = 2048.0
#: The ~100k-DOF mesh of the interface model's row (issue 28, item 5): its time (s) and
#: peak memory (MB) targets, and the longest it may run before it is stopped.
HUGE = (96, 24, 12)
HUGE_TARGETS = (120.0, 4096.0)
HUGE_TIMEOUT = 1800.0
#: The interface model's row: fixed-interface modes, characteristic constraint modes (the
#: first-loading shapes of mode 2 on top).
INTERFACE = (20, 10)


def _model(counts: tuple[int, int, int], normal: str = "fixed") -> Any:
    from microslip.fe.clamp import MeshClamp, clamped_model
    from microslip.fe.examples import cantilever_mesh

    return clamped_model(cantilever_mesh(*counts), MeshClamp(
        "contact", "clamp", normal_force=2000.0, modulus=70000.0, poisson_ratio=0.33,
        friction=0.5, stick_slope=1e4, normal_contact=normal, normal_slope=1e6))


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # KB on Linux


def _stage_peak_mb() -> float | None:
    """The resident peak since the last :func:`_reset_peak` (Linux's VmHWM), MB; None where
    /proc is not there."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None


def _reset_peak() -> None:
    """Start a new resident peak (Linux: ``5`` to /proc/self/clear_refs); this also lowers
    ``ru_maxrss``, so the memory row keeps the largest stage peak itself."""
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")
    except OSError:
        pass


def child(row: str, counts: tuple[int, int, int]) -> dict[str, Any]:
    """Run one row in this process; its time (s), the model's set-up (s), peak RSS (MB)."""
    from microslip.dynamics.modal_odd import epmc_odd
    from microslip.meshdynamics.modes import linear_modes
    from microslip.meshdynamics.qsma import qsma, qsma_amplitudes
    from microslip.meshdynamics.reduce import build_rom, rom_structure

    t0 = time.perf_counter()
    model = _model(counts, "penalty" if row == "epmc3d" else "fixed")
    out: dict[str, Any] = {"dof": int(model.dof), "setup_s": time.perf_counter() - t0}
    if row == "modes":
        t0 = time.perf_counter()
        modes = linear_modes(model, RHO, 10, response_set="response")
        out.update(seconds=time.perf_counter() - t0, note=f"f2 {modes.frequencies_Hz[1]:.1f} Hz")
    elif row == "build":
        t0 = time.perf_counter()
        rom = build_rom(model, RHO, modes=20, response_set="response")
        out.update(seconds=time.perf_counter() - t0, note=f"ROM {rom.dofs} DOF")
    elif row == "epmc":
        rom = build_rom(model, RHO, modes=20, response_set="response")
        s = rom_structure(rom)
        a = np.geomspace(2e-3, 3e-2, 20)
        epmc_odd(rom_structure(build_rom(_model((6, 1, 1)), RHO, modes=2)),
                 a[:2], 7, mode=1)  # compile the kernels on a tiny model
        t0 = time.perf_counter()
        c = epmc_odd(s, a, 7, mode=1)
        out.update(seconds=time.perf_counter() - t0,
                   note=f"{c.frequency[0]:.1f} -> {c.frequency[-1]:.1f} Hz, zeta "
                        f"{c.damping_ratio[-1]:.4f}")
    elif row == "epmc3d":
        from microslip.dynamics.modal import epmc

        rom = build_rom(model, RHO, modes=20, response_set="response")
        s = rom_structure(rom)
        a = np.geomspace(2e-3, 3e-2, 20)
        epmc(s, a[:1], 7, mode=1)  # compile the 3-D element's kernel (a stuck amplitude)
        t0 = time.perf_counter()
        c = epmc(s, a, 7, mode=1)
        out.update(seconds=time.perf_counter() - t0,
                   note=f"{c.frequency[0]:.1f} -> {c.frequency[-1]:.1f} Hz, zeta "
                        f"{c.damping_ratio[-1]:.4f}; every harmonic (3-D elements are not odd)")
    elif row == "qsma":
        mode = linear_modes(model, RHO, 6, response_set="response").select(2)
        t0 = time.perf_counter()
        curve = qsma(model, mode, count=10)
        unsettled = len(curve.warnings)
        out.update(seconds=time.perf_counter() - t0,
                   note=f"zeta at top {curve.damping_ratio[-1]:.4f}"
                        + (f", {unsettled} warnings" if unsettled else ""))
    elif row == "interface":
        return _interface_row(model, out)
    elif row == "memory":
        peaks = {"set-up": _stage_peak_mb()}
        _reset_peak()
        t0 = time.perf_counter()
        modes = linear_modes(model, RHO, 10, response_set="response")
        t_modes = time.perf_counter() - t0
        peaks["modes"] = _stage_peak_mb()
        _reset_peak()
        t0 = time.perf_counter()
        rom = build_rom(model, RHO, modes=20, response_set="response")
        t_build = time.perf_counter() - t0
        peaks["ROM build"] = _stage_peak_mb()
        _reset_peak()
        mode = modes.select(2)
        t0 = time.perf_counter()
        q = qsma_amplitudes(model, mode, 1)
        curve = qsma(model, mode, q)
        t_qsma = time.perf_counter() - t0
        peaks["QSMA"] = _stage_peak_mb()
        known = [p for p in peaks.values() if p is not None]
        staged = ", ".join(f"{k} {v:.0f}" for k, v in peaks.items() if v is not None)
        out.update(seconds=t_modes + t_build + t_qsma,
                   note=f"modes {t_modes:.1f} s, ROM build {t_build:.1f} s ({rom.dofs} DOF), "
                        f"1 QSMA amplitude {t_qsma:.1f} s (zeta "
                        f"{curve.damping_ratio[0]:.2e}); peak MB by stage: {staged}")
        out["peak_MB"] = max([*known, _peak_mb()])
        return out
    else:
        raise SystemExit(f"unknown row {row!r}")
    out["peak_MB"] = _peak_mb()
    return out


def _interface_row(model: Any, out: dict[str, Any]) -> dict[str, Any]:
    """The interface model's row: the ten stuck modes, the interface model built on the full
    FE (:func:`~microslip.meshdynamics.interfacerom.build_interface_model`: ``INTERFACE[0]``
    fixed-interface modes, ``INTERFACE[1]`` static characteristic modes plus mode 2's
    first-loading shapes; no contact-node ROM), and the EPMC of mode 2 over 20 amplitudes with 7
    harmonics (the kernels compiled before the clock, on a tiny model). Each stage's time
    and resident peak; a JSON line after each stage, so that a row stopped by its timeout
    still shows the stages it finished."""
    from microslip.dynamics.modal_odd import epmc_odd
    from microslip.meshdynamics.interfacerom import build_interface_model, build_interface_rom
    from microslip.meshdynamics.modes import linear_modes
    from microslip.meshdynamics.reduce import build_rom

    tiny = build_interface_rom(build_rom(_model((6, 1, 1)), RHO, modes=2), 2, mode=1)
    epmc_odd(tiny.structure(np.ones(tiny.dofs)), [1e-3, 1e-2], 7)  # compile the kernels
    stages: dict[str, str] = {}
    total = 0.0
    peak = 0.0
    cpu = time.process_time()

    def stage(name: str, t0: float) -> None:
        # the CPU seconds beside the wall time: on a shared machine the wall time is the
        # load's, the CPU time the row's own
        nonlocal total, peak, cpu
        dt = time.perf_counter() - t0
        used, cpu = time.process_time() - cpu, time.process_time()
        mb = _stage_peak_mb() or _peak_mb()
        total += dt
        peak = max(peak, mb)
        stages[name] = f"{dt:.1f} s ({used:.1f} s CPU)/{mb:.0f} MB"
        out.update(seconds=total, peak_MB=peak,
                   note="; ".join(f"{k} {v}" for k, v in stages.items()))
        print(json.dumps(out), flush=True)
        _reset_peak()

    _reset_peak()
    t0 = time.perf_counter()
    cpu = time.process_time()
    modes = linear_modes(model, RHO, 10, response_set="response")
    stage("modes", t0)
    t0 = time.perf_counter()
    reduced = build_interface_model(model, RHO, INTERFACE[1], INTERFACE[0], modes.select(2),
                                    "response")
    stage(f"reduction ({reduced.dofs} DOF)", t0)
    assert reduced.output is not None
    s = reduced.structure(modes.select(2).direction @ reduced.output)
    a = np.geomspace(2e-3, 3e-2, 20)
    t0 = time.perf_counter()
    c = epmc_odd(s, a, 7, mode=1)
    stage("EPMC", t0)
    out["note"] += (f"; {c.frequency[0]:.1f} -> {c.frequency[-1]:.1f} Hz, zeta "
                    f"{c.damping_ratio[-1]:.4f}")
    return out


def _spawn(row: str, mesh: str, timeout: float) -> dict[str, Any]:
    cmd = [sys.executable, os.path.abspath(__file__), "--child", row, mesh]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                              check=False)
    except subprocess.TimeoutExpired as stopped:
        partial = stopped.stdout.decode() if isinstance(stopped.stdout, bytes) else ""
        lines = partial.strip().splitlines()
        last: dict[str, Any] = json.loads(lines[-1]) if lines else {}
        return {**last, "seconds": None,
                "note": f"stopped after {timeout:.0f} s; done: {last.get('note', 'nothing')}"}
    if done.returncode != 0:
        tail = (done.stderr.strip().splitlines() or ["?"])[-1]
        return {"seconds": None, "note": f"failed: {tail}"}
    result: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the 24x6x2 mesh only")
    ap.add_argument("--large", action="store_true",
                    help="add the 50k-DOF memory row and the interface model on ~100k DOF")
    ap.add_argument("--large-only", action="store_true",
                    help="the 50k-DOF memory row alone (several minutes)")
    ap.add_argument("--penalty", action="store_true",
                    help="add the penalty ROM's EPMC on 24x6x2 (minutes)")
    ap.add_argument("--timeout", type=float, default=None, metavar="S",
                    help="stop a timed row after S s (default 10 x its target + 60 s; the "
                         "memory row runs up to 3600 s)")
    ap.add_argument("--child", nargs=2, metavar=("ROW", "MESH"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        row, mesh = args.child
        counts = tuple(int(c) for c in mesh.split("x"))
        print(json.dumps(child(row, counts)))  # type: ignore[arg-type]
        return
    load0 = os.getloadavg()
    t_all = time.perf_counter()
    meshes = [] if args.large_only else ["24x6x2"] if args.quick else list(MESHES)
    print(f"{'mesh':>9} {'DOF':>6} {'row':<27} {'time s':>8} {'target s':>9} {'ok':>3} "
          f"{'peak MB':>8} {'set-up s':>9}  note")
    for mesh in meshes:
        scale = 1.0 if mesh == "24x6x2" else 10.0
        rows = {**TARGETS, **(EXTRA if mesh == "24x6x2" and args.penalty else {})}
        for row, target in rows.items():
            limit = scale * target
            r = _spawn(row, mesh, args.timeout or 10 * limit + 60.0)
            t = r.get("seconds")
            ok = "-" if t is None else ("yes" if t <= limit else "NO")
            shown = f"{t:8.2f}" if t is not None else f"{'over':>8}"
            print(f"{mesh:>9} {r.get('dof', 0):>6} {LABELS[row]:<27} {shown} {limit:>9.0f} "
                  f"{ok:>3} {r.get('peak_MB', float('nan')):>8.0f} "
                  f"{r.get('setup_s', float('nan')):>9.2f}  {r.get('note', '')}", flush=True)
    if args.large or args.large_only:
        mesh = "x".join(map(str, LARGE))
        r = _spawn("memory", mesh, 3600.0)
        peak = r.get("peak_MB")
        ok = "-" if peak is None else ("yes" if peak <= MEMORY_MB else "NO")
        shown = f"{peak:8.0f}" if peak is not None else f"{'over':>8}"
        print(f"{mesh:>9} {r.get('dof', 0):>6} {'peak memory MB':<27} {shown} "
              f"{MEMORY_MB:>9.0f} {ok:>3} {'':>8} {r.get('setup_s', float('nan')):>9.2f}  "
              f"{r.get('note', '')}", flush=True)
    if args.large or args.large_only:
        mesh = "x".join(map(str, HUGE))
        r = _spawn("interface", mesh, HUGE_TIMEOUT)
        t, peak = r.get("seconds"), r.get("peak_MB")
        ok = "-" if t is None else ("yes" if t <= HUGE_TARGETS[0] and peak is not None
                                    and peak <= HUGE_TARGETS[1] else "NO")
        shown = f"{t:8.2f}" if t is not None else f"{'over':>8}"
        print(f"{mesh:>9} {r.get('dof', 0):>6} {LABELS['interface']:<27} {shown} "
              f"{HUGE_TARGETS[0]:>9.0f} {ok:>3} {r.get('peak_MB', float('nan')):>8.0f} "
              f"{r.get('setup_s', float('nan')):>9.2f}  {r.get('note', '')} (target "
              f"{HUGE_TARGETS[1]:.0f} MB)", flush=True)
    load1 = os.getloadavg()
    print(f"load average (1 min) {load0[0]:.2f} at the start, {load1[0]:.2f} at the end, on "
          f"{os.cpu_count()} CPUs; {time.perf_counter() - t_all:.0f} s in all")


if __name__ == "__main__":
    main()
