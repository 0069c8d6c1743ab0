"""A new user's part for the tests of issue 34: a steel plate 100 x 25 x 4 mm whose end
x in [0, 25] sits on the rigid base ("contact"), pressed by a 12 mm washer ("washer", a disk
of radius 6 on the top face at (12.5, 12.5)); the other end x = 100 is loaded ("tip", and
"response", the same face). An unstructured quad mesh of the top view (gmsh, recombined),
extruded in two layers: hexahedra that are not a grid.

    /work/main/.venv/bin/python tests/data/meshes/make_plate_modal.py tests/data/meshes/plate.msh
"""
import sys

import gmsh

SIZE = 6.0  # mm, the triangles' size before the subdivision into quads (about 3 mm)


def plate(out: str) -> None:
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("plate")
    occ = gmsh.model.occ
    whole = occ.addRectangle(0, 0, 0, 100, 25)
    clamp = occ.addRectangle(0, 0, 0, 25, 25)
    disk = occ.addDisk(12.5, 12.5, 0, 6, 6)
    occ.fragment([(2, whole)], [(2, clamp), (2, disk)])
    occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", SIZE)
    gmsh.option.setNumber("Mesh.MeshSizeMin", SIZE / 2)
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    gmsh.option.setNumber("Mesh.Algorithm", 8)  # frontal-Delaunay for quads
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 2)  # blossom full-quad
    gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 1)  # every cell a quad
    surfaces = gmsh.model.getEntities(2)
    occ.extrude(surfaces, 0, 0, 4, numElements=[2], recombine=True)
    occ.synchronize()
    e = 1e-6
    groups: dict[str, list[int]] = {"contact": [], "washer": [], "tip": []}
    for _, s in gmsh.model.getEntities(2):
        x0, _, z0, x1, _, z1 = gmsh.model.getBoundingBox(2, s)
        if abs(z0) < e and abs(z1) < e and x1 <= 25 + e:
            groups["contact"].append(s)
        if abs(z0 - 4) < e and abs(z1 - 4) < e and x0 >= 6.5 - e and x1 <= 18.5 + e:
            groups["washer"].append(s)
        if abs(x0 - 100) < e and abs(x1 - 100) < e:
            groups["tip"].append(s)
    gmsh.model.addPhysicalGroup(3, [v for _, v in gmsh.model.getEntities(3)], name="PLATE")
    for name, tags in groups.items():
        assert tags, name
        gmsh.model.addPhysicalGroup(2, tags, name=name)
    gmsh.model.addPhysicalGroup(2, groups["tip"], name="response")
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.write(out)
    gmsh.finalize()


if __name__ == "__main__":
    plate(sys.argv[1] if len(sys.argv) > 1 else "plate.msh")
