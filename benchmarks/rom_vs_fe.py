"""The contact-node ROM's EPMC against the full FE's quasi-static modal analysis (issue 23).

On the cantilever example (``microslip.fe.examples.cantilever_mesh``; E 70000 MPa, nu 0.33,
rho 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3), per mode (default: 2, the
lowest bending in the contact plane, and 1, the lowest out of it) and per amplitude of the
full FE's grid (first slip to near gross sliding, :func:`~microslip.meshdynamics.qsma.
qsma_amplitudes`), measured in one run:

* ``FE``: the full FE's QSMA (frequency from the loop's first harmonic, zeta = W / (2 pi a^2
  w^2)) at modal force q; its response amplitude a (mm, first harmonic of the response set's
  mean displacement along the mode);
* ``EPMC``: the ROM's EPMC (``--harmonics``) at that same amplitude a (no interpolation),
  the relative errors against FE and the issue's targets (frequency 0.5 %, damping 5 %,
  over the microslip range: damping ratio from 0.1 % to 5 %);
* ``ROM-QSMA``: the same quasi-static analysis on the ROM at the same modal force q
  (:func:`microslip.dynamics.modal.quasi_static`, 15 harmonics): it separates the ROM's
  error (ROM-QSMA against FE) from the method's (EPMC against ROM-QSMA: the dynamics).

Run: ``PYTHONPATH=src python benchmarks/rom_vs_fe.py [--quick] [--normal-contact penalty]``
(``--quick``: the 12x3x1 mesh, 3 amplitudes).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass

import numpy as np

from microslip.dynamics.modal import ModalCurve, epmc, quasi_static
from microslip.dynamics.modal_odd import epmc_odd
from microslip.fe.clamp import MeshClamp
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.case import (
    StructureCase,
    amplitude_grid,
    prepare_structure,
    structure_rom,
)
from microslip.meshdynamics.modes import Mode
from microslip.meshdynamics.qsma import QSMACurve, qsma
from microslip.meshdynamics.reduce import rom_structure

E, NU, RHO, MU, FN, LAM, KN = 70000.0, 0.33, 2700.0, 0.5, 2000.0, 1e4, 1e6
#: The issue's targets: frequency (first harmonic) and damping ratio, relative.
TARGET_F, TARGET_Z = 0.005, 0.05
#: The microslip range: damping ratio from this ...
MICROSLIP_BOTTOM = 0.001
#: ... to this.
MICROSLIP_TOP = 0.05
#: Harmonics of the ROM's quasi-static analysis.
QSMA_HARMONICS = 15


@dataclass(frozen=True)
class Comparison:
    """One mode: the FE's QSMA, the ROM's EPMC and QSMA on its converged points, seconds."""

    mode: Mode
    fe: QSMACurve
    ok: np.ndarray
    epmc: ModalCurve
    rom_qsma: ModalCurve
    rom_dofs: int
    times: tuple[float, float, float]


def compare(mesh: tuple[int, int, int], number: int, count: int, harmonics: int,
            rom_modes: int, normal: str) -> Comparison:
    clamp = MeshClamp("contact", "clamp", normal_force=FN, modulus=E, poisson_ratio=NU,
                      friction=MU, stick_slope=LAM, normal_contact=normal, normal_slope=KN)
    prepared = prepare_structure(StructureCase(
        cantilever_mesh(*mesh), clamp, density=RHO, mode=number, response_set="response",
        rom_modes=rom_modes))
    model, mode = prepared.model, prepared.mode
    t0 = time.perf_counter()
    forces, _ = amplitude_grid(prepared, count)
    fe = qsma(model, mode, forces)
    t_fe = time.perf_counter() - t0
    ok = np.isfinite(fe.amplitude_mm)
    t0 = time.perf_counter()
    rom = structure_rom(prepared)
    assert rom.output is not None
    s = rom_structure(rom, mode.direction @ rom.output)
    method = epmc if rom.per_node == 3 else epmc_odd
    ep = method(s, fe.amplitude_mm[ok], harmonics, mode=number - 1)
    t_ep = time.perf_counter() - t0
    t0 = time.perf_counter()
    rq = quasi_static(s, forces[ok], QSMA_HARMONICS, samples=256, mode=number - 1)
    t_rq = time.perf_counter() - t0
    return Comparison(mode=mode, fe=fe, ok=ok, epmc=ep, rom_qsma=rq, rom_dofs=rom.dofs,
                      times=(t_fe, t_ep, t_rq))


def report(r: Comparison, harmonics: int) -> bool:
    mode, fe, ok, ep, rq = r.mode, r.fe, r.ok, r.epmc, r.rom_qsma
    t_fe, t_ep, t_rq = r.times
    print(f"\nmode {mode.number} ({mode.label}), stuck {mode.frequency_Hz:.2f} Hz; "
          f"FE QSMA {t_fe:.1f} s, ROM ({r.rom_dofs} DOF) EPMC {harmonics} harmonics "
          f"{t_ep:.1f} s, ROM-QSMA {t_rq:.1f} s")
    print(f"{'a mm':>10} {'FE f Hz':>10} {'FE zeta':>9} {'EPMC f Hz':>10} {'EPMC zeta':>9} "
          f"{'df %':>7} {'dzeta %':>8} {'RQ f Hz':>10} {'RQ zeta':>9} {'df %':>7} "
          f"{'dzeta %':>8}  range")
    good = True
    j = 0
    for i, a in enumerate(fe.amplitude_mm):
        if not ok[i]:
            print(f"{'nan':>10}  FE failed: {fe.points[i].message}")
            continue
        f, z = fe.frequency_Hz[i], fe.damping_ratio[i]
        ef, ez = ep.frequency[j], ep.damping_ratio[j]
        qf, qz = rq.frequency[j], rq.damping_ratio[j]
        j += 1
        inside = MICROSLIP_BOTTOM <= z <= MICROSLIP_TOP
        dz = (ez / z - 1) * 100 if z > 0 else math.nan
        qdz = (qz / z - 1) * 100 if z > 0 else math.nan
        met = abs(ef / f - 1) <= TARGET_F and (z == 0 or abs(ez / z - 1) <= TARGET_Z)
        if inside:
            good &= met
        print(f"{a:10.4e} {f:10.3f} {z:9.5f} {ef:10.3f} {ez:9.5f} {(ef / f - 1) * 100:+7.3f} "
              f"{dz:+8.2f} {qf:10.3f} {qz:9.5f} {(qf / f - 1) * 100:+7.3f} {qdz:+8.2f}  "
              f"{('microslip ' + ('met' if met else 'NOT met')) if inside else 'outside'}")
    print(f"targets over the microslip range ({MICROSLIP_BOTTOM:.1%} <= zeta <= "
          f"{MICROSLIP_TOP:.0%}): frequency "
          f"{TARGET_F:.1%}, damping ratio {TARGET_Z:.0%}: {'met' if good else 'NOT met'} "
          "(EPMC against FE; RQ = the ROM's own QSMA against FE: the ROM's error alone)")
    return good


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="12x3x1 mesh, 3 amplitudes")
    p.add_argument("--mesh", type=int, nargs=3, default=None, metavar=("NX", "NY", "NZ"))
    p.add_argument("--amplitudes", type=int, default=None)
    p.add_argument("--harmonics", type=int, default=7)
    p.add_argument("--rom-modes", type=int, default=60)
    p.add_argument("--modes", type=int, nargs="+", default=[2, 1])
    p.add_argument("--normal-contact", choices=("fixed", "penalty"), default="fixed")
    args = p.parse_args()
    mesh = tuple(args.mesh) if args.mesh else ((12, 3, 1) if args.quick else (24, 6, 2))
    count = args.amplitudes or (3 if args.quick else 5)
    print(f"cantilever {mesh[0]}x{mesh[1]}x{mesh[2]}, {args.normal_contact} normal contact, "
          f"{count} amplitudes, ROM {args.rom_modes} fixed-interface modes")
    for number in args.modes:
        report(compare((mesh[0], mesh[1], mesh[2]), number, count, args.harmonics,
                       args.rom_modes, args.normal_contact), args.harmonics)


if __name__ == "__main__":
    main()
