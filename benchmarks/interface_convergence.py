"""The interface model's convergence in the number of interface modes (issue 28, item 4).

Against the contact-node ROM's EPMC (7 harmonics, the same fixed-interface modes) on the
cantilever (``--mesh 24x6x2``, default; ``48x12x4``), modes 1 and 2, fixed normal contact
(``--penalty``: penalty, normal slope 1e6 N/mm^3): the largest relative error in frequency
and in damping ratio over the amplitudes where the ROM's damping ratio is above 1e-4
(microslip), for the characteristic constraint modes alone and with the studied mode's
first-loading shapes, both built on the ROM (:func:`build_interface_rom`) and, for the
latter, on the full FE directly (:func:`build_interface_model`).

Run: ``python3 benchmarks/interface_convergence.py [--mesh 48x12x4] [--penalty]``.
Units: errors in percent.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from microslip.dynamics.modal import epmc
from microslip.dynamics.modal_odd import epmc_odd
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics.interfacerom import build_interface_model, build_interface_rom
from microslip.meshdynamics.modes import linear_modes
from microslip.meshdynamics.reduce import build_rom, rom_structure

RHO = 2700.0
FIXED_MODES = 60
#: Amplitudes (mm) per mode: first slip to near gross sliding on the cantilever.
AMPLITUDES = {1: np.geomspace(2.2e-2, 1.8e-1, 5), 2: np.geomspace(3.6e-3, 3e-2, 5)}
COUNTS = (5, 10, 20, 40, 80)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="24x6x2")
    ap.add_argument("--penalty", action="store_true")
    args = ap.parse_args()
    counts = tuple(int(c) for c in args.mesh.split("x"))
    normal = "penalty" if args.penalty else "fixed"
    model = build_mesh_model(cantilever_mesh(*counts), rigid_base(contact_set="contact",
                                                                  clamp_set="clamp",
                                                                  normal_force=2000.0,
                                                                  modulus=70000.0,
                                                                  poisson_ratio=0.33, friction=0.5,
                                                                  stick_slope=1e4,
                                                                  normal_contact=normal,
                                                                  normal_slope=1e6))
    rom = build_rom(model, RHO, modes=FIXED_MODES, response_set="response")
    stuck = linear_modes(model, RHO, 2, "stuck", "response")
    method = epmc if args.penalty else epmc_odd
    nb = rom.boundary.size
    print(f"cantilever {args.mesh}, {normal} normal contact: {len(rom.slip_force)} contact "
          f"nodes, {nb} boundary dofs; ROM {rom.dofs} DOF; errors against its EPMC, %")
    print(f"{'mode':>4} {'model':<26} {'DOF':>5} {'f err %':>9} {'zeta err %':>11} {'s':>6}")
    for number in (1, 2):
        mode = stuck.select(number)
        a = AMPLITUDES[number]
        t0 = time.perf_counter()
        ref = method(rom_structure(rom, mode.direction @ rom.output), a, 7, mode=number - 1)
        print(f"{number:>4} {'contact-node ROM':<26} {rom.dofs:>5} {0.0:9.3f} {0.0:11.2f} "
              f"{time.perf_counter() - t0:6.1f}  zeta {ref.damping_ratio.min():.2e} to "
              f"{ref.damping_ratio.max():.2e}")
        slipping = ref.damping_ratio > 1e-4
        cases = [(f"{n} CC modes", lambda n=n: build_interface_rom(rom, n))
                 for n in COUNTS if n <= nb]
        cases += [(f"{n} CC + first loading", lambda n=n, k=number: build_interface_rom(
            rom, n, k - 1)) for n in (10, 20)]
        cases += [(f"{n} + loading, direct", lambda n=n, md=mode: build_interface_model(
            model, RHO, n, FIXED_MODES, md, "response")) for n in (10, 20)]
        for label, build in cases:
            t0 = time.perf_counter()
            reduced = build()
            s = reduced.structure(mode.direction @ reduced.output)
            try:
                c = method(s, a, 7, mode=number - 1)
            except Exception as exc:  # a case that does not converge is a row, not a stop
                print(f"{number:>4} {label:<26} {reduced.dofs:>5} failed: {exc}")
                continue
            df = np.max(np.abs(c.frequency / ref.frequency - 1.0)) * 100
            dz = np.max(np.abs(c.damping_ratio / ref.damping_ratio - 1.0)[slipping]) * 100
            print(f"{number:>4} {label:<26} {reduced.dofs:>5} {df:9.3f} {dz:11.2f} "
                  f"{time.perf_counter() - t0:6.1f}", flush=True)


if __name__ == "__main__":
    main()
