"""Example clamp geometries that are not a box, and the built-in box, as :class:`HexMesh`.

The meshes are structured hexahedra on node planes (numbered slice by slice along x, as the
built-in box is, so the stiffness stays banded), with named node sets and element-face
surfaces for the roles. ``python -m microslip.fe.examples DIR`` writes the files that are in
the repository's ``examples/`` (:func:`write_examples`). Units: mm.

- :func:`cantilever_mesh`: a bar clamped over its first 50.8 mm on a rigid base, overhanging
  101.6 mm beyond the clamp (the paper's loads "originate from the portion of the cantilever
  structure that extends beyond the clamped zone");
- :func:`bolt_pad_mesh`: a stepped bracket, thick where it is clamped, thin in the arm, its
  clamping pressure on a square washer pad and its contact on part of the bottom face;
- :func:`post_on_plate_mesh`: a slightly rectangular post standing on a square foot flange,
  its two lowest bending modes (in x and in y) close, so that a force at 45 degrees puts the
  interface on an ellipse (issue 23, item 6);
- :func:`box_hexmesh`: the paper's box (the clamped zone of a
  :class:`~microslip.params.ClampParams`, mesh level or ``"NXxNYxNZ"``), the mesh the
  built-in solver (:mod:`microslip.fe.builtin.box`) and CalculiX run it on.
"""

from __future__ import annotations

import itertools
import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ParameterError
from ..meshlevels import level_axes, mesh_counts
from ..params import ClampParams, preset
from .hexmesh import HexMesh
from .meshcheck import boundary_faces
from .meshfile import write_inp

__all__ = [
    "BOLT_PAD",
    "CANTILEVER",
    "POST_ON_PLATE",
    "BoltPad",
    "PostOnPlate",
    "bolt_pad_mesh",
    "box_hexmesh",
    "box_inp",
    "cantilever_mesh",
    "grid_mesh",
    "on_block",
    "post_on_plate_mesh",
    "to_hex20",
    "write_examples",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
Where = Callable[[FloatArray, FloatArray, FloatArray], NDArray[np.bool_]]

#: The cantilever case (mm, MPa, N): clamped length, overhang, width, thickness; aluminium.
CANTILEVER = {"clamped_length": 50.8, "overhang": 101.6, "width": 25.4, "thickness": 6.35,
              "modulus": 70000.0, "poisson_ratio": 0.33, "friction": 0.5,
              "normal_force": 2000.0}


def grid_mesh(xs: ArrayLike, ys: ArrayLike, zs: ArrayLike,
              keep: Where | None = None, node_sets: dict[str, Where] | None = None,
              surfaces: Sequence[str] = (), source: str = "grid") -> HexMesh:
    """8-node hexahedra on the node planes ``xs``, ``ys``, ``zs`` (increasing, mm).

    ``keep(x, y, z)`` at element centres selects the elements (default: all); unused nodes are
    dropped. ``node_sets``: name -> predicate on node coordinates. The names in ``surfaces``
    also become element-face surfaces: the boundary faces whose corners are all in the set.
    Nodes are numbered slice by slice along x; elements list the corners of their low-z face
    counter-clockwise seen from +z, then the high-z face (CalculiX's C3D8 order).
    """
    x, y, z = (np.asarray(a, dtype=float) for a in (xs, ys, zs))
    for name, a in zip("xyz", (x, y, z), strict=True):
        if a.ndim != 1 or len(a) < 2 or not np.all(np.diff(a) > 0):
            raise ParameterError(f"the {name} node planes must increase, got {a.tolist()}")
    nx, ny, nz = len(x) - 1, len(y) - 1, len(z) - 1
    gx, gy, gz = np.meshgrid(x, y, z, indexing="ij")
    nodes = np.stack([gx.ravel(), gy.ravel(), gz.ravel()], axis=1)
    gi, gj, gk = (a.ravel() for a in np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz),
                                                 indexing="ij"))
    sj, si = nz + 1, (ny + 1) * (nz + 1)
    n0 = (gi * (ny + 1) + gj) * (nz + 1) + gk
    base = np.stack([n0, n0 + si, n0 + si + sj, n0 + sj], axis=1)
    elements = np.concatenate([base, base + 1], axis=1).astype(np.int64)
    if keep is not None:
        centre = nodes[elements].mean(axis=1)
        elements = elements[keep(centre[:, 0], centre[:, 1], centre[:, 2])]
    used = np.unique(elements)
    row = np.full(len(nodes), -1, dtype=np.int64)
    row[used] = np.arange(len(used))
    nodes, elements = nodes[used], row[elements]
    sets = {k: np.flatnonzero(f(nodes[:, 0], nodes[:, 1], nodes[:, 2]))
            for k, f in (node_sets or {}).items()}
    mesh = HexMesh(nodes, elements, sets, source=source)
    if not surfaces:
        return mesh
    faces = {}
    for name in surfaces:
        f = mesh.faces(name)
        faces[name] = f[boundary_faces(mesh, f)]
    return HexMesh(nodes, elements, sets, faces, source=source)


