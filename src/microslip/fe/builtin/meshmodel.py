"""The frictional finite-element model on the user's own hexahedral mesh (issue 22).

The same physics as the built-in box (:mod:`.solve`), on any :class:`~microslip.fe.hexmesh.HexMesh`
of 8-node hexahedra:

* the elastic body (C3D8I or C3D8, :func:`~microslip.fe.builtin.element.assemble_hex8`; on
  20-node meshes C3D20R or C3D20, :mod:`.hex20`, whose contact nodes get CalculiX's
  node-to-face areas and, under ``fixed`` normal contact, N_i from the recovered pressure);
* a flat *contact* set on a rigid base: its nodes carry the circular Coulomb friction of
  :mod:`.contact` with the stick stiffness k_i = lambda A_i, A_i the node's share of the
  contact faces' area (CalculiX's node-to-surface share, a quarter of each face at each of
  its corners: on a parallelogram the consistent share of a uniform traction, as the box's
  tributary areas; :data:`LINEAR_CONTACT_WEIGHTS`); the normal contact is ``fixed``
  (u_n = 0 held, N_i the normal reactions of the clamping step) or ``penalty``
  (N_i = k_n A_i max(0, -u_n), lift-off allowed), exactly as :mod:`.normal`;
* the *clamping step* first: a uniform pressure F_N / A_clamp on the clamp set's faces
  (consistent nodal forces, :func:`~microslip.fe.hexmesh.face_load`), with the friction
  active from zero slip (:func:`~microslip.fe.builtin.solve.clamping_step`).

The body is solved in the contact plane's frame: the mesh is rotated so that the contact
face's outward normal is -z (no rotation when it already is), so that every contact node has
its tangential dofs x, y and its normal dof z, as in the box. Nodes are renumbered by reverse
Cuthill-McKee when that narrows the band (LAPACK banded Cholesky, :mod:`.linalg`); a mesh
whose band stays wide is factorised by SuperLU. The tangential loading is :mod:`.meshrun`.
Units: N, mm, MPa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...blas import single_threaded_blas
from ...errors import ParameterError
from ..assembly import Assembly, as_assembly
from ..hanging import hanging_of
from ..hexmesh import HexMesh, face_load
from ..meshload import MeshLoad
from .bodies import contact_layout, element_materials, ground_springs, relative_transform
from .condense import Reduced, condense
from .element import assemble_hex8, hex8_b_matrices
from .hex20 import (
    DEFAULT_CONTACT_WEIGHTS,
    HEX20_ELEMENTS,
    QuadContact,
    RecoveredNormal,
    assemble_hex20,
    contact_areas,
    face_nodes20,
    hex20_b_matrices,
)
from .linalg import Backend, make_backend
from .meshgeometry import FLAT_TOL, connected, contact_rotation, numbering, plane, set_faces
from .model import NewtonOptions
from .normal import PenaltyNormal, check_normal_contact
from .solve import clamping_step, contact_partition

__all__ = [
    "AUTO_BAND_LIMIT",
    "CONDENSE_MIN_DOF",
    "LINEAR_CONTACT_WEIGHTS",
    "MESH_ELEMENTS",
    "MESH_LINEAR_SOLVERS",
    "MeshModel",
    "SpentBackend",
    "build_mesh_model",
    "set_faces",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: ``auto`` takes the banded Cholesky while the half-bandwidth (dofs) is at most this.
AUTO_BAND_LIMIT = 1200
#: ``condensed=None`` condenses the body onto the contact from this many free dofs on.
CONDENSE_MIN_DOF = 1000
#: Linear solvers of the own-mesh model: ``auto`` (banded or splu by the band) and those of
#: :data:`~microslip.fe.builtin.linalg.LINEAR_SOLVERS`.
MESH_LINEAR_SOLVERS = ("auto", "banded", "splu", "cholmod")
_IDENTITY = np.eye(3)
#: Passes at most of the clamping step's active set under ``fixed`` normal contact (held
#: nodes in tension released, released ones below the base pressed back).
MAX_ACTIVE_SET = 30


@dataclass(frozen=True, eq=False)
class MeshModel:
    """A clamped body of the user's mesh after the clamping step, ready for tangential loads.

    Attributes
    ----------
    mesh : HexMesh
    assembly : Assembly
        What it was built from (contacts, preloads, supports, materials, contact law); the
        shorthand's names ``contact_set``, ``clamp_set``, ``modulus``, ``poisson_ratio``,
        ``friction``, ``clamp_force`` (F_N, N: the largest preload) and ``stick_slope`` are
        read from it.
    element : str
    normal : PenaltyNormal or None
        ``penalty`` normal contact; None: ``fixed``.
    rotation : ndarray, shape (3, 3)
        Rows: the contact plane's axes e1, e2 and its inward normal e3 (global components);
        the model's frame is ``R @ x``.
    order : ndarray of int, shape (n_used,)
        Mesh node of each model node (the solver's numbering).
    index : ndarray of int, shape (3 n_used,)
        Free-dof position of each model dof (3 node + component, model frame), -1 if held.
    free : ndarray of int
        Model dofs that are unknowns.
    stiffness : scipy.sparse.csr_matrix
        K of the free dofs, N/mm.
    contact_nodes : ndarray of int, shape (n_c,)
        Mesh nodes of the contact set.
    contact_dofs : ndarray of int, shape (n_c, 2)
        Free-dof positions of their e1 and e2 dofs.
    contact_area : ndarray, shape (n_c,)
        A_i, mm^2 (sum: the contact faces' area).
    contact_stiffness : ndarray, shape (n_c,)
        lambda A_i, N/mm.
    normal_force : ndarray, shape (n_c,)
        N_i after the clamping step, N.
    friction_limit : ndarray, shape (n_c,)
        mu N_i, N.
    clamp_load : ndarray
        Nodal forces of the clamping pressure on the free dofs, N.
    u0, slip0 : ndarray
        Free-dof displacements (mm) and contact slips (n_c, 2; mm) after clamping.
    size : float
        Largest extent of the mesh, mm.
    backend : Backend
        The linear solver of the free dofs' tangent; a :class:`SpentBackend` (its name only)
        when the body is condensed.
    reduced : Reduced or None
        The body condensed onto the contact dofs (:mod:`.condense`), which the tangential
        loading then steps; None: the loading steps every free dof.
    transform : scipy.sparse.csr_matrix or None
        T with u = T v (model frame, every model dof): the nodal displacements from the
        model's unknowns, whose contact nodes of a pair hold their displacement relative to
        their partner (:mod:`.bodies`); None: the identity (no pair).
    contact_master : ndarray of int, shape (n_c,) or None
        Model node of each contact node's partner on the counter face (-1: the rigid base).
    ground : scipy.sparse.csr_matrix or None
        A free-free assembly's six determinate soft springs on the free dofs (in
        ``stiffness``; :func:`~.bodies.ground_springs`), which the modes take out; None: the
        assembly is held.
    """

    mesh: HexMesh
    assembly: Assembly
    element: str
    normal: PenaltyNormal | None
    rotation: FloatArray = field(repr=False)
    order: IntArray = field(repr=False)
    index: IntArray = field(repr=False)
    free: IntArray = field(repr=False)
    stiffness: sp.csr_matrix = field(repr=False)
    contact_nodes: IntArray = field(repr=False)
    contact_dofs: IntArray = field(repr=False)
    contact_area: FloatArray = field(repr=False)
    contact_stiffness: FloatArray = field(repr=False)
    normal_force: FloatArray = field(repr=False)
    friction_limit: FloatArray = field(repr=False)
    clamp_load: FloatArray = field(repr=False)
    u0: FloatArray = field(repr=False)
    slip0: FloatArray = field(repr=False)
    size: float
    clamp_iterations: int
    backend: Backend = field(repr=False)
    setup_s: float
    newton: NewtonOptions
    reduced: Reduced | None = field(default=None, repr=False)
    transform: sp.csr_matrix | None = field(default=None, repr=False)
    contact_master: IntArray | None = field(default=None, repr=False)
    ground: sp.csr_matrix | None = field(default=None, repr=False)

    @property
    def free_free(self) -> bool:
        """No support and no rigid base: six rigid-body modes, set aside by the modes."""
        return self.ground is not None

    # the assembly's values under the names the studies read
    @property
    def contact_set(self) -> str:
        return self.assembly.contact_set

    @property
    def clamp_set(self) -> str:
        return self.assembly.clamp_set

    @property
    def modulus(self) -> float:
        return self.assembly.modulus

    @property
    def poisson_ratio(self) -> float:
        return self.assembly.poisson_ratio

    @property
    def friction(self) -> float:
        return self.assembly.friction

    @property
    def clamp_force(self) -> float:
        return self.assembly.clamp_force

    @property
    def stick_slope(self) -> float:
        return self.assembly.stick_slope

    @property
    def dof(self) -> int:
        """Number of unknowns (free dofs)."""
        return int(self.free.size)

    @property
    def normal_contact(self) -> str:
        """``fixed`` or ``penalty``."""
        return "fixed" if self.normal is None else "penalty"

    @property
    def closed(self) -> NDArray[np.bool_]:
        """(n_c,): True where the contact node presses on the base after the clamping step
        (N_i > 0). The others (``penalty`` normal contact, lifted off by the clamping) are
        *open*: they carry nothing in the stuck linearisation (no stick spring, no normal
        penalty) until they close."""
        return np.asarray(self.normal_force > 0.0)

    @property
    def preload(self) -> FloatArray:
        """(n_c,): the signed normal preload after clamping, N: N_i for ``fixed`` normal
        contact; k_n A_i (-u_n,i) for ``penalty``, which is N_i where the node is closed and
        minus the normal slope times its gap where it is open (< 0: the force the gap must
        close before the node presses again)."""
        if self.normal is None:
            return np.asarray(self.normal_force, dtype=float)
        return np.asarray(self.normal.stiffness * self.normal.penetration(self.u0), dtype=float)

    @property
    def force_scale(self) -> float:
        """mu F_N, N: the largest tangential force the interface carries; the scale of the
        residual tolerance."""
        return self.friction * self.clamp_force

    def model_nodes(self, nodes: IntArray) -> IntArray:
        """Model node numbers of mesh nodes."""
        inv = np.full(len(self.mesh.nodes), -1, dtype=np.int64)
        inv[self.order] = np.arange(self.order.size)
        out = inv[nodes]
        if np.any(out < 0):
            raise ParameterError(f"{self.mesh.source}: a set holds nodes of no element")
        return out

    def unit_load(self, load: MeshLoad) -> FloatArray:
        """Nodal forces on the free dofs of a uniform traction of total 1 N over the load's
        set along its direction (consistent shares); also the weights of its work-conjugate
        displacement (force-weighted mean of the set's displacements along the direction)."""
        nodes, share, _ = face_load(self.mesh, set_faces(self.mesh, load.set, "set of a load"))
        d = self.rotation @ np.asarray(load.direction, dtype=float)
        base = 3 * self.model_nodes(nodes)
        if self.transform is not None:  # nodal forces f act on v as T^T f
            full = np.zeros(self.index.size)
            for c in range(3):
                full[base + c] = share * d[c]
            return self.model_forces(full)
        out = np.zeros(self.free.size)
        for c in range(3):
            pos = self.index[base + c]
            held = pos < 0
            out[pos[~held]] = share[~held] * d[c]
        return out

    def model_forces(self, full: FloatArray) -> FloatArray:
        """Nodal forces on every model dof (model frame, N) as forces on the free dofs
        (T^T f restricted to the unknowns)."""
        f = np.asarray(full, dtype=float)
        if self.transform is not None:
            f = np.asarray(self.transform.T @ f)
        return np.asarray(f[self.free], dtype=float)

    def nodal(self, full: FloatArray) -> FloatArray:
        """Model-dof values (..., 3 n_used) as nodal displacements (u = T v)."""
        if self.transform is None:
            return full
        return np.asarray((self.transform @ full.reshape(-1, full.shape[-1]).T).T
                          ).reshape(full.shape)

    def global_vectors(self, u: FloatArray) -> FloatArray:
        """Free-dof displacements (..., dof) as mesh-node vectors (..., n_nodes, 3), global
        frame, mm (held dofs and nodes of no element: 0). A free-free assembly's are given
        without its rigid-body motion (the least-squares rigid motion of its nodes, weighted
        by their volumes, removed: its soft determinate support fixes no physical frame)."""
        u = np.asarray(u, dtype=float)
        full = np.zeros((*u.shape[:-1], self.index.size))
        full[..., self.free] = u
        local = self.nodal(full).reshape(*u.shape[:-1], self.order.size, 3)
        out = np.zeros((*u.shape[:-1], len(self.mesh.nodes), 3))
        # the identity (the contact already faces -z) is skipped: one copy of every state
        # fewer when a run's fields are converted (qsma records 400 states of 50k dofs)
        out[..., self.order, :] = (local if np.array_equal(self.rotation, _IDENTITY)
                                   else local @ self.rotation)
        if self.free_free:
            out[..., self.order, :] -= _rigid_part(self, out[..., self.order, :])
        return out

    def describe(self) -> dict[str, Any]:
        """What the solver built (the JSON's ``model`` object, issue 34): the mesh's size, the
        element and the normal law; each role set's faces and area (mm^2); each preload's
        pressure F / A (MPa); the contact nodes closed and open after the preload step; the
        bodies, the supports and the assembly."""
        from .bodies import body_labels

        sets: dict[str, Any] = {}
        roles = [(c.face, "contact") for c in self.assembly.contacts]
        roles += [(c.counter, "counter face") for c in self.assembly.contacts if c.counter]
        roles += [(p.face, "preload") for p in self.assembly.preloads]
        for name, role in roles:
            faces = set_faces(self.mesh, name, role)
            sets[name] = {"role": role, "faces": len(faces),
                          "area_mm2": float(face_load(self.mesh, faces)[2])}
        for p in self.assembly.preloads:
            sets[p.face]["force_N"] = p.force
            sets[p.face]["pressure_MPa"] = p.force / sets[p.face]["area_mm2"]
        for s in self.assembly.supports:
            sets.setdefault(s.set, {"role": "support"})["directions"] = s.directions
        closed = int(np.count_nonzero(self.closed))
        return {"source": self.mesh.source, "nodes": len(self.mesh.nodes),
                "elements": len(self.mesh.elements), "element": self.element,
                "dof": self.dof, "bodies": body_labels(self.mesh)[0],
                "normal_contact": self.normal_contact, "sets": sets,
                "contact_nodes": int(self.contact_nodes.size),
                "contact_area_mm2": float(self.contact_area.sum()),
                "closed_after_preload": closed,
                "open_after_preload": int(self.contact_nodes.size) - closed,
                "contact_force_N": float(self.normal_force.sum()),
                "linear_solver": self.backend.name if self.reduced is None
                else f"condensed ({self.reduced.keep.size} contact dofs)",
                "assembly": self.assembly.describe()}


class SpentBackend:
    """The full model's linear solver once the body is condensed (:mod:`.condense`): the
    tangential loading then factorises only the condensed tangent, so the full factor (on
    the 50k-DOF cantilever the banded backend's K and reference factor, 0.4 GB) is dropped;
    its name and half-bandwidth are kept for the reports and for rebuilding the model.
    (A plain class: :class:`~.linalg.Backend` wants ``name`` settable.)"""

    def __init__(self, name: str, half_bandwidth: int | None = None) -> None:
        self.name, self.half_bandwidth = name, half_bandwidth

    def factor(self, d: FloatArray) -> Any:
        raise RuntimeError(f"the full {self.name} factor was dropped when the body was "
                           "condensed; step the condensed body (model.reduced)")


def _spent(backend: Backend) -> SpentBackend:
    return SpentBackend(backend.name, getattr(backend, "half_bandwidth", None))


def _poisson(nu: Any) -> float:
    try:
        x = float(nu)
    except (TypeError, ValueError):
        x = math.nan
    if not (math.isfinite(x) and -1.0 < x < 0.5):
        raise ParameterError(f"poisson_ratio must be in (-1, 0.5), got {nu!r}")
    return x


def _backend(name: str, k_ff: sp.csr_matrix, cdofs: IntArray, kc: FloatArray,
             kn: FloatArray | None) -> Backend:
    if name not in MESH_LINEAR_SOLVERS:
        raise ParameterError(f"unknown linear solver {name!r}; choose one of "
                             f"{', '.join(MESH_LINEAR_SOLVERS)}")
    if name == "auto":
        coo = sp.tril(k_ff, format="coo")
        kd = int(np.max(coo.row - coo.col)) if coo.nnz else 0
        name = "banded" if kd <= AUTO_BAND_LIMIT else "splu"
    backend = make_backend(name, k_ff, cdofs[:, 0], cdofs[:, 1], kc, kn)
    if name != "banded":  # the banded backend factorised the all-stick tangent already
        d = [kc, np.zeros_like(kc), kc] + ([] if kn is None else [kn])
        try:
            backend.factor(np.stack(d, axis=1))
        except RuntimeError:
            raise ParameterError("the stiffness is singular with every contact node stuck: "
                                 "the contact does not hold the body") from None
    return backend


def build_mesh_model(mesh: HexMesh, assembly: Assembly | Any, *, element: str | None = None,
                     linear_solver: str = "auto", newton: NewtonOptions | None = None,
                     condensed: bool | None = None,
                     contact_weights: str = DEFAULT_CONTACT_WEIGHTS) -> MeshModel:
    """Assemble the bodies of a mesh and solve the clamping (preload) step.

    Parameters
    ----------
    mesh : HexMesh
        8- or 20-node hexahedra, mm.
    assembly : Assembly or MeshClamp
        The contacts (a face on the rigid base, or a face and its counter face on another
        body, conforming), the preloads, the supports, the materials and the contact law
        (:class:`~microslip.fe.assembly.Assembly`; a
        :class:`~microslip.fe.clamp.MeshClamp` is its rigid-base shorthand).
    element : {"C3D8I", "C3D8"} for 8-node meshes, {"C3D20R", "C3D20"} for 20-node ones
        Default: C3D8I, C3D20R (:data:`MESH_ELEMENTS`).
    linear_solver : {"auto", "banded", "splu", "cholmod"}
        ``auto``: banded Cholesky while the half-bandwidth is at most
        :data:`AUTO_BAND_LIMIT` dofs, SuperLU beyond.
    newton : NewtonOptions, optional
    condensed : bool, optional
        Step the tangential loading on the body condensed onto its contact dofs
        (:mod:`.condense`; the same answer to rounding, much faster when the contact is a
        small part of the body). Default: when the model has at least
        :data:`CONDENSE_MIN_DOF` free dofs and the contact at most a quarter of them.
    contact_weights : str
        The nodal areas of the contact faces: on 20-node meshes a name of
        :data:`~microslip.fe.builtin.hex20.CONTACT_WEIGHTS` (default CalculiX's node-to-face
        1/100 and 24/100 of each face's area), on 8-node ones of
        :data:`LINEAR_CONTACT_WEIGHTS` (default CalculiX's node-to-surface quarters).

    Returns
    -------
    MeshModel

    Examples
    --------
    >>> from microslip import preset
    >>> from microslip.fe.assembly import rigid_base
    >>> p = preset("table1")
    >>> from microslip.fe.examples import box_hexmesh
    >>> m = build_mesh_model(box_hexmesh(p, (8, 2, 1)), rigid_base(
    ...     contact_set="contact", clamp_set="clamp", normal_force=445.0, modulus=p.modulus,
    ...     poisson_ratio=p.poisson_ratio, friction=p.friction))
    >>> m.dof, round(float(m.normal_force.sum()), 6)
    (135, 445.0)
    """
    t0 = time.perf_counter()
    if not isinstance(mesh, HexMesh):
        raise ParameterError(f"mesh must be a HexMesh, got {type(mesh).__name__}")
    assembly = as_assembly(assembly)
    kind = MESH_ELEMENTS[mesh.nodes_per_element]
    element = kind.default if element is None else element
    if element not in kind.elements:
        raise ParameterError(f"unknown element {element!r} for {mesh.nodes_per_element}-node "
                             f"hexahedra; choose one of {', '.join(kind.elements)}")
    f_n = assembly.clamp_force
    mu, lam, k_n = assembly.friction, assembly.stick_slope, assembly.normal_slope
    penalty = check_normal_contact(assembly.normal_contact) == "penalty"
    newton = NewtonOptions() if newton is None else newton

    try:
        kind.jacobians(mesh.nodes[mesh.elements])
    except ParameterError as exc:
        raise ParameterError(f"{mesh.source}: {exc}") from None
    layout = contact_layout(mesh, assembly)
    contact_faces, outward, offset = layout.faces, layout.outward, layout.offset
    size = float(np.max(np.ptp(mesh.nodes, axis=0)))
    groups = element_materials(mesh, assembly.materials)
    bolts = tuple(np.concatenate([_face_nodes_of(mesh, b.head), _face_nodes_of(mesh, b.nut)])
                  for b in assembly.shanks)
    hanging = hanging_of(mesh)  # a locally refined mesh's constraints (:mod:`..hanging`)
    joined = layout.numbering_elements(mesh.elements, bolts)
    if hanging is not None:
        if mesh.nodes_per_element != 8:
            raise ParameterError(f"{mesh.source}: hanging nodes on 20-node hexahedra are not "
                                 "supported; refine the 8-node mesh")
        joined = np.concatenate([joined, hanging.numbering_rows(joined.shape[1])])
    order = numbering(joined, np.unique(mesh.face_corners(contact_faces)))
    on_base = layout.base_body_nodes(order)
    if on_base.size and float(np.max(mesh.nodes[on_base] @ outward - offset)) > FLAT_TOL * size:
        raise ParameterError(f"{mesh.source}: the body reaches through the plane of its "
                             f"contact set {layout.base_name!r}: the rigid base would cut it")
    inv = np.full(len(mesh.nodes), -1, dtype=np.int64)
    inv[order] = np.arange(order.size)
    elements = inv[mesh.elements]
    if assembly.is_shorthand:
        connected(mesh, elements, order.size, contact_faces, assembly.contact_set)
    else:
        layout.check_held(mesh, assembly)
    rotation = contact_rotation(outward)
    nodes = mesh.nodes[order]
    if not np.array_equal(rotation, np.eye(3)):
        nodes = nodes @ rotation.T
    k_all = None
    for rows, mat in groups:
        part = kind.assemble(nodes, elements if len(groups) == 1 else elements[rows],
                             mat.modulus, mat.poisson_ratio, element)
        k_all = part if k_all is None else k_all + part
    assert k_all is not None

    c_mesh, area, quad = _contact_areas(mesh, contact_faces, contact_weights)
    if hanging is not None:  # a hanging node's area goes to its parents (T^T a)
        c_mesh, area = hanging.lump(c_mesh, area)
    c_model = inv[c_mesh]
    sort = np.argsort(c_model)
    contact_nodes, contact = c_mesh[sort], c_model[sort]
    area = area[sort]
    master = layout.masters(contact_nodes)
    n_all = 3 * order.size
    # Preloads: each force along its face's inward normal, consistent shares (of a uniform
    # traction, or of its distribution: Preload.shares).
    full = np.zeros(n_all)
    for (face, force), preload in zip(layout.preloads, assembly.preloads, strict=True):
        k_mesh, k_share = preload.shares(mesh, face)
        push = -(rotation @ plane(mesh, face, "")[0])
        base = 3 * inv[k_mesh]
        for c in range(3):
            full[base + c] += force * k_share * push[c]
    transform = None
    if np.any(master >= 0) or hanging is not None:
        # relative interface coordinates and hanging nodes: u = T v (:mod:`.bodies`)
        paired = master >= 0
        transform = relative_transform(
            contact[paired], inv[master[paired]], order.size,
            None if hanging is None else hanging.in_numbering(inv))
        k_all = (transform.T @ k_all @ transform).tocsr()
        full = np.asarray(transform.T @ full)
        if hanging is not None:  # the product drops the entries that cancel
            k_all = _node_blocks(k_all)
    supports = layout.support_dofs(inv, rotation)
    ground = None
    if layout.free_free:  # determinate soft springs against the rigid motions (:mod:`.bodies`)
        _check_balanced(mesh, full, nodes, size)
        ground = ground_springs(nodes, contact, k_all)
        k_all = (k_all + ground).tocsr()
    if hanging is not None:  # a hanging node's own unknowns are held (its row is in T)
        held_h = hanging.dofs(inv)
        supports = held_h if supports is None else np.union1d(supports, held_h)
    gap = layout.gaps(mesh, contact_nodes)
    # fixed normal contact: nodes the clamp pulls off the base are released (active set);
    # quadratic faces recover N_i from the pressure instead (their corner reactions are
    # negative by the face's consistent weights, not by lift-off): one pass. A curved face
    # starts with the nodes that touch the base held (at u_n = -g_0) and the others released
    released = None if penalty or quad is not None else np.zeros(contact.size, dtype=bool)
    if gap is not None and not penalty:
        released = gap > FLAT_TOL * size
    if (gap is not None and released is not None and assembly.rigid_base_only
            and condensed is not False and n_all >= CONDENSE_MIN_DOF):
        # a curved face pressed under fixed contact: the active set on the condensed
        # candidates, the tangential loading on the pressing nodes (:mod:`.curved`)
        return _curved_model(mesh, assembly, element, k_all, contact, contact_nodes, area,
                             np.where(released, gap, 0.0), supports, full, newton, rotation,
                             order, size, t0, inv, master, linear_solver, transform)
    try:
        for _ in range(MAX_ACTIVE_SET):
            free, index, k_ff, k_rf, cdofs, kc, springs = contact_partition(
                k_all, contact, area, lam, k_n, penalty, released, supports,
                None if gap is None or not penalty else gap)
            with single_threaded_blas():  # a threaded BLAS only fights for the 2 cores here
                backend = _backend(linear_solver, k_ff, cdofs, kc,
                                   None if springs is None else springs.stiffness)
            clamp = full[free]
            held = 3 * (contact if released is None else contact[~released]) + 2
            clamp_fixed = None if penalty or not np.any(full[held]) else full[held]
            if gap is not None and released is not None:  # held at u_n = -g_0
                g_h = gap[~released]
                clamp = clamp + np.asarray(k_rf.T @ g_h)
                clamp_fixed = full[held] + np.asarray(k_all[held][:, held] @ g_h)
            reactions: Any = k_rf
            if quad is not None and not penalty:  # quadratic faces: N_i from the pressure
                reactions = RecoveredNormal(k_rf, quad.permuted(sort), clamp_fixed)
                clamp_fixed = None
            try:
                normal, limit, u, resp, iters = clamping_step(
                    k_ff, reactions, backend, cdofs, kc, springs, clamp, newton, mu, f_n,
                    clamp_fixed, released)
            except ParameterError as exc:
                if quad is None or penalty:
                    raise
                # no active set here: a node-by-node release on the recovered N_i (a face's
                # pressure shared among its nodes) cycles on lifting parts (lap.msh, bracket)
                raise ParameterError(
                    f"{mesh.source}: {str(exc).split('; ')[0]}, and fixed normal contact on "
                    "20-node faces cannot release them (their normal forces come from the "
                    "face's recovered pressure, which ties neighbouring nodes together, so "
                    "hex8's node-by-node release never settles); use --element hex8 with "
                    "fixed contact, or --normal-contact penalty with hex20") from None
            if released is None:
                break
            # release the held nodes in tension; press back the released ones below the base
            below = np.zeros(contact.size, dtype=bool)
            below[released] = u[index[3 * contact[released] + 2]] + (
                0.0 if gap is None else gap[released]) < 0.0
            new = (released | ((normal <= 0.0) & ~released)) & ~below
            if np.array_equal(new, released):
                break
            if np.all(new):
                raise ParameterError(f"{mesh.source}: the clamp pulls every contact node off "
                                     "the base: nothing holds the body")
            released = new
        else:
            raise ParameterError(f"{mesh.source}: the clamping step's contact state (which "
                                 f"nodes press, which lift off) did not settle in "
                                 f"{MAX_ACTIVE_SET} passes")
    except (np.linalg.LinAlgError, RuntimeError) as err:
        if assembly.is_shorthand:
            raise ParameterError(
                f"{mesh.source}: the body is not held after clamping (its stiffness is "
                f"singular: {err}); the contact set {assembly.contact_set!r} must be the face "
                f"on the base and the clamp set {assembly.clamp_set!r} must press the body "
                "onto it") from None
        raise ParameterError(
            f"{mesh.source}: the assembly is not held after its preload step (its stiffness "
            f"is singular: {err}); every body needs a support, a face on the rigid base or a "
            "contact pressed by a preload, and the supports must stop its rigid motions"
        ) from None
    n_keep = contact.size * (3 if penalty else 2)
    if condensed is None:
        condensed = free.size >= CONDENSE_MIN_DOF and 4 * n_keep <= free.size
    if assembly.shanks:  # the bolts' shanks carry load after the preload (:mod:`.shank`)
        shank = _shanks(mesh, assembly, nodes, inv, transform)[free][:, free]
        k_ff = (k_ff + shank).tocsr()
        clamp = clamp + np.asarray(shank @ u)
        if not condensed:  # the condensation factorises its own
            with single_threaded_blas():
                backend = _backend(linear_solver, k_ff, cdofs, kc,
                                   None if springs is None else springs.stiffness)
    if condensed:  # the full factor goes before the condensation builds its own
        backend = _spent(backend)
    with single_threaded_blas():
        reduced = (condense(k_ff, cdofs, springs, clamp, u, AUTO_BAND_LIMIT) if condensed
                   else None)
    return MeshModel(
        mesh=mesh, assembly=assembly, element=element,
        normal=springs, rotation=rotation, order=order, index=index, free=free,
        stiffness=k_ff, contact_nodes=contact_nodes, contact_dofs=cdofs, contact_area=area,
        contact_stiffness=kc, normal_force=normal, friction_limit=limit, clamp_load=clamp,
        u0=u, slip0=resp.slip, size=size, clamp_iterations=iters, backend=backend,
        setup_s=time.perf_counter() - t0, newton=newton, reduced=reduced,
        transform=transform, contact_master=np.where(master >= 0, inv[master], -1),
        ground=None if ground is None else sp.csr_matrix(ground[free][:, free]))


#: The last free-free model's rigid fit (the model itself kept, so an id is never reused).
_RIGID_FITS: dict[int, tuple[Any, FloatArray, FloatArray, FloatArray]] = {}


def _rigid_part(model: MeshModel, u: FloatArray) -> FloatArray:
    """The least-squares rigid motion t + theta x r of nodal fields u (..., n_used, 3), the
    nodes weighted by their volumes (the row sums of a unit-density consistent mass)."""
    key = id(model)
    if key not in _RIGID_FITS or _RIGID_FITS[key][0] is not model:
        from .mass import mass_matrix

        x = model.mesh.nodes[model.order]
        inv = np.full(len(model.mesh.nodes), -1, dtype=np.int64)
        inv[model.order] = np.arange(model.order.size)
        w = np.asarray(mass_matrix(x, inv[model.mesh.elements][:, :8], 1.0).sum(axis=1)
                       ).ravel()[0::3] if model.mesh.nodes_per_element == 8 else np.ones(len(x))
        w = w / w.sum()
        c = w @ x
        r = x - c
        j = (w @ np.einsum("ij,ij->i", r, r)) * np.eye(3) - np.einsum("i,ij,ik->jk", w, r, r)
        _RIGID_FITS.clear()  # one model at a time
        _RIGID_FITS[key] = (model, w, r, np.linalg.inv(j))
    _, w, r, j_inv = _RIGID_FITS[key]
    t = np.einsum("i,...ic->...c", w, u)
    theta = np.einsum("jk,...k->...j", j_inv, np.einsum("i,...ic->...c", w, np.cross(r, u)))
    return np.asarray(t[..., None, :] + np.cross(theta[..., None, :], r))


def _check_balanced(mesh: HexMesh, full: FloatArray, nodes: FloatArray, size: float) -> None:
    """A free-free assembly's preloads must balance (no net force or moment: a bolt presses
    its head and its nut alike); else they would push it away."""
    f = full.reshape(-1, 3)
    force = f.sum(axis=0)
    moment = np.cross(nodes - nodes.mean(axis=0), f).sum(axis=0)
    scale = float(np.abs(f).sum())
    if np.linalg.norm(force) > 1e-9 * scale or np.linalg.norm(moment) > 1e-9 * scale * size:
        raise ParameterError(
            f"{mesh.source}: the preloads push the free-free assembly (net force "
            f"{np.linalg.norm(force):.4g} N, moment {np.linalg.norm(moment):.4g} N·mm) and "
            "nothing holds it: hold it with --fixed SET, put a face on the rigid base, or "
            "balance the preloads (a bolt presses its head and its nut alike)")


def _face_nodes_of(mesh: HexMesh, name: str) -> IntArray:
    return face_load(mesh, set_faces(mesh, name, "bolt face"))[0]


def _shanks(mesh: HexMesh, assembly: Assembly, nodes: FloatArray, inv: IntArray,
            transform: sp.csr_matrix | None) -> sp.csr_matrix:
    """The shanks' stiffness on every model dof (model frame; T^T S T with pairs)."""
    from .shank import shank_stiffness

    total = sp.csr_matrix((3 * len(nodes), 3 * len(nodes)))
    for b in assembly.shanks:
        faces = []
        for name in (b.head, b.nut):
            k_mesh, share, _ = face_load(mesh, set_faces(mesh, name, "bolt face"))
            faces.append((inv[k_mesh], share))
        total = total + shank_stiffness(nodes, faces[0], faces[1], b.diameter,
                                        b.modulus or assembly.modulus, b.poisson_ratio,
                                        f"bolt {b.head}:{b.nut}")
    if transform is not None:
        total = transform.T @ total @ transform
    return sp.csr_matrix(total)


def _curved_model(mesh: HexMesh, assembly: Assembly, element: str, k_all: sp.csr_matrix,
                  contact: IntArray, contact_nodes: IntArray, area: FloatArray,
                  gap: FloatArray, supports: IntArray | None, full: FloatArray,
                  newton: NewtonOptions, rotation: FloatArray, order: IntArray, size: float,
                  t0: float, inv: IntArray, master: IntArray, linear_solver: str,
                  transform: sp.csr_matrix | None) -> MeshModel:
    """:func:`build_mesh_model` of a curved face on the rigid base under ``fixed`` normal
    contact (:func:`~.curved.curved_clamping`); ``k_all`` and ``full`` are already in the
    model's unknowns (T^T K T, T^T f, with ``transform`` T, if any: constraints that keep
    the contact nodes on the rigid base, as a refined mesh's hanging nodes)."""
    from .curved import curved_clamping, likely_contact

    xy = (mesh.nodes[contact_nodes] @ rotation.T)[:, :2]
    soft = min(m.modulus / (1.0 - m.poisson_ratio**2) for m in assembly.materials)
    guess = likely_contact(xy, gap, soft, assembly.clamp_force)
    try:
        c = curved_clamping(k_all, contact, area, gap, supports, full, assembly.stick_slope,
                            assembly.normal_slope, assembly.friction, assembly.clamp_force,
                            newton, AUTO_BAND_LIMIT, mesh.source, MAX_ACTIVE_SET, guess)
    except (np.linalg.LinAlgError, RuntimeError) as err:
        raise ParameterError(
            f"{mesh.source}: the body is not held after clamping (its stiffness is singular: "
            f"{err}); the contact set {assembly.contact_set!r} must be the face on the base "
            f"and the clamp set {assembly.clamp_set!r} must press the body onto it") from None
    name = "banded" if c.reduced.solver.band is not None else "splu"
    if linear_solver not in ("auto", name):
        name = linear_solver
    return MeshModel(
        mesh=mesh, assembly=assembly, element=element, normal=None, rotation=rotation,
        order=order, index=c.index, free=c.free, stiffness=c.stiffness,
        contact_nodes=contact_nodes, contact_dofs=c.contact_dofs, contact_area=area,
        contact_stiffness=c.contact_stiffness, normal_force=c.normal,
        friction_limit=c.limit, clamp_load=c.clamp_load, u0=c.u, slip0=c.slip, size=size,
        clamp_iterations=c.iterations, backend=SpentBackend(name), setup_s=time.perf_counter()
        - t0, newton=newton, reduced=c.reduced, transform=transform,
        contact_master=np.where(master >= 0, inv[master], -1))


def _node_blocks(k: sp.csr_matrix) -> sp.csr_matrix:
    """``k`` with every node's 3 x 3 diagonal block in its sparsity pattern (explicit zeros
    where T^T K T cancelled an entry), which the sparse backends' contact entries need."""
    n = k.shape[0] // 3
    a, b = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")
    base = 3 * np.arange(n)[:, None]
    rows = (base + a.ravel()).ravel()
    cols = (base + b.ravel()).ravel()
    coo = k.tocoo()
    out = sp.csr_matrix((np.concatenate([coo.data, np.zeros(rows.size)]),
                         (np.concatenate([coo.row, rows]), np.concatenate([coo.col, cols]))),
                        shape=k.shape)
    out.sort_indices()
    return out


@dataclass(frozen=True)
class MeshElements:
    """The elements of a mesh of n-node hexahedra: their names (the first the default), the
    Jacobian check and the stiffness assembly."""

    elements: tuple[str, ...]
    jacobians: Any
    assemble: Any

    @property
    def default(self) -> str:
        return self.elements[0]


#: Nodes per element -> the built-in elements of such a mesh.
MESH_ELEMENTS = {8: MeshElements(("C3D8I", "C3D8"), hex8_b_matrices, assemble_hex8),
                 20: MeshElements(tuple(HEX20_ELEMENTS), hex20_b_matrices, assemble_hex20)}


def _quarters(mesh: HexMesh, faces: IntArray) -> tuple[IntArray, FloatArray]:
    """CalculiX's node-to-surface areas of 4-node faces: a quarter of each face's area
    (2 x 2 Gauss points) at each of its corners, summed over a node's faces."""
    corners = mesh.face_corners(faces)
    nodes = np.unique(corners).astype(np.int64)
    x = mesh.nodes[corners]  # (k, 4, 3)
    g = np.array([-1.0, 1.0]) / np.sqrt(3.0)
    area = np.zeros(len(faces))
    for xi in g:
        for eta in g:
            dxi = 0.25 * np.array([-(1 - eta), 1 - eta, 1 + eta, -(1 + eta)])
            deta = 0.25 * np.array([-(1 - xi), -(1 + xi), 1 + xi, 1 - xi])
            t1 = np.einsum("m,kmc->kc", dxi, x)
            t2 = np.einsum("m,kmc->kc", deta, x)
            area += np.linalg.norm(np.cross(t1, t2), axis=1)
    at = np.searchsorted(nodes, corners.ravel())
    quarter = np.bincount(at, weights=np.repeat(area / 4.0, 4), minlength=nodes.size)
    return nodes, np.asarray(quarter, dtype=float)


#: Nodal areas A_i of the contact nodes of 4-node faces: name -> description. They differ
#: where a face is not a parallelogram (an unstructured or graded mesh; issue 33: on a gmsh
#: plate up to 18 % at a node and 5 % in W).
LINEAR_CONTACT_WEIGHTS = {
    "calculix": "CalculiX node-to-surface: a quarter of each face's area at each corner "
                "(the built-in solver's nodal law is CalculiX's, node for node)",
    "consistent": "the consistent shares of a uniform traction, integral of N_i dA",
}


def _contact_areas(mesh: HexMesh, faces: IntArray, weights: str
                   ) -> tuple[IntArray, FloatArray, QuadContact | None]:
    """The contact nodes, their areas A_i (mm^2) and (20-node faces) what recovers their
    normal forces (:class:`~.hex20.QuadContact`); None for 4-node faces, whose areas are
    named by :data:`LINEAR_CONTACT_WEIGHTS`."""
    if mesh.nodes_per_element == 8:
        if weights not in LINEAR_CONTACT_WEIGHTS:
            raise ParameterError(f"unknown contact weights {weights!r} for 4-node faces; "
                                 f"choose one of {', '.join(LINEAR_CONTACT_WEIGHTS)}")
        if weights == "calculix":
            nodes, area = _quarters(mesh, faces)
            return nodes, area, None
        nodes, share, total = face_load(mesh, faces)
        return nodes, share * total, None
    fn = face_nodes20(mesh.elements, faces)
    quad = contact_areas(mesh.nodes[fn], fn, weights)
    return quad.nodes, quad.area, quad
