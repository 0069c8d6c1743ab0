"""CalculiX input deck of the user's own mesh and its assembly (issues 22 and 32), one card
per function.

The deck of :func:`build_mesh_deck` (its cards from :mod:`~microslip.fe.calculix.deck`;
the paper's box too, :mod:`~microslip.fe.calculix.boxrun`) is written for any
:class:`~microslip.fe.hexmesh.HexMesh` of one or more bodies, with the roles given by an
:class:`~microslip.fe.assembly.Assembly` naming the mesh's sets (its cards:
:mod:`.assemblydeck`):

1. the user's mesh: C3D8I for 8-node hexahedra (the built-in solver's element), C3D20R for
   20-node ones; node and element ids are the mesh's rows + 1; a material per element set;
2. under each contact face on the rigid base (``Contact(face)``) a rigid base
   (:func:`base_slab`): a flat slab of fixed C3D8 bricks below the contact plane, larger than
   the contact faces by one grid spacing all round;
3. each contact a penalty ``*CONTACT PAIR``: slave the contact face, master the base's upper
   face or the counter face of another body (``Contact(face, counter)``), face-to-face
   (``TYPE=SURFACE TO SURFACE``, default) or, with ``formulation="node-to-surface"``
   (:mod:`.contactform`), node-to-surface (the built-in solver's nodal law); linear
   pressure-overclosure law with the normal slope (``normal_contact="penalty"``, lift-off
   allowed) and Coulomb friction mu with the stick slope lambda (``*FRICTION``);
4. the supports as ``*BOUNDARY`` on their node sets' held components;
5. step 1: every preload's pressure F / A on its faces (``*DSLOAD``, P), friction active;
6. step 2: the loads F_l(t) = A_l sin(2 pi t + phi_l) (:class:`~microslip.fe.meshload.MeshLoad`)
   as ``*CLOAD`` nodal forces, the consistent shares of a uniform traction on each load's
   faces (:func:`~microslip.fe.hexmesh.face_load`) times its direction, each scaled by a
   tabular ``*AMPLITUDE`` exact at every increment end
   (:func:`~.meshhistory.load_history`, ``DIRECT`` increments); u of every loaded node to
   the ``.dat`` file, u and the contact slips and tractions to the ``.frd`` file at every
   increment.

The rigid-base shorthand (a :class:`~microslip.fe.clamp.MeshClamp`, or
:func:`~microslip.fe.assembly.rigid_base`: one body, one contact on the base, one preload, one
material) writes the deck of issue 22 card for card. Unlike the box deck there is no symmetry
plane unless a support holds one: as in the built-in solver, the in-plane rigid-body motions
of a body on the base are held by friction alone.

``normal_contact="fixed"`` (the built-in solver's default: normal forces frozen at the clamping
step's) has no CalculiX counterpart: a contact's pressure always follows the overclosure. It is
refused with one line; ``validate --mesh`` compares a ``fixed`` case as a hard (stiff penalty)
contact on both sides (:mod:`.compare`).

Units: N, mm, MPa; time in cycles (1 s per cycle).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import ParameterError
from ..assembly import Assembly, as_assembly
from ..clamp import MeshClamp
from ..hexmesh import HexMesh, face_load
from ..meshload import MeshLoad
from .assemblydeck import (
    ResolvedAssembly,
    ResolvedContact,
    boundary_rows,
    contact_cards,
    dsload_card,
    material_cards,
    preload_cards,
    resolve_assembly,
    support_cards,
)
from .contactform import (
    CONTACT_FORMULATIONS,
    N2S_TENSION_RATIO,
    ContactFormulation,
    check_formulation,
)
from .deck import (
    _name,
    amplitude_card,
    boundary_card,
    cload_card,
    contact_file_card,
    controls_card,
    elements_card,
    end_step_card,
    heading_card,
    node_file_card,
    node_print_card,
    nodes_card,
    nset_card,
    static_card,
    step_card,
)
from .meshhistory import _STARTUP_TEXT, LoadHistory, load_history

__all__ = [
    "CLAMP_TIME",
    "CONTACT_FORMULATIONS",
    "LOADED_NSET",
    "MESH_ELEMENTS",
    "N2S_TENSION_RATIO",
    "NORMAL_CONTACTS",
    "BaseSlab",
    "ContactFormulation",
    "MeshLoadPlan",
    "base_slab",
    "build_frequency_deck",
    "build_mesh_deck",
    "check_formulation",
    "dsload_card",
    "element_surface_card",
    "load_plan",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: CalculiX element of the user's mesh by nodes per element.
MESH_ELEMENTS = {8: "C3D8I", 20: "C3D20R"}
#: Normal contact laws CalculiX can model: name -> what it means.
NORMAL_CONTACTS = {
    "penalty": "linear pressure-overclosure law (slope normal_slope, N/mm^3), lift-off allowed",
}
#: Name of the node set of every loaded node (its displacements go to the .dat file).
LOADED_NSET = "NLOADED"
#: Step time of the clamping step, s (step 2's increment times follow it).
CLAMP_TIME = 1.0
#: Most grid lines of the base along one in-plane axis before it falls back to a uniform grid.
MAX_BASE_LINES = 400


def element_surface_card(name: str, faces: ArrayLike) -> str:
    """Element-face ``*SURFACE`` from rows (element, face) with 0-based element rows and faces
    0..5 (S1..S6), as :meth:`HexMesh.faces` returns them.

    >>> element_surface_card("SCONTACT", [[0, 0], [3, 1]])
    '*SURFACE, NAME=SCONTACT, TYPE=ELEMENT\\n1, S1\\n4, S2\\n'
    """
    f = np.asarray(faces)
    if (f.ndim != 2 or f.shape[1] != 2 or f.shape[0] == 0 or not np.issubdtype(f.dtype, np.integer)
            or np.any(f[:, 0] < 0) or np.any((f[:, 1] < 0) | (f[:, 1] > 5))):
        raise ParameterError(f"surface {name}: faces must be rows (element >= 0, face 0..5)")
    return (f"*SURFACE, NAME={_name('surface', name)}, TYPE=ELEMENT\n"
            + "".join(f"{int(e) + 1}, S{int(k) + 1}\n" for e, k in f))


@dataclass(frozen=True, eq=False)
class BaseSlab:
    """The rigid base: fixed C3D8 bricks below the contact plane (ids follow the mesh's).

    Attributes
    ----------
    nodes : ndarray, shape (m, 3)
        Base node coordinates, mm.
    elements : ndarray of int, shape (k, 8)
        Base connectivity, 0-based rows of ``nodes`` (C3D8 order; face S2 is the upper face).
    normal : ndarray, shape (3,)
        Unit normal of the contact plane pointing from the base into the body.
    """

    nodes: FloatArray
    elements: IntArray
    normal: FloatArray


def _grid_lines(values: FloatArray, tol: float, fallback: float) -> FloatArray:
    """Distinct coordinates of the contact nodes along an in-plane axis (merged within tol),
    with one more line each side at the mean spacing; a uniform grid if there are too many."""
    v = np.sort(values)
    keep = np.concatenate([[True], np.diff(v) > tol])
    lines = v[keep]
    if lines.size > MAX_BASE_LINES:
        n = max(1, math.ceil((lines[-1] - lines[0]) / fallback))
        lines = np.linspace(lines[0], lines[-1], min(n, MAX_BASE_LINES - 1) + 1)
    if lines.size < 2:
        raise ParameterError("the contact faces have no extent in the contact plane")
    h = (lines[-1] - lines[0]) / (lines.size - 1)
    return np.concatenate([[lines[0] - h], lines, [lines[-1] + h]])


def base_slab(mesh: HexMesh, contact_faces: ArrayLike, set_name: str = "contact") -> BaseSlab:
    """A rigid flat base just below the contact faces (they must lie in one plane).

    The base is a structured slab of C3D8 bricks whose upper face is the contact plane and
    whose grid lines, in the plane, pass through the contact faces' corner nodes plus one
    line each side (at most :data:`MAX_BASE_LINES` per axis, else a uniform grid of about the
    faces' size); its thickness is the body's extent normal to the plane. For a plane normal to
    a coordinate axis the in-plane axes are the other two.
    """
    faces = np.asarray(contact_faces, dtype=np.int64).reshape(-1, 2)
    corners = mesh.face_corners(faces)
    x = mesh.nodes[corners]  # (k, 4, 3)
    area_vec = 0.5 * np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])  # along the inward normal
    s = area_vec.sum(axis=0)
    if not np.linalg.norm(s) > 0:
        raise ParameterError(f"{mesh.source}: set {set_name!r}: the contact faces have no area")
    up = s / np.linalg.norm(s)  # HEX_FACES order: right-hand normal points into the element
    pts = mesh.nodes[np.unique(corners)]
    size = float(np.ptp(mesh.nodes, axis=0).max())
    level = pts @ up
    if np.ptp(level) > 1e-6 * size:
        raise ParameterError(
            f"{mesh.source}: set {set_name!r} is not flat (its nodes lie up to "
            f"{np.ptp(level):.3g} mm apart normal to it); the rigid base needs a flat contact face")
    axis = int(np.argmax(np.abs(up)))
    if abs(abs(up[axis]) - 1.0) < 1e-12:
        up = np.zeros(3)
        up[axis] = np.sign(s[axis])
        others = [a for a in range(3) if a != axis]
        e1, e2 = np.eye(3)[others[0]], np.eye(3)[others[1]]
        if np.dot(np.cross(e1, e2), up) < 0:
            e1, e2 = e2, e1
    else:
        e1 = np.cross(up, np.eye(3)[int(np.argmin(np.abs(up)))])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(up, e1)
    c = float(np.mean(pts @ up)) if np.ptp(pts @ up) > 0 else float((pts @ up)[0])
    edge = float(np.mean(np.linalg.norm(x - np.roll(x, 1, axis=1), axis=2)))
    tol = 1e-9 * size
    bu = _grid_lines(pts @ e1, tol, edge)
    bv = _grid_lines(pts @ e2, tol, edge)
    used = mesh.nodes[np.unique(mesh.elements)] @ up
    thickness = float(np.max(used) - c)
    if not thickness > 0 or float(np.min(used)) < c - 1e-6 * size:
        raise ParameterError(
            f"{mesh.source}: set {set_name!r}: the body reaches below the contact plane (up to "
            f"{c - float(np.min(used)):.3g} mm); the contact set must be an outer face that "
            "rests on the base")
    bw = np.array([-thickness, 0.0])
    gi, gj, gk = np.meshgrid(np.arange(bu.size), np.arange(bv.size), np.arange(2), indexing="ij")
    gi, gj, gk = (a.transpose(2, 1, 0).ravel() for a in (gi, gj, gk))  # first index fastest
    bid = np.zeros((bu.size, bv.size, 2), dtype=np.int64)
    bid[gi, gj, gk] = np.arange(gi.size)
    xyz = (bu[gi][:, None] * e1 + bv[gj][:, None] * e2 + (c + bw[gk])[:, None] * up)
    ci, cj = np.meshgrid(np.arange(bu.size - 1), np.arange(bv.size - 1), indexing="ij")
    ci, cj = ci.T.ravel(), cj.T.ravel()
    corner = ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
              (0, 1, 1))
    conn = np.stack([bid[ci + a, cj + b, k] for a, b, k in corner], axis=1)
    return BaseSlab(np.asarray(xyz, dtype=float), conn.astype(np.int64), up)


@dataclass(frozen=True, eq=False)
class MeshLoadPlan:
    """Where each load acts and how it is read back.

    Attributes
    ----------
    loads : tuple of MeshLoad
    nodes : tuple of ndarray of int
        Per load, the 0-based nodes of its faces.
    shares : tuple of ndarray
        Per load, the consistent shares of a uniform traction of 1 N (sum 1); the
        work-conjugate displacement of load l is sum_i shares_i (u_i . d_l).
    areas : tuple of float
        Per load, the area of its faces, mm^2.
    loaded : ndarray of int
        Every loaded node, 0-based, sorted (the printed node set).
    """

    loads: tuple[MeshLoad, ...]
    nodes: tuple[IntArray, ...]
    shares: tuple[FloatArray, ...]
    areas: tuple[float, ...]
    loaded: IntArray

    def conjugate(self, u: FloatArray) -> FloatArray:
        """Work-conjugate displacement of each load, shape (k, loads), from nodal displacements
        ``u`` of the loaded nodes, shape (k, len(loaded), 3), mm."""
        out = np.empty((u.shape[0], len(self.loads)))
        for j, (ld, nodes, w) in enumerate(zip(self.loads, self.nodes, self.shares,
                                               strict=True)):
            rows = np.searchsorted(self.loaded, nodes)
            out[:, j] = (u[:, rows, :] @ np.asarray(ld.direction)) @ w
        return out


def load_plan(mesh: HexMesh, loads: Sequence[MeshLoad]) -> MeshLoadPlan:
    """The faces, nodes and consistent shares of every load (sets resolved by
    :meth:`HexMesh.faces`)."""
    if not loads:
        raise ParameterError("at least one load is needed (SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG])")
    nodes, shares, areas = [], [], []
    for ld in loads:
        if not isinstance(ld, MeshLoad):
            raise ParameterError(f"loads must be MeshLoad, got {type(ld).__name__}")
        faces = mesh.faces(ld.set)
        if faces.size == 0:
            raise ParameterError(f"{mesh.source}: set {ld.set!r} holds no element face")
        n, w, a = face_load(mesh, faces)
        nodes.append(n)
        shares.append(w)
        areas.append(a)
    loaded = np.unique(np.concatenate(nodes))
    return MeshLoadPlan(tuple(loads), tuple(nodes), tuple(shares), tuple(areas), loaded)


def _load_cards(plan: MeshLoadPlan, history: LoadHistory, first_node: int = 1
                ) -> tuple[str, str]:
    """The amplitudes and the ``*CLOAD`` cards of the loads.

    One amplitude ``L<j>`` per load; the force of load j on node i along dof k is
    A_j share_i d_jk. CalculiX keeps one load per node and dof (a second ``*CLOAD`` on the
    same node and dof replaces the first), so a node and dof loaded by several loads gets the
    sum of their forces, r sin(2 pi t + psi), with an amplitude ``M<m>`` per distinct psi.
    """
    nl = len(plan.loads)
    times = history.step_time
    f_all = [history.factors[:, j] for j in range(nl)]
    # coefficient of each load on each (node, dof)
    coef: dict[tuple[int, int], np.ndarray] = {}
    for j, (ld, nodes, w) in enumerate(zip(plan.loads, plan.nodes, plan.shares, strict=True)):
        for k in range(3):
            d = ld.direction[k]
            if d == 0.0:
                continue
            for n, s in zip(nodes.tolist(), w.tolist(), strict=True):
                c = coef.setdefault((n, k), np.zeros(nl))
                c[j] += ld.amplitude * s * d
    amps = [amplitude_card(f"L{j + 1}", times, f_all[j]) for j in range(nl)]
    single: dict[tuple[int, int], list[tuple[int, float]]] = {}
    mixed: dict[tuple[bytes, int], list[tuple[int, float]]] = {}
    mixed_names: dict[bytes, str] = {}
    for (n, k), c in sorted(coef.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        nz = np.flatnonzero(c)
        if nz.size == 0:
            continue
        if nz.size == 1:
            single.setdefault((int(nz[0]), k), []).append((n, float(c[nz[0]])))
            continue
        # sum_j c_j f_j(t), tabulated as one amplitude per distinct shape
        total = sum(c[j] * f_all[j] for j in range(nl))
        scale = float(np.max(np.abs(total)))
        if scale == 0.0:
            continue
        shape = np.round(total / scale, 12)
        key = shape.tobytes()
        if key not in mixed_names:
            name = f"M{len(mixed_names) + 1}"
            mixed_names[key] = name
            amps.append(amplitude_card(name, times, total / scale))
        mixed.setdefault((key, k), []).append((n, scale))
    cloads = []
    for (j, k), rows in sorted(single.items()):
        ids = [first_node + n for n, _ in rows]
        cloads.append(cload_card(ids, k + 1, [v for _, v in rows], amplitude=f"L{j + 1}"))
    for (key, k), rows in mixed.items():
        ids = [first_node + n for n, _ in rows]
        cloads.append(cload_card(ids, k + 1, [v for _, v in rows], amplitude=mixed_names[key]))
    return "".join(amps), "".join(cloads)


def _layout(mesh: HexMesh, r: ResolvedAssembly) -> list[tuple[ResolvedContact, BaseSlab, int, int]]:
    """The rigid bases of the contacts on the base: (contact, slab, first node id, first
    element id), numbered after the mesh's nodes and elements in the contacts' order."""
    out = []
    node0, el0 = mesh.nodes.shape[0] + 1, mesh.elements.shape[0] + 1
    for c in r.contacts:
        if c.on_base:
            slab = base_slab(mesh, c.faces, c.contact.face)
            out.append((c, slab, node0, el0))
            node0 += slab.nodes.shape[0]
            el0 += slab.elements.shape[0]
    return out


def _body_cards(mesh: HexMesh, layout: Sequence[tuple[ResolvedContact, BaseSlab, int, int]],
                etype: str, heading: str) -> list[str]:
    """The heading, every node (the bodies', then each base's), the bodies' elements (BODY),
    each base's elements (BASE<k>) and each base's node set NBASE<k>."""
    parts = [heading_card(heading),
             nodes_card(np.vstack([mesh.nodes, *(b.nodes for _, b, _, _ in layout)])),
             elements_card(etype, "BODY", mesh.elements + 1, first=1)]
    parts += [elements_card("C3D8", f"BASE{c.suffix}", b.elements + n0, first=e0)
              for c, b, n0, e0 in layout]
    parts += [nset_card(f"NBASE{c.suffix}", np.arange(n0, n0 + b.nodes.shape[0]))
              for c, b, n0, _ in layout]
    return parts


def _surface_cards(r: ResolvedAssembly,
                   layout: Sequence[tuple[ResolvedContact, BaseSlab, int, int]]) -> list[str]:
    """SCONTACT<k> of every contact, SCLAMP<k> of every preload, SBASE<k> (face S2, the top)
    of every base and SCOUNTER<k> of every counter face."""
    out = [element_surface_card(c.slave, c.faces) for c in r.contacts]
    out += [element_surface_card(p.surface, p.faces) for p in r.preloads]
    for c, b, _, e0 in layout:
        ids = np.arange(e0 - 1, e0 - 1 + b.elements.shape[0])
        out.append(element_surface_card(c.master, np.column_stack([ids, np.ones_like(ids)])))
    out += [element_surface_card(c.master, c.counter_faces) for c in r.contacts
            if c.counter_faces is not None]
    return out


def _boundary(r: ResolvedAssembly,
              layout: Sequence[tuple[ResolvedContact, BaseSlab, int, int]]) -> str:
    """Every base node held, then the supports."""
    rows = [(f"NBASE{c.suffix}", 1, 3) for c, _, _, _ in layout] + boundary_rows(r)
    if not rows:
        raise ParameterError(
            "the assembly holds nothing: no contact on the rigid base and no support; give a "
            "support (--fixed SET[:DIRECTIONS]) to the body that carries the others")
    return boundary_card(rows)


def _clamping_step(r: ResolvedAssembly) -> list[str]:
    """The clamping step's opening: its comment, ``*STEP``, ``*STATIC`` and the preloads."""
    comments, dsloads = preload_cards(r)
    return [*comments, step_card(100), static_card(1.0, CLAMP_TIME, direct=False), *dsloads]


def _where(r: ResolvedAssembly) -> str:
    """The heading's tail: where the bodies touch."""
    a = r.assembly
    if len(a.contacts) == 1 and a.rigid_base_only:
        return "on a rigid base"
    return "contacts " + "; ".join(c.label + (" on a rigid base" if c.counter is None else "")
                                   for c in a.contacts)


def _check_normal_contact(a: Assembly) -> None:
    if a.normal_contact not in NORMAL_CONTACTS:
        raise ParameterError(
            f"normal_contact must be {' or '.join(repr(k) for k in NORMAL_CONTACTS)} for "
            f"CalculiX, got {a.normal_contact!r}: its contact pressure always follows the "
            "overclosure, so normal forces frozen at the clamping step ('fixed') have no "
            "counterpart; compare with the built-in solver's 'penalty' (validate --mesh compares "
            "'fixed' with CalculiX's stiff penalty contact, and says so)")


def build_mesh_deck(mesh: HexMesh, assembly: Assembly | MeshClamp, *,
                    loads: Sequence[MeshLoad], increments_per_cycle: int = 40,
                    cycles: int = 1, max_iterations: int = 26, startup: str = "quarter",
                    formulation: str = "face-to-face") -> str:
    """The complete ``.inp`` deck of the user's mesh and its assembly.

    Parameters
    ----------
    mesh : HexMesh
        8-node (C3D8I) or 20-node (C3D20R) hexahedra, mm; one or more bodies.
    assembly : Assembly or MeshClamp
        The contacts (on another body or on a rigid base), the preloads (the clamping step),
        the supports, the materials and the contact law (:mod:`.assemblydeck`). The law's
        ``normal_contact`` must be a key of :data:`NORMAL_CONTACTS` (``"penalty"``; ``"fixed"``
        is refused). The rigid-base shorthand (a :class:`~microslip.fe.clamp.MeshClamp`, or
        :func:`~microslip.fe.assembly.rigid_base`) writes the one-body deck of issue 22.
    loads : sequence of MeshLoad
        F_l(t) = A_l sin(2 pi t + phi_l) on their sets (:func:`~.meshhistory.load_factors`).
    increments_per_cycle, cycles : int
        Equal ``DIRECT`` increments per cycle (a multiple of 4) and full cycles after the
        start-up (:func:`~.meshhistory.load_history`).
    max_iterations : int
        Equilibrium iterations per increment (``*CONTROLS`` I_C; the box deck's 26).
    startup : str
        How the loads start (:data:`~.meshhistory.STARTUPS`): ``"quarter"`` (the paper's load
        step) or ``"ramp"`` (the built-in own-mesh solver's sine cycles, sample for sample).
    formulation : str
        A key of :data:`CONTACT_FORMULATIONS`: ``"face-to-face"`` (default) or
        ``"node-to-surface"`` (the built-in solver's nodal law).

    Returns
    -------
    str
        The deck text, ending with a newline.
    """
    if not isinstance(mesh, HexMesh):
        raise ParameterError("build_mesh_deck needs a HexMesh")
    a = as_assembly(assembly)
    _check_normal_contact(a)
    check_formulation(formulation)
    r = resolve_assembly(mesh, a)
    plan = load_plan(mesh, loads)
    history = load_history(plan.loads, increments_per_cycle, cycles, startup)
    layout = _layout(mesh, r)
    etype = MESH_ELEMENTS[mesh.nodes_per_element]
    n_el = mesh.elements.shape[0]
    amps, cloads = _load_cards(plan, history)
    n = int(history.time.size - 1)
    dt = 1.0 / increments_per_cycle
    ext = np.ptp(mesh.nodes, axis=0)
    loads_txt = "; ".join(
        f"{ld.set} {ld.amplitude:g} N along ({', '.join(f'{d:g}' for d in ld.direction)}) "
        f"at {ld.phase_deg:g} deg" for ld in plan.loads)
    parts = [
        *_body_cards(mesh, layout, etype,
                     f"microslip own mesh {mesh.source}: {n_el} {etype}, "
                     f"{ext[0]:g} x {ext[1]:g} x {ext[2]:g} mm, {_where(r)}"),
        nset_card(LOADED_NSET, plan.loaded + 1),
        support_cards(r),
        *_surface_cards(r, layout),
        *material_cards(r),
        *contact_cards(r, formulation),
        _boundary(r, layout),
        amps,
        *_clamping_step(r),
        node_print_card(LOADED_NSET),
        node_file_card(),
        contact_file_card(),
        end_step_card(),
        f"** step 2: {loads_txt}; {cycles} cycle(s) after {_STARTUP_TEXT[startup]}, "
        f"{increments_per_cycle} increments per cycle\n",
        step_card(n + 10),
        static_card(dt, float(history.step_time[-1]), direct=True),
        controls_card(max_iterations),
        cloads,
        node_print_card(LOADED_NSET),
        node_file_card(),
        contact_file_card(),
        end_step_card(),
    ]
    return "".join(parts)


def build_frequency_deck(mesh: HexMesh, assembly: Assembly | MeshClamp, *,
                         density_kg_m3: float | None = None, modes: int = 10,
                         element: str | None = None) -> str:
    """The deck of the linear modes about the clamped state (issue 23): the deck of
    :func:`build_mesh_deck` without loads, the materials with ``*DENSITY`` (t/mm^3), step 1
    the preloads, step 2 ``*STEP, PERTURBATION`` with ``*FREQUENCY``: only there does
    CalculiX linearise the contact of the clamping step (normal slope and stick slope); a
    frequency step without it ignores the contact, and every mode is a 0 Hz rigid motion.
    The eigenvalues go to the ``.dat`` file (:func:`~microslip.fe.calculix.meshrun.
    read_frequencies`). Face-to-face penalty contact with the assembly's normal slope, whatever
    its ``normal_contact``. ``density_kg_m3``: the density of a material that gives none.
    ``element``: the 8-node element type (default C3D8I, the built-in solver's; C3D8 for a
    comparison free of the two incompatible-mode formulations)."""
    if not isinstance(mesh, HexMesh):
        raise ParameterError("build_frequency_deck needs a HexMesh")
    if density_kg_m3 is not None:
        _check_positive("density", density_kg_m3, "kg/m^3")
    if isinstance(modes, bool) or not isinstance(modes, int) or not 1 <= modes <= 1000:
        raise ParameterError(f"modes must be a whole number in [1, 1000], got {modes!r}")
    r = resolve_assembly(mesh, assembly)
    layout = _layout(mesh, r)
    etype = MESH_ELEMENTS[mesh.nodes_per_element]
    if element is not None:
        if mesh.nodes_per_element != 8 or element not in ("C3D8I", "C3D8"):
            raise ParameterError(f"element must be C3D8I or C3D8 for 8-node hexahedra, got "
                                 f"{element!r}")
        etype = element
    parts = [
        *_body_cards(mesh, layout, etype,
                     f"microslip own mesh {mesh.source}: linear modes about the clamped "
                     f"state, {mesh.elements.shape[0]} {etype}"),
        support_cards(r),
        *_surface_cards(r, layout),
        *material_cards(r, density=True, default_density=density_kg_m3),
        *contact_cards(r, "face-to-face"),
        _boundary(r, layout),
        *_clamping_step(r),
        end_step_card(),
        "** step 2: linear modes with the contact linearised about the clamped state\n",
        "*STEP, PERTURBATION\n*FREQUENCY\n",
        f"{modes}\n",
        end_step_card(),
    ]
    return "".join(parts)


def _check_positive(name: str, value: float, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}") from None
    if not (math.isfinite(v) and v > 0):
        raise ParameterError(f"{name} must be > 0 {unit}, got {value!r}")
    return v