def _planes(stops: Sequence[float], size: float) -> FloatArray:
    """Node planes through every stop, segments split into ceil(length / size) equal parts."""
    out = [np.array([stops[0]], dtype=float)]
    for a, b in itertools.pairwise(stops):
        n = max(1, math.ceil((b - a) / size - 1e-9))
        seg = a + (b - a) * np.arange(1, n + 1) / n
        seg = np.round(seg, 10)
        seg[-1] = b
        out.append(seg)
    return np.concatenate(out)


def _near(a: FloatArray, v: float) -> NDArray[np.bool_]:
    return np.asarray(np.abs(a - v) <= 1e-9 * max(1.0, abs(v)), dtype=np.bool_)


def cantilever_mesh(nx: int = 24, ny: int = 6, nz: int = 2, quadratic: bool = False,
                    clamped_length: float = CANTILEVER["clamped_length"],
                    overhang: float = CANTILEVER["overhang"],
                    width: float = CANTILEVER["width"],
                    thickness: float = CANTILEVER["thickness"]) -> HexMesh:
    """A bar clamped over ``0 <= x <= clamped_length`` with a free overhang beyond (mm).

    ``nx`` elements along the whole length ``clamped_length + overhang`` (equal sizes; the
    clamp edge must fall on a node plane: with the default sizes nx a multiple of 3, e.g.
    24 -> 8 elements under the clamp and 16 in the overhang), ``ny`` across, ``nz`` through
    the thickness. Sets (node sets; the first three also surfaces): ``contact`` the bottom
    face z = 0 under the clamped length, ``clamp`` the top face z = t over it, ``tip`` the free
    end face x = clamped_length + overhang, ``response`` the tip end's nodes.

    >>> m = cantilever_mesh(6, 1, 1)
    >>> len(m.elements), len(m.faces("contact")), len(m.faces("tip"))
    (6, 2, 1)
    """
    total = round(clamped_length + overhang, 10)
    under = nx * clamped_length / total
    if isinstance(nx, bool) or not isinstance(nx, int) or nx < 2 or not math.isclose(
            under, round(under), abs_tol=1e-9) or round(under) in (0, nx):
        raise ParameterError(
            f"nx must put a node plane at the clamp edge x = {clamped_length:g} mm: "
            f"nx * {clamped_length:g} / {total:g} a whole number between 1 and nx - 1, "
            f"got nx = {nx!r}")
    n1 = round(under)
    xs = np.concatenate([np.linspace(0.0, clamped_length, n1 + 1),
                         np.linspace(clamped_length, total, nx - n1 + 1)[1:]])
    xs = np.round(xs, 10)  # planes to 1e-10 mm: 152.4, not 152.39999999999998, in the file
    xs[n1], xs[-1] = clamped_length, total

    def clamped(x: FloatArray) -> NDArray[np.bool_]:
        return np.asarray(x <= clamped_length * (1 + 1e-12), dtype=np.bool_)

    sets: dict[str, Where] = {
        "contact": lambda x, y, z: clamped(x) & _near(z, 0.0),
        "clamp": lambda x, y, z: clamped(x) & _near(z, thickness),
        "tip": lambda x, y, z: _near(x, total),
        "response": lambda x, y, z: _near(x, total),
    }
    mesh = grid_mesh(xs, np.round(np.linspace(0.0, width, ny + 1), 10),
                     np.round(np.linspace(0.0, thickness, nz + 1), 10),
                     node_sets=sets, surfaces=("contact", "clamp", "tip"),
                     source=f"cantilever {nx}x{ny}x{nz}")
    return to_hex20(mesh) if quadratic else mesh


