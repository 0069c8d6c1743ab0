"""Write examples/brb/brb.msh: a Brake-Reuss-type beam, two halves bolted in a lap (gmsh).

Two steel beam halves of square section 25.4 x 25.4 mm (0 <= y, z <= 25.4), 711 mm long
together (0 <= x <= 711), joined by a 120 mm lap centred at x = 355.5 in which each half is
cut to half thickness (12.7 mm):

* half A: the full section for 0 <= x <= 293.5, its lower half (z <= 12.7) on to x = 415.5;
* half B: its upper half (z >= 12.7) from x = 295.5, the full section for 417.5 <= x <= 711;
* the lap: 295.5 <= x <= 415.5, where A's top face (z = 12.7) lies on B's bottom face.

Each half's shoulder stands 2 mm off the other half's end (A's at x = 293.5 facing B's end
x = 295.5, B's at x = 417.5 facing A's end x = 415.5), so the halves touch nowhere but in the
lap (a shoulder on the other's end would be coincident nodes with no contact between them).
Three bolts along the lap's centre line y = 12.7, at x = 315.5, 355.5 and 395.5 (the lap's
centre and +-40 mm), modelled without holes: each head presses a 16 x 16 mm square washer
patch on B's top (z = 25.4), each nut the same patch on A's bottom (z = 0); the mesh lines
follow the patches' edges.

Each half is a grid of boxes fragmented within the half only, meshed with transfinite,
recombined structured hexahedra (8 nodes): about ``--size`` mm (default 4) in the lap and
across the section (8 across the width, 4 through each half-thickness), about
``--arm-size`` mm (default 6) along the arms outside the lap. The halves are not fragmented
together: ``lap_a`` and ``lap_b`` have the same face mesh, every node of one has a node of
the other at the same place (with another number). Free-free: no support set.

Physical groups (the sets ``microslip.fe.meshfile.read_mesh`` gives):

==================  ===============================================================
``HALF_A``          volume: half A's hexahedra (element set; the material names it)
``HALF_B``          volume: half B's hexahedra
``lap_a``           A's top face in the lap, 295.5 <= x <= 415.5, z = 12.7 (contact face)
``lap_b``           B's bottom face in the lap, the same place (its counter face)
``head1..head3``    the washer patches on B's top, z = 25.4, at x = 315.5, 355.5, 395.5
``nut1..nut3``      the washer patches on A's bottom, z = 0, at the same x
``tip``             B's end face x = 711 (the load set)
``response``        B's end face x = 711 (the response set, = ``tip``)
==================  ===============================================================

Run from the checkout with the venv's Python (gmsh's Python API; gmsh is a tool to make the
file, not a dependency of microslip):

    .venv/bin/python examples/brb/make_brb.py [--size 4] [--arm-size 6] [--out FILE]

The file is gmsh's MSH 4.1 (ASCII). Units: mm.
"""

from __future__ import annotations

import argparse
import itertools
import math
from collections.abc import Callable, Sequence
from pathlib import Path

#: Beam (mm): total length, section side, half-thickness; the lap's centre and length; the
#: gap between a shoulder and the other half's end.
LENGTH, SIDE = 711.0, 25.4
HALF = 0.5 * SIDE
LAP_CENTRE, LAP = 355.5, 120.0
GAP = 2.0
#: Bolts: offsets from the lap's centre along x, the washer patch's side (mm).
BOLTS, PATCH = (-40.0, 0.0, 40.0), 16.0
#: Elements through each half-thickness, at least.
MIN_THROUGH = 2
#: Tolerance for picking faces by their bounding boxes (mm).
EPS = 1e-6

Box = tuple[float, float, float, float, float, float]


def counts(cuts: Sequence[float], size: Callable[[float, float], float],
           least: int = 1) -> dict[tuple[float, float], int]:
    """Elements of each segment between consecutive cuts: ceil(length / size(a, b)), >= least."""
    return {(a, b): max(least, math.ceil((b - a) / size(a, b) - 1e-9))
            for a, b in itertools.pairwise(cuts)}


