"""An assembly and its loads against the mesh they name, before anything is built.

What a command line or a case file states about a mesh (its sets, materials, contacts,
preloads, supports and loads) is checked here against the mesh, and what the mesh offers is
found here for ``case new --mesh``:

* :func:`bodies`: the bodies of a mesh (connected parts of elements sharing nodes);
* :func:`interface_pairs`: sets of two bodies whose nodes coincide one to one (a conforming
  interface, the contacts ``case new`` proposes);
* :func:`check_on_mesh`: every set named exists (the closest name otherwise), every element
  has a material, a counter face lies on another body than its face, bodies that touch have
  a contact between them, every body is held, and the values fit the mesh's scale: a part
  under 1 mm across, or a clamping pressure F/A above the modulus, is a unit mistake
  (errors); a pressure outside the plausible band warns.

Each finding is one line; :class:`Findings` keeps them all (``case check`` prints every one),
and the command line raises the first. Units: N, mm, MPa.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError

if TYPE_CHECKING:
    from ..fe.assembly import Assembly
    from ..fe.hexmesh import HexMesh

__all__ = ["Findings", "MeshOffer", "bodies", "body_name", "check_on_mesh", "interface_pairs",
           "offer", "set_nodes", "volume_sets"]

IntArray = NDArray[np.int64]

#: Nodes closer than this fraction of the part's size coincide (as the FE's check).
COINCIDENT = 1e-9
#: A part smaller than this across (mm), with forces in N, is a mesh in metres.
SMALLEST_PART_MM = 1.0
#: F / A over the modulus outside this band warns (a pressure of 1e-8 E or 1e-2 E is
#: unusual for a clamp in N, mm and MPa); above 1 (the pressure above the modulus) it is an
#: error: no clamp is meant so.
PRESSURE_TO_MODULUS = (1e-8, 1e-2)


@dataclass(frozen=True)
class Findings:
    """What the checks found: ``errors`` (each one line; a command refuses to run) and
    ``warnings`` (borderline values)."""

    errors: tuple[str, ...]
    warnings: tuple[str, ...]

    def raise_first(self) -> None:
        """Raise the first error as a ParameterError (one line)."""
        if self.errors:
            raise ParameterError(self.errors[0])


def bodies(mesh: HexMesh) -> IntArray:
    """The body of every element (0-based, numbered in the order of their first element):
    elements that share a node belong to the same body."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components

    e = mesh.elements
    n = len(mesh.nodes)
    rows = np.repeat(np.arange(len(e)), e.shape[1])
    incidence = sp.csr_matrix((np.ones(e.size), (rows, e.ravel())), shape=(len(e), n))
    _, label = connected_components(incidence @ incidence.T, directed=False)
    _, first = np.unique(label, return_index=True)
    order = np.argsort(np.argsort(first))  # renumber by first element
    return np.asarray(order[label], dtype=np.int64)


def _node_bodies(mesh: HexMesh, labels: IntArray) -> IntArray:
    out = np.full(len(mesh.nodes), -1, dtype=np.int64)
    out[mesh.elements] = labels[:, None]
    return out


def volume_sets(mesh: HexMesh) -> tuple[str, ...]:
    """Sets that are volume groups (a gmsh physical volume read as a node set, or a node set
    equal to an element set's nodes): never a face, a load's face or a contact."""
    out = {n for n, d in mesh.set_dims.items() if d == 3}
    for name, rows in mesh.element_sets.items():
        nodes = np.unique(mesh.elements[rows])
        out |= {s for s, v in mesh.node_sets.items() if np.array_equal(v, nodes)}
        out.add(name)
    return tuple(sorted(n for n in out if n in mesh.node_sets or n in mesh.surfaces))