@dataclass(frozen=True)
class BoltPad:
    """The bolt-pad bracket (mm): length, width, the thick part's length and thickness, the
    arm's thickness, the washer pad's side and centre, the contact's length from x = 0."""

    length: float = 80.0
    width: float = 40.0
    block_length: float = 40.0
    block_thickness: float = 12.0
    arm_thickness: float = 6.0
    pad: float = 16.0
    pad_x: float = 20.0
    pad_y: float = 20.0
    contact_length: float = 40.0


BOLT_PAD = BoltPad()


def on_block(bar: HexMesh, layers: int = 1, thickness: float = 6.35,
             wide: int = 0) -> HexMesh:
    """An assembly: the cantilever ``bar`` (:func:`cantilever_mesh`) standing on a block
    ``thickness`` (mm) thick, in ``layers`` element layers, under its contact face, with the
    same in-plane nodes (a conforming interface: coincident, distinct nodes); ``wide`` more
    elements of the block beyond the bar in +-y (the counter face larger than the face).
    Sets: the bar's, ``bar_int`` (its contact face), ``base_int`` (the block's top),
    ``base_fix`` (its bottom); element sets ``BAR``, ``BASE``."""
    c = bar.node_sets["contact"]
    xs, ys = np.unique(bar.nodes[c, 0]), np.unique(bar.nodes[c, 1])
    dy = ys[1] - ys[0]
    ys = np.concatenate([ys[0] - dy * np.arange(wide, 0, -1), ys,
                         ys[-1] + dy * np.arange(1, wide + 1)])
    b = grid_mesh(np.linspace(0.0, float(xs[-1] - xs[0]), xs.size),
                  np.linspace(0.0, float(ys[-1] - ys[0]), ys.size),
                  np.linspace(0.0, thickness, layers + 1))
    nodes_b = b.nodes + np.array([xs[0], ys[0], -thickness])
    n = len(bar.nodes)
    top = np.flatnonzero(np.isclose(nodes_b[:, 2], 0.0)) + n
    bottom = np.flatnonzero(np.isclose(nodes_b[:, 2], -thickness)) + n
    sets = {**bar.node_sets, "bar_int": c, "base_int": top, "base_fix": bottom}
    return HexMesh(np.vstack([bar.nodes, nodes_b]), np.vstack([bar.elements, b.elements + n]),
                   sets, source="cantilever on block",
                   element_sets={"BAR": np.arange(len(bar.elements)),
                                 "BASE": len(bar.elements) + np.arange(len(b.elements))})