def build(size: float, arm_size: float, out: Path) -> Path:
    """Mesh the beam (``size`` mm in the lap and across, ``arm_size`` along the arms) and write
    ``out`` (.msh)."""
    import gmsh

    lap0, lap1 = LAP_CENTRE - 0.5 * LAP, LAP_CENTRE + 0.5 * LAP
    shoulder_a, shoulder_b = lap0 - GAP, lap1 + GAP
    h = 0.5 * PATCH
    patches = [(LAP_CENTRE + d - h, LAP_CENTRE + d + h) for d in BOLTS]
    inner = [lap0, *itertools.chain.from_iterable(patches), lap1]
    xa = [0.0, shoulder_a, *inner]
    xb = [*inner, shoulder_b, LENGTH]
    ys = [0.0, HALF - h, HALF + h, SIDE]
    zs = [0.0, HALF, SIDE]

    def along(a: float, b: float) -> float:
        return arm_size if b <= shoulder_a + EPS or a >= shoulder_b - EPS else size

    per_axis = (counts(sorted(set(xa + xb)), along), counts(ys, lambda a, b: size),
                counts(zs, lambda a, b: size, MIN_THROUGH))

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("brb")
        half_a = _body(gmsh, xa, ys, zs, lambda x, z: x < shoulder_a or z < HALF)
        half_b = _body(gmsh, xb, ys, zs, lambda x, z: x > shoulder_b or z > HALF)
        gmsh.model.occ.synchronize()
        _structured(gmsh, per_axis)
        gmsh.model.addPhysicalGroup(3, half_a, name="HALF_A")
        gmsh.model.addPhysicalGroup(3, half_b, name="HALF_B")

        def flat(axis: int, at: float, lo: float = -math.inf, hi: float = math.inf,
                 patch: bool = False) -> Callable[[Box], bool]:
            def pick(bb: Box) -> bool:
                on = abs(bb[axis] - at) < EPS and abs(bb[axis + 3] - at) < EPS
                inside = bb[0] >= lo - EPS and bb[3] <= hi + EPS
                if patch:
                    inside = inside and bb[1] >= HALF - h - EPS and bb[4] <= HALF + h + EPS
                return on and inside
            return pick

        groups = [("lap_a", half_a, flat(2, HALF, lap0, lap1)),
                  ("lap_b", half_b, flat(2, HALF, lap0, lap1))]
        for i, (p0, p1) in enumerate(patches, start=1):
            groups += [(f"head{i}", half_b, flat(2, SIDE, p0, p1, patch=True)),
                       (f"nut{i}", half_a, flat(2, 0.0, p0, p1, patch=True))]
        groups += [("tip", half_b, flat(0, LENGTH)), ("response", half_b, flat(0, LENGTH))]
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


def _body(gmsh, xs: Sequence[float], ys: Sequence[float], zs: Sequence[float],  # type: ignore[no-untyped-def]
          keep: Callable[[float, float], bool]) -> list[int]:
    """One body: the boxes of the grid ``xs`` x ``ys`` x ``zs`` whose centre (x, z) ``keep``
    accepts, fragmented together (joined, shared nodes), not with any other body; its volume
    tags."""
    occ = gmsh.model.occ
    boxes = [(3, occ.addBox(x0, y0, z0, x1 - x0, y1 - y0, z1 - z0))
             for x0, x1 in itertools.pairwise(xs)
             for y0, y1 in itertools.pairwise(ys)
             for z0, z1 in itertools.pairwise(zs) if keep(0.5 * (x0 + x1), 0.5 * (z0 + z1))]
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
    p.add_argument("--size", type=float, default=4.0,
                   help="element size in the lap and across the section, mm (default 4)")
    p.add_argument("--arm-size", type=float, default=6.0,
                   help="element length along the arms outside the lap, mm (default 6)")
    p.add_argument("--out", type=Path, default=here / "brb.msh",
                   help="the .msh file to write (default: brb.msh next to this script)")
    a = p.parse_args(argv)
    for name, v in (("--size", a.size), ("--arm-size", a.arm_size)):
        if not (math.isfinite(v) and v > 0):
            p.error(f"{name} must be > 0 mm, got {v}")
    print(build(a.size, a.arm_size, a.out))


if __name__ == "__main__":
    main()
