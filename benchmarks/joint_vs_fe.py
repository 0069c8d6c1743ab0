"""The whole-joint model against the full FE (issue 23, item 4): frequency and damping ratio
at equal amplitude.

Run: ``python3 benchmarks/joint_vs_fe.py`` (``--quick``: the 12x3x1 mesh, 4 amplitudes).

The cantilever example (:func:`microslip.fe.examples.cantilever_mesh` 24x6x2, C3D8I):
E 70000 MPa, nu 0.33, density 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3,
``fixed`` normal contact; response set ``response`` (the tip). For the in-plane bending
(mode 2) and the out-of-plane bending (mode 1), on the modal forces of the full FE's grid
(:func:`~microslip.fe.builtin.qsma.qsma_amplitudes`, first slip to near gross sliding):

* ``fe``: quasi-static modal analysis of the full frictional FE (the truth);
* ``joint``: EPMC (7 harmonics) on the whole-joint model
  (:mod:`microslip.fe.builtin.wholejoint`) with its default torsion joint (``iwan``, the
  rotation's own first-loading curve), and ``stuck`` torsion (the classical linear spring),
  at the FE's own amplitudes (equal amplitude: the response set's first harmonic along the
  mode).

Printed: the stuck frequencies and their error, the share of the interface's work done by
its rigid motion along the mode's first loading (what the whole-joint model keeps), and per
amplitude the two curves with the relative differences (percent). One run.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.builtin.modes import linear_modes
from microslip.fe.builtin.qsma import qsma, qsma_amplitudes
from microslip.fe.builtin.reduce import build_rom
from microslip.fe.builtin.wholejoint import build_whole_joint, whole_joint_epmc
from microslip.fe.examples import cantilever_mesh

RHO = 2700.0
HARMONICS, SAMPLES = 7, 64


def _pct(x: float, ref: float) -> str:
    if not (math.isfinite(x) and math.isfinite(ref)) or ref == 0:
        return f"{'-':>8}"
    return f"{100 * (x / ref - 1):+8.1f}"


def compare(model: object, number: int, count: int) -> None:
    modes = linear_modes(model, RHO, 6, "stuck", "response")  # type: ignore[arg-type]
    mode = modes.select(number)
    scale = float(np.linalg.norm(modes.response_motion[number - 1])) / (
        2 * math.pi * mode.frequency_Hz) ** 2
    forces = qsma_amplitudes(model, mode, count)  # type: ignore[arg-type]
    t0 = time.perf_counter()
    fe = qsma(model, mode, forces)  # type: ignore[arg-type]
    t_fe = time.perf_counter() - t0
    # at equal amplitude: the FE's own (its softening makes it exceed the linear map q r /
    # omega^2); a failed FE point keeps the linear map
    amplitudes = np.where(np.isfinite(fe.amplitude_mm), fe.amplitude_mm, forces * scale)
    rom = build_rom(model, RHO, modes=60, response_set="response")  # type: ignore[arg-type]
    assert rom.output is not None
    out = mode.direction @ rom.output
    curves, joints, times = {}, {}, {}
    for torsion in ("iwan", "stuck"):
        t0 = time.perf_counter()
        wj = build_whole_joint(rom, model, mode, out, torsion=torsion,  # type: ignore[arg-type]
                               backbone=None if not joints else joints["iwan"].backbone)
        curves[torsion], failed = whole_joint_epmc(wj, amplitudes, HARMONICS, SAMPLES,
                                                   mode.frequency_Hz)
        for w in failed:
            print(f"  warning ({torsion} torsion): {w}")
        joints[torsion], times[torsion] = wj, time.perf_counter() - t0
    wj = joints["iwan"]
    stuck = float(wj.stuck_frequencies()[wj.mode_index(mode.frequency_Hz)])
    bb = wj.backbone
    share = bb.loading.rigid_work / np.where(bb.loading.work > 0, bb.loading.work, np.nan)
    print(f"\nmode {number} ({mode.label}): full FE stuck {mode.frequency_Hz:.2f} Hz, "
          f"whole-joint stuck {stuck:.2f} Hz ({_pct(stuck, mode.frequency_Hz).strip()} %)")
    print(f"  joint: translation from the {bb.source} loading, direction "
          f"({bb.direction[0]:+.3f}, {bb.direction[1]:+.3f}) in the contact plane; torsion "
          f"{'curve' if bb.rotation.size else 'none (the mode does not turn the interface)'}")
    k = np.unique(np.linspace(1, share.size - 1, 5).astype(int))
    print("  share of the interface's work through its rigid motion along the first loading: "
          + ", ".join(f"{s:.2f} (stuck {a:.2f})" for s, a in
                      zip(share[k], bb.loading.stuck_share[k], strict=True)))
    print(f"  wall: full-FE QSMA {t_fe:.1f} s, whole joint (build + EPMC) "
          f"{times['iwan']:.1f} s, {times['stuck']:.1f} s")
    print(f"  {'a (mm)':>10} {'f_FE (Hz)':>10} {'zeta_FE':>9} | {'f_WJ (Hz)':>10} "
          f"{'zeta_WJ':>9} {'df %':>8} {'dzeta %':>8} | {'f_WJs':>10} {'zeta_WJs':>9} "
          f"{'df %':>8} {'dzeta %':>8}")
    for i, a in enumerate(amplitudes):
        ff, zf = fe.frequency_Hz[i], fe.damping_ratio[i]
        row = f"  {a:10.4g} {ff:10.2f} {zf:9.4g} |"
        for torsion in ("iwan", "stuck"):
            c = curves[torsion]
            fj, zj = c.frequency[i], c.damping_ratio[i]
            row += (f" {fj:10.2f} {zj:9.4g} {_pct(fj, ff)} {_pct(zj, zf)}"
                    + (" |" if torsion == "iwan" else ""))
        print(row)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="12x3x1 mesh, 4 amplitudes")
    args = p.parse_args()
    counts = (12, 3, 1) if args.quick else (24, 6, 2)
    model = build_mesh_model(cantilever_mesh(*counts), contact_set="contact",
                             clamp_set="clamp", normal_force=2000.0, modulus=70000.0,
                             poisson_ratio=0.33, friction=0.5, stick_slope=1e4)
    print(f"cantilever {'x'.join(map(str, counts))}: {model.dof} dofs, "
          f"{model.contact_nodes.size} contact nodes")
    for number in (2, 1):
        compare(model, number, 4 if args.quick else 8)


if __name__ == "__main__":
    main()
