"""Read the user's hexahedral mesh from a file, and write a :class:`HexMesh` as a CalculiX deck.

:func:`read_mesh` picks the reader by the file's suffix (:data:`READERS`): ``.inp``
(CalculiX/Abaqus) by the small parser of :mod:`~microslip.fe.meshinp`, every other format
meshio reads (gmsh ``.msh``, ``.vtu``, ``.med``, ...) through meshio (imported only here).
:func:`write_inp` writes nodes, elements (C3D8I for 8-node, C3D20R for 20-node hexahedra),
node sets and element-face surfaces, so that ``read_mesh`` gives the same mesh back.

How sets are named, by format
-----------------------------
``.inp``
    ``*NSET, NSET=name`` gives the node set ``name``; ``*SURFACE, NAME=name`` (TYPE=ELEMENT)
    the surface ``name`` (``*SURFACE, TYPE=NODE``: the node set ``name``). An element set of
    2-D elements (``*ELEMENT, TYPE=CPS4/S4/..., ELSET=name``, as gmsh exports a physical
    surface) gives the node set ``name`` of their nodes and, when every one of them is a
    quadrilateral lying on a hexahedron's face, also the surface ``name``.
meshio formats
    ``point_sets`` give node sets of the same name. Cell sets and gmsh physical groups give
    the node set of their cells' nodes, named as the group (an unnamed gmsh group: its
    dimension and number, ``surface3``, ``volume1``); a group of quadrilaterals lying on
    hexahedron faces also gives the surface of that name. Element numbers in messages count
    the hexahedra in the file's order from 1.

Nodes used by no hexahedron are dropped (a stray reference node would make the stiffness
singular); node sets lose them too. Units as in the file: mm.
"""

from __future__ import annotations

import contextlib
import io
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from .hexmesh import HEX_FACES, HexMesh
from .meshinp import HEX_HINT, parse_inp

__all__ = ["HEX_HINT", "READERS", "read_inp", "read_mesh", "read_meshio", "write_inp"]

IntArray = NDArray[np.int64]

#: meshio cell types read as hexahedra, and how many of their nodes are the C3D8/C3D20 ones
#: (a 27-node hexahedron drops its face and body centres).
_MESHIO_HEX = {"hexahedron": 8, "hexahedron20": 20, "hexahedron27": 20}
#: Solid cells that are not hexahedra: refused.
_MESHIO_OTHER_SOLIDS = {"tetra": "tetrahedra", "tetra10": "tetrahedra", "wedge": "wedges",
                        "wedge15": "wedges", "pyramid": "pyramids", "pyramid13": "pyramids"}
_QUADS = {"quad", "quad8", "quad9"}
#: Dimension of meshio's lower-dimensional cell types (any other: a solid, 3).
_CELL_DIM = {"vertex": 0, "line": 1, "line3": 1, "triangle": 2, "triangle6": 2, "quad": 2,
             "quad8": 2, "quad9": 2}
_GMSH_DIM = {0: "point", 1: "curve", 2: "surface", 3: "volume"}


def read_mesh(path: str | Path) -> HexMesh:
    """The hexahedral mesh in ``path``, by the reader of its suffix (:data:`READERS`).

    Raises :class:`~microslip.errors.ParameterError` (one line naming the file) when the
    file is missing or unreadable, or holds no hexahedra (with :data:`HEX_HINT`).
    """
    p = Path(path)
    if not p.is_file():
        raise ParameterError(f"{path}: no such mesh file")
    reader = READERS.get(p.suffix.lower(), read_meshio)
    return reader(p)


