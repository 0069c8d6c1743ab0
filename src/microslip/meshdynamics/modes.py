"""Linear modes of a clamped body of the user's mesh, the contact stuck or free (issue 23).

After the clamping step (:func:`~microslip.fe.builtin.meshmodel.build_mesh_model`) the
contact's tangent is linear while every node sticks:

* ``stuck``: the tangential stick springs lambda A_i on both in-plane dofs and the normal
  stiffness of every contact node the clamping step leaves closed (N_i > 0): u_n held
  (``fixed``) or its penalty k_n A_i (``penalty``); a node the clamping lifted off (open,
  N_i = 0) carries nothing, as in the frictional FE, where its limit mu N_i is 0;
* ``free``: the tangential springs removed, the normal kept: the body may slide and turn in
  the contact plane, so its three in-plane rigid motions are 0 Hz modes.

K omega^2 phi = ... is solved as (K - omega^2 M) phi = 0 with the consistent mass of
:mod:`.mass` (K in N/mm, M in t: omega^2 in 1/s^2) by sparse shift-invert Lanczos (ARPACK),
phi mass-normalised (phi^T M phi = 1, mm / sqrt(t)). Each mode is described by the motion
of a response set: the mean displacement of its nodes (a unit direction, global axes) and a
label from a rigid fit of the set's motion (:func:`describe_motion`). Units: N, mm, t, s, Hz.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..blas import single_threaded_blas
from ..errors import MicroslipError, ParameterError
from ..fe.builtin.mass import density_t_per_mm3, mass_matrix
from ..fe.builtin.meshmodel import AUTO_BAND_LIMIT, MeshModel, set_faces

__all__ = [
    "CONTACT_STATES",
    "LABELS",
    "Mode",
    "Modes",
    "describe_motion",
    "linear_modes",
    "modal_mass",
    "modal_stiffness",
    "response_nodes",
    "shift_inverse",
    "write_modes_vtu",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def _stuck(model: MeshModel) -> sp.csr_matrix:
    """lambda A_i on both in-plane dofs of every contact node closed after clamping (an open
    node carries nothing: :attr:`~.meshmodel.MeshModel.closed`)."""
    n = model.dof
    c = model.contact_dofs
    rows = [c[:, 0], c[:, 1]]
    k = np.where(model.closed, model.contact_stiffness, 0.0)
    vals = [k, k]
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(rows))),
                         shape=(n, n))


def _none(model: MeshModel) -> sp.csr_matrix:
    return sp.csr_matrix((model.dof, model.dof))


#: Contact states of the linear modes: name -> the tangential springs it adds.
CONTACT_STATES: dict[str, Callable[[MeshModel], sp.csr_matrix]] = {
    "stuck": _stuck,
    "free": _none,
}


def _normal_springs(model: MeshModel) -> sp.csr_matrix:
    """k_n A_i on the u_n of every contact node closed after clamping (``penalty``; N_i > 0,
    :attr:`~.meshmodel.MeshModel.closed`)."""
    n = model.dof
    if model.normal is None:
        return sp.csr_matrix((n, n))
    k = np.where(model.closed, model.normal.stiffness, 0.0)
    d = model.normal.dofs
    return sp.csr_matrix((k, (d, d)), shape=(n, n))


def _check_contact(contact: str) -> str:
    if contact not in CONTACT_STATES:
        raise ParameterError(f"unknown contact state {contact!r}; choose one of "
                             f"{', '.join(CONTACT_STATES)}")
    return contact


def modal_stiffness(model: MeshModel, contact: str = "stuck") -> sp.csr_matrix:
    """The linear stiffness (free dofs, model frame, N/mm) about the clamped state: the body's
    K plus the contact's tangent (``stuck``: stick springs and normal stiffness; ``free``:
    normal stiffness only)."""
    k = model.stiffness + CONTACT_STATES[_check_contact(contact)](model) + _normal_springs(model)
    return sp.csr_matrix(0.5 * (k + k.T))


def modal_mass(model: MeshModel, density_kg_m3: float) -> sp.csr_matrix:
    """The consistent mass on the model's free dofs (model frame, t); the density in kg/m^3,
    for every body whose material (:class:`~microslip.fe.assembly.Material`) gives none.

    The mass of a node block is rho-weighted identity in x, y, z, so it is the same in the
    contact frame as in the global one. An assembly's relative interface coordinates
    (u = T v) give T^T M T."""
    from ..fe.builtin.bodies import element_materials

    inv = np.full(len(model.mesh.nodes), -1, dtype=np.int64)
    inv[model.order] = np.arange(model.order.size)
    nodes, elements = model.mesh.nodes[model.order], inv[model.mesh.elements]
    groups = element_materials(model.mesh, model.assembly.materials)
    m: sp.csr_matrix | None = None
    for rows, mat in groups:
        rho = density_t_per_mm3(density_kg_m3 if mat.density is None else mat.density)
        part = mass_matrix(nodes, elements if len(groups) == 1 else elements[rows], rho)
        m = part if m is None else m + part
    assert m is not None
    if model.transform is not None:
        m = model.transform.T @ m @ model.transform
    return sp.csr_matrix(m.tocsr()[model.free][:, model.free])


#: Labels of a mode's shape (:func:`describe_motion`): name -> what dominates the response
#: set's rigid-fit motion.
LABELS: dict[str, str] = {
    "axial": "translation along the axis (contact centroid to response set)",
    "bending in the contact plane": "translation across the axis, in the contact plane",
    "bending out of plane": "translation along the contact normal, across the axis",
    "torsion": "rotation about the axis (times the set's radius of gyration about it)",
    "mixed": "no part holds 80 % of the squared motion",
}
#: Share of the squared motion that names a mode.
LABEL_SHARE = 0.8


def describe_motion(points: FloatArray, motion: FloatArray, axis: FloatArray,
                    normal: FloatArray) -> tuple[str, dict[str, float]]:
    """Label the motion of a set of nodes (points (k, 3) mm, motion (k, 3)) by a rigid fit.

    The set's motion is fitted (least squares) by a translation t of its centroid and a small
    rotation r. With the axis a (unit; from the contact's centroid to the set's) and the
    contact normal n, four parts: axial |t . a|, in-plane bending |t - (t.a) a - (t.n') n'|
    (n' the normal made orthogonal to a), out-of-plane bending |t . n'|, torsion
    |r . a| rho_a (rho_a the set's radius of gyration about the axis). A part holding at least
    :data:`LABEL_SHARE` of the sum of squares names the mode; otherwise ``mixed``. When the
    axis is along the normal (a post on a plate) out-of-plane bending is empty and every
    bending is in the contact plane. Returns the label and the shares.
    """
    x = points - points.mean(axis=0)
    t = motion.mean(axis=0)
    a = axis / np.linalg.norm(axis)
    # rotation: motion - t ~ r x x  =>  least squares in r
    rel = motion - t
    skew = np.zeros((len(x), 3, 3))
    skew[:, 0, 1], skew[:, 0, 2] = x[:, 2], -x[:, 1]
    skew[:, 1, 0], skew[:, 1, 2] = -x[:, 2], x[:, 0]
    skew[:, 2, 0], skew[:, 2, 1] = x[:, 1], -x[:, 0]
    r = np.linalg.lstsq(skew.reshape(-1, 3), rel.reshape(-1), rcond=None)[0]
    radial = x - np.outer(x @ a, a)
    rho = math.sqrt(float(np.mean(np.sum(radial**2, axis=1))))
    n = normal - (normal @ a) * a
    nn = float(np.linalg.norm(n))
    n = n / nn if nn > 1e-6 else np.zeros(3)
    parts = {
        "axial": float(t @ a) ** 2,
        "bending out of plane": float(t @ n) ** 2,
        "torsion": (float(r @ a) * rho) ** 2,
    }
    parts["bending in the contact plane"] = max(
        float(t @ t) - parts["axial"] - parts["bending out of plane"], 0.0)
    total = sum(parts.values())
    shares = {k: (v / total if total > 0 else 0.0) for k, v in parts.items()}
    best = max(shares, key=lambda k: shares[k])
    return (best if shares[best] >= LABEL_SHARE else "mixed"), shares


@dataclass(frozen=True, eq=False)
class Mode:
    """One mode of :class:`Modes` (:meth:`Modes.select`), what the quasi-static modal analysis
    (:mod:`.qsma`) loads the body with.

    Attributes
    ----------
    number : int
        1-based.
    frequency_Hz : float
    vector : ndarray, shape (dof,)
        phi on the free dofs (model frame), phi^T M phi = 1.
    inertia : ndarray, shape (dof,)
        M phi, the inertial load pattern (model frame).
    direction : ndarray, shape (3,)
        Unit direction of the response set's motion (global axes).
    label : str
    response_set : str or None
    """

    number: int
    frequency_Hz: float
    vector: FloatArray = field(repr=False)
    inertia: FloatArray = field(repr=False)
    direction: FloatArray = field(repr=False)
    label: str
    response_set: str | None


@dataclass(frozen=True, eq=False)
class Modes:
    """Linear modes of a clamped mesh (:func:`linear_modes`).

    Attributes
    ----------
    contact : str
        ``stuck`` or ``free``.
    density_kg_m3 : float
    frequencies_Hz : ndarray, shape (n,)
        Increasing, Hz (0 for a rigid motion: ``free`` contact).
    vectors : ndarray, shape (n, dof)
        phi on the model's free dofs (model frame), mass-normalised: phi^T M phi = 1.
    shapes : ndarray, shape (n, n_nodes, 3)
        The same per mesh node, global axes, mm / sqrt(t) (held dofs 0).
    response_set : str or None
        The set that describes the modes (None: every node).
    response_motion : ndarray, shape (n, 3)
        Mean displacement of the set's nodes in each mode (global axes).
    directions : ndarray, shape (n, 3)
        response_motion as unit vectors (0 where the set does not move).
    labels : tuple of str
        :data:`LABELS` per mode.
    shares : tuple of dict
        The label parts' shares per mode.
    inertia : ndarray, shape (n, dof)
        M phi of each mode (model frame).
    """

    contact: str
    density_kg_m3: float
    frequencies_Hz: FloatArray
    vectors: FloatArray = field(repr=False)
    shapes: FloatArray = field(repr=False)
    response_set: str | None
    response_motion: FloatArray = field(repr=False)
    directions: FloatArray = field(repr=False)
    labels: tuple[str, ...]
    shares: tuple[dict[str, float], ...] = field(repr=False)
    inertia: FloatArray = field(repr=False, default_factory=lambda: np.zeros((0, 0)))

    @property
    def count(self) -> int:
        return int(self.frequencies_Hz.size)

    def mode(self, number: int) -> int:
        """The 0-based index of mode ``number`` (1-based), checked."""
        if isinstance(number, bool) or not isinstance(number, (int, np.integer)) or not (
                1 <= number <= self.count):
            raise ParameterError(f"mode must be a whole number in [1, {self.count}] (the "
                                 f"modes computed), got {number!r}")
        return int(number) - 1

    def direction(self, number: int) -> FloatArray:
        """Unit direction of the response set's motion in mode ``number`` (1-based); refused
        when the set does not move in it (its mean motion below 1e-6 of the largest nodal
        motion)."""
        i = self.mode(number)
        peak = float(np.max(np.linalg.norm(self.shapes[i], axis=1)))
        if float(np.linalg.norm(self.response_motion[i])) <= 1e-6 * peak:
            raise ParameterError(f"response set {self.response_set!r} does not move in mode "
                                 f"{number} ({self.labels[i]}); choose another mode or set")
        return np.asarray(self.directions[i])

    def select(self, number: int) -> Mode:
        """Mode ``number`` (1-based), its response set checked to move
        (:meth:`direction`)."""
        i = self.mode(number)
        return Mode(number=i + 1, frequency_Hz=float(self.frequencies_Hz[i]),
                    vector=self.vectors[i], inertia=self.inertia[i],
                    direction=self.direction(number), label=self.labels[i],
                    response_set=self.response_set)

    def summary(self) -> list[dict[str, Any]]:
        """One plain dict per mode, for JSON."""
        return [{"mode": i + 1, "frequency_Hz": float(f), "label": lab,
                 "direction": [float(v) for v in d]}
                for i, (f, lab, d) in enumerate(zip(self.frequencies_Hz, self.labels,
                                                     self.directions, strict=True))]


def response_nodes(model: MeshModel, response_set: str | None) -> IntArray:
    """Mesh nodes of a response set (a node set, or the corners of a surface's faces); None:
    every node of an element."""
    mesh = model.mesh
    if response_set is None:
        return np.asarray(model.order)
    if response_set in mesh.node_sets:
        return np.asarray(mesh.node_sets[response_set], dtype=np.int64)
    faces = set_faces(mesh, response_set, "response set")
    return np.unique(mesh.face_corners(faces))


def shift_inverse(a: sp.spmatrix) -> spla.LinearOperator:
    """x -> A^-1 x for a symmetric positive definite A (K - sigma M of shift-invert Lanczos),
    factorised once: LAPACK banded Cholesky when the model's numbering keeps the
    half-bandwidth within :data:`~.meshmodel.AUTO_BAND_LIMIT` dofs (on the 50k-DOF cantilever
    its factor is 0.2 GB, SuperLU's 0.5 GB and several times that while factorising), else
    SuperLU on the minimum-degree ordering of A^T + A (fewer fill-ins than its default
    COLAMD on a stiffness). Raises RuntimeError when A is singular or not definite."""
    coo = sp.tril(a, format="coo")
    n = a.shape[0]
    kd = int(np.max(coo.row - coo.col)) if coo.nnz else 0
    if kd <= AUTO_BAND_LIMIT:
        ab = np.zeros((kd + 1, n), order="F")
        ab[coo.row - coo.col, coo.col] = coo.data  # LAPACK lower band storage
        del coo
        try:
            cb = sla.cholesky_banded(ab, lower=True, overwrite_ab=True, check_finite=False)
        except np.linalg.LinAlgError as exc:
            raise RuntimeError(str(exc)) from None

        def solve(x: FloatArray) -> FloatArray:
            return np.asarray(sla.cho_solve_banded((cb, True), x, check_finite=False))

        return spla.LinearOperator((n, n), matvec=solve, dtype=np.float64)
    del coo
    lu = spla.splu(sp.csc_matrix(a), permc_spec="MMD_AT_PLUS_A")
    return spla.LinearOperator((n, n), matvec=lu.solve, dtype=np.float64)


#: An eigenvalue w^2 at most this times the largest computed is a rigid motion's rounding.
RIGID = 1e-9


def _eigen(k: sp.csr_matrix, m: sp.csr_matrix, n: int, contact: str) -> tuple[FloatArray,
                                                                             FloatArray]:
    # shift below 0: with the contact free K is singular (in-plane rigid motions)
    scale = float(k.diagonal().max() / m.diagonal().max())
    sigma = -1e-8 * scale if contact == "free" else 0.0
    kk = min(n, k.shape[0] - 2)
    try:
        with single_threaded_blas():  # a threaded BLAS only fights for the cores here
            op = shift_inverse(k - sigma * m if sigma else k)
            # a fixed start vector: ARPACK's random one makes every run differ in the last
            # digits
            w, v = spla.eigsh(k, k=kk, M=m, sigma=sigma, which="LM", OPinv=op,
                              v0=np.ones(k.shape[0]))
    except RuntimeError as exc:  # singular factor
        raise ParameterError(f"the linear modes could not be computed ({exc}): is the body "
                             "held by its contact?") from None
    del op  # the factor
    order = np.argsort(w)
    w, v = w[order], v[:, order]
    norm = np.sqrt(np.einsum("ij,ij->j", v, m @ v))
    v = v / norm
    # sign: the largest component positive (reproducible shapes)
    big = np.argmax(np.abs(v), axis=0)
    v = v * np.sign(v[big, np.arange(v.shape[1])])
    # rigid motions (free contact) come out at w^2 of rounding size: they are 0 Hz
    w = np.where(w <= RIGID * float(np.max(np.abs(w))), 0.0, w)
    return w, v.T.copy()


def linear_modes(model: MeshModel, density_kg_m3: float, n_modes: int = 10,
                 contact: str = "stuck", response_set: str | None = None) -> Modes:
    """The lowest linear modes of a clamped mesh about its clamped state.

    Parameters
    ----------
    model : MeshModel
        :func:`~microslip.fe.builtin.meshmodel.build_mesh_model` (after the clamping step).
    density_kg_m3 : float
        rho, kg/m^3 (aluminium 2700).
    n_modes : int
        Modes computed (>= 1).
    contact : {"stuck", "free"}
        :data:`CONTACT_STATES`.
    response_set : str, optional
        The set whose motion describes the modes (default: every node).

    Returns
    -------
    Modes
    """
    if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or not (
            1 <= n_modes <= max(1, model.dof - 2)):
        raise ParameterError(f"n_modes must be a whole number in [1, {model.dof - 2}], "
                             f"got {n_modes!r}")
    contact = _check_contact(contact)
    k = modal_stiffness(model, contact)
    m = modal_mass(model, density_kg_m3)
    w2, vec = _eigen(k, m, int(n_modes), contact)
    freq = np.sqrt(w2) / (2 * math.pi)
    shapes = model.global_vectors(vec)
    nodes = response_nodes(model, response_set)
    motion = shapes[:, nodes].mean(axis=1)
    size = np.linalg.norm(motion, axis=1)
    peak = np.max(np.linalg.norm(shapes, axis=2), axis=1)
    moving = size > 1e-6 * peak
    dirs = np.where(moving[:, None], motion / np.where(moving, size, 1.0)[:, None], 0.0)
    points = model.mesh.nodes[nodes]
    contact_centre = model.mesh.nodes[model.contact_nodes].mean(axis=0)
    axis = points.mean(axis=0) - contact_centre
    normal = model.rotation[2]
    if float(np.linalg.norm(axis)) <= 1e-9 * model.size:
        axis = normal
    labels, shares = [], []
    for i in range(freq.size):
        lab, sh = describe_motion(points, shapes[i, nodes], axis, normal)
        labels.append(lab)
        shares.append(sh)
    return Modes(contact=contact, density_kg_m3=float(density_kg_m3), frequencies_Hz=freq,
                 vectors=vec, shapes=shapes, response_set=response_set,
                 response_motion=motion, directions=dirs, labels=tuple(labels),
                 shares=tuple(shares), inertia=np.asarray((m @ vec.T).T))


def write_modes_vtu(model: MeshModel, modes: Modes, path: str | os.PathLike[str]) -> Path:
    """One VTU file of the mesh with a point array ``mode_<k>_<f>Hz`` (the mass-normalised
    shape, scaled to a largest nodal motion of 1 mm) per mode, for ParaView's Warp By Vector.
    Written atomically."""
    from ..io import atomic_path

    try:
        import meshio
    except ImportError:
        raise MicroslipError("VTU export needs meshio: pip install 'microslip[fe]'") from None
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    data: dict[str, Any] = {}
    for i, f in enumerate(modes.frequencies_Hz):
        s = modes.shapes[i]
        peak = float(np.max(np.linalg.norm(s, axis=1))) or 1.0
        data[f"mode_{i + 1}_{f:.6g}Hz"] = s / peak
    mesh = meshio.Mesh(np.asarray(model.mesh.nodes), [("hexahedron", np.asarray(
        model.mesh.elements))], point_data=data)
    with atomic_path(out) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
    return out