def _face_nodes(mesh: HexMesh, faces: IntArray) -> IntArray:
    """Every node of the faces (element, face): the corners, and the mid-side nodes of a
    20-node mesh."""
    from ..fe.hexmesh import HEX20_FACE_MIDSIDES

    rows = [mesh.face_corners(faces).ravel()]
    if mesh.nodes_per_element == 20:
        table = np.asarray(HEX20_FACE_MIDSIDES, dtype=np.int64)
        rows.append(mesh.elements[faces[:, 0][:, None], table[faces[:, 1]]].ravel())
    return np.unique(np.concatenate(rows))


def set_nodes(mesh: HexMesh, name: str) -> IntArray:
    """The nodes of the element faces of set ``name`` (empty if it holds none)."""
    faces = mesh.faces(name)
    if len(faces) == 0:
        return np.zeros(0, dtype=np.int64)
    return _face_nodes(mesh, faces)


def _size(mesh: HexMesh) -> float:
    return float(np.max(np.ptp(mesh.nodes[np.unique(mesh.elements)], axis=0)))


def body_name(mesh: HexMesh, labels: IntArray, body: int) -> str:
    """``body 2 (BASE)``: the body's number and the element sets inside it (or its first
    element)."""
    inside = [n for n, rows in sorted(mesh.element_sets.items())
              if len(rows) and np.all(labels[rows] == body)]
    if not inside:
        first = int(np.flatnonzero(labels == body)[0])
        return f"body {body + 1} (the one with element {mesh.element_label(first)})"
    return f"body {body + 1} ({', '.join(inside[:3])}{', ...' if len(inside) > 3 else ''})"


def interface_pairs(mesh: HexMesh, labels: IntArray | None = None
                    ) -> tuple[tuple[str, str], ...]:
    """The conforming interfaces of a mesh: (face, counter) set names on two bodies whose
    faces' nodes coincide one to one. The counter (the master side) is the set of the body
    with fewer elements (the coarser one, usually the support or the base), the face (the
    contact nodes) the other's; of sets with the same nodes the first name is taken."""
    from scipy.spatial import cKDTree

    labels = bodies(mesh) if labels is None else labels
    if labels.max() == 0:
        return ()
    node_body = _node_bodies(mesh, labels)
    tol = COINCIDENT * _size(mesh)
    skip = set(volume_sets(mesh))
    seen: dict[tuple[int, bytes], str] = {}
    for name in mesh.set_names():
        if name in skip:
            continue
        rows = set_nodes(mesh, name)
        owners = np.unique(node_body[rows]) if len(rows) else np.zeros(0)
        if len(owners) == 1:
            seen.setdefault((int(owners[0]), rows.tobytes()), name)
    sizes = np.bincount(labels)
    found: list[tuple[str, str]] = []
    items = [(body, np.frombuffer(key, dtype=np.int64), name)
             for (body, key), name in seen.items()]
    for i, (b1, r1, n1) in enumerate(items):
        for b2, r2, n2 in items[i + 1:]:
            if b1 == b2 or len(r1) != len(r2):
                continue
            dist, j = cKDTree(mesh.nodes[r2]).query(mesh.nodes[r1])
            if np.all(dist <= tol) and len(np.unique(j)) == len(r2):
                big_first = (-sizes[b1], n1) <= (-sizes[b2], n2)
                found.append((n1, n2) if big_first else (n2, n1))
    return tuple(sorted(found))


def _missing(mesh: HexMesh, name: str, role: str, names: Sequence[str], kind: str) -> str:
    folded = {n.lower(): n for n in names}
    close = ([folded[name.lower()]] if name.lower() in folded
             else difflib.get_close_matches(name, list(names), n=1, cutoff=0.6))
    hint = f"; did you mean {close[0]!r}?" if close else ""
    listing = ", ".join(names) if names else f"no {kind}s"
    return f"{mesh.source}: no {kind} named {name!r} (the {role}){hint} The mesh has: {listing}"


def _face_roles(assembly: Assembly) -> list[tuple[str, str]]:
    out = []
    for c in assembly.contacts:
        out.append((c.face, "contact set"))
        if c.counter is not None:
            out.append((c.counter, f"counter set of contact {c.label}"))
    out += [(p.face, "clamp set" if len(assembly.preloads) == 1 else "preload set")
            for p in assembly.preloads]
    return out