def read_meshio(path: str | Path) -> HexMesh:
    """Hexahedra and named sets of any file meshio reads (gmsh ``.msh``, ``.vtu``, ...)."""
    import meshio

    src = str(path)
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # meshio's gmsh reader prints
            m = meshio.read(path)
    except (meshio.ReadError, OSError, ValueError, KeyError, IndexError) as err:
        raise ParameterError(f"{src}: not a mesh meshio can read ({err})") from None
    others = sorted({_MESHIO_OTHER_SOLIDS[b.type] for b in m.cells
                     if b.type in _MESHIO_OTHER_SOLIDS and len(b.data)})
    if others:
        raise ParameterError(f"{src}: the mesh has {' and '.join(others)}; {HEX_HINT}")
    blocks = [i for i, b in enumerate(m.cells) if b.type in _MESHIO_HEX and len(b.data)]
    if not blocks:
        raise ParameterError(f"{src}: no hexahedra in the mesh; {HEX_HINT}")
    sizes = {_MESHIO_HEX[m.cells[i].type] for i in blocks}
    if len(sizes) > 1:
        raise ParameterError(f"{src}: the mesh mixes 8- and 20-node hexahedra; use one kind")
    size = sizes.pop()  # one block per gmsh volume: every block cut to the same size
    elements = np.concatenate([np.asarray(m.cells[i].data)[:, :size] for i in blocks])
    groups = _meshio_groups(m)
    node_sets = {name: np.asarray(v, dtype=np.int64) for name, v in m.point_sets.items()}
    dims = {name: max(_CELL_DIM.get(t, 3) for t, _ in cells) for name, cells in groups.items()}
    mesh = assemble(src, np.asarray(m.points, dtype=float), elements.astype(np.int64),
                    node_sets, groups, node_ids=None, element_ids=None)
    return HexMesh(mesh.nodes, mesh.elements, mesh.node_sets, mesh.surfaces, source=src,
                   set_dims=dims, element_sets=_volume_sets(elements, groups, size))


def _volume_sets(elements: IntArray, groups: Mapping[str, list[tuple[str, IntArray]]],
                 size: int) -> dict[str, IntArray]:
    """The element rows of every group of hexahedra (gmsh volume groups)."""
    key = {tuple(sorted(r)): i for i, r in enumerate(elements[:, :8].tolist())}
    out = {}
    for name, cells in groups.items():
        rows = [key.get(tuple(sorted(r[:8]))) for t, c in cells if t in _MESHIO_HEX
                for r in np.asarray(c)[:, :size].tolist()]
        found = [r for r in rows if r is not None]
        if found:
            out[name] = np.array(found, dtype=np.int64)
    return out


def _meshio_groups(m: Any) -> dict[str, list[tuple[str, IntArray]]]:
    """Named groups of cells, each a list of (cell type, connectivity rows)."""
    groups: dict[str, list[tuple[str, IntArray]]] = {}
    for name, per_block in m.cell_sets.items():
        if name.startswith("gmsh:"):
            continue
        for block, idx in zip(m.cells, per_block, strict=False):
            if idx is not None and len(idx):
                groups.setdefault(name, []).append(
                    (block.type, np.asarray(block.data)[np.asarray(idx, dtype=np.int64)]))
    tags = m.cell_data.get("gmsh:physical")
    if tags is None:
        return groups
    names = {(int(v[1]), int(v[0])): k for k, v in m.field_data.items() if len(v) >= 2}
    for block, phys in zip(m.cells, tags, strict=False):
        dim = block.dim
        for tag in np.unique(phys):
            name = names.get((dim, int(tag)), f"{_GMSH_DIM.get(dim, 'group')}{int(tag)}")
            if name in m.cell_sets:
                continue  # already read from meshio's cell sets (gmsh 4.1)
            groups.setdefault(name, []).append(
                (block.type, np.asarray(block.data)[np.asarray(phys) == tag]))
    return groups


def assemble(src: str, points: NDArray[np.float64], elements: IntArray,
             node_sets: Mapping[str, IntArray],
             groups: Mapping[str, list[tuple[str, IntArray]]],
             node_ids: IntArray | None, element_ids: IntArray | None,
             surfaces: Mapping[str, IntArray] | None = None,
             element_sets: Mapping[str, IntArray] | None = None) -> HexMesh:
    """A :class:`HexMesh` from raw rows (0-based into ``points``), dropping unused nodes.

    ``groups``: named groups of lower-dimensional cells (type, connectivity rows) that become
    node sets, and surfaces when every cell is a quadrilateral on a hexahedron face.
    """
    sets = {k: np.asarray(v, dtype=np.int64) for k, v in node_sets.items()}
    faces = dict(surfaces or {})
    lookup: dict[tuple[int, ...], tuple[int, int]] | None = None
    for name, cells in groups.items():
        nodes = np.unique(np.concatenate([c.ravel() for _, c in cells]))
        sets[name] = np.union1d(sets.get(name, np.zeros(0, np.int64)), nodes)
        if name in faces or not all(t in _QUADS for t, _ in cells):
            continue
        quads = np.concatenate([c[:, :4] for _, c in cells])
        lookup = _face_lookup(elements) if lookup is None else lookup
        found = [lookup.get(tuple(sorted(q.tolist()))) for q in quads]
        if all(f is not None for f in found):
            faces[name] = np.array(found, dtype=np.int64).reshape(-1, 2)
    used = np.unique(elements)
    row = np.full(len(points), -1, dtype=np.int64)
    row[used] = np.arange(len(used))
    kept = {k: row[v[(v >= 0) & (v < len(points))]] for k, v in sets.items()}
    return HexMesh(points[used], row[elements], {k: v[v >= 0] for k, v in kept.items()},
                   faces, source=src,
                   node_ids=None if node_ids is None else node_ids[used],
                   element_ids=element_ids, element_sets=dict(element_sets or {}))


