"""Speed of the reduced model with every contact node (issue 23 targets).

Run: ``python3 benchmarks/bench_rom.py`` (``--quick``: one repeat).

The cantilever example (:func:`microslip.fe.examples.cantilever_mesh` 24x6x2, C3D8I):
aluminium E 70000 MPa, nu 0.33, density 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope
1e4 N/mm^3, ``fixed`` normal contact (the 2-D circular element per contact node; the 3-D
penalty element's EPMC is a row of ``bench_structure.py``). Rows, beside the targets:

* ROM build: the clamping step's model is given; the consistent mass, 20 fixed-interface
  modes, the constraint modes and the reduced matrices (target under 5 s);
* ROM EPMC: the in-plane bending mode (the response set's mean y), 20 amplitudes from
  stuck to near gross sliding, 7 harmonics (target under 5 s): the balance on every
  harmonic (:func:`~microslip.dynamics.modal.epmc`) and on the odd ones only
  (:func:`~microslip.dynamics.modal_odd.epmc_odd`, the same curve for these odd joint
  forces).

Also the stuck frequencies' error against the full FE for a few mode counts. Best of
``--repeat``.
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
from microslip.meshdynamics.reduce import build_rom, convergence, full_mass, rom_structure

TARGETS = {"build": 5.0, "epmc": 5.0}
RHO = 2700.0


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=2)
    p.add_argument("--quick", action="store_true")
    args = p.parse_args()
    repeat = 1 if args.quick else args.repeat
    model = build_mesh_model(cantilever_mesh(24, 6, 2), rigid_base(contact_set="contact",
                                                                   clamp_set="clamp",
                                                                   normal_force=2000.0,
                                                                   modulus=70000.0,
                                                                   poisson_ratio=0.33, friction=0.5,
                                                                   stick_slope=1e4))
    build = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        rom = build_rom(model, RHO, modes=20, response_set="response")
        build.append(time.perf_counter() - t0)
    s = rom_structure(rom)
    a = np.geomspace(2e-3, 3e-2, 20)
    epmc_odd(s, a[:2], 7, mode=1)  # compile the kernels once
    run, odd = [], []
    for _ in range(repeat):
        t0 = time.perf_counter()
        curve = epmc(s, a, 7, mode=1)
        run.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        fast = epmc_odd(s, a, 7, mode=1)
        odd.append(time.perf_counter() - t0)
    print(f"cantilever 24x6x2: {model.dof} dofs, {model.contact_nodes.size} contact nodes; "
          f"ROM {rom.dofs} dofs ({rom.boundary.size} contact + {rom.modes} modes)")
    print(f"  ROM build         {min(build):7.2f} s   (target < {TARGETS['build']:.0f} s)")
    print(f"  ROM EPMC 20 x H7  {min(run):7.2f} s   (target < {TARGETS['epmc']:.0f} s), every "
          "harmonic")
    print(f"  ROM EPMC 20 x H7  {min(odd):7.2f} s   (target < {TARGETS['epmc']:.0f} s), odd "
          "harmonics (largest difference in frequency "
          f"{np.max(np.abs(fast.frequency / curve.frequency - 1)):.1e}, relative)")
    print(f"  in-plane mode: {curve.frequency[0]:.2f} Hz stuck -> {curve.frequency[-1]:.2f} Hz, "
          f"damping ratio {curve.damping_ratio[-1]:.4f} at {a[-1]:.3g} mm")
    table = convergence(model, RHO, [5, 10, 20, 40, 80], compare=6,
                        mass=full_mass(model, RHO))
    print("  stuck frequencies (Hz), full FE: "
          + ", ".join(f"{f:.6g}" for f in table["full_Hz"]))  # type: ignore[union-attr]
    for n, err in zip(table["modes"], table["relative_error"], strict=True):
        worst = max(abs(float(e)) for e in err)  # type: ignore[union-attr]
        print(f"  {n:3d} modes: largest relative error of the 6 lowest {worst:.2e}")


if __name__ == "__main__":
    main()