def check_on_mesh(mesh: HexMesh, assembly: Assembly, loads: Iterable[Any] = (),
                  sets: Iterable[tuple[str, str]] = (),
                  spell: Callable[[str], str] | None = None) -> Findings:
    """Check ``assembly`` and the sets of ``loads`` (:class:`~microslip.fe.meshload.MeshLoad`
    or set names) and ``sets`` ((name, role) pairs: a response set) against ``mesh``.

    ``spell(dest)`` names an option in advice (``--contact``; default: the flag).
    """
    from ..fe.meshcheck import check_set

    say = spell or (lambda d: "--" + d.replace("_", "-"))
    errors: list[str] = []
    warnings: list[str] = []
    faces: dict[str, Any] = {}
    for name, role in _face_roles(assembly):
        if name in faces:
            continue
        try:
            faces[name] = check_set(mesh, name, role, boundary=True)
        except ParameterError as exc:
            faces[name] = None
            errors.append(str(exc))
    names = mesh.set_names()
    for s in assembly.supports:
        if s.set not in mesh.node_sets and s.set not in mesh.surfaces:
            errors.append(_missing(mesh, s.set, "support set", names, "set"))
    for load in loads:
        name = getattr(load, "set", load)
        try:
            check_set(mesh, str(name), "set of a load")
        except ParameterError as exc:
            errors.append(str(exc))
    for name, role in sets:
        if name not in mesh.node_sets and name not in mesh.surfaces:
            errors.append(_missing(mesh, name, role, names, "set"))
    elsets = tuple(sorted(mesh.element_sets))
    modulus = np.full(len(mesh.elements), np.nan)
    default = [m for m in assembly.materials if m.elset is None]
    if default:
        modulus[:] = default[0].modulus
    for m in assembly.materials:
        if m.elset is None:
            continue
        if m.elset not in mesh.element_sets:
            errors.append(_missing(mesh, m.elset, f"element set of --material {m.elset}",
                                   elsets, "element set"))
            continue
        modulus[mesh.element_sets[m.elset]] = m.modulus
    bare = np.flatnonzero(np.isnan(modulus))
    if len(bare) and not any(e.startswith(f"{mesh.source}: no element set") for e in errors):
        errors.append(f"{mesh.source}: {len(bare)} of {len(mesh.elements)} elements (e.g. "
                      f"element {mesh.element_label(int(bare[0]))}) have no material: give "
                      f"their element set a {say('material')}, or {say('modulus')} and "
                      f"{say('poisson_ratio')} for every element no {say('material')} names")
    labels = bodies(mesh)
    if labels.max() > 0:
        # what follows from a set named wrong (a body then held by nothing) is not said twice
        errors += _body_errors(mesh, assembly, labels, faces, say, whole=not errors)
    size = _size(mesh)
    if size < SMALLEST_PART_MM:
        errors.append(f"{mesh.source}: the part is {size:.3g} mm across, with forces in N: "
                      "microslip reads the mesh in mm, so this is a mesh in metres (scale "
                      "its coordinates x 1000; gmsh: Mesh.ScalingFactor 1000)")
    else:
        _pressures(mesh, assembly, faces, modulus, errors, warnings)
    return Findings(tuple(dict.fromkeys(errors)), tuple(warnings))