def _face_lookup(elements: IntArray) -> dict[tuple[int, ...], tuple[int, int]]:
    """(sorted corner nodes) -> (element, face) of every hexahedron face."""
    out: dict[tuple[int, ...], tuple[int, int]] = {}
    for f, idx in enumerate(HEX_FACES):
        for e, corners in enumerate(elements[:, list(idx)].tolist()):
            out.setdefault(tuple(sorted(corners)), (e, f))
    return out


#: Element type written for each element size.
INP_TYPES = {8: "C3D8I", 20: "C3D20R"}


def write_inp(mesh: HexMesh, path: str | Path) -> Path:
    """Write ``mesh`` as a CalculiX/Abaqus ``.inp`` mesh (nodes, elements, sets, surfaces).

    Coordinates are written with the shortest text that reads back to the same float, and the
    file's node and element numbers are kept, so ``read_mesh(write_inp(mesh, p))`` gives
    ``mesh`` back exactly. The file is written whole or not at all. Returns the path.
    """
    p = Path(path)
    for name in mesh.set_names():
        if not name or any(c in name for c in ",=*\n\t ") or name.startswith(("-", ".")):
            raise ParameterError(f"set name {name!r} cannot be written to a .inp file "
                                 "(no spaces, commas, '=' or '*')")
    nid = np.arange(1, len(mesh.nodes) + 1) if mesh.node_ids is None else mesh.node_ids
    eid = (np.arange(1, len(mesh.elements) + 1) if mesh.element_ids is None
           else mesh.element_ids)
    out = [f"** {Path(mesh.source).name}: {len(mesh.nodes)} nodes, {len(mesh.elements)} "
           f"{mesh.nodes_per_element}-node hexahedra, written by microslip (units mm)",
           "*NODE"]
    out += [f"{i}, {x!r}, {y!r}, {z!r}" for i, (x, y, z)
            in zip(nid.tolist(), mesh.nodes.tolist(), strict=True)]
    out.append(f"*ELEMENT, TYPE={INP_TYPES[mesh.nodes_per_element]}, ELSET=EALL")
    for i, conn in zip(eid.tolist(), nid[mesh.elements].tolist(), strict=True):
        ids = [str(i), *map(str, conn)]
        out += [", ".join(ids[k:k + 16]) + ("," if k + 16 < len(ids) else "")
                for k in range(0, len(ids), 16)]
    for name, rows in mesh.node_sets.items():
        out.append(f"*NSET, NSET={name}")
        ids = [str(i) for i in nid[rows].tolist()]
        out += [", ".join(ids[k:k + 16]) for k in range(0, len(ids), 16)]
    for name, rows in mesh.element_sets.items():
        out.append(f"*ELSET, ELSET={name}")
        ids = [str(i) for i in eid[rows].tolist()]
        out += [", ".join(ids[k:k + 16]) for k in range(0, len(ids), 16)]
    for name, faces in mesh.surfaces.items():
        out.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        out += [f"{eid[e]}, S{f + 1}" for e, f in faces.tolist()]
    tmp = p.with_name(p.name + ".part")
    tmp.write_text("\n".join(out) + "\n", encoding="ascii")
    tmp.replace(p)
    return p


def read_inp(path: str | Path) -> HexMesh:
    """Hexahedra, node sets and surfaces of a CalculiX/Abaqus ``.inp`` file
    (:func:`~microslip.fe.meshinp.parse_inp`)."""
    d = parse_inp(path)
    return assemble(str(path), d.points, d.elements, d.node_sets, d.groups, d.node_ids,
                    d.element_ids, d.surfaces, d.element_sets)


#: Readers by file suffix; any other suffix goes to meshio.
READERS: dict[str, Callable[[Path], HexMesh]] = {".inp": read_inp}
