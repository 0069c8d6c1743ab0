"""The bodies of an assembly on a mesh: which elements form each body, its material, how the
contact faces pair with their counter faces, what holds each body, and the transformation to
relative interface coordinates that lets the solver see every contact node as "a node on the
ground" (issue 32).

Relative coordinates: a contact node s of a face paired with the node m of its counter face
at the same place keeps, as its unknowns, the relative displacement g = u_s - u_m; the
node's absolute displacement is u_s = g + u_m. With v the model's unknowns (the masters' and
every other node's own displacements, the slaves' relative ones), u = T v with T = I + P,
P holding a 1 at (3 s + c, 3 m + c). The stiffness becomes T^T K T and a load T^T f; the
friction and normal laws act on g exactly as they act on a node on the rigid base, so the
kernels, the condensation and the stepping are those of the rigid base, and a mesh with no
pair (T = I) is solved bit for bit as before. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components

from ...errors import ParameterError
from ..assembly import Assembly, Material
from ..hexmesh import HexMesh

__all__ = ["Pairing", "body_labels", "check_coincident", "check_held", "element_materials",
           "pair_faces", "relative_transform"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Nodes closer than this fraction of the part's size are at the same place.
COINCIDENT = 1e-9


def body_labels(mesh: HexMesh) -> tuple[int, IntArray]:
    """The number of bodies (connected parts of elements) and each node's body (-1: a node of
    no element)."""
    n = len(mesh.nodes)
    e = mesh.elements
    rows = np.repeat(e[:, :1], e.shape[1], axis=1).ravel()
    graph = sp.coo_matrix((np.ones(rows.size), (rows, e.ravel())), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    used = np.zeros(n, dtype=bool)
    used[e.ravel()] = True
    _, dense = np.unique(label[used], return_inverse=True)
    out = np.full(n, -1, dtype=np.int64)
    out[used] = dense.ravel()
    return int(dense.max()) + 1 if dense.size else 0, out


def body_name(mesh: HexMesh, label: IntArray, body: int) -> str:
    """A body in words: the element set that is exactly it, else its first element."""
    elems = np.flatnonzero(label[mesh.elements[:, 0]] == body)
    for name, rows in mesh.element_sets.items():
        if rows.size == elems.size and np.array_equal(rows, elems):
            return f"body {name}"
    for name, rows in mesh.element_sets.items():
        if np.all(np.isin(elems, rows)):
            return f"the body in element set {name} (element {mesh.element_label(int(elems[0]))})"
    return f"the body of element {mesh.element_label(int(elems[0]))}"


def element_materials(mesh: HexMesh, materials: tuple[Material, ...]
                      ) -> list[tuple[IntArray, Material]]:
    """Each material's element rows; one line naming what is wrong: an unknown element set,
    an element in two sets of different materials, elements with no material."""
    owner = np.full(len(mesh.elements), -1, dtype=np.int64)
    out: list[tuple[IntArray, Material]] = []
    for k, m in enumerate(materials):
        if m.elset is None:
            continue
        if m.elset not in mesh.element_sets:
            names = ", ".join(sorted(mesh.element_sets)) or "no element sets"
            raise ParameterError(f"{mesh.source}: no element set named {m.elset!r} (a "
                                 f"material's); the mesh has {names}")
        rows = mesh.element_sets[m.elset]
        twice = rows[owner[rows] >= 0]
        if twice.size:
            other = materials[int(owner[twice[0]])].elset
            raise ParameterError(f"{mesh.source}: element {mesh.element_label(int(twice[0]))} "
                                 f"is in the element sets {other!r} and {m.elset!r}, each "
                                 "with a material; give each element one")
        owner[rows] = k
    rest = np.flatnonzero(owner < 0)
    default = [k for k, m in enumerate(materials) if m.elset is None]
    if rest.size and not default:
        named = sorted(n for n, r in mesh.element_sets.items() if np.any(np.isin(r, rest)))
        where = (f" (element set{'s' if len(named) > 1 else ''} {', '.join(named)})" if named
                 else f" (e.g. element {mesh.element_label(int(rest[0]))})")
        raise ParameterError(f"{mesh.source}: {rest.size} elements have no material{where}; "
                             "give each body a --material, or --modulus and --poisson-ratio "
                             "for every other element")
    if rest.size:
        owner[rest] = default[0]
    for k, m in enumerate(materials):
        rows = np.flatnonzero(owner == k)
        if rows.size:
            out.append((rows, m))
    return out


@dataclass(frozen=True)
class Pairing:
    """The contact nodes of one face and their partners.

    ``nodes`` the face's nodes (mesh rows, as the face's nodal areas are ordered);
    ``master`` the counter face's node at the same place (mesh rows; -1 for the rigid base).
    """

    nodes: IntArray
    master: IntArray


def pair_faces(mesh: HexMesh, label: IntArray, face: str, counter: str,
               face_nodes: IntArray, counter_nodes: IntArray) -> IntArray:
    """The counter face's node at the place of each of ``face_nodes`` (mesh rows), or one
    line naming the unpaired nodes and where they are. A counter face on the face's own body
    is refused."""
    from scipy.spatial import cKDTree

    size = float(np.max(np.ptp(mesh.nodes, axis=0)))
    body_f = np.unique(label[face_nodes])
    body_c = np.unique(label[counter_nodes])
    if np.intersect1d(body_f, body_c).size:
        raise ParameterError(f"{mesh.source}: contact {face}:{counter}: the counter face is on "
                             "the same body as the face; a contact pairs faces of two bodies "
                             "(a face on the rigid base has no counter face)")
    dist, near = cKDTree(mesh.nodes[counter_nodes]).query(mesh.nodes[face_nodes])
    lost = np.flatnonzero(dist > COINCIDENT * size)
    if lost.size:
        x = mesh.nodes[face_nodes[lost[0]]]
        where = ", ".join(f"{v:.6g}" for v in x)
        raise ParameterError(
            f"{mesh.source}: contact {face}:{counter}: {lost.size} of the {face_nodes.size} "
            f"nodes of {face!r} have no node of {counter!r} at their place (e.g. node "
            f"{mesh.node_label(int(face_nodes[lost[0]]))} at ({where}) mm, nearest "
            f"{float(dist[lost[0]]):.3g} mm away); the interface must be conforming: mesh the "
            "two faces alike (non-conforming node-to-surface contact is not supported yet)")
    master = counter_nodes[near]
    if np.unique(master).size != master.size:
        raise ParameterError(f"{mesh.source}: contact {face}:{counter}: two nodes of {face!r} "
                             f"pair with the same node of {counter!r}")
    return np.asarray(master, dtype=np.int64)


def check_coincident(mesh: HexMesh, paired: IntArray, label: IntArray) -> None:
    """Refuse nodes of two bodies at the same place that no contact pairs (``paired``: the
    mesh rows of every paired node, both sides), naming the sets they lie on."""
    from scipy.spatial import cKDTree

    used = np.unique(mesh.elements)
    size = float(np.max(np.ptp(mesh.nodes[used], axis=0)))
    pairs = cKDTree(mesh.nodes[used]).query_pairs(COINCIDENT * size, output_type="ndarray")
    if not len(pairs):
        return
    a, b = used[pairs[:, 0]], used[pairs[:, 1]]
    bad = ~(np.isin(a, paired) & np.isin(b, paired))
    if not np.any(bad):
        return
    lone = np.union1d(a[bad], b[bad])
    sets = sorted(n for n, rows in mesh.node_sets.items() if np.any(np.isin(rows, lone)))
    x = ", ".join(f"{v:.6g}" for v in mesh.nodes[a[bad][0]])
    same = label[a[bad][0]] == label[b[bad][0]]
    faces = f" on the faces {', '.join(sets)}" if sets else ""
    what = ("the same body has two nodes at one place (a crack or an unmerged seam)" if same
            else "two bodies touch there but no contact pairs them: name the pair with "
                 "--contact FACE:COUNTER_FACE")
    raise ParameterError(f"{mesh.source}: {int(bad.sum())} node pairs lie at the same place "
                         f"(e.g. at ({x}) mm){faces}: {what}")


def check_held(mesh: HexMesh, label: IntArray, n_bodies: int, assembly: Assembly,
               grounded_nodes: IntArray, links: list[tuple[int, int]]) -> None:
    """Refuse a body held by nothing: no support, no rigid-base contact, and no contact path
    to a body that has one (``grounded_nodes``: nodes of supports and of rigid-base faces;
    ``links``: pairs of bodies joined by a contact)."""
    grounded = np.zeros(n_bodies, dtype=bool)
    grounded[np.unique(label[grounded_nodes])] = True
    free_free = not grounded.any()
    if free_free:  # no support and no base at all: one free-free assembly, if it holds together
        grounded[links[0][0] if links else 0] = True
    changed = True
    while changed:
        changed = False
        for a, b in links:
            if grounded[a] != grounded[b]:
                grounded[a] = grounded[b] = True
                changed = True
    loose = np.flatnonzero(~grounded)
    if loose.size and free_free:
        names = ", ".join(body_name(mesh, label, int(b)) for b in loose[:3])
        raise ParameterError(
            f"{mesh.source}: {names} touch no other body: a free-free assembly (no support, no "
            "rigid base) must hold together through its contacts; give it a contact or a "
            "support (--fixed SET)")
    if loose.size:
        names = ", ".join(body_name(mesh, label, int(b)) for b in loose[:3])
        more = f" and {loose.size - 3} more" if loose.size > 3 else ""
        raise ParameterError(
            f"{mesh.source}: {names}{more} held by nothing: no support, no face on the rigid "
            "base and no contact to a body that has one (its preloads would push it away); "
            "hold it with --fixed SET[:DIRECTIONS] or give it a contact")


def relative_transform(slaves: IntArray, masters: IntArray, n_nodes: int,
                       constraints: Any = None) -> sp.csr_matrix:
    """T (3 n square, CSR) with u = T v: identity, plus u_s = v_s + v_m for every slave model
    node s and its master m (every component).

    ``constraints`` (:class:`~microslip.fe.hanging.HangingNodes` in the model's numbering):
    rows u_h = sum_k w_k u_k of hanging nodes, applied after the pairs (T = H (I + P)): a
    hanging node moves with its parents' nodal displacements, its own column of T is zero
    (its unknowns are to be held), and a parent that is a slave brings its master along."""
    c = np.arange(3)
    rows = (3 * slaves[:, None] + c).ravel()
    cols = (3 * masters[:, None] + c).ravel()
    n = 3 * n_nodes
    p = sp.csr_matrix((np.ones(rows.size), (rows, cols)), shape=(n, n))
    t = (sp.identity(n, format="csr") + p).tocsr()
    if constraints is None:
        return t
    h = sp.kron(constraints.matrix(n_nodes), sp.identity(3), format="csr")
    return (h @ t).tocsr()


@dataclass(frozen=True, eq=False)
class ContactLayout:
    """Where an assembly's contacts, preloads and supports lie on a mesh (checked).

    ``faces`` every contact face (element, face), the contact nodes' faces; ``outward`` and
    ``offset`` the contact plane (every contact face's outward normal; a pair whose face
    looks the other way has its face and counter face swapped); ``pairs`` (face nodes,
    counter nodes) of each contact with a counter face; ``preloads`` (faces, force N).
    """

    faces: IntArray
    outward: FloatArray
    offset: float
    base_name: str
    base_faces: IntArray
    pairs: tuple[tuple[str, str, IntArray, IntArray], ...]
    preloads: tuple[tuple[IntArray, float], ...]
    label: IntArray
    n_bodies: int
    supports: tuple[tuple[str, IntArray, tuple[int, ...]], ...] = ()
    curved: bool = False

    @property
    def free_free(self) -> bool:
        """No support and no rigid base: the assembly floats (its preloads balance)."""
        return self.base_faces.size == 0 and not self.supports

    def gaps(self, mesh: HexMesh, contact_nodes: IntArray) -> FloatArray | None:
        """Each contact node's initial gap to the rigid base along the inward normal (mm,
        >= 0), or None when every contact face is flat on it (no gaps)."""
        if not self.curved:
            return None
        gap = self.offset - mesh.nodes[contact_nodes] @ self.outward
        gap[self.masters(contact_nodes) >= 0] = 0.0  # conforming pairs touch
        return np.asarray(np.maximum(gap, 0.0), dtype=float)

    def masters(self, contact_nodes: IntArray) -> IntArray:
        """The counter face's node (mesh row) at each contact node, -1 on the rigid base."""
        return _masters(self, contact_nodes)

    def numbering_elements(self, elements: IntArray,
                           coupled: tuple[IntArray, ...] = ()) -> IntArray:
        """The elements, plus a row joining each pair of nodes at the interface, so that the
        banded numbering keeps a node and its partner close; ``coupled``: groups of nodes a
        bolt's shank joins (its head and nut faces), chained into rows too."""
        width = elements.shape[1]
        rows = [elements]
        if self.pairs:
            s = np.concatenate([p[2] for p in self.pairs])
            m = np.concatenate([p[3] for p in self.pairs])
            rows.append(np.tile(np.stack([s, m], axis=1), (1, width // 2)))
        for group in coupled:  # overlapping windows: a chain through the group
            g = np.asarray(group, dtype=np.int64)
            if g.size < 2:
                continue
            step = max(1, width // 2)
            starts = np.arange(0, max(g.size - width, 0) + step, step)
            idx = np.minimum(starts[:, None] + np.arange(width), g.size - 1)
            rows.append(g[idx])
        if len(rows) == 1:
            return elements
        return np.concatenate(rows).astype(np.int64)

    def base_body_nodes(self, order: IntArray) -> IntArray:
        """Nodes that must not cross the rigid base: those of the bodies on it."""
        if self.base_faces.size == 0:
            return np.zeros(0, dtype=np.int64)
        on = np.unique(self.label[self.base_faces])
        return order[np.isin(self.label[order], on)]

    def check_held(self, mesh: HexMesh, assembly: Assembly) -> None:
        links = [(int(self.label[p[2][0]]), int(self.label[p[3][0]])) for p in self.pairs]
        grounded = [self.base_faces] + [nodes for _, nodes, _ in self.supports]
        check_held(mesh, self.label, self.n_bodies, assembly,
                   np.concatenate(grounded).astype(np.int64), links)

    def support_dofs(self, inv: IntArray, rotation: FloatArray) -> IntArray | None:
        """The model dofs the supports hold (None: no support). A support that holds some
        global directions only needs the contact plane along the global axes."""
        if not self.supports:
            return None
        # a global axis is a model axis when the contact frame is a signed permutation of the
        # global one (a contact face normal to x, y or z, either way)
        axis = np.argmax(np.abs(rotation), axis=0)
        aligned = bool(np.allclose(np.abs(rotation).max(axis=0), 1.0, rtol=0, atol=1e-12))
        out = []
        for name, nodes, comps in self.supports:
            if not aligned and len(comps) < 3:
                raise ParameterError(f"support {name}: holding some directions only needs the "
                                     "contact faces normal to a global axis (this mesh's "
                                     "contact plane is turned); hold xyz or rotate the mesh")
            model = comps if len(comps) == 3 else tuple(int(axis[c]) for c in comps)
            out.append((3 * inv[nodes][:, None] + np.asarray(model)).ravel())
        return np.unique(np.concatenate(out)).astype(np.int64)


def _set_nodes(mesh: HexMesh, name: str) -> IntArray:
    from ..meshcheck import check_set

    if name in mesh.node_sets:
        if not len(mesh.node_sets[name]):
            raise ParameterError(f"{mesh.source}: set {name!r} (a support) is empty")
        return np.asarray(mesh.node_sets[name], dtype=np.int64)
    faces = check_set(mesh, name, "support")
    return _face_nodes(mesh, faces)


def _face_nodes(mesh: HexMesh, faces: IntArray) -> IntArray:
    """Every node of the faces (corners, and mid-sides on 20-node meshes)."""
    if mesh.nodes_per_element == 20:
        from .hex20 import face_nodes20

        return np.unique(face_nodes20(mesh.elements, faces))
    return np.unique(mesh.face_corners(faces))


def contact_layout(mesh: HexMesh, assembly: Assembly) -> ContactLayout:
    """Check and place the contacts and preloads of ``assembly`` on ``mesh``."""
    from .meshgeometry import base_plane, plane, set_faces

    n_bodies, label = body_labels(mesh)
    found = []
    curved = False
    for c in assembly.contacts:
        faces = set_faces(mesh, c.face, "contact set", boundary=True)
        if c.counter is None:
            out, off, bent = base_plane(mesh, faces, c.face)
            curved = curved or bent
        else:
            out, off = plane(mesh, faces, c.face)
        found.append((c, faces, out, off))
    base = [f for f in found if f[0].counter is None]
    ref = base[0] if base else found[0]
    outward, offset = ref[2], ref[3]
    faces_all, pairs, base_faces = [], [], []
    for c, faces, out, off in found:
        if c.counter is None:
            if float(np.linalg.norm(out - outward)) > 1e-6 or abs(off - offset) > 1e-6 * max(
                    1.0, float(np.max(np.ptp(mesh.nodes, axis=0)))):
                raise ParameterError(f"{mesh.source}: the faces {ref[0].face!r} and {c.face!r} "
                                     "on the rigid base are not in one plane; the rigid base "
                                     "is one flat plane")
            faces_all.append(faces)
            base_faces.append(_face_nodes(mesh, faces))
            continue
        counter = set_faces(mesh, c.counter, "counter face", boundary=True)
        face_name, counter_name = c.face, c.counter
        if float(np.linalg.norm(out + outward)) < 1e-6:  # looks the other way: swap sides
            faces, counter = counter, faces
            face_name, counter_name = c.counter, c.face
            out = plane(mesh, faces, face_name)[0]
        if float(np.linalg.norm(out - outward)) > 1e-6:
            raise ParameterError(f"{mesh.source}: the contact faces {ref[0].face!r} and "
                                 f"{face_name!r} are not parallel; the built-in solver takes "
                                 "contacts in one plane orientation")
        nodes_f = _face_nodes(mesh, faces)
        nodes_c = _face_nodes(mesh, counter)
        master = pair_faces(mesh, label, face_name, counter_name, nodes_f, nodes_c)
        faces_all.append(faces)
        pairs.append((face_name, counter_name, nodes_f, master))
    slaves = np.concatenate([p[2] for p in pairs]) if pairs else np.zeros(0, np.int64)
    masters = np.concatenate([p[3] for p in pairs]) if pairs else np.zeros(0, np.int64)
    if slaves.size and np.unique(slaves).size != slaves.size:
        raise ParameterError(f"{mesh.source}: a node lies on two contact faces; name each "
                             "interface once")
    both = np.intersect1d(slaves, masters)
    if both.size:
        raise ParameterError(f"{mesh.source}: node {mesh.node_label(int(both[0]))} is on a "
                             "contact face and on a counter face at once (three bodies "
                             "meeting at one node) ; not supported")
    if n_bodies > 1 or pairs:
        check_coincident(mesh, np.concatenate([slaves, masters]), label)
    preloads = []
    for p in assembly.preloads:
        faces = set_faces(mesh, p.face, "clamp set" if assembly.is_shorthand
                          else "preload face", boundary=True)
        plane(mesh, faces, p.face)
        preloads.append((faces, p.force))
    supports = []
    for sup in assembly.supports:
        nodes = _set_nodes(mesh, sup.set)
        nodes = nodes[label[nodes] >= 0]
        if np.intersect1d(nodes, slaves).size:
            raise ParameterError(f"{mesh.source}: support {sup.set!r} holds nodes of the "
                                 "contact face of a pair; hold the counter face's body instead")
        supports.append((sup.set, nodes, sup.components))
    base_nodes = (np.concatenate(base_faces) if base_faces else np.zeros(0, np.int64))
    return ContactLayout(np.concatenate(faces_all), outward, offset,
                         base[0][0].face if base else "", base_nodes, tuple(pairs),
                         tuple(preloads), label, n_bodies, tuple(supports), curved)


def _masters(layout: ContactLayout, contact_nodes: IntArray) -> IntArray:
    out = np.full(contact_nodes.size, -1, dtype=np.int64)
    for _, _, nodes_f, master in layout.pairs:
        sort = np.argsort(nodes_f)
        pos = np.searchsorted(nodes_f[sort], contact_nodes)
        pos = np.minimum(pos, nodes_f.size - 1)
        hit = nodes_f[sort][pos] == contact_nodes
        out[hit] = master[sort][pos[hit]]
    return out


#: The free-free assembly's determinate springs, times the stiffness's mean diagonal: soft
#: enough that their six modes sit far below the elastic ones (about 1e-3 of them), stiff
#: enough for a well-conditioned factor.
GROUND_SCALE = 1e-6


def ground_springs(nodes: FloatArray, avoid: IntArray, stiffness: sp.csr_matrix
                   ) -> sp.csr_matrix:
    """Six springs on three nodes far apart (3-2-1: a statically determinate support) that
    stop a free-free assembly's rigid motions in the factorisations. Being determinate, they
    carry nothing under self-equilibrated loads (preloads, a mode's inertia forces): the
    static answer is exact whatever their stiffness; the modes leave them out.
    ``nodes`` model-frame positions, ``avoid`` nodes not to use (the contact nodes, whose
    dofs are relative)."""
    ok = np.setdiff1d(np.arange(len(nodes)), avoid)
    x = nodes[ok]
    a = int(np.argmin(x[:, 0] + 1e-3 * x[:, 1] + 1e-6 * x[:, 2]))
    b = int(np.argmax(np.linalg.norm(x - x[a], axis=1)))
    ab = x[b] - x[a]
    off = np.linalg.norm(np.cross(x - x[a], ab), axis=1)
    c = int(np.argmax(off))
    if not off[c] > 1e-9 * float(np.linalg.norm(ab)) ** 2:
        raise ParameterError("a free-free assembly whose nodes lie on one line")
    normal = np.cross(ab, x[c] - x[a])
    along = int(np.argmax(np.abs(ab)))
    dofs = [3 * ok[a] + k for k in range(3)]
    dofs += [3 * ok[b] + k for k in range(3) if k != along]
    dofs += [3 * ok[c] + int(np.argmax(np.abs(normal)))]
    k = GROUND_SCALE * float(np.mean(stiffness.diagonal()))
    n = stiffness.shape[0]
    return sp.csr_matrix((np.full(6, k), (dofs, dofs)), shape=(n, n))
