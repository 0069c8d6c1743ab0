"""Hertz-Mindlin, the exact 3-D microslip test (issue 33): the built-in FE against Hertz's contact
radius and Mindlin's dissipated energy, in one run.

    PYTHONPATH=src .venv/bin/python benchmarks/hertz_mindlin.py [--sources] [--mesh FILE]

A block with the paraboloid bottom z = r^2 / 200 (R = 100 mm; tests/data/meshes/make_hertz.py)
pressed on the rigid base by P = 500 N (``fixed`` normal contact), E = 70000 MPa, mu = 0.5,
stick slope 1e8 N/mm^3; the tangential force Q on the top, its moment about the contact
cancelled by +-Q on the top's halves (``--load top:1,0,0:Q --load top_right:0,0,1:Q
--load top_left:0,0,-1:Q``, as the issue's check). For nu = 0.45 and 0.3 it prints the
contact radius (``pressed.hertz_radius_mm``: the Hertz pressure of the same second moment)
against a = (3 P R / (4 E*))^(1/3), and W at Q*/(mu P) = 0.5 and 0.8 against Mindlin's
(:func:`microslip.closedform.cattaneo_mindlin_dissipation`, K = (2 - nu)/G), with the times.

``--sources`` adds where the error comes from, on nu = 0.45:

* the mesh at the contact edge: hertz_block.inp (0.19 mm squares, a/4) and hertz_polar's
  rings 0.09, 0.045 (the committed mesh) and 0.03 mm apart;
* the stick slope: 1e7, 1e8, 1e9 N/mm^3 (the elastic slip before sliding, mu p / lambda);
* the nodal lumping of the pressure: the FE's N_i replaced by Hertz's pressure integrated
  over each node's area (the same pressing nodes), W again.

Units: N, mm, MPa, N·mm.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from microslip import closedform as cf
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import MeshModel, build_mesh_model
from microslip.fe.builtin.meshrun import SineCycles, solve_mesh
from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshfile import read_mesh
from microslip.fe.meshload import MeshLoad

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "meshes"
E, P, R, MU = 70000.0, 500.0, 100.0, 0.5
RATIOS = (0.5, 0.8)


def loads(q: float) -> list[MeshLoad]:
    return [MeshLoad("top", (1.0, 0.0, 0.0), q), MeshLoad("top_right", (0.0, 0.0, 1.0), q),
            MeshLoad("top_left", (0.0, 0.0, -1.0), q)]


def polar(step: float) -> HexMesh:
    sys.path.insert(0, str(DATA))
    import make_hertz

    return make_hertz.hertz_polar({"step": step})


def build(mesh: HexMesh, nu: float, stick: float = 1e8) -> tuple[MeshModel, float]:
    t = time.perf_counter()
    model = build_mesh_model(mesh, rigid_base(
        contact_set="bottom", clamp_set="top", normal_force=P, modulus=E, poisson_ratio=nu,
        friction=MU, stick_slope=stick, normal_contact="fixed"))
    return model, time.perf_counter() - t


def radius(model: MeshModel) -> float:
    x = model.mesh.nodes[model.contact_nodes]
    n = model.normal_force
    return float(np.sqrt(2.5 * np.sum(n * (x[:, 0] ** 2 + x[:, 1] ** 2)) / n.sum()))


def dissipation(model: MeshModel, x: float) -> tuple[float, float, int]:
    t = time.perf_counter()
    res = solve_mesh(model, loads(x * MU * P), SineCycles())
    return res.dissipated_energy, time.perf_counter() - t, res.cycles


def row(label: str, model: MeshModel, nu: float, setup: float) -> None:
    a = cf.hertz_contact_radius(P, R, cf.contact_modulus(E, nu))
    k = cf.mindlin_compliance(E, nu)
    ra = radius(model)
    print(f"{label:34s} nodes {len(model.mesh.nodes):6d}  pressing {int(model.closed.sum()):4d}  "
          f"a {ra:.4f} mm ({ra / a - 1:+.2%} of {a:.4f})  build {setup:6.1f} s", flush=True)
    for x in RATIOS:
        w, t, cycles = dissipation(model, x)
        w0 = cf.cattaneo_mindlin_dissipation(x * MU * P, MU, P, a, k)
        print(f"{'':34s} Q*/(mu P) = {x}: W {w:.6g} N mm, Mindlin {w0:.6g} ({w / w0 - 1:+.2%})"
              f", {cycles} cycles, {t:.1f} s", flush=True)


def hertz_lumped(model: MeshModel, nu: float) -> MeshModel:
    """The model with N_i = Hertz's pressure integrated over node i's area (2-point rule
    across a node's ring: the area A_i as a disc of the node's radius), scaled to sum P, on
    the FE's pressing nodes."""
    x = model.mesh.nodes[model.contact_nodes]
    r = np.hypot(x[:, 0], x[:, 1])
    e_star = cf.contact_modulus(E, nu)
    n = np.asarray(cf.hertz_pressure(r, P, R, e_star)) * model.contact_area
    n[~model.closed] = 0.0
    n *= P / n.sum()
    return replace(model, normal_force=n, friction_limit=MU * n)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mesh", default=str(DATA / "hertz_polar.inp"))
    ap.add_argument("--sources", action="store_true", help="the error's sources too")
    args = ap.parse_args()
    t0 = time.perf_counter()
    mesh = read_mesh(args.mesh)
    for nu in (0.45, 0.3):
        model, setup = build(mesh, nu)
        row(f"{Path(args.mesh).name}, nu = {nu}", model, nu, setup)
    if args.sources:
        print("\nthe mesh at the contact edge (nu = 0.45):")
        for label, m in (("hertz_block.inp (0.19 mm)", read_mesh(DATA / "hertz_block.inp")),
                         ("polar, rings 0.09 mm", polar(0.09)),
                         ("polar, rings 0.03 mm", polar(0.03))):
            model, setup = build(m, 0.45)
            row(label, model, 0.45, setup)
        print("\nthe stick slope (hertz_polar.inp, nu = 0.45):")
        for stick in (1e7, 1e9):
            model, setup = build(mesh, 0.45, stick)
            row(f"stick slope {stick:g}", model, 0.45, setup)
        print("\nthe nodal lumping of the pressure (hertz_polar.inp, nu = 0.45):")
        model, setup = build(mesh, 0.45)
        row("N_i from Hertz's pressure", hertz_lumped(model, 0.45), 0.45, setup)
    print(f"\ntotal {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
