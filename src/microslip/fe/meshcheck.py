"""Bad-input checks of the user's mesh and its role sets, before anything is built.

:func:`check_roles` is what the own-mesh solver and the CalculiX deck writer call first: every
role set (contact, clamp, loads) must exist (a typo gets the closest name), hold element faces,
and, for the contact and the clamp, lie on the boundary; every element must have a positive
Jacobian determinant at its corners and Gauss points (:func:`check_elements`), and no two
nodes may coincide (:func:`check_joined`: volumes meshed apart). Each failure
is one :class:`~microslip.errors.ParameterError` line naming the file, the set or element (the
file's number) and what is wrong; the command line turns it into exit code 1.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from .hexmesh import HexMesh
from .meshload import MeshLoad

__all__ = ["boundary_faces", "check_elements", "check_joined", "check_roles", "check_set",
           "jacobian_dets", "scale_warnings"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Natural coordinates of the C3D20 nodes (the first 8: the C3D8 corners), CalculiX order.
_CORNERS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
          (0, 4), (1, 5), (2, 6), (3, 7))
_NODE_XI = np.vstack([_CORNERS, [0.5 * (_CORNERS[a] + _CORNERS[b]) for a, b in _EDGES]])
#: A determinant below this fraction of the element's bounding-box volume counts as zero.
DEGENERATE = 1e-10


def _derivatives(xi: FloatArray, quadratic: bool) -> FloatArray:
    """dN_a/dxi_i of the 8-node (trilinear) or 20-node (serendipity) hexahedron at points
    ``xi`` (p, 3) -> (p, 3, 8 or 20)."""
    if not quadratic:
        s = 1.0 + xi[:, None, :] * _CORNERS[None]  # (p, 8, 3)
        return np.stack([0.125 * _CORNERS[:, i] * s[:, :, (i + 1) % 3] * s[:, :, (i + 2) % 3]
                         for i in range(3)], axis=1)
    c = _NODE_XI
    x = xi[:, None, :]  # (p, 1, 3)
    d = np.zeros((len(xi), 3, 20))
    s = 1.0 + x[:, :8] * c[None, :8]  # corners (p, 8, 3)
    lin = x[:, :, 0] * c[None, :8, 0] + x[:, :, 1] * c[None, :8, 1] + x[:, :, 2] * c[None, :8, 2]
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        # N = 1/8 s_i s_j s_k (sum - 2): dN/dxi_i = 1/8 c_i s_j s_k (sum - 2 + s_i)
        d[:, i, :8] = 0.125 * c[None, :8, i] * s[:, :, j] * s[:, :, k] * (lin - 2.0 + s[:, :, i])
    for a in range(8, 20):
        ca = c[a]
        zero = int(np.flatnonzero(ca == 0)[0])
        others = [m for m in range(3) if m != zero]
        q = 1.0 - xi[:, zero] ** 2
        s1 = 1.0 + xi[:, others[0]] * ca[others[0]]
        s2 = 1.0 + xi[:, others[1]] * ca[others[1]]
        d[:, zero, a] = -0.5 * xi[:, zero] * s1 * s2
        d[:, others[0], a] = 0.25 * q * ca[others[0]] * s2
        d[:, others[1], a] = 0.25 * q * s1 * ca[others[1]]
    return d


def _points(quadratic: bool) -> FloatArray:
    """Corners and Gauss points (2 x 2 x 2; 3 x 3 x 3 for 20 nodes) where J is checked."""
    g = np.sqrt(0.6) if quadratic else 1.0 / np.sqrt(3.0)
    line = [-g, 0.0, g] if quadratic else [-g, g]
    gauss = np.array([(a, b, c) for a in line for b in line for c in line])
    return np.vstack([_CORNERS, gauss])


def jacobian_dets(mesh: HexMesh) -> FloatArray:
    """det J of every element at its corners and Gauss points, shape (e, p), mm^3."""
    quadratic = mesh.nodes_per_element == 20
    d = _derivatives(_points(quadratic), quadratic)  # (p, 3, m)
    x = mesh.nodes[mesh.elements]  # (e, m, 3)
    jac = np.matmul(d[None], x[:, None])  # (e, p, 3, 3): J_ij = dN_a/dxi_i x_aj
    return np.asarray(np.linalg.det(jac), dtype=float)


def check_elements(mesh: HexMesh) -> None:
    """Refuse an inverted or degenerate element: det J <= 0 at a corner or Gauss point.

    Zero means below :data:`DEGENERATE` times the element's bounding-box volume (a collapsed
    edge or face). The message names the first bad element by its number in the file.
    """
    dets = jacobian_dets(mesh)
    x = mesh.nodes[mesh.elements[:, :8]]
    box = np.prod(x.max(axis=1) - x.min(axis=1), axis=1) / 8.0  # det J of a box element
    bad = np.flatnonzero((dets <= DEGENERATE * box[:, None]).any(axis=1) | ~(box > 0))
    if not len(bad):
        return
    e = int(bad[0])
    more = f" (and {len(bad) - 1} more)" if len(bad) > 1 else ""
    label = mesh.element_label(e)
    if np.all(dets[e] < -DEGENERATE * box[e]):
        what = ("is inverted (negative Jacobian determinant): its nodes 1-4 must run "
                "counter-clockwise seen from nodes 5-8, as in CalculiX's C3D8")
    elif np.any(dets[e] < -DEGENERATE * box[e]):
        what = "is distorted inside out (the Jacobian determinant changes sign)"
    else:
        what = "is degenerate (zero volume at a corner: coincident nodes or a collapsed face)"
    raise ParameterError(f"{mesh.source}: element {label}{more} {what}")


def boundary_faces(mesh: HexMesh, faces: IntArray) -> NDArray[np.bool_]:
    """Whether each face (element, face 0..5) lies on the boundary (belongs to one element)."""
    all_faces = np.stack(np.meshgrid(np.arange(len(mesh.elements)), np.arange(6),
                                     indexing="ij"), axis=-1).reshape(-1, 2)
    keys = np.sort(mesh.face_corners(all_faces), axis=1)
    order = np.lexsort(keys.T[::-1])
    same = np.all(keys[order[1:]] == keys[order[:-1]], axis=1)  # equal to the next in order
    shared = np.zeros(len(keys), dtype=bool)
    shared[order[1:][same]] = True
    shared[order[:-1][same]] = True
    return np.asarray(~shared.reshape(-1, 6)[faces[:, 0], faces[:, 1]], dtype=bool)


def _missing(mesh: HexMesh, name: str, role: str) -> ParameterError:
    names = mesh.set_names()
    folded = {n.lower(): n for n in names}
    close = ([folded[name.lower()]] if name.lower() in folded
             else difflib.get_close_matches(name, names, n=1, cutoff=0.6))
    hint = f"; did you mean {close[0]!r}?" if close else ""
    listing = ", ".join(names) if names else "no named sets"
    return ParameterError(f"{mesh.source}: no set named {name!r} (the {role}){hint} "
                          f"The mesh has: {listing}")


def check_set(mesh: HexMesh, name: str, role: str, boundary: bool = False) -> IntArray:
    """The faces of set ``name`` for ``role`` (e.g. "contact set"), or one line saying why not:
    missing, empty, no whole element face, or (``boundary``) faces inside the body."""
    if name not in mesh.node_sets and name not in mesh.surfaces:
        raise _missing(mesh, name, role)
    size = len(mesh.surfaces[name]) if name in mesh.surfaces else len(mesh.node_sets[name])
    if size == 0:
        raise ParameterError(f"{mesh.source}: set {name!r} (the {role}) is empty")
    dim = mesh.set_dims.get(name)
    wrong = (dim is not None and dim < 2) or (boundary and dim == 3)
    if wrong:
        raise ParameterError(
            f"{mesh.source}: set {name!r} (the {role}) is a {_DIM_NAMES[int(dim or 0)]} group "
            f"of the mesh file; the {role} must be a surface group (2-D: quadrilaterals on "
            "the hexahedra's faces)")
    faces = mesh.faces(name)
    if len(faces) == 0:
        raise ParameterError(
            f"{mesh.source}: set {name!r} (the {role}) holds no element face: none of the "
            f"faces has all its corner nodes among its {size} nodes")
    if boundary:
        inner = ~boundary_faces(mesh, faces)
        if inner.any():
            e, f = faces[np.flatnonzero(inner)[0]]
            raise ParameterError(
                f"{mesh.source}: set {name!r} (the {role}) is not on the boundary: "
                f"{int(inner.sum())} of its {len(faces)} faces are shared by two elements "
                f"(e.g. face S{int(f) + 1} of element {mesh.element_label(int(e))})")
    return faces


#: A group's dimension in words, for messages.
_DIM_NAMES = {0: "point (0-D)", 1: "curve (1-D)", 2: "surface (2-D)", 3: "volume (3-D)"}
#: Nodes closer than this fraction of the part's size count as coincident.
COINCIDENT = 1e-9
#: The clamping pressure F_N / A over the modulus outside this range is not a clamp in mm, N
#: and MPa: a mesh in metres (areas 1e6 too small) or a modulus in Pa (1e6 too large).
PRESSURE_TO_MODULUS = (1e-8, 1e-2)
#: A part smaller than this across (mm) is probably a mesh in metres.
SMALLEST_PART_MM = 1.0


def check_joined(mesh: HexMesh) -> None:
    """Refuse nodes at the same place as others: volumes meshed apart and not joined (each
    would be a body of its own, touching the other without any contact between them)."""
    from scipy.spatial import cKDTree

    used = np.unique(mesh.elements)
    x = mesh.nodes[used]
    size = float(np.max(np.ptp(x, axis=0)))
    pairs = cKDTree(x).query_pairs(COINCIDENT * size, output_type="ndarray")
    if not len(pairs):
        return
    a, b = (int(used[i]) for i in pairs[0])
    where = ", ".join(f"{v:.6g}" for v in mesh.nodes[a])
    raise ParameterError(
        f"{mesh.source}: {len(pairs)} nodes lie at the same place as others (e.g. nodes "
        f"{mesh.node_label(a)} and {mesh.node_label(b)} at ({where}) mm): volumes meshed apart "
        "are not joined; join them before meshing (gmsh: BooleanFragments, or Coherence Mesh)")


def scale_warnings(mesh: HexMesh, clamp: str, normal_force: float,
                   modulus: float) -> list[str]:
    """Warnings (not errors) that the units are not mm, N and MPa: the part is under
    :data:`SMALLEST_PART_MM` across, or the clamping pressure F_N / A over the modulus lies
    outside :data:`PRESSURE_TO_MODULUS`."""
    out = []
    size = float(np.max(np.ptp(mesh.nodes[np.unique(mesh.elements)], axis=0)))
    if size < SMALLEST_PART_MM:
        out.append(f"{mesh.source}: the part is {size:.3g} mm across; microslip reads the "
                   "mesh in mm: a mesh in metres needs its coordinates x 1000 (gmsh: "
                   "Mesh.ScalingFactor 1000)")
    from .hexmesh import face_load

    area = face_load(mesh, mesh.faces(clamp))[2]
    ratio = normal_force / area / modulus
    lo, hi = PRESSURE_TO_MODULUS
    if not lo <= ratio <= hi:
        what = ("a mesh in metres (areas 1e6 too small)?" if ratio > hi
                else "a modulus in Pa instead of MPa, or a mesh in micrometres?")
        out.append(f"the clamping pressure F_N / A = {normal_force / area:.3g} MPa is "
                   f"{ratio:.2g} times the modulus ({modulus:g} MPa), outside [{lo:g}, {hi:g}] "
                   f"for a clamp in N, mm and MPa: {what}")
    return out


def check_roles(mesh: HexMesh, contact: str, clamp: str,
                loads: Iterable[MeshLoad | str] = ()) -> None:
    """Check the role sets and the elements of ``mesh`` before a solver builds anything.

    ``contact`` (the face on the rigid base) and ``clamp`` (the face carrying the clamping
    pressure) must be boundary faces, none in both; each load's set must hold element faces
    (it may lie inside the body, as the box's mid-length section does). Then
    :func:`check_elements`.
    A load direction of zero length is refused by :class:`~microslip.fe.meshload.MeshLoad`.
    """
    base = check_set(mesh, contact, "contact set", boundary=True)
    pressed = check_set(mesh, clamp, "clamp set", boundary=True)
    both = np.intersect1d(base[:, 0] * 6 + base[:, 1], pressed[:, 0] * 6 + pressed[:, 1])
    if len(both):
        raise ParameterError(
            f"{mesh.source}: the contact set {contact!r} and the clamp set {clamp!r} share "
            f"{len(both)} faces; the clamping pressure must act on other faces than the base")
    for load in loads:
        name = load.set if isinstance(load, MeshLoad) else str(load)
        check_set(mesh, name, "set of a load")
    check_joined(mesh)
    check_elements(mesh)


def check_assembly(mesh: HexMesh, assembly: Any, loads: Iterable[MeshLoad | str] = ()) -> None:
    """:func:`check_roles` for an :class:`~microslip.fe.assembly.Assembly`: its shorthand
    (one body on the rigid base) exactly as :func:`check_roles`; otherwise every contact,
    counter, preload and support set must exist and hold element faces on the boundary, each
    load's set must hold faces, and the elements must be sound (the builder pairs the
    interfaces and checks their coincident nodes)."""
    from .assembly import as_assembly

    a = as_assembly(assembly)
    if a.is_shorthand:
        check_roles(mesh, a.contact_set, a.clamp_set, loads)
        return
    for c in a.contacts:
        check_set(mesh, c.face, "contact set", boundary=True)
        if c.counter is not None:
            check_set(mesh, c.counter, "counter face", boundary=True)
    for p in a.preloads:
        check_set(mesh, p.face, "preload face", boundary=True)
    for s in a.supports:
        if s.set not in mesh.node_sets:
            check_set(mesh, s.set, "support")
    for load in loads:
        name = load.set if isinstance(load, MeshLoad) else str(load)
        check_set(mesh, name, "set of a load")
    check_elements(mesh)
