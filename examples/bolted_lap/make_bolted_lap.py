"""Write examples/bolted_lap/bolted_lap.msh: two steel plates joined by one bolt in a lap (gmsh).

Two plates 100 x 25 x 4 mm overlap by 25 mm:

* plate A: 0 <= x <= 100, 0 <= y <= 25, 0 <= z <= 4;
* plate B: 75 <= x <= 175, 0 <= y <= 25, 4 <= z <= 8;
* the lap: 75 <= x <= 100, where A's top face lies on B's bottom face (z = 4).

One bolt at the lap's centre (x = 87.5, y = 12.5), modelled without a hole: its head presses
a 12 x 12 mm square washer patch on B's top (z = 8), its nut the same patch on A's bottom
(z = 0), 81.5 <= x <= 93.5, 6.5 <= y <= 18.5; the mesh lines follow the patches' edges.

Each plate is a grid of boxes (cut at the lap's ends and the patch's edges) fragmented within
the plate only, meshed with transfinite, recombined structured hexahedra (8 nodes) of about
``--size`` mm (default 2.5; at least 2 through each plate's thickness). The plates are not
fragmented together: the lap is a conforming interface, A's and B's faces there have the
same face mesh, every node of ``a_int`` has a node of ``b_int`` at the same place (with
another number), and nothing joins the plates but the contact a solver puts there.

Physical groups (the sets ``microslip.fe.meshfile.read_mesh`` gives):

============  ====================================================================
``PLATE_A``   volume: plate A's hexahedra (element set; the material names it)
``PLATE_B``   volume: plate B's hexahedra
``a_int``     A's top face in the lap, 75 <= x <= 100, z = 4 (the contact face)
``b_int``     B's bottom face in the lap, 75 <= x <= 100, z = 4 (its counter face)
``head``      the washer patch on B's top, z = 8 (the bolt head's preload)
``nut``       the washer patch on A's bottom, z = 0 (the nut's preload)
``fix``       A's end face x = 0 (the support)
``tip``       B's end face x = 175 (the load set)
``response``  B's end face x = 175 (the response set, = ``tip``)
============  ====================================================================

Run from the checkout with the venv's Python (gmsh's Python API; gmsh is a tool to make the
file, not a dependency of microslip):

    .venv/bin/python examples/bolted_lap/make_bolted_lap.py
    .venv/bin/python examples/bolted_lap/make_bolted_lap.py --size 5 \\
        --out tests/data/meshes/bolted_lap_small.msh

The file is gmsh's MSH 4.1 (ASCII). Units: mm.
"""

from __future__ import annotations

import argparse
import itertools
import math
from collections.abc import Callable, Sequence
from pathlib import Path

#: Plates (mm): length, width, thickness; B starts where the lap starts.
LENGTH, WIDTH, THICK = 100.0, 25.0, 4.0
LAP_START = 75.0
#: The bolt's washer patch: side and centre (mm).
PATCH, BOLT_X, BOLT_Y = 12.0, 87.5, 12.5
#: Elements through each plate's thickness, at least.
MIN_THROUGH = 2
#: Tolerance for picking faces by their bounding boxes (mm).
EPS = 1e-6

Box = tuple[float, float, float, float, float, float]


def counts(cuts: Sequence[float], size: float, least: int = 1) -> dict[tuple[float, float], int]:
    """Elements of each segment between consecutive cuts: ceil(length / size), >= least."""
    return {(a, b): max(least, math.ceil((b - a) / size - 1e-9))
            for a, b in itertools.pairwise(cuts)}