def bolt_pad_mesh(size: float = 4.0, quadratic: bool = False) -> HexMesh:
    """A stepped bracket clamped by a bolt washer: elements of about ``size`` mm.

    The block ``0 <= x <= 40``, ``0 <= y <= 40``, ``0 <= z <= 12`` continues as an arm
    ``40 <= x <= 80`` of thickness 6 (its top steps down at x = 40). Sets: ``contact`` the
    bottom face z = 0 under the block (x <= 40; the arm's bottom is free), ``clamp`` a
    16 x 16 washer pad centred at (20, 20) on top of the block, ``end`` the arm's end face
    x = 80 (the loaded face), ``response`` its nodes. Node planes pass through every edge of
    the pad and the step.

    >>> m = bolt_pad_mesh(20.0)
    >>> len(m.elements), len(m.faces("clamp")), len(m.faces("contact"))
    (24, 1, 9)
    """
    g = BOLT_PAD
    if not (math.isfinite(size) and size > 0):
        raise ParameterError(f"element size must be > 0 mm, got {size!r}")
    half = 0.5 * g.pad
    cx, cy = g.pad_x, g.pad_y
    xs = _planes([0.0, cx - half, cx + half, g.block_length, g.length], size)
    ys = _planes([0.0, cy - half, cy + half, g.width], size)
    zs = _planes([0.0, g.arm_thickness, g.block_thickness], size)
    tol = 1e-9 * g.length

    def keep(x: FloatArray, y: FloatArray, z: FloatArray) -> NDArray[np.bool_]:
        return np.asarray((x < g.block_length) | (z < g.arm_thickness), dtype=np.bool_)

    def on_pad(x: FloatArray, y: FloatArray, z: FloatArray) -> NDArray[np.bool_]:
        return np.asarray(_near(z, g.block_thickness) & (np.abs(x - cx) <= half + tol)
                          & (np.abs(y - cy) <= half + tol), dtype=np.bool_)

    sets: dict[str, Where] = {
        "contact": lambda x, y, z: _near(z, 0.0) & (x <= g.contact_length + tol),
        "clamp": on_pad,
        "end": lambda x, y, z: _near(x, g.length),
        "response": lambda x, y, z: _near(x, g.length),
    }
    mesh = grid_mesh(xs, ys, zs, keep=keep, node_sets=sets,
                     surfaces=("contact", "clamp", "end"), source=f"bolt pad {size:g} mm")
    return to_hex20(mesh) if quadratic else mesh


@dataclass(frozen=True)
class PostOnPlate:
    """The post-on-plate example (mm): a square foot flange (side, thickness) centred on the
    origin of the x-y plane, a post of cross-section ``post_x`` x ``post_y`` and height
    ``post_height`` standing on its middle. ``post_x`` < ``post_y``: the post bends in x
    (about y) about 5 % below its bending in y."""

    flange: float = 30.0
    flange_thickness: float = 4.0
    post_x: float = 10.0
    post_y: float = 10.5
    post_height: float = 40.0


POST_ON_PLATE = PostOnPlate()


