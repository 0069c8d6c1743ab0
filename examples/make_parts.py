"""Hexahedral test parts built in gmsh from extruded quad cross-sections (structured).

lap:   a bolted lap: a 60 x 30 x 5 mm plate on the rigid base (contact: its bottom under x in
       [0, 30]), a 14 x 14 washer pad on top (clamp), continuing as the free lap to x = 60;
       load on the end face x = 60 ("tip").
root:  a blade-root-like block: a 24 x 12 x 10 root on the base (contact: whole bottom), the
       clamp on its two top shoulders, a 3 mm blade rising 40 mm from the middle of the
       root's top; load on the blade's top face ("tip"); response set = tip.
"""
import sys
import gmsh

def seg_points(xs):
    return xs

def build(name, xcuts, ycuts, zcuts, keep, nx, ny, nz, groups, out):
    """Union of boxes of a tensor grid (xcuts x ycuts x zcuts) where keep(i,j,k) holds,
    meshed with nx[i] x ny[j] x nz[k] hexahedra; physical surfaces by selector."""
    gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(name)
    occ = gmsh.model.occ
    vols = {}
    for i in range(len(xcuts) - 1):
        for j in range(len(ycuts) - 1):
            for k in range(len(zcuts) - 1):
                if keep(i, j, k):
                    vols[(i, j, k)] = occ.addBox(xcuts[i], ycuts[j], zcuts[k],
                                                 xcuts[i+1]-xcuts[i], ycuts[j+1]-ycuts[j],
                                                 zcuts[k+1]-zcuts[k])
    occ.fragment([(3, v) for v in vols.values()], [])
    occ.synchronize()
    # transfinite on every curve by its direction and length
    for (dim, c) in gmsh.model.getEntities(1):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(1, c)
        dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
        big = max(dx, dy, dz)
        if dx == big:
            i = min(range(len(xcuts)-1), key=lambda i: abs(xcuts[i]-x0) + abs(xcuts[i+1]-x1))
            n = nx[i]
        elif dy == big:
            j = min(range(len(ycuts)-1), key=lambda j: abs(ycuts[j]-y0) + abs(ycuts[j+1]-y1))
            n = ny[j]
        else:
            k = min(range(len(zcuts)-1), key=lambda k: abs(zcuts[k]-z0) + abs(zcuts[k+1]-z1))
            n = nz[k]
        gmsh.model.mesh.setTransfiniteCurve(c, n + 1)
    for (dim, s) in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(s); gmsh.model.mesh.setRecombine(2, s)
    for (dim, v) in gmsh.model.getEntities(3):
        gmsh.model.mesh.setTransfiniteVolume(v)
    gmsh.model.addPhysicalGroup(3, [v for _, v in gmsh.model.getEntities(3)], name="body")
    for gname, sel in groups.items():
        tags = []
        for (dim, s) in gmsh.model.getEntities(2):
            bb = gmsh.model.getBoundingBox(2, s)
            if sel(bb):
                tags.append(s)
        assert tags, gname
        gmsh.model.addPhysicalGroup(2, tags, name=gname)
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.write(out)
    gmsh.finalize()

E = 1e-4
def flat(z):
    return lambda bb, z=z: abs(bb[2]-z) < E and abs(bb[5]-z) < E

def lap(out, f=1):
    xc = [0, 8, 22, 30, 60]; yc = [0, 8, 22, 30]; zc = [0, 5]
    build("lap", xc, yc, zc, lambda i, j, k: True,
          [2*f, 4*f, 2*f, 8*f], [2*f, 4*f, 2*f], [2*f],
          {"contact": lambda bb: flat(0)(bb) and bb[3] <= 30 + E,
           "clamp": lambda bb: flat(5)(bb) and bb[0] >= 8-E and bb[3] <= 22+E and bb[1] >= 8-E and bb[4] <= 22+E,
           "tip": lambda bb: abs(bb[0]-60) < E and abs(bb[3]-60) < E}, out)

def root(out, f=1):
    xc = [0, 10.5, 13.5, 24]; yc = [0, 12]; zc = [0, 10, 50]
    keep = lambda i, j, k: k == 0 or i == 1
    build("root", xc, yc, zc, keep, [3*f, 1*f, 3*f], [4*f], [3*f, 10*f],
          {"contact": flat(0),
           "clamp": lambda bb: flat(10)(bb) and (bb[3] <= 10.5+E or bb[0] >= 13.5-E),
           "tip": flat(50)}, out)

if __name__ == "__main__":
    here = __import__("pathlib").Path(__file__).resolve().parent
    lap(str(here / "lap.msh")); root(str(here / "root.msh"))
