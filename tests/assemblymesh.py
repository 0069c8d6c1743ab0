"""A two-body mesh for the assembly tests: the examples' cantilever bar (clamped length
50.8 mm, overhang 101.6 mm, 25.4 x 6.35 mm) standing on a base block under its clamped
length, with a conforming interface (coincident, distinct nodes). Units: mm.

Sets: ``bar_int`` (the bar's bottom under the clamp) and ``base_int`` (the block's top),
``clamp`` (the bar's top over the clamped length), ``base_fix`` (the block's bottom),
``tip`` (the bar's free end); element sets ``BAR`` and ``BASE``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from microslip.fe.examples import grid_mesh
from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshfile import write_inp

CLAMPED, LENGTH, WIDTH, THICK, BASE = 50.8, 152.4, 25.4, 6.35, 10.0


def _near(a: np.ndarray, v: float) -> np.ndarray:
    return np.abs(a - v) <= 1e-9 * max(1.0, abs(v))


def bar_on_base(scale: float = 1.0, share_nodes: bool = False) -> HexMesh:
    """The bar (6 x 2 x 1 elements along, across, through) on the block (2 x 2 x 1) with
    coincident interface nodes; ``scale`` multiplies the coordinates (1e-3: a mesh in
    metres); ``share_nodes`` merges the interface nodes (one body, glued)."""
    xs = np.array([0.0, 25.4, 50.8, 76.2, 101.6, 127.0, 152.4])
    ys = np.array([0.0, 12.7, 25.4])
    bar = grid_mesh(xs, ys, [0.0, THICK], node_sets={
        "bar_int": lambda x, y, z: (x <= CLAMPED + 1e-9) & _near(z, 0.0),
        "clamp": lambda x, y, z: (x <= CLAMPED + 1e-9) & _near(z, THICK),
        "tip": lambda x, y, z: _near(x, LENGTH)}, surfaces=("bar_int", "clamp", "tip"))
    base = grid_mesh(xs[:3], ys, [-BASE, 0.0], node_sets={
        "base_int": lambda x, y, z: _near(z, 0.0),
        "base_fix": lambda x, y, z: _near(z, -BASE)}, surfaces=("base_int", "base_fix"))
    n = len(bar.nodes)
    nodes = np.vstack([bar.nodes, base.nodes])
    elements = np.vstack([bar.elements, base.elements + n])
    if share_nodes:
        same = {tuple(np.round(p, 9)): i for i, p in enumerate(bar.nodes)}
        remap = np.array([same.get(tuple(np.round(p, 9)), n + i)
                          for i, p in enumerate(base.nodes)])
        elements = np.vstack([bar.elements, remap[base.elements]])
        keep = np.unique(elements)
        row = np.full(len(nodes), -1)
        row[keep] = np.arange(len(keep))
        nodes, elements = nodes[keep], row[elements]
        node_sets = {k: np.unique(row[v]) for k, v in bar.node_sets.items()}
        node_sets.update({k: np.unique(row[remap[v]]) for k, v in base.node_sets.items()})
        surfaces = {}
    else:
        node_sets = {**bar.node_sets, **{k: v + n for k, v in base.node_sets.items()}}
        m = len(bar.elements)
        surfaces = {**bar.surfaces,
                    **{k: v + np.array([m, 0]) for k, v in base.surfaces.items()}}
    esets = {"BAR": np.arange(len(bar.elements)),
             "BASE": len(bar.elements) + np.arange(len(base.elements))}
    return HexMesh(nodes * scale, elements, node_sets, surfaces, source="bar_on_base",
                   element_sets=esets)


def write_bar_on_base(path: Path, **kw: object) -> str:
    """:func:`bar_on_base` written as a .inp file; returns its path as text."""
    write_inp(bar_on_base(**kw), path)  # type: ignore[arg-type]
    return str(path)