def _pressures(mesh: HexMesh, assembly: Assembly, faces: dict[str, Any],
               modulus: NDArray[np.float64], errors: list[str], warnings: list[str]) -> None:
    """F / A of every preload against the modulus of the elements under its face."""
    from ..fe.hexmesh import face_load

    lo, hi = PRESSURE_TO_MODULUS
    for p in assembly.preloads:
        f = faces.get(p.face)
        if f is None or len(f) == 0:
            continue
        area = face_load(mesh, f)[2]
        e = float(np.nanmin(modulus[f[:, 0]])) if np.any(np.isfinite(modulus[f[:, 0]])) \
            else float("nan")
        if not (area > 0 and np.isfinite(e)):
            continue
        pressure = p.force / area
        ratio = pressure / e
        where = f"the clamping pressure F/A on {p.face!r} = {p.force:g} N / {area:.4g} mm^2 " \
                f"= {pressure:.3g} MPa"
        if ratio > 1.0:
            errors.append(f"{mesh.source}: {where} is {ratio:.3g} times the modulus ({e:g} "
                          "MPa): no clamp is meant so; a mesh in metres (areas 1e6 too "
                          "small), or a force in mN?")
        elif not lo <= ratio <= hi:
            what = ("a mesh in metres (areas 1e6 too small)?" if ratio > hi
                    else "a modulus in Pa instead of MPa, or a mesh in micrometres?")
            warnings.append(f"{where} is {ratio:.2g} times the modulus ({e:g} MPa), outside "
                            f"[{lo:g}, {hi:g}] for a clamp in N, mm and MPa: {what}")


def _body_errors(mesh: HexMesh, assembly: Assembly, labels: IntArray,
                 faces: dict[str, Any], say: Callable[[str], str], whole: bool) -> list[str]:
    """Counter faces on their own body; with ``whole`` (no error found before) and none of
    those, bodies touching with no contact named and bodies held by nothing."""
    from scipy.spatial import cKDTree

    out: list[str] = []
    node_body = _node_bodies(mesh, labels)

    def owner(name: str) -> int | None:
        f = faces.get(name)
        if f is None or len(f) == 0:
            return None
        b = np.unique(labels[f[:, 0]])
        return int(b[0]) if len(b) == 1 else None

    links: list[tuple[int, int]] = []
    paired = np.zeros(len(mesh.nodes), dtype=bool)
    for c in assembly.contacts:
        if c.counter is None:
            continue
        a, b = owner(c.face), owner(c.counter)
        for name in (c.face, c.counter):
            f = faces.get(name)
            if f is not None and len(f):
                paired[_face_nodes(mesh, f)] = True
        if a is not None and a == b:
            out.append(f"{mesh.source}: contact {c.label}: the counter set {c.counter!r} lies "
                       f"on the same body as {c.face!r} ({body_name(mesh, labels, a)}); a "
                       "counter face belongs to another body")
        elif a is not None and b is not None:
            links.append((a, b))
    if out or not whole:
        return out
    used = np.unique(mesh.elements)
    pairs = cKDTree(mesh.nodes[used]).query_pairs(COINCIDENT * _size(mesh),
                                                  output_type="ndarray")
    if len(pairs):
        i, j = used[pairs[:, 0]], used[pairs[:, 1]]
        loose = (node_body[i] != node_body[j]) & ~(paired[i] & paired[j])
        if np.any(loose):
            b1, b2 = sorted((int(node_body[i[loose][0]]), int(node_body[j[loose][0]])))
            hits = [p for p in interface_pairs(mesh, labels)
                    if {owner_of(mesh, labels, q) for q in p} == {b1, b2}]
            hint = (f"name it: {_contact_text(say, *hits[0])}" if hits else
                    "name a set of each side's interface nodes and give "
                    f"{_contact_text(say, 'SET', 'COUNTER_SET')}")
            out.append(f"{mesh.source}: {body_name(mesh, labels, b1)} and "
                       f"{body_name(mesh, labels, b2)} touch at {int(np.count_nonzero(loose))} "
                       f"coincident nodes with no contact named between them: {hint}")
            return out  # held or not follows from the contact to be named
    held = {owner(c.face) for c in assembly.contacts if c.counter is None}
    for s in assembly.supports:
        held |= _set_bodies(mesh, node_body, s.set)
    held.discard(None)
    if not held and links:  # free-free (no support, no base): it must hold together, and
        held = {links[0][0]}  # its preloads must balance
        net = _net_preload(mesh, assembly, faces)
        if net > 1e-6 * sum(p.force for p in assembly.preloads):
            out.append(f"{mesh.source}: the preloads push the free-free assembly (net force "
                       f"{net:.4g} N) and nothing holds it: hold it ({say('fixed')}) or "
                       "balance the preloads (a bolt presses its head and its nut alike)")
            return out
    grew = True
    while grew:
        grew = False
        for a, b in links:
            if (a in held) != (b in held):
                held |= {a, b}
                grew = True
    for body in range(int(labels.max()) + 1):
        if body not in held:
            out.append(f"{mesh.source}: {body_name(mesh, labels, body)} is held by nothing: "
                       f"no support ({say('fixed')}), no contact on the rigid base and no "
                       "contact with a body that is held")
            break
    return out


