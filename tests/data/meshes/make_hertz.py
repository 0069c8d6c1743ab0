"""Write ``hertz_block.inp``: a block whose bottom face is a paraboloid, for Hertz contact
(numpy and microslip only; ``PYTHONPATH=src .venv/bin/python tests/data/meshes/make_hertz.py``).

The block is 20 x 20 mm in plan (-10 <= x, y <= 10, its axis the z axis) and 10 mm tall: its
top face is z = 10, its bottom face the paraboloid z = r^2 / (2 R), R = 100 mm, r the
distance from the axis (touching z = 0 at the axis, z = 1 at the plan's corners). Pressed on
a flat, it makes a Hertz contact of radius a = (3 F R / (4 E*))^(1/3): on a rigid flat, of
aluminium (E* = E / (1 - nu^2) = 78.6 GPa), 0.99 mm at 1 kN and 1.42 mm at 3 kN.

The mesh is structured 8-node hexahedra on an O-grid in plan: a central square
-1.5 <= x, y <= 1.5 of 16 x 16 elements of 0.1875 mm, and a ring of 64 x 13 elements between
that square and the plan's outline, the radial size growing geometrically (ratio 1.19)
from 0.1875 mm at the square to about 1.5 mm at the outline (and the tangential size from
0.1875 to 1.25 mm). Every plan node's column has 11 layers of elements from the paraboloid
to the top, the layer thickness growing geometrically from 0.15 mm at the bottom (at the
axis) to about 2.6 mm at the top. The line x = 0 is a mesh line of the top face. 13452
nodes, 11968 elements (40356 DOF).

Sets (node sets and element-face surfaces):

===============  =================================================================
``bottom``       the curved bottom face (the contact face)
``top``          the whole top face z = 10
``top_left``     the top face's half x <= 0
``top_right``    the top face's half x >= 0
===============  =================================================================

Element set ``BLOCK``: every element. Units: mm.

``hertz_polar.inp`` (:func:`hertz_polar`, the Hertz-Mindlin test of issue 33): a 6 x 6 x 3 mm
block with the same paraboloid, meshed for Mindlin's slip annulus: the plan is an O-grid
whose rings are *circles* from r = 0.57 to 0.9 mm (the contact edge a = 0.753 mm of E = 70000,
nu = 0.45, 500 N lies on them), 0.045 mm apart from the 0.3 mm central square (12 x 12
elements) to r = 0.9 mm, then growing by 1.6 to the square outline; 48 elements around. The
layers grow from 0.045 mm at the paraboloid by 1.6 to the top. Same sets (``bottom``,
``top``, ``top_left``, ``top_right``) and element set ``BLOCK``. 10161 nodes.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshcheck import boundary_faces
from microslip.fe.meshfile import write_inp

HERE = Path(__file__).resolve().parent
#: Plan half-width, height at the axis, radius of the paraboloid (mm).
HALF, HEIGHT, RADIUS = 10.0, 10.0, 100.0
#: The central square's half-width (mm) and its elements across (even: x = 0 a mesh line).
CORE, CORE_ELEMENTS = 1.5, 16
#: Elements from the central square to the outline, and from the bottom to the top.
RING_ELEMENTS, LAYERS = 13, 11
#: The first layer's thickness at the axis (mm).
FIRST_LAYER = 0.15


def graded(first: float, total: float, n: int) -> np.ndarray:
    """n + 1 stations 0 .. 1: n steps growing geometrically, the first ``first / total``."""
    lo, hi = 1.0, 2.0
    for _ in range(200):  # bisection on the ratio: first * (q^n - 1) / (q - 1) = total
        q = 0.5 * (lo + hi)
        lo, hi = (q, hi) if first * (q**n - 1) / (q - 1) < total else (lo, q)
    steps = first * q ** np.arange(n)
    t = np.concatenate([[0.0], np.cumsum(steps)])
    return t / t[-1]


def plan() -> tuple[np.ndarray, np.ndarray]:
    """The O-grid in plan: nodes (m, 2) and counter-clockwise quadrilaterals (k, 4)."""
    n = CORE_ELEMENTS
    s = np.linspace(-1.0, 1.0, n + 1)
    s[n // 2] = 0.0
    gx, gy = np.meshgrid(s, s, indexing="ij")
    core = CORE * np.stack([gx.ravel(), gy.ravel()], axis=1)
    ids = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)  # ids[i, j]: x_i, y_j
    quads = [np.stack([ids[:-1, :-1].ravel(), ids[1:, :-1].ravel(), ids[1:, 1:].ravel(),
                       ids[:-1, 1:].ravel()], axis=1)]
    # the square's perimeter, counter-clockwise from (-1, -1), as grid ids and unit points
    ring = np.concatenate([ids[:-1, 0], ids[n, :-1], ids[:0:-1, n], ids[0, :0:-1]])
    unit = core[ring] / CORE
    g = graded(2 * CORE / n, HALF - CORE, RING_ELEMENTS)
    levels = [ring]
    nodes = [core]
    count = len(core)
    for k in range(1, RING_ELEMENTS + 1):
        r = CORE + (HALF - CORE) * g[k]
        nodes.append(np.round(r * unit, 12))
        levels.append(count + np.arange(len(ring)))
        count += len(ring)
    lv = np.stack(levels)  # (levels, perimeter)
    nxt = np.roll(np.arange(len(ring)), -1)
    for k in range(RING_ELEMENTS):
        quads.append(np.stack([lv[k], lv[k + 1], lv[k + 1][nxt], lv[k][nxt]], axis=1))
    xy = np.vstack(nodes)
    q = np.vstack(quads)
    p = xy[q]
    area = 0.5 * np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, axis=1)
                        - np.roll(p[:, :, 0], -1, axis=1) * p[:, :, 1], axis=1)
    q[area < 0] = q[area < 0][:, ::-1]
    return xy, q


def hertz_block() -> HexMesh:
    """The block as a :class:`HexMesh` (layer by layer from the bottom)."""
    xy, q = plan()
    m = len(xy)
    bottom = (xy[:, 0] ** 2 + xy[:, 1] ** 2) / (2 * RADIUS)
    t = graded(FIRST_LAYER, HEIGHT, LAYERS)
    z = bottom[None, :] + (HEIGHT - bottom[None, :]) * t[:, None]  # (layers + 1, m)
    z[-1] = HEIGHT
    nodes = np.column_stack([np.tile(xy, (LAYERS + 1, 1)), z.ravel()])
    elements = np.vstack([np.hstack([q + k * m, q + (k + 1) * m]) for k in range(LAYERS)])
    layer = np.repeat(np.arange(LAYERS + 1), m)
    x = nodes[:, 0]
    sets = {"bottom": np.flatnonzero(layer == 0), "top": np.flatnonzero(layer == LAYERS),
            "top_left": np.flatnonzero((layer == LAYERS) & (x <= 0.0)),
            "top_right": np.flatnonzero((layer == LAYERS) & (x >= 0.0))}
    mesh = HexMesh(nodes, elements, sets, source="hertz block")
    faces = {}
    for name in sets:
        f = mesh.faces(name)
        faces[name] = f[boundary_faces(mesh, f)]
    return HexMesh(nodes, elements, sets, faces, source="hertz_block.inp",
                   element_sets={"BLOCK": np.arange(len(elements))})


#: hertz_polar: plan half-width and height (mm), the central square's half-width (mm) and its
#: elements across, where the fine circular rings end (mm), their spacing (mm), the growth of
#: the rings beyond and of the layers, the rings over which the square turns into a circle.
POLAR = {"half": 3.0, "height": 3.0, "core": 0.3, "core_elements": 12, "fine_to": 0.9,
         "step": 0.045, "growth": 1.6, "layer_growth": 1.6, "blend": 6}


def polar_stations(core: float, fine_to: float, step: float, half: float, growth: float
                   ) -> np.ndarray:
    """Ring radii: ``step`` apart from ``core`` to ``fine_to``, then growing by ``growth``;
    the last is ``half``."""
    r = [core]
    while r[-1] < fine_to - 1e-9:
        r.append(r[-1] + step)
    h = step
    while True:
        h *= growth
        if r[-1] + h >= half - 0.3 * h:
            break
        r.append(r[-1] + h)
    r.append(half)
    return np.array(r)


def polar_plan(p: dict[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """The plan of :func:`hertz_polar`: nodes (m, 2) and counter-clockwise quadrilaterals. A
    ring's node on the ray through the square's perimeter point u is r ((1 - w) u + w u/|u|):
    w goes from 0 (a square, at the core) to 1 (a circle) over ``blend`` rings, and back to 0
    (the square outline) beyond ``fine_to``."""
    n = int(p["core_elements"])
    s = np.linspace(-1.0, 1.0, n + 1)
    s[n // 2] = 0.0
    gx, gy = np.meshgrid(s, s, indexing="ij")
    unit = np.stack([gx.ravel(), gy.ravel()], axis=1)
    ids = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    quads = [np.stack([ids[:-1, :-1].ravel(), ids[1:, :-1].ravel(), ids[1:, 1:].ravel(),
                       ids[:-1, 1:].ravel()], axis=1)]
    ring = np.concatenate([ids[:-1, 0], ids[n, :-1], ids[:0:-1, n], ids[0, :0:-1]])
    square = unit[ring]
    circle = square / np.linalg.norm(square, axis=1)[:, None]
    r = polar_stations(p["core"], p["fine_to"], p["step"], p["half"], p["growth"])
    w = np.minimum(1.0, np.arange(r.size) / p["blend"])
    beyond = r > p["fine_to"]
    t = (r - p["fine_to"]) / (p["half"] - p["fine_to"])
    w = np.where(beyond, np.clip(1.0 - t, 0.0, 1.0) ** 2, w)
    nodes = [p["core"] * unit]
    levels = [ring]
    count = len(unit)
    for j in range(1, r.size):
        nodes.append(np.round(r[j] * (square * (1.0 - w[j]) + circle * w[j]), 12))
        levels.append(count + np.arange(len(ring)))
        count += len(ring)
    lv = np.stack(levels)
    nxt = np.roll(np.arange(len(ring)), -1)
    for j in range(r.size - 1):
        quads.append(np.stack([lv[j], lv[j + 1], lv[j + 1][nxt], lv[j][nxt]], axis=1))
    xy = np.vstack(nodes)
    q = np.vstack(quads)
    pt = xy[q]
    area = 0.5 * np.sum(pt[:, :, 0] * np.roll(pt[:, :, 1], -1, axis=1)
                        - np.roll(pt[:, :, 0], -1, axis=1) * pt[:, :, 1], axis=1)
    q[area < 0] = q[area < 0][:, ::-1]
    return xy, q


def _block(xy: np.ndarray, q: np.ndarray, t: np.ndarray, height: float, source: str
           ) -> HexMesh:
    """Columns of hexahedra over the plan (xy, q) from the paraboloid to the top z = height,
    at the stations t (0 .. 1) of each column; the sets of the module docstring."""
    m = len(xy)
    layers = t.size - 1
    bottom = (xy[:, 0] ** 2 + xy[:, 1] ** 2) / (2 * RADIUS)
    z = bottom[None, :] + (height - bottom[None, :]) * t[:, None]
    z[-1] = height
    nodes = np.column_stack([np.tile(xy, (layers + 1, 1)), z.ravel()])
    elements = np.vstack([np.hstack([q + k * m, q + (k + 1) * m]) for k in range(layers)])
    layer = np.repeat(np.arange(layers + 1), m)
    x = nodes[:, 0]
    sets = {"bottom": np.flatnonzero(layer == 0), "top": np.flatnonzero(layer == layers),
            "top_left": np.flatnonzero((layer == layers) & (x <= 0.0)),
            "top_right": np.flatnonzero((layer == layers) & (x >= 0.0))}
    mesh = HexMesh(nodes, elements, sets, source=source)
    faces = {}
    for name in sets:
        f = mesh.faces(name)
        faces[name] = f[boundary_faces(mesh, f)]
    return HexMesh(nodes, elements, sets, faces, source=source,
                   element_sets={"BLOCK": np.arange(len(elements))})


def hertz_polar(p: dict[str, float] | None = None) -> HexMesh:
    """The block of ``hertz_polar.inp`` (module docstring; ``p`` overrides :data:`POLAR`)."""
    p = {**POLAR, **(p or {})}
    xy, q = polar_plan(p)
    z = [0.0]
    h = p["step"]
    while z[-1] + h < p["height"] - 0.3 * h:
        z.append(z[-1] + h)
        h *= p["layer_growth"]
    z.append(p["height"])
    return _block(xy, q, np.array(z) / p["height"], p["height"], "hertz_polar.inp")


def write(directory: Path = HERE) -> Path:
    """Write ``hertz_block.inp`` into ``directory``; returns its path."""
    return write_inp(hertz_block(), Path(directory) / "hertz_block.inp")


def write_polar(directory: Path = HERE) -> Path:
    """Write ``hertz_polar.inp`` into ``directory``; returns its path."""
    return write_inp(hertz_polar(), Path(directory) / "hertz_polar.inp")


if __name__ == "__main__":
    where = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE
    print(write(where))
    print(write_polar(where))
