"""Two close modes that share the interface: coupled (circular) against decoupled joints on
the post-on-plate example, checked on the full FE (issue 23, item 6).

Run: ``python3 benchmarks/two_mode.py`` (``--forces``, ``--check-forces``, ``--plot FILE``).

The mesh ``examples/post_on_plate.inp`` (:func:`microslip.fe.examples.post_on_plate_mesh`):
a 10 x 10.5 x 40 mm post on a 30 x 30 x 4 mm foot flange, aluminium (E 70000 MPa, nu 0.33,
2700 kg/m^3), mu 0.5, F_N 2000 N on the flange's top around the post, stick slope
1e4 N/mm^3, fixed normal contact. The Craig-Bampton ROM keeps every contact node and 10
fixed-interface modes; linear modal damping 0.5 % in its stuck modes. Forced by F cos(w t)
on the post's top at 45 degrees: the frequency response through both bending resonances
with circular and with decoupled joints (harmonic balance, 3 harmonics: 1 harmonic
underestimates the microslip W_J by about 20 % here), then the full FE at
the circular curve's x peak, y peak and roundest interface orbit under the quasi-static
equivalent load (:mod:`microslip.meshdynamics.twomode`).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from microslip.fe.meshfile import read_mesh
from microslip.meshdynamics.twomode import TwoModeCase, check_points, two_mode_study

MESH = Path(__file__).resolve().parents[1] / "examples" / "post_on_plate.inp"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", default=str(MESH))
    p.add_argument("--forces", type=float, nargs="+", default=[3.0, 10.0, 15.0],
                   help="forcing amplitudes, N")
    p.add_argument("--check-forces", type=float, nargs="*", default=[3.0, 10.0],
                   help="the forces whose circular curves the full FE checks, N")
    p.add_argument("--damping", type=float, default=0.005, help="linear modal damping ratio")
    p.add_argument("--harmonics", type=int, default=3)
    p.add_argument("--plot", default=None, help="figure file (.png, .pdf, .svg)")
    args = p.parse_args()
    case = TwoModeCase(damping_ratio=args.damping, harmonics=args.harmonics)
    t0 = time.perf_counter()
    s = two_mode_study(read_mesh(args.mesh), case, args.forces, args.check_forces)
    wall = time.perf_counter() - t0
    f1, f2 = s.pair.frequencies_Hz
    print(f"mesh {args.mesh}: {s.dof} DOF, {s.contact_nodes} contact nodes; ROM {s.rom_dofs} "
          f"coordinates")
    print(f"stuck modes (full FE): {f1:.1f} Hz {s.pair.labels[0]} along "
          f"{s.pair.directions[0].round(3).tolist()}, {f2:.1f} Hz {s.pair.labels[1]} along "
          f"{s.pair.directions[1].round(3).tolist()}; separation {100 * s.pair.separation:.2f} %"
          f"; ROM {s.rom_frequencies_Hz[0]:.1f} Hz, {s.rom_frequencies_Hz[1]:.1f} Hz")
    print(f"forcing at {case.angle_deg:g} deg on the top, {s.frequency_range[0]:.0f}-"
          f"{s.frequency_range[1]:.0f} Hz, zeta_0 {case.damping_ratio:g}, "
          f"{case.harmonics} harmonic(s)")
    print()
    print("F (N)  coupling   peak  f (Hz)    top amp (mm)  W_J (N·mm)  orbit b/a  curve")
    for c in s.curves:
        for pk in c.peaks:
            print(f"{c.force:5g}  {c.coupling:9s}  {pk.axis}     {pk.frequency_Hz:8.1f}  "
                  f"{pk.amplitude_mm:12.5g}  {pk.joint_energy_Nmm:10.4g}  "
                  f"{pk.orbit.ratio:9.3f}  "
                  + ("ok" if c.success else
                     f"{c.message}{'' if pk.complete else ': not a peak'}"))
        print(f"{'':5s}  {c.coupling:9s}  roundest orbit b/a {c.orbit_ratio.max():.3f} at "
              f"{c.frequency_Hz[c.orbit_ratio.argmax()]:.1f} Hz")
    print()
    print("decoupled vs circular, (decoupled - circular) / circular:")
    print("F (N)  peak  amplitude  frequency  W_J at the peak")
    for d in s.differences():
        print(f"{d['force_N']:5g}  {d['axis']}     {100 * float(d['amplitude']):+7.2f} %  "
              f"{100 * float(d['frequency']):+7.3f} %  {100 * float(d['joint_energy']):+7.2f} %")
    print()
    print("full FE check: W per cycle under the quasi-static equivalent of the circular "
          "harmonic solution (N·mm)")
    print("F (N)  point      f (Hz)   b/a    modes' share  W_J harmonic  W ROM circ.  "
          "W ROM decoupl.  W full FE  FE/circ-1  decoupl/FE-1  nodes: b/a  angle (deg)")
    for k in s.checks:
        print(f"{k.force:5g}  {k.point:9s}  {k.frequency_Hz:7.1f}  {k.orbit_ratio:5.3f}  "
              f"{k.inertia_share:12.4f}  {k.rom_harmonic_Nmm:12.5g}  {k.rom_circular_Nmm:11.5g}  "
              f"{k.rom_decoupled_Nmm:14.5g}  {k.fe_Nmm:9.5g}  "
              f"{100 * (k.fe_Nmm / k.rom_circular_Nmm - 1):+8.3f} %  "
              f"{100 * (k.rom_decoupled_Nmm / k.fe_Nmm - 1):+8.2f} %  "
              f"{k.node_ratio:10.3f}  {k.node_angle_deg:11.1f}"
              + ("" if k.fe_settled else "  (FE not settled)"))
    print(f"\nwall {wall:.1f} s")
    if args.plot:
        from microslip.plot.twomode import plot_two_mode

        done = [c.force for c in s.curves if c.coupling == "circular" and c.success]
        top = s.curve(max(done), "circular") if done else s.curves[0]
        plot_two_mode(s.curves, args.plot, list(check_points(top).items()), top.force,
                      title="post on plate: circular (solid) and decoupled (dashed) joints")
        print(f"figure: {args.plot}")


if __name__ == "__main__":
    main()
