"""Write the two-body test assemblies ``cantilever_on_block.inp`` and
``cantilever_on_block_wide.inp`` (numpy and microslip only; run with the checkout's Python:
``PYTHONPATH=src .venv/bin/python tests/data/meshes/make_assemblies.py``).

The examples' cantilever bar (:func:`microslip.fe.examples.cantilever_mesh`, 24 x 6 x 2
C3D8I, 152.4 x 25.4 x 6.35 mm, 0 <= z <= 6.35) stands on a deformable base block under its
clamped length. The block is meshed on its own (2 elements through its thickness 6.35 mm,
-6.35 <= z <= 0); its top face's nodes are at the places of the bar's contact face's nodes
(the same node planes), with other numbers: a conforming interface, not a welded one.

``cantilever_on_block.inp``
    the block under 0 <= x <= 50.8, 0 <= y <= 25.4 (8 x 6 x 2 elements): its top face and
    the bar's contact face are the same 48 faces, node for node.
``cantilever_on_block_wide.inp``
    the block wider than the bar: one element beyond x = 0 (to x = -6.35) and two beyond the
    bar in -y and +y (to y = -8.4667 and 33.8667), 9 x 10 x 2 elements: a counter face
    larger than the face (every node of ``bar_int`` has a partner, the block's other top
    nodes have none). The block does not reach past the clamp edge x = 50.8: there the bar's
    free bottom would lie on the block's top, with coincident nodes and no contact.

Sets (node sets; all but ``response`` also element-face surfaces):

=============  ===============================================================
``contact``    the bar's bottom under the clamped length, z = 0, x <= 50.8 (as in
               ``examples/cantilever.inp``)
``clamp``      the bar's top over the clamped length, z = 6.35 (the clamping pressure)
``tip``        the bar's free end face x = 152.4 (the load set)
``response``   the tip's nodes (node set only)
``bar_int``    the bar's interface face: the same faces as ``contact``
``base_int``   the block's top face z = 0 (the counter face of ``bar_int``)
``base_fix``   the block's bottom face z = -6.35 (the support)
=============  ===============================================================

Element sets: ``BAR`` (the bar's 288 elements, numbered first) and ``BASE`` (the block's).
Units: mm.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from microslip.fe.examples import cantilever_mesh, grid_mesh
from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshfile import write_inp

HERE = Path(__file__).resolve().parent
#: The bar's clamped length and thickness (mm); the block is as thick as the bar.
CLAMPED, THICKNESS = 50.8, 6.35
#: Files written: name -> (extra elements beyond the bar in -x, in -y and +y).
FILES = {"cantilever_on_block.inp": (0, 0), "cantilever_on_block_wide.inp": (1, 2)}


def _extend(planes: np.ndarray, before: int, after: int) -> np.ndarray:
    """The node planes with ``before`` / ``after`` more at the first / last plane's spacing."""
    lo, hi = planes[1] - planes[0], planes[-1] - planes[-2]
    head = planes[0] - lo * np.arange(before, 0, -1)
    tail = planes[-1] + hi * np.arange(1, after + 1)
    return np.round(np.concatenate([head, planes, tail]), 10)


def cantilever_on_block(extra_x: int = 0, extra_y: int = 0) -> HexMesh:
    """The bar on its base block; the block ``extra_x`` elements longer in -x and ``extra_y``
    elements wider on each side in y than the bar's clamped length."""
    bar = cantilever_mesh(24, 6, 2)
    xb = np.unique(bar.nodes[:, 0])
    yb = np.unique(bar.nodes[:, 1])
    xs = _extend(xb[xb <= CLAMPED + 1e-9], extra_x, 0)
    ys = _extend(yb, extra_y, extra_y)
    zs = np.round(np.linspace(-THICKNESS, 0.0, 3), 10)
    tol = 1e-9 * CLAMPED
    block = grid_mesh(xs, ys, zs, node_sets={
        "base_int": lambda x, y, z: np.abs(z) <= tol,
        "base_fix": lambda x, y, z: np.abs(z + THICKNESS) <= tol},
        surfaces=("base_int", "base_fix"))
    n, e = len(bar.nodes), len(bar.elements)
    nodes = np.vstack([bar.nodes, block.nodes])
    elements = np.vstack([bar.elements, block.elements + n])
    node_sets = {**bar.node_sets, "bar_int": bar.node_sets["contact"],
                 **{k: v + n for k, v in block.node_sets.items()}}
    surfaces = {**bar.surfaces, "bar_int": bar.surfaces["contact"],
                **{k: v + np.array([e, 0]) for k, v in block.surfaces.items()}}
    element_sets = {"BAR": np.arange(e), "BASE": np.arange(e, len(elements))}
    return HexMesh(nodes, elements, node_sets, surfaces, source="cantilever on block",
                   element_sets=element_sets)


def write_all(directory: Path = HERE) -> list[Path]:
    """Write every file of :data:`FILES` into ``directory``; returns their paths."""
    out = []
    for name, (ex, ey) in FILES.items():
        m = cantilever_on_block(ex, ey)
        out.append(write_inp(HexMesh(m.nodes, m.elements, m.node_sets, m.surfaces,
                                     source=name, element_sets=m.element_sets),
                             Path(directory) / name))
    return out


if __name__ == "__main__":
    for p in write_all(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE):
        print(p)