def post_on_plate_mesh(size: float = 2.5, section: float | None = None,
                       flange_size: float | None = None,
                       geometry: PostOnPlate = POST_ON_PLATE) -> HexMesh:
    """A slightly rectangular post standing on a square foot flange: elements of about
    ``size`` mm along the post's height and through the flange, ``section`` mm (default
    ``size``) across the post, ``flange_size`` mm (default ``2 size``) across the flange
    outside the post's footprint.

    The flange ``|x|, |y| <= flange / 2``, ``0 <= z <= flange_thickness`` carries the post
    ``|x| <= post_x / 2``, ``|y| <= post_y / 2`` up to ``z = flange_thickness +
    post_height``; node planes pass through the post's faces. Sets (node sets; the first
    three also surfaces): ``contact`` the flange's bottom face z = 0 (on the rigid base),
    ``clamp`` the flange's top face around the post (the clamping pressure), ``top`` the
    post's free end face (the forcing), ``response`` its nodes. The two lowest stuck modes
    are the post's bending in x and in y, about 5 % apart (10 x 10.5 mm): a force at 45
    degrees on ``top`` excites both.

    >>> m = post_on_plate_mesh(5.0, 5.0, 10.0)
    >>> len(m.faces("contact")), len(m.faces("clamp")), len(m.faces("top"))
    (20, 14, 6)
    """
    g = geometry
    for name, v in (("element size", size), ("section element size", section),
                    ("flange element size", flange_size)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise ParameterError(f"{name} must be > 0 mm, got {v!r}")
    if not (0 < g.post_x < g.flange and 0 < g.post_y < g.flange):
        raise ParameterError(f"the post ({g.post_x:g} x {g.post_y:g} mm) must fit on the "
                             f"flange ({g.flange:g} mm)")
    outer = 2.0 * size if flange_size is None else flange_size
    inner = size if section is None else section
    hf, hx, hy = 0.5 * g.flange, 0.5 * g.post_x, 0.5 * g.post_y

    def across(half: float) -> FloatArray:
        side = _planes([half, hf], outer)
        return np.concatenate([-side[::-1], _planes([-half, half], inner)[1:-1], side])

    xs, ys = across(hx), across(hy)
    top = g.flange_thickness + g.post_height
    zs = _planes([0.0, g.flange_thickness, top], size)
    tol = 1e-9 * g.flange

    def in_post(x: FloatArray, y: FloatArray) -> NDArray[np.bool_]:
        return np.asarray((np.abs(x) < hx - tol) & (np.abs(y) < hy - tol), dtype=np.bool_)

    def keep(x: FloatArray, y: FloatArray, z: FloatArray) -> NDArray[np.bool_]:
        return np.asarray((z < g.flange_thickness) | in_post(x, y), dtype=np.bool_)

    sets: dict[str, Where] = {
        "contact": lambda x, y, z: _near(z, 0.0),
        "clamp": lambda x, y, z: _near(z, g.flange_thickness) & ~in_post(x, y),
        "top": lambda x, y, z: _near(z, top),
        "response": lambda x, y, z: _near(z, top),
    }
    return grid_mesh(xs, ys, zs, keep=keep, node_sets=sets,
                     surfaces=("contact", "clamp", "top"),
                     source=f"post on plate {size:g}/{inner:g}/{outer:g} mm")


#: Corner pairs of the 12 edges of a C3D20, in the order of its nodes 9-20.
HEX20_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
               (0, 4), (1, 5), (2, 6), (3, 7))


def to_hex20(mesh: HexMesh) -> HexMesh:
    """The same mesh with 20-node hexahedra: a node at the middle of every edge.

    A mid-edge node joins a node set when both ends of its edge are in it; surfaces keep their
    faces. The new nodes follow the corners (numbered edge by edge, element by element).
    """
    if mesh.nodes_per_element != 8:
        raise ParameterError(f"{mesh.source}: to_hex20 needs 8-node hexahedra")
    pairs = mesh.elements[:, np.asarray(HEX20_EDGES)]  # (e, 12, 2)
    keys = np.sort(pairs.reshape(-1, 2), axis=1)
    unique, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)  # number the edges in the order they are met
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    n = len(mesh.nodes)
    mids = n + rank[inverse.reshape(-1)].reshape(-1, 12)
    edges = unique[order]
    nodes = np.vstack([mesh.nodes, 0.5 * (mesh.nodes[edges[:, 0]] + mesh.nodes[edges[:, 1]])])
    sets = {}
    for name, rows in mesh.node_sets.items():
        inset = np.zeros(n, dtype=np.bool_)
        inset[rows] = True
        extra = n + np.flatnonzero(inset[edges[:, 0]] & inset[edges[:, 1]])
        sets[name] = np.concatenate([rows, extra])
    return HexMesh(nodes, np.concatenate([mesh.elements, mids], axis=1), sets,
                   dict(mesh.surfaces), source=mesh.source + " hex20")


#: Upper bound on the nodes of a box mesh (memory guard: about 1e6 dofs).
MAX_BOX_NODES = 350_000


