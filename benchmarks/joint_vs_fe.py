"""The whole-joint model against the full FE (issue 23, item 4): frequency and damping ratio
at equal amplitude.

Run: ``python3 benchmarks/joint_vs_fe.py`` (``--quick``: the 12x3x1 mesh, 4 amplitudes).

The cantilever example (:func:`microslip.fe.examples.cantilever_mesh` 24x6x2, C3D8I):
E 70000 MPa, nu 0.33, density 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3,
``fixed`` normal contact; response set ``response`` (the tip). For the in-plane bending
(mode 2) and the out-of-plane bending (mode 1), on the modal forces of the full FE's grid
(:func:`~microslip.meshdynamics.qsma.qsma_amplitudes`, first slip to near gross sliding):

* ``fe``: quasi-static modal analysis of the full frictional FE (the truth);
* ``joint``: EPMC (7 harmonics) on the whole-joint model
  (:mod:`microslip.meshdynamics.wholejoint`) as ``--solver joint`` builds it (torsion joint
  ``iwan``, the rotation's own first-loading curve); ``stuckT`` the same with the classical
  linear torsion spring; ``work`` with the work-equivalent backbone (``--backbone work``);
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

from microslip.fe.clamp import MeshClamp
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.case import (
    PreparedStructure,
    StructureCase,
    amplitude_grid,
    prepare_structure,
    structure_rom,
)
from microslip.meshdynamics.qsma import qsma
from microslip.meshdynamics.wholejoint import build_whole_joint, whole_joint_epmc

RHO = 2700.0
HARMONICS, SAMPLES = 7, 64
#: Whole-joint variants: name -> (torsion, backbone) of :func:`build_whole_joint`.
VARIANTS = {"joint": ("iwan", "fe"), "stuckT": ("stuck", "fe"), "work": ("iwan", "work")}


def _pct(x: float, ref: float) -> str:
    if not (math.isfinite(x) and math.isfinite(ref)) or ref == 0:
        return f"{'-':>8}"
    return f"{100 * (x / ref - 1):+8.1f}"


def compare(prepared: PreparedStructure, count: int) -> None:
    """The full FE's QSMA on the study's grid (:func:`amplitude_grid`) against the whole
    joint's variants, all on the library's prepared structure and its one ROM."""
    model, mode, number = prepared.model, prepared.mode, prepared.number
    forces, linear = amplitude_grid(prepared, count)
    t0 = time.perf_counter()
    fe = qsma(model, mode, forces)
    t_fe = time.perf_counter() - t0
    # at equal amplitude: the FE's own (its softening makes it exceed the linear map q r /
    # omega^2); a failed FE point keeps the linear map
    amplitudes = np.where(np.isfinite(fe.amplitude_mm), fe.amplitude_mm, linear)
    rom = structure_rom(prepared)
    assert rom.output is not None
    out = mode.direction @ rom.output
    curves, joints, times = {}, {}, {}
    for name, (torsion, backbone) in VARIANTS.items():
        t0 = time.perf_counter()
        wj = build_whole_joint(rom, model, mode, out, torsion=torsion, backbone=backbone)
        curves[name], failed = whole_joint_epmc(wj, amplitudes, HARMONICS, SAMPLES,
                                                mode.frequency_Hz)
        for w in failed:
            print(f"  warning ({name}): {w}")
        joints[name], times[name] = wj, time.perf_counter() - t0
    print(f"\nmode {number} ({mode.label}): full FE stuck {mode.frequency_Hz:.2f} Hz; "
          f"full-FE QSMA {t_fe:.1f} s")
    for name, wj in joints.items():
        stuck = float(wj.stuck_frequencies()[wj.mode_index(mode.frequency_Hz)])
        bb = wj.backbone
        print(f"  {name:>6}: stuck {stuck:.2f} Hz ({_pct(stuck, mode.frequency_Hz).strip()} %), "
              f"translation from the {bb.source} loading, torsion "
              f"{wj.torsion if bb.rotation.size else 'stuck (the mode does not turn it)'}, "
              f"initial slope {bb.force[1] / bb.displacement[1]:.4g} N/mm (stuck interface "
              f"{bb.stuck_stiffness:.4g}), build + EPMC {times[name]:.1f} s")
    loading = joints["joint"].backbone.loading
    assert loading is not None
    share = loading.rigid_work / np.where(loading.work > 0, loading.work, np.nan)
    k = np.unique(np.linspace(1, share.size - 1, 5).astype(int))
    print("  share of the interface's work through its rigid motion along the first loading: "
          + ", ".join(f"{s:.2f} (stuck {a:.2f})" for s, a in
                      zip(share[k], loading.stuck_share[k], strict=True)))
    head = f"  {'a (mm)':>10} {'f_FE (Hz)':>10} {'zeta_FE':>9}"
    for name in VARIANTS:
        head += f" | {'f_' + name:>10} {'zeta_' + name:>11} {'df %':>7} {'dzeta %':>8}"
    print(head)
    for i, a in enumerate(amplitudes):
        ff, zf = fe.frequency_Hz[i], fe.damping_ratio[i]
        row = f"  {a:10.4g} {ff:10.2f} {zf:9.4g}"
        for name in VARIANTS:
            fj, zj = curves[name].frequency[i], curves[name].damping_ratio[i]
            row += f" | {fj:10.2f} {zj:11.4g} {_pct(fj, ff)[1:]} {_pct(zj, zf)}"
        print(row)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="12x3x1 mesh, 4 amplitudes")
    args = p.parse_args()
    counts = (12, 3, 1) if args.quick else (24, 6, 2)
    clamp = MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
                      poisson_ratio=0.33, friction=0.5, stick_slope=1e4)
    mesh = cantilever_mesh(*counts)
    for number in (2, 1):
        prepared = prepare_structure(StructureCase(mesh, clamp, density=RHO, mode=number,
                                                   response_set="response", rom_modes=60))
        model = prepared.model
        print(f"cantilever {'x'.join(map(str, counts))}: {model.dof} dofs, "
              f"{model.contact_nodes.size} contact nodes")
        compare(prepared, 4 if args.quick else 8)


if __name__ == "__main__":
    main()
