"""An 8-node hexahedral mesh as a 20-node one: a node at the middle of every edge, sets carried.

:func:`promote_mesh` is what ``--element hex20`` does to a mesh of 8-node hexahedra, so that
the same user mesh runs both ways (``--element hex8`` and ``hex20``). Every edge of the mesh
gets one new node at its mid-point (the trilinear element's edges are straight, so the
quadratic mesh fills the same volume); an edge shared by several elements gets one node.
The sets are carried:

* a **surface** (element, face) keeps its faces (the face numbers S1..S6 are the same for
  C3D8 and C3D20);
* a **node set** gains the mid-edge node of every edge whose two ends are in the set.

The old nodes keep their rows and coordinates; the new ones follow, in the order of their
edges. A mesh of 20-node hexahedra is returned as it is. Units: mm.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from .hexmesh import HexMesh

__all__ = ["ELEMENT_ORDERS", "as_element", "demote_mesh", "promote_mesh"]

IntArray = NDArray[np.int64]

#: ``--element`` of a mesh run: name -> nodes per element.
ELEMENT_ORDERS = {"hex8": 8, "hex20": 20}

#: The 12 edges of a C3D8/C3D20 row as (corner, corner), in the order of C3D20's mid-edge
#: nodes 9..20.
_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
          (0, 4), (1, 5), (2, 6), (3, 7))


#: A mid-edge node lies at its edge's middle when within this fraction of the mesh's size.
MIDPOINT_TOL = 1e-9


def demote_mesh(mesh: HexMesh) -> HexMesh:
    """The 8-node mesh under a 20-node one whose mid-edge nodes lie at their edges' middles
    (a promoted mesh, or straight-edged quadratic elements): the corner nodes only, renumbered,
    node sets cut to them, surfaces kept. Refuses curved edges (the refinement of the corner
    mesh would not fill the same volume).

    >>> from microslip.fe.hexmesh import HexMesh
    >>> cube = HexMesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
    ...                 [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], [list(range(8))])
    >>> demote_mesh(promote_mesh(cube)).elements.tolist()
    [[0, 1, 2, 3, 4, 5, 6, 7]]
    """
    if mesh.nodes_per_element == 8:
        return mesh
    e = mesh.elements
    ends = e[:, np.asarray(_EDGES)]  # (n_e, 12, 2)
    mid = 0.5 * (mesh.nodes[ends[..., 0]] + mesh.nodes[ends[..., 1]])
    size = float(np.max(np.ptp(mesh.nodes, axis=0)))
    if float(np.max(np.abs(mesh.nodes[e[:, 8:]] - mid))) > MIDPOINT_TOL * size:
        raise ParameterError(f"{mesh.source}: --refine subdivides 20-node hexahedra only when "
                             "their edges are straight with the mid-edge node at the middle; "
                             "this mesh has curved edges (refine it in the mesher)")
    corners = np.unique(e[:, :8])
    inv = np.full(len(mesh.nodes), -1, dtype=np.int64)
    inv[corners] = np.arange(corners.size)
    sets = {k: inv[v][inv[v] >= 0] for k, v in mesh.node_sets.items()}
    return HexMesh(mesh.nodes[corners], inv[e[:, :8]], sets, dict(mesh.surfaces),
                   source=mesh.source, set_dims=dict(mesh.set_dims),
                   element_sets=dict(mesh.element_sets),
                   node_ids=None if mesh.node_ids is None else mesh.node_ids[corners],
                   element_ids=mesh.element_ids)


def as_element(mesh: HexMesh, element: str | None) -> HexMesh:
    """``mesh`` as the hexahedra ``element`` names (:data:`ELEMENT_ORDERS`; None: as it is):
    an 8-node mesh is promoted to ``hex20``; a 20-node mesh is refused as ``hex8`` (its
    mid-edge nodes would be dropped)."""
    if element is None:
        return mesh
    if element not in ELEMENT_ORDERS:
        raise ParameterError(f"--element must be one of {', '.join(ELEMENT_ORDERS)}, got "
                             f"{element!r}")
    if ELEMENT_ORDERS[element] == mesh.nodes_per_element:
        return mesh
    if element == "hex20":
        return promote_mesh(mesh)
    raise ParameterError(f"{mesh.source}: --element hex8 on a mesh of 20-node hexahedra would "
                         "drop its mid-edge nodes; use --element hex20 (or export linear "
                         "hexahedra)")


def promote_mesh(mesh: HexMesh) -> HexMesh:
    """``mesh`` with 20-node elements (mid-edge nodes added), its sets carried.

    >>> from microslip.fe.hexmesh import HexMesh
    >>> cube = HexMesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
    ...                 [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], [list(range(8))],
    ...                {"bottom": [0, 1, 2, 3]})
    >>> q = promote_mesh(cube)
    >>> q.elements.shape, q.node_sets["bottom"].tolist() == sorted(
    ...     [0, 1, 2, 3, *q.elements[0, 8:12].tolist()])
    ((1, 20), True)
    """
    if mesh.nodes_per_element == 20:
        return mesh
    e = mesh.elements
    pairs = np.sort(e[:, np.asarray(_EDGES)], axis=2).reshape(-1, 2)  # (12 n_e, 2)
    edges, inverse = np.unique(pairs, axis=0, return_inverse=True)
    n_old = len(mesh.nodes)
    mid = n_old + inverse.reshape(len(e), 12)
    nodes = np.concatenate([mesh.nodes, 0.5 * (mesh.nodes[edges[:, 0]]
                                                 + mesh.nodes[edges[:, 1]])])
    sets = {}
    for name, rows in mesh.node_sets.items():
        inset = np.zeros(n_old, dtype=bool)
        inset[rows] = True
        both = np.flatnonzero(inset[edges[:, 0]] & inset[edges[:, 1]])
        sets[name] = np.concatenate([rows, n_old + both]).astype(np.int64)
    ids = None
    if mesh.node_ids is not None:
        top = int(mesh.node_ids.max())
        ids = np.concatenate([mesh.node_ids, top + 1 + np.arange(len(edges))])
    return HexMesh(nodes, np.concatenate([e, mid], axis=1), sets, dict(mesh.surfaces),
                   source=f"{mesh.source} (hex20)", node_ids=ids,
                   element_ids=mesh.element_ids, set_dims=dict(mesh.set_dims),
                   element_sets=dict(mesh.element_sets))
