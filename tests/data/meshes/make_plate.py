"""Write ``plate_washer.msh``: a new user's steel plate, an unstructured gmsh hexahedral mesh
(issue 33, the built-in solver against CalculiX node to surface on any mesh).

Run from this directory with the venv's Python (gmsh's Python API; the tests read the
committed file, not gmsh): ``../../../.venv/bin/python make_plate.py``.

A 100 x 25 x 4 mm plate (0 <= x <= 100, 0 <= y <= 25, 0 <= z <= 4). Its plan is meshed by
gmsh's frontal-Delaunay for quadrangles (``Mesh.Algorithm`` 8, recombined, 2.5 mm, no
transfinite lines: the quadrilaterals are not parallelograms) and extruded through the
thickness in 2 layers of hexahedra. The plan holds the line x = 25 and a 12 mm circle about
(12.5, 12.5), so that the sets below are unions of faces:

===========  ===============================================================
``contact``  the bottom z = 0 under 0 <= x <= 25 (on the rigid base)
``washer``   the 12 mm disc about (12.5, 12.5) on the top z = 4 (the clamp)
``end``      the end face x = 100 (the load)
``bottom``   the whole bottom z = 0
===========  ===============================================================

Volume group ``PLATE``. Units: mm.
"""

from __future__ import annotations

import sys
from pathlib import Path

import gmsh

HERE = Path(__file__).resolve().parent
#: Element size (mm) and layers through the thickness.
SIZE, LAYERS = 2.5, 2


def plate(out: Path, size: float = SIZE, layers: int = LAYERS) -> Path:
    """Mesh the plate and write it to ``out`` (gmsh 4.1 ASCII)."""
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("plate_washer")
        occ = gmsh.model.occ
        clamped = occ.addRectangle(0, 0, 0, 25, 25)
        free = occ.addRectangle(25, 0, 0, 75, 25)
        washer = occ.addDisk(12.5, 12.5, 0, 6, 6)
        occ.fragment([(2, clamped), (2, free)], [(2, washer)])
        occ.synchronize()
        gmsh.option.setNumber("Mesh.Algorithm", 8)  # frontal-Delaunay for quadrangles
        gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.RandomSeed", 0)
        surfaces = [t for _, t in gmsh.model.getEntities(2)]
        for s in surfaces:
            gmsh.model.mesh.setRecombine(2, s)
        occ.extrude([(2, s) for s in surfaces], 0, 0, 4, numElements=[layers], recombine=True)
        occ.synchronize()
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], name="PLATE")

        def faces(pick: object) -> list[int]:
            return [s for _, s in gmsh.model.getEntities(2)
                    if pick(gmsh.model.getBoundingBox(2, s))]  # type: ignore[operator]

        e = 1e-6
        on = lambda z: (lambda b: abs(b[2] - z) < e and abs(b[5] - z) < e)  # noqa: E731
        gmsh.model.addPhysicalGroup(2, faces(on(0.0)), name="bottom")
        gmsh.model.addPhysicalGroup(2, faces(lambda b: on(0.0)(b) and b[3] <= 25 + e),
                                    name="contact")
        gmsh.model.addPhysicalGroup(2, faces(lambda b: on(4.0)(b) and b[3] - b[0] < 12.5),
                                    name="washer")
        gmsh.model.addPhysicalGroup(2, faces(lambda b: abs(b[0] - 100) < e
                                             and abs(b[3] - 100) < e), name="end")
        gmsh.model.mesh.generate(3)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.write(str(out))
    finally:
        gmsh.finalize()
    return out


if __name__ == "__main__":
    print(plate(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE / "plate_washer.msh"))
