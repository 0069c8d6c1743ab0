"""A small parser of CalculiX/Abaqus ``.inp`` meshes: nodes, hexahedra, sets and surfaces.

Read: ``*NODE``; ``*ELEMENT`` with ``TYPE=`` C3D8, C3D8I, C3D8R, C3D20, C3D20R (hexahedra) and
``ELSET=``; 2-D and 1-D elements (CPS4, S4, ... as gmsh exports physical surfaces) only for
the node sets of their element sets; ``*NSET`` and ``*ELSET`` (with ``GENERATE``, and names of
sets defined before); ``*SURFACE, TYPE=ELEMENT`` with lines ``ELSET, Sk`` or
``element, Sk`` (k = 1..6), ``TYPE=NODE`` as a node set. Keywords and parameters are
case-insensitive, ``**`` starts a comment, a data line ending in a comma continues on the
next, node and element numbers may have gaps (they become 0-based rows in the file's order).
Every other keyword (materials, steps, ...) is skipped with its data lines. Refused with one
line naming the file and the line: ``*INCLUDE``, several ``*INSTANCE``, tetrahedra and wedges.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError

__all__ = ["HEX_HINT", "HEX_TYPES", "InpData", "parse_inp"]

IntArray = NDArray[np.int64]
FloatArray = NDArray[np.float64]

#: How to make hexahedra, for the message that refuses a mesh without them.
HEX_HINT = ("microslip needs an all-hexahedral mesh (8- or 20-node); in gmsh set "
            "'Mesh.RecombineAll = 1; Mesh.Recombine3DAll = 1;', or extrude with "
            "'Layers{n}; Recombine;', or mesh transfinite volumes with 'Recombine Volume'")

#: Hexahedral element types and their node counts.
HEX_TYPES = {"C3D8": 8, "C3D8I": 8, "C3D8R": 8, "C3D20": 20, "C3D20R": 20}
#: Solid element types that are refused (prefix -> what they are).
_REFUSED = {"C3D4": "tetrahedra", "C3D10": "tetrahedra", "C3D6": "wedges", "C3D15": "wedges"}
#: 2-D element types read as quadrilaterals (for surfaces), by their first letters.
_QUAD_PREFIXES = ("CPS4", "CPE4", "CAX4", "S4", "M3D4", "SFM3D4", "CPS8", "CPE8", "CAX8",
                  "S8", "M3D8", "SFM3D8", "S9", "M3D9", "CPS9", "CPE9")


@dataclass
class InpData:
    """What a ``.inp`` file holds, as 0-based rows (elements: the hexahedra only)."""

    points: FloatArray
    elements: IntArray
    node_ids: IntArray
    element_ids: IntArray
    node_sets: dict[str, IntArray] = field(default_factory=dict)
    surfaces: dict[str, IntArray] = field(default_factory=dict)
    groups: dict[str, list[tuple[str, IntArray]]] = field(default_factory=dict)
    element_sets: dict[str, IntArray] = field(default_factory=dict)


@dataclass
class _Block:
    keyword: str
    params: dict[str, str]
    line: int
    data: list[tuple[int, list[str]]]


def _blocks(path: Path) -> list[_Block]:
    """Keyword blocks: the keyword, its parameters and its data lines split at commas."""
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as err:
        raise ParameterError(f"{path}: cannot read ({err.strerror})") from None
    blocks: list[_Block] = []
    pending: list[str] = []
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            if pending:
                blocks[-1].data.append((n - 1, pending))
                pending = []
            words = [w.strip() for w in line[1:].split(",")]
            params = {}
            for w in words[1:]:
                if w:
                    key, _, value = w.partition("=")
                    params[key.strip().upper()] = value.strip()
            blocks.append(_Block(" ".join(words[0].upper().split()), params, n, []))
            continue
        if not blocks:
            raise ParameterError(f"{path}, line {n}: data before the first keyword")
        continued = line.endswith(",")
        pending += [w.strip() for w in line.rstrip(",").split(",")]
        if not continued:
            blocks[-1].data.append((n, pending))
            pending = []
    if pending:
        blocks[-1].data.append((len(text.splitlines()), pending))
    return blocks


def _ints(path: Path, n: int, words: list[str]) -> list[int]:
    try:
        return [int(w) for w in words if w]
    except ValueError:
        raise ParameterError(f"{path}, line {n}: expected whole numbers, got "
                             f"{', '.join(words)!r}") from None


def _members(path: Path, block: _Block, sets: dict[str, list[int]], what: str) -> list[int]:
    """Ids of a *NSET/*ELSET block: numbers, GENERATE ranges, or names of earlier sets."""
    out: list[int] = []
    generate = "GENERATE" in block.params
    for n, words in block.data:
        if generate:
            v = _ints(path, n, words)
            if len(v) not in (2, 3) or (len(v) == 3 and v[2] <= 0) or v[1] < v[0]:
                raise ParameterError(f"{path}, line {n}: GENERATE needs first, last[, step] "
                                     f"with first <= last and step > 0, got {words}")
            out += list(range(v[0], v[1] + 1, v[2] if len(v) == 3 else 1))
            continue
        for w in (w for w in words if w):
            if w.lstrip("-").isdigit():
                out.append(int(w))
            elif w in sets:
                out += sets[w]
            else:
                raise ParameterError(f"{path}, line {n}: {w!r} is neither a {what} number nor "
                                     f"a {what} set defined above")
    return out


def _name(path: Path, block: _Block, key: str) -> str:
    name = block.params.get(key, "")
    if not name:
        raise ParameterError(f"{path}, line {block.line}: *{block.keyword} needs {key}=")
    return name


def parse_inp(path: str | Path) -> InpData:
    """Parse a CalculiX/Abaqus ``.inp`` mesh (see the module docstring)."""
    p = Path(path)
    nodes: dict[int, tuple[float, float, float]] = {}
    hexes: dict[int, list[int]] = {}
    hex_size: set[int] = set()
    others: dict[int, tuple[str, list[int]]] = {}
    nsets: dict[str, list[int]] = {}
    elsets: dict[str, list[int]] = {}
    surfaces: dict[str, list[tuple[int, int]]] = {}
    instances = 0
    for b in _blocks(p):
        if b.keyword == "INCLUDE":
            raise ParameterError(f"{p}, line {b.line}: *INCLUDE is not read; paste the "
                                 f"included file {b.params.get('INPUT', '')!r} into this one")
        if b.keyword == "INSTANCE":
            instances += 1
            if instances > 1 or b.data:
                raise ParameterError(f"{p}, line {b.line}: only one part instance without "
                                     "translation or rotation is read; export a flat input")
        elif b.keyword == "NODE":
            for n, words in b.data:
                try:
                    i, x, y, z = int(words[0]), *(float(w) for w in [*words[1:], "0", "0"][:3])
                except (ValueError, IndexError):
                    raise ParameterError(f"{p}, line {n}: a node line is 'number, x, y, z', "
                                         f"got {', '.join(words)!r}") from None
                if i in nodes:
                    raise ParameterError(f"{p}, line {n}: node {i} is defined twice")
                nodes[i] = (x, y, z)
            if "NSET" in b.params:
                nsets.setdefault(b.params["NSET"], []).extend(
                    int(w[0]) for _, w in b.data)
        elif b.keyword == "ELEMENT":
            _elements(p, b, hexes, hex_size, others, elsets)
        elif b.keyword == "NSET":
            nsets.setdefault(_name(p, b, "NSET"), []).extend(_members(p, b, nsets, "node"))
        elif b.keyword == "ELSET":
            elsets.setdefault(_name(p, b, "ELSET"), []).extend(
                _members(p, b, elsets, "element"))
        elif b.keyword == "SURFACE":
            name = _name(p, b, "NAME")
            kind = b.params.get("TYPE", "ELEMENT").upper()
            if kind == "NODE":
                nsets.setdefault(name, []).extend(
                    _members(p, _Block(b.keyword, {}, b.line, [(n, w[:1]) for n, w in b.data]),
                             nsets, "node"))
            elif kind == "ELEMENT":
                surfaces.setdefault(name, []).extend(_surface(p, b, elsets))
            else:
                raise ParameterError(f"{p}, line {b.line}: *SURFACE TYPE={kind} is not read; "
                                     "use TYPE=ELEMENT or TYPE=NODE")
    if not hexes:
        raise ParameterError(f"{p}: no hexahedra (*ELEMENT TYPE=C3D8, C3D8I, C3D8R, C3D20 or "
                             f"C3D20R) in the file; {HEX_HINT}")
    if len(hex_size) > 1:
        raise ParameterError(f"{p}: the file mixes 8- and 20-node hexahedra; use one kind")
    node_ids = np.fromiter(nodes, dtype=np.int64, count=len(nodes))
    sorter = np.argsort(node_ids, kind="stable")
    sorted_ids = node_ids[sorter]
    element_ids = np.fromiter(hexes, dtype=np.int64, count=len(hexes))
    erow = {i: r for r, i in enumerate(hexes)}

    def rows(ids: list[int] | IntArray, where: str) -> IntArray:
        """0-based rows of node numbers (any shape), or one line naming the first unknown."""
        a = np.asarray(ids, dtype=np.int64)
        pos = np.minimum(np.searchsorted(sorted_ids, a), len(sorted_ids) - 1)
        found = sorted_ids[pos] == a if len(sorted_ids) else np.zeros(a.shape, dtype=bool)
        if not np.all(found):
            raise ParameterError(f"{p}: {where} refers to node {int(a[~found].flat[0])}, "
                                 "which is not defined (no *NODE line)")
        return np.asarray(sorter[pos], dtype=np.int64)

    conn = np.array(list(hexes.values()), dtype=np.int64)
    try:
        elements = rows(conn, "an element")
    except ParameterError:
        first = next(e for e, c in hexes.items() if not np.isin(c, sorted_ids).all())
        elements = rows(hexes[first], f"element {first}")  # raises, naming the element
    node_sets = {k: rows(v, f"node set {k!r}").reshape(-1) for k, v in nsets.items()}
    faces = {}
    for name, pairs in surfaces.items():
        bad = [e for e, _ in pairs if e not in erow]
        if bad:
            raise ParameterError(f"{p}: surface {name!r} names element {bad[0]}, which is not a "
                                 "hexahedron of the file")
        faces[name] = np.array([(erow[e], f) for e, f in pairs], dtype=np.int64).reshape(-1, 2)
    groups: dict[str, list[tuple[str, IntArray]]] = {}
    for name, ids in elsets.items():
        for e in ids:
            if e in others:
                kind, nodes_of = others[e]
                groups.setdefault(name, []).append(
                    (kind, rows(nodes_of, f"element {e}")[None, :]))
    points = np.array(list(nodes.values()), dtype=float).reshape(-1, 3)
    esets = {name: np.array([erow[e] for e in ids if e in erow], dtype=np.int64)
             for name, ids in elsets.items()}
    esets = {k: v for k, v in esets.items() if len(v) and k.upper() != "EALL"}
    return InpData(points, elements, node_ids, element_ids, node_sets, faces, groups, esets)


def _elements(p: Path, b: _Block, hexes: dict[int, list[int]], hex_size: set[int],
              others: dict[int, tuple[str, list[int]]], elsets: dict[str, list[int]]) -> None:
    """Read one *ELEMENT block into ``hexes`` (or ``others``, 2-D/1-D) and its ELSET."""
    kind = b.params.get("TYPE", "").upper()
    if not kind:
        raise ParameterError(f"{p}, line {b.line}: *ELEMENT needs TYPE=")
    refused = next((v for k, v in _REFUSED.items() if kind.startswith(k)), None)
    if refused:
        raise ParameterError(f"{p}, line {b.line}: TYPE={kind} elements are {refused}; "
                             f"{HEX_HINT}")
    size = HEX_TYPES.get(kind)
    if size is None and kind.startswith("C3D"):
        raise ParameterError(f"{p}, line {b.line}: element TYPE={kind} is not read; use one of "
                             f"{', '.join(HEX_TYPES)}")
    rows = [(n, _ints(p, n, words)) for n, words in b.data]
    if size is not None and any(len(v) != size + 1 for _, v in rows):
        # the numbers in chunks of size + 1, however the lines break
        flat = [(n, x) for n, v in rows for x in v]
        rows = [(flat[k][0], [x for _, x in flat[k:k + size + 1]])
                for k in range(0, len(flat), size + 1)]
    ids = []
    for n, v in rows:
        if size is not None and len(v) != size + 1:
            raise ParameterError(f"{p}, line {n}: a {kind} element needs its number and "
                                 f"{size} nodes, got {len(v)} numbers")
        if v[0] in hexes or v[0] in others:
            raise ParameterError(f"{p}, line {n}: element {v[0]} is defined twice")
        if size is not None:
            hexes[v[0]] = v[1:]
            hex_size.add(size)
        else:
            quad = kind.startswith(_QUAD_PREFIXES)
            others[v[0]] = ("quad" if quad else kind.lower(), v[1:])
        ids.append(v[0])
    if "ELSET" in b.params:
        elsets.setdefault(b.params["ELSET"], []).extend(ids)


def _surface(p: Path, b: _Block, elsets: dict[str, list[int]]) -> list[tuple[int, int]]:
    """(element id, face 0..5) of the lines ``ELSET or element, Sk`` of an element surface."""
    out: list[tuple[int, int]] = []
    for n, words in b.data:
        label = words[1].upper() if len(words) > 1 else ""
        if label not in {f"S{k}" for k in range(1, 7)}:
            raise ParameterError(f"{p}, line {n}: a surface line is 'ELSET or element, Sk' "
                                 f"with k = 1..6, got {', '.join(words)!r}")
        face = int(label[1]) - 1
        if words[0].isdigit():
            out.append((int(words[0]), face))
        elif words[0] in elsets:
            out += [(e, face) for e in elsets[words[0]]]
        else:
            raise ParameterError(f"{p}, line {n}: {words[0]!r} is neither an element number "
                                 "nor an element set defined above")
    return out
