"""The geometry the built-in solver needs of a mesh of the user's own: a set's faces (each
geometric face once), its plane and outward normal, the rotation that takes that normal to
-z, the node numbering (banded, the contact last) and the check that the contact holds every
part. Units: mm.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components, reverse_cuthill_mckee

from ...errors import ParameterError
from ..hexmesh import HexMesh
from ..meshcheck import check_set

__all__ = ["CURVED_MAX_DEG", "FLAT_TOL", "base_plane", "connected", "contact_rotation",
           "numbering", "plane", "set_faces"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Largest angle (rad) between the face normals of a set that counts as flat.
FLAT_TOL = 1e-6


def set_faces(mesh: HexMesh, name: str, role: str, boundary: bool = False) -> IntArray:
    """The element faces (element, face) of a set, checked (:func:`~microslip.fe.meshcheck.
    check_set`), each geometric face once.

    A set on a section inside the body (the box's ``centre``) holds the faces of the elements
    on both sides of it; the first of the two is kept, so the section's area counts once.
    """
    faces = check_set(mesh, name, role, boundary)
    keys = np.sort(mesh.face_corners(faces), axis=1)
    _, first = np.unique(keys, axis=0, return_index=True)
    return faces[np.sort(first)]


def plane(mesh: HexMesh, faces: IntArray, name: str) -> tuple[FloatArray, float]:
    """Outward unit normal of a flat set of faces and the plane's offset n . x (mm)."""
    x = mesh.nodes[mesh.face_corners(faces)]  # (k, 4, 3)
    inward = np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])
    length = np.linalg.norm(inward, axis=1)
    if np.any(length <= 0.0):
        raise ParameterError(f"{mesh.source}: set {name!r} has a degenerate face")
    out = -inward / length[:, None]
    n = out.sum(axis=0)
    if not np.linalg.norm(n) > 0.5 * len(out):
        raise ParameterError(f"{mesh.source}: set {name!r} is not flat (its faces face "
                             "opposite ways); the built-in solver needs one flat face")
    n /= np.linalg.norm(n)
    angle = float(np.max(np.linalg.norm(out - n, axis=1)))
    size = float(np.max(np.ptp(mesh.nodes, axis=0)))
    offset = float(np.mean(x.reshape(-1, 3) @ n))
    gap = float(np.max(np.abs(x.reshape(-1, 3) @ n - offset)))
    if angle > FLAT_TOL or gap > FLAT_TOL * size:
        raise ParameterError(
            f"{mesh.source}: set {name!r} is not flat (its face normals differ by up to "
            f"{math.degrees(2 * math.asin(min(angle / 2, 1.0))):.3g} deg, its nodes lie up to "
            f"{gap:.3g} mm off one plane); the built-in solver needs one flat face")
    return n, offset


#: Largest angle (deg) between a curved contact face's normals and their mean: a face within it
#: (a paraboloid, a crowned pad) touches the rigid base at its lowest points and carries each
#: node's gap to the base; beyond it the face is refused as not flat.
CURVED_MAX_DEG = 30.0


def base_plane(mesh: HexMesh, faces: IntArray, name: str) -> tuple[FloatArray, float, bool]:
    """The rigid base under a contact face: the outward unit normal, the base plane's offset
    n . x (mm) and whether the face is curved. A flat face gives :func:`plane`'s; a curved one
    (every face normal within :data:`CURVED_MAX_DEG` of their mean) the plane normal to the
    mean normal through its outermost node, so that each node keeps its gap to the base."""
    try:
        n, offset = plane(mesh, faces, name)
        return n, offset, False
    except ParameterError as err:
        flat_error = err
    x = mesh.nodes[mesh.face_corners(faces)]
    inward = np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])
    length = np.linalg.norm(inward, axis=1)
    if np.any(length <= 0.0):
        raise flat_error
    out = -inward / length[:, None]
    n = out.sum(axis=0)
    if not np.linalg.norm(n) > 0.5 * len(out):
        raise flat_error
    n /= np.linalg.norm(n)
    if float(np.degrees(np.arccos(np.clip(np.min(out @ n), -1.0, 1.0)))) > CURVED_MAX_DEG:
        raise flat_error
    return n, float(np.max(x.reshape(-1, 3) @ n)), True


def contact_rotation(outward: FloatArray) -> FloatArray:
    """R with R @ outward = (0, 0, -1): rows e1, e2 (in the plane) and e3 = -outward. The
    identity when the normal already is -z."""
    e3 = -outward
    if np.allclose(e3, (0.0, 0.0, 1.0), rtol=0.0, atol=1e-12):
        return np.eye(3)
    ref = np.eye(3)[int(np.argmin(np.abs(e3)))]
    e1 = ref - (ref @ e3) * e3
    e1 /= np.linalg.norm(e1)
    return np.stack([e1, np.cross(e3, e1), e3])


def numbering(elements: IntArray, contact: IntArray) -> IntArray:
    """The order of the used nodes: as given, or reverse Cuthill-McKee when that narrows the
    band by a third or more; then reversed if that moves the first contact node back by a
    tenth of the nodes or more (the contact last: the banded factor's leading block, which the
    contact's changes leave alone, grows, and so does the part of K_ii^-1 K_ic that is zero
    in the condensation). ``order[k]`` is the mesh node of internal node k."""
    order = band_order(elements)
    at = np.flatnonzero(np.isin(order, contact))
    if at.size and (order.size - 1 - int(at[-1])) - int(at[0]) >= order.size // 10:
        return order[::-1].copy()
    return order


def band_order(elements: IntArray) -> IntArray:
    """The used nodes of ``elements`` in reverse Cuthill-McKee order where that narrows the
    band by a third or more, else as given."""
    used = np.unique(elements)
    local = np.searchsorted(used, elements)
    width = int(np.max(local.max(axis=1) - local.min(axis=1)))
    rows = np.repeat(local, local.shape[1], axis=1).ravel()
    cols = np.tile(local, (1, local.shape[1])).ravel()
    graph = sp.coo_matrix((np.ones(rows.size), (rows, cols)),
                          shape=(used.size, used.size)).tocsr()
    perm = np.asarray(reverse_cuthill_mckee(graph, symmetric_mode=True), dtype=np.int64)
    inv = np.empty_like(perm)
    inv[perm] = np.arange(perm.size)
    renum = inv[local]
    if int(np.max(renum.max(axis=1) - renum.min(axis=1))) <= 2 * width // 3:
        return used[perm]
    return used


def connected(mesh: HexMesh, elements: IntArray, n: int, contact_faces: IntArray,
               name: str) -> None:
    """Refuse a mesh with parts that the contact does not hold (rigid-body motion)."""
    rows = np.repeat(elements[:, :1], elements.shape[1], axis=1).ravel()
    graph = sp.coo_matrix((np.ones(rows.size), (rows, elements.ravel())), shape=(n, n))
    count, label = connected_components(graph, directed=False)
    if count == 1:
        return
    held = np.unique(label[elements[contact_faces[:, 0], 0]])
    loose = ~np.isin(label[elements[:, 0]], held)
    if np.any(loose):
        raise ParameterError(
            f"{mesh.source}: {int(np.count_nonzero(loose))} elements are not connected to the "
            f"contact set {name!r}; nothing holds them (join them to the body or remove them)")