def _contact_text(say: Callable[[str], str], face: str, counter: str) -> str:
    """A contact as the caller writes it: ``--contact A:B`` or ``[[mesh.contact]] face = "A",
    counter = "B"``."""
    flag = say("contact")
    if flag.startswith("--"):
        return f"{flag} {face}:{counter}"
    return f'{flag} face = "{face}", counter = "{counter}"'


def owner_of(mesh: HexMesh, labels: IntArray, name: str) -> int | None:
    """The body that set ``name``'s faces lie on, None if several or none."""
    f = mesh.faces(name)
    b = np.unique(labels[f[:, 0]]) if len(f) else np.zeros(0)
    return int(b[0]) if len(b) == 1 else None


def _set_bodies(mesh: HexMesh, node_body: IntArray, name: str) -> set[int | None]:
    """The bodies the nodes of set ``name`` lie on."""
    rows = mesh.node_sets.get(name)
    if rows is None:
        f = mesh.surfaces.get(name)
        rows = None if f is None or len(f) == 0 else _face_nodes(mesh, f)
    if rows is None:
        return set()
    return {int(b) for b in np.unique(node_body[rows]) if b >= 0}


@dataclass(frozen=True)
class MeshOffer:
    """What a mesh offers a case file (``case new --mesh``): its sets by kind, its bodies and
    the interfaces between them.

    ``faces`` are the sets that hold element faces and are no volume group (the candidates
    for a contact, a preload, a support or a load); ``bodies`` one entry per body, the
    element sets inside it; ``pairs`` the conforming interfaces (:func:`interface_pairs`).
    """

    node_sets: tuple[str, ...]
    surfaces: tuple[str, ...]
    element_sets: tuple[str, ...]
    volumes: tuple[str, ...]
    faces: tuple[str, ...]
    bodies: tuple[tuple[str, ...], ...]
    body_names: tuple[str, ...]
    pairs: tuple[tuple[str, str], ...]


def offer(mesh: HexMesh) -> MeshOffer:
    """The :class:`MeshOffer` of ``mesh``."""
    labels = bodies(mesh)
    volumes = volume_sets(mesh)
    faces = tuple(n for n in mesh.set_names()
                  if n not in volumes and len(mesh.faces(n)) > 0)
    inside = tuple(tuple(n for n, rows in sorted(mesh.element_sets.items())
                         if len(rows) and np.all(labels[rows] == b))
                   for b in range(int(labels.max()) + 1))
    return MeshOffer(tuple(sorted(mesh.node_sets)), tuple(sorted(mesh.surfaces)),
                     tuple(sorted(mesh.element_sets)), volumes, faces, inside,
                     tuple(body_name(mesh, labels, b) for b in range(len(inside))),
                     interface_pairs(mesh, labels))


def _net_preload(mesh: HexMesh, assembly: Assembly, faces: dict[str, Any]) -> float:
    """|sum of the preloads' forces| (N): each F along its face's mean inward normal."""
    total = np.zeros(3)
    for p in assembly.preloads:
        f = faces.get(p.face)
        if f is None or len(f) == 0:
            continue
        x = mesh.nodes[mesh.face_corners(np.asarray(f))]
        inward = 0.5 * np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1]).sum(axis=0)
        area = float(np.linalg.norm(inward))
        if area > 0:
            total += p.force * inward / area
    return float(np.linalg.norm(total))
