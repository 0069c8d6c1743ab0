"""Write the small gmsh meshes of tests/test_fe_meshfile_bad.py (run from this directory with
the venv's Python: gmsh's Python API; the tests read the committed files, not gmsh).

A 4 x 1 x 1 mm bar as two 2 x 1 x 1 boxes, 2 hexahedra per edge (transfinite, recombined),
physical groups body (volume), contact (bottom z = 0), clamp (top z = 1), tip (end x = 4):

* ``two_volumes.msh``: the boxes fragmented (joined: shared nodes on x = 2);
* ``separate_volumes.msh``: the boxes meshed apart (coincident, unjoined nodes on x = 2);
* ``contact_curve.msh``: ``contact`` a curve group (the bottom's edge y = 0);
* ``contact_volume.msh``: ``contact`` a volume group (the first box);
* ``metres.msh``: the joined bar scaled by 1e-3 (a mesh in metres).
"""

from __future__ import annotations

import gmsh


def bar(name: str, scale: float = 1.0, contact_dim: int = 2, joined: bool = True) -> None:
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(name)
    s = scale
    a = gmsh.model.occ.addBox(0, 0, 0, 2 * s, s, s)
    b = gmsh.model.occ.addBox(2 * s, 0, 0, 2 * s, s, s)
    if joined:
        gmsh.model.occ.fragment([(3, a)], [(3, b)])
    gmsh.model.occ.synchronize()
    for _, tag in gmsh.model.getEntities(1):
        gmsh.model.mesh.setTransfiniteCurve(tag, 3)
    for _, tag in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(tag)
        gmsh.model.mesh.setRecombine(2, tag)
    volumes = [t for _, t in gmsh.model.getEntities(3)]
    for tag in volumes:
        gmsh.model.mesh.setTransfiniteVolume(tag)
    gmsh.model.addPhysicalGroup(3, volumes, name="body")

    def box(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float,
            dim: int) -> list[int]:
        return [t for _, t in gmsh.model.getEntitiesInBoundingBox(
            x0 * s, y0 * s, z0 * s, x1 * s, y1 * s, z1 * s, dim)]

    contact = {2: box(-1, -1, -0.1, 5, 2, 0.1, 2), 1: box(-1, -1, -0.1, 5, 0.1, 0.1, 1),
               3: volumes[:1]}[contact_dim]
    gmsh.model.addPhysicalGroup(contact_dim, contact, name="contact")
    gmsh.model.addPhysicalGroup(2, box(-1, -1, 0.9, 5, 2, 1.1, 2), name="clamp")
    gmsh.model.addPhysicalGroup(2, box(3.9, -1, -0.1, 4.1, 2, 1.1, 2), name="tip")
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(f"{name}.msh")
    gmsh.finalize()


if __name__ == "__main__":
    bar("two_volumes")
    bar("separate_volumes", joined=False)
    bar("contact_curve", contact_dim=1)
    bar("contact_volume", contact_dim=3)
    bar("metres", scale=1e-3)