def build(size: float, out: Path) -> Path:
    """Mesh the two plates with elements of about ``size`` mm and write ``out`` (.msh)."""
    import gmsh

    h = 0.5 * PATCH
    xa = [0.0, LAP_START, BOLT_X - h, BOLT_X + h, LENGTH]
    xb = [LAP_START, BOLT_X - h, BOLT_X + h, LENGTH, LAP_START + LENGTH]
    ys = [0.0, BOLT_Y - h, BOLT_Y + h, WIDTH]
    za, zb = [0.0, THICK], [THICK, 2 * THICK]
    per_axis = (counts(sorted(set(xa + xb)), size), counts(ys, size),
                counts(sorted(set(za + zb)), size, MIN_THROUGH))

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("bolted_lap")
        plate_a = _body(gmsh, xa, ys, za)
        plate_b = _body(gmsh, xb, ys, zb)
        gmsh.model.occ.synchronize()
        _structured(gmsh, per_axis)
        gmsh.model.addPhysicalGroup(3, plate_a, name="PLATE_A")
        gmsh.model.addPhysicalGroup(3, plate_b, name="PLATE_B")

        def flat(axis: int, at: float, lo: float = -math.inf, hi: float = math.inf,
                 patch: bool = False) -> Callable[[Box], bool]:
            def pick(bb: Box) -> bool:
                on = abs(bb[axis] - at) < EPS and abs(bb[axis + 3] - at) < EPS
                inside = bb[0] >= lo - EPS and bb[3] <= hi + EPS
                if patch:
                    inside = inside and bb[1] >= BOLT_Y - h - EPS and bb[4] <= BOLT_Y + h + EPS
                return on and inside
            return pick

        groups = [
            ("a_int", plate_a, flat(2, THICK, LAP_START, LENGTH)),
            ("b_int", plate_b, flat(2, THICK, LAP_START, LENGTH)),
            ("head", plate_b, flat(2, 2 * THICK, BOLT_X - h, BOLT_X + h, patch=True)),
            ("nut", plate_a, flat(2, 0.0, BOLT_X - h, BOLT_X + h, patch=True)),
            ("fix", plate_a, flat(0, 0.0)),
            ("tip", plate_b, flat(0, LAP_START + LENGTH)),
            ("response", plate_b, flat(0, LAP_START + LENGTH)),
        ]
        for name, body, pick in groups:
            gmsh.model.addPhysicalGroup(2, _faces(gmsh, body, pick), name=name)
        gmsh.model.mesh.generate(3)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        out.parent.mkdir(parents=True, exist_ok=True)
        gmsh.write(str(out))
    finally:
        gmsh.finalize()
    return out


def _body(gmsh, xs: Sequence[float], ys: Sequence[float], zs: Sequence[float]) -> list[int]:  # type: ignore[no-untyped-def]
    """One body: the boxes of the grid ``xs`` x ``ys`` x ``zs`` fragmented together (joined,
    shared nodes), not with any other body; its volume tags."""
    occ = gmsh.model.occ
    boxes = [(3, occ.addBox(x0, y0, z0, x1 - x0, y1 - y0, z1 - z0))
             for x0, x1 in itertools.pairwise(xs)
             for y0, y1 in itertools.pairwise(ys)
             for z0, z1 in itertools.pairwise(zs)]
    if len(boxes) > 1:
        boxes, _ = occ.fragment(boxes[:1], boxes[1:])
    return [t for d, t in boxes if d == 3]


def _structured(gmsh, per_axis: Sequence[dict[tuple[float, float], int]]) -> None:  # type: ignore[no-untyped-def]
    """Transfinite curves (each gets the elements of the segments it spans along its axis),
    transfinite recombined surfaces and transfinite volumes: structured hexahedra, the same
    face mesh on coincident faces of different bodies."""
    for _, c in gmsh.model.getEntities(1):
        bb = gmsh.model.getBoundingBox(1, c)
        ext = [bb[i + 3] - bb[i] for i in range(3)]
        axis = ext.index(max(ext))
        lo, hi = bb[axis], bb[axis + 3]
        n = sum(k for (a, b), k in per_axis[axis].items() if a >= lo - EPS and b <= hi + EPS)
        gmsh.model.mesh.setTransfiniteCurve(c, n + 1)
    for _, s in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(s)
        gmsh.model.mesh.setRecombine(2, s)
    for _, v in gmsh.model.getEntities(3):
        gmsh.model.mesh.setTransfiniteVolume(v)


def _faces(gmsh, volumes: list[int], pick: Callable[[Box], bool]) -> list[int]:  # type: ignore[no-untyped-def]
    """The body's boundary surfaces whose bounding box ``pick`` accepts (never the other
    body's coincident faces: only this body's boundary is searched)."""
    bound = gmsh.model.getBoundary([(3, v) for v in volumes], combined=True, oriented=False)
    tags = [t for d, t in bound if d == 2 and pick(tuple(gmsh.model.getBoundingBox(2, t)))]
    if not tags:
        raise RuntimeError("no face picked")
    return tags


def main(argv: Sequence[str] | None = None) -> None:
    here = Path(__file__).resolve().parent
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=float, default=2.5, help="element size, mm (default 2.5)")
    p.add_argument("--out", type=Path, default=here / "bolted_lap.msh",
                   help="the .msh file to write (default: bolted_lap.msh next to this script)")
    a = p.parse_args(argv)
    if not (math.isfinite(a.size) and a.size > 0):
        p.error(f"--size must be > 0 mm, got {a.size}")
    print(build(a.size, a.out))


if __name__ == "__main__":
    main()