def box_hexmesh(params: ClampParams, spec: Any = "coarse") -> HexMesh:
    """The paper's clamped zone L x w x t of ``params`` as a :class:`HexMesh`: a mesh level or
    ``"NXxNYxNZ"`` (:mod:`microslip.meshlevels`: counts and node planes from the geometry,
    graded on a squat body, the same as CalculiX's) or counts ``(nx, ny, nz)`` (uniform).

    Node ``(i, j, k)`` (along x, y, z) is number ``(i (ny + 1) + j) (nz + 1) + k``: slice by
    slice along the bar, so the stiffness is a band whose width does not grow with nx.
    Node sets: ``contact`` (bottom, z = 0), ``clamp`` (top, z = t), ``tip`` (end face x = L)
    and, when nx is even, ``centre`` (the mid-length node plane i = nx / 2, inside the body);
    the first three are also surfaces.

    >>> m = box_hexmesh(preset("table1"), "4x2x1")
    >>> len(m.nodes), sorted(m.node_sets)
    (30, ['centre', 'clamp', 'contact', 'tip'])
    """
    dims = (params.length, params.width, params.thickness)
    (nx, ny, nz), graded = mesh_counts(params, spec)
    count = (nx + 1) * (ny + 1) * (nz + 1)
    if count > MAX_BOX_NODES:
        raise ParameterError(f"mesh {nx}x{ny}x{nz} has {count} nodes; at most {MAX_BOX_NODES}")
    x, y, z = level_axes(*dims, (nx, ny, nz), graded)
    gx, gy, gz = np.meshgrid(x, y, z, indexing="ij")
    nodes = np.stack([gx.ravel(), gy.ravel(), gz.ravel()], axis=1)
    gi, gj, gk = (a.ravel() for a in np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz),
                                                 indexing="ij"))
    sj, si = nz + 1, (ny + 1) * (nz + 1)
    n0 = (gi * (ny + 1) + gj) * (nz + 1) + gk
    base = np.stack([n0, n0 + si, n0 + si + sj, n0 + sj], axis=1)
    elements = np.concatenate([base, base + 1], axis=1).astype(np.int64)

    def plane(i: Any, j: Any, k: Any) -> NDArray[np.int64]:
        a, b, c = np.meshgrid(i, j, k, indexing="ij")
        return np.asarray(((a * (ny + 1) + b) * (nz + 1) + c).ravel(), dtype=np.int64)

    ii, jj, kk = np.arange(nx + 1), np.arange(ny + 1), np.arange(nz + 1)
    sets = {"contact": plane(ii, jj, kk[:1]), "clamp": plane(ii, jj, kk[-1:]),
            "tip": plane(ii[-1:], jj, kk)}
    if nx % 2 == 0:
        sets["centre"] = plane(ii[nx // 2: nx // 2 + 1], jj, kk)
    source = f"box {nx}x{ny}x{nz}"
    mesh = HexMesh(nodes, elements, sets, source=source)
    surfaces = {k: mesh.faces(k) for k in ("contact", "clamp", "tip")}
    return HexMesh(nodes, elements, sets, surfaces, source=source)


def box_inp(params: ClampParams, spec: Any, path: str | Path) -> Path:
    """Write :func:`box_hexmesh` as a CalculiX ``.inp`` mesh file; returns the path."""
    return write_inp(box_hexmesh(params, spec), path)


#: The files of ``examples/``: name -> the mesh.
EXAMPLES: dict[str, Callable[[], HexMesh]] = {
    "cantilever.inp": lambda: cantilever_mesh(24, 6, 2),
    "cantilever_hex20.inp": lambda: cantilever_mesh(24, 6, 2, quadratic=True),
    "bolt_pad.inp": lambda: bolt_pad_mesh(4.0),
    "post_on_plate.inp": lambda: post_on_plate_mesh(2.5, 5.0, 5.0),
    "box_table1_24x4x1.inp": lambda: box_hexmesh(preset("table1"), "24x4x1"),
}


def write_examples(directory: str | Path) -> list[Path]:
    """Write every file of :data:`EXAMPLES` into ``directory``; returns their paths."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    out = []
    for name, make in EXAMPLES.items():
        mesh = make()
        out.append(write_inp(HexMesh(mesh.nodes, mesh.elements, mesh.node_sets, mesh.surfaces,
                                     source=name), d / name))
    return out


if __name__ == "__main__":  # pragma: no cover - the generator of examples/
    for p in write_examples(sys.argv[1] if len(sys.argv) > 1 else "examples"):
        print(p)
