"""Write examples/bracket.inp: a flange clamped on a base by a bar, with an upright web (gmsh).

The part a new user meshes in gmsh (issues 28 and 29): an L-bracket whose flange
(60 x 30 x 5 mm, 0 <= x <= 60, 0 <= y <= 30, 0 <= z <= 5) rests on the rigid base z = 0 and
is pressed onto it by a clamping bar 15 mm wide across the whole width (the strip
10 <= x <= 25 of the flange's top), and whose web (5 mm thick, 45 <= x <= 50) rises from the
flange to z = 40. Under penalty normal contact the flange bends round the bar's line load
and lifts off the base away from it: part of the contact is open after the clamping step.

The profile in the x-z plane is meshed as transfinite quadrilaterals and extruded along y in
layers with recombination, so every element is an 8-node hexahedron (about 5 mm; 2.5 mm
through the flange). The physical groups are the roles:

=========  ===================================================================
contact    the flange's bottom face z = 0 (the face on the rigid base)
clamp      the bar's strip on the flange's top, 10 <= x <= 25, z = 5
top        the web's top face z = 40 (the load set)
response   the web's top face's nodes (the response set)
=========  ===================================================================

The mesh is taken from gmsh's API (nodes, hexahedra, each group's quadrilaterals) and
:func:`microslip.fe.meshfile.write_inp` writes the ``.inp`` with node sets and element-face
surfaces, so the file needs no gmsh to be read. Run from the checkout:

    PYTHONPATH=src .venv/bin/python examples/make_bracket.py [examples/bracket.inp]

Units: mm.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

#: Stations along x of the profile's blocks (mm) and the elements in each.
X_STOPS = (0.0, 10.0, 25.0, 45.0, 50.0, 60.0)
X_ELEMENTS = (2, 3, 4, 1, 2)
#: Flange thickness (mm) and its elements; the web's top (mm) and its elements above it.
FLANGE, FLANGE_ELEMENTS = 5.0, 2
WEB_TOP, WEB_ELEMENTS = 40.0, 7
#: The web's block (index into the x blocks) and the clamping bar's.
WEB_BLOCK, CLAMP_BLOCK = 3, 1
#: gmsh element types: 8-node hexahedron, 4-node quadrilateral.
HEX8, QUAD4 = 5, 3
#: Width (mm, along y) and its element layers.
WIDTH, WIDTH_ELEMENTS = 30.0, 6


def build(path: Path) -> Path:
    """Mesh the bracket with gmsh and write it as ``path`` (.inp); returns the path."""
    import gmsh

    from microslip.fe.meshfile import write_inp

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("bracket")
        geo = gmsh.model.geo
        pts: dict[tuple[float, float], int] = {}

        def point(x: float, z: float) -> int:
            if (x, z) not in pts:
                pts[(x, z)] = geo.addPoint(x, 0.0, z)
            return pts[(x, z)]

        lines: dict[tuple[int, int], int] = {}

        def line(a: int, b: int, n: int) -> int:
            if (b, a) in lines:
                return -lines[(b, a)]
            if (a, b) not in lines:
                lines[(a, b)] = geo.addLine(a, b)
                geo.mesh.setTransfiniteCurve(lines[(a, b)], n + 1)
            return lines[(a, b)]

        def block(x0: float, x1: float, z0: float, z1: float, nx: int, nz: int) -> int:
            p = [point(x0, z0), point(x1, z0), point(x1, z1), point(x0, z1)]
            loop = geo.addCurveLoop([line(p[0], p[1], nx), line(p[1], p[2], nz),
                                     line(p[2], p[3], nx), line(p[3], p[0], nz)])
            s = geo.addPlaneSurface([loop])
            geo.mesh.setTransfiniteSurface(s)
            geo.mesh.setRecombine(2, s)
            return s

        flange = [block(X_STOPS[i], X_STOPS[i + 1], 0.0, FLANGE, X_ELEMENTS[i],
                        FLANGE_ELEMENTS) for i in range(len(X_ELEMENTS))]
        web = block(X_STOPS[WEB_BLOCK], X_STOPS[WEB_BLOCK + 1], FLANGE, WEB_TOP,
                    X_ELEMENTS[WEB_BLOCK], WEB_ELEMENTS)
        volumes = []
        bottom, clamp, top = [], [], []
        for s in [*flange, web]:
            out = geo.extrude([(2, s)], 0.0, WIDTH, 0.0, numElements=[WIDTH_ELEMENTS],
                              recombine=True)
            volumes.append(out[1][1])
        geo.synchronize()
        # the faces of the roles, by where they lie (the extruded side faces of the profile)
        eps = 1e-6
        for dim, tag in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
            if abs(y1 - y0) < WIDTH - eps:
                continue  # the profile's own faces at y = 0 and y = WIDTH
            if abs(z1) < eps:
                bottom.append(tag)
            elif (abs(z0 - FLANGE) < eps and abs(z1 - FLANGE) < eps
                  and x0 >= X_STOPS[CLAMP_BLOCK] - eps and x1 <= X_STOPS[CLAMP_BLOCK + 1] + eps):
                clamp.append(tag)
            elif abs(z0 - WEB_TOP) < eps and abs(z1 - WEB_TOP) < eps:
                top.append(tag)
        for name, tags in (("contact", bottom), ("clamp", clamp), ("top", top),
                           ("response", top)):
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        body = gmsh.model.addPhysicalGroup(3, volumes, name="bracket")
        gmsh.model.mesh.generate(3)
        mesh = _hexmesh(gmsh, body)
    finally:
        gmsh.finalize()
    return write_inp(mesh, path)


def _hexmesh(gmsh: Any, body: int) -> Any:
    """The generated mesh as a HexMesh: gmsh's 8-node hexahedra (type 5; gmsh orders their
    nodes as CalculiX's C3D8) and each surface group's quadrilaterals (type 3) as a node set
    and an element-face surface (:func:`microslip.fe.meshfile.assemble`); ``response`` as a
    node set only, as in the other examples."""
    from microslip.fe.meshfile import assemble

    tags, coords, _ = gmsh.model.mesh.getNodes()
    row = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    row[tags.astype(np.int64)] = np.arange(tags.size)
    points = coords.reshape(-1, 3)
    hexes = []
    for tag in gmsh.model.getEntitiesForPhysicalGroup(3, body):
        _, conn = gmsh.model.mesh.getElementsByType(HEX8, tag)
        hexes.append(row[conn.astype(np.int64)].reshape(-1, 8))
    elements = np.concatenate(hexes)
    groups: dict[str, list[tuple[str, NDArray[np.int64]]]] = {}
    node_sets: dict[str, NDArray[np.int64]] = {}
    for dim, ptag in gmsh.model.getPhysicalGroups(2):
        name = gmsh.model.getPhysicalName(dim, ptag)
        quads = [row[gmsh.model.mesh.getElementsByType(QUAD4, t)[1].astype(np.int64)]
                 .reshape(-1, 4) for t in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag)]
        if name == "response":
            node_sets[name] = np.unique(np.concatenate(quads))
        else:
            groups[name] = [("quad", q) for q in quads]
    return assemble("bracket.inp", points, elements, node_sets, groups, None, None)


if __name__ == "__main__":
    out = build(Path(sys.argv[1] if len(sys.argv) > 1 else "examples/bracket.inp"))
    print(out)
