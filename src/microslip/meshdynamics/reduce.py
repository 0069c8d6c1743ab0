"""A reduced model with every contact node: Craig-Bampton on the user's mesh (issue 23, item 3).

The body of a :class:`~.meshmodel.MeshModel` (its stiffness K without the contact springs,
the consistent mass M of :mod:`.mass`) is reduced onto

* the *boundary*: every contact node's contact dofs, kept physical (tangential e1, e2 with
  ``fixed`` normal contact; e1, e2 and the normal e3 with ``penalty``), because the contact
  is the nonlinear element and each node carries its own law;
* n *fixed-interface modes*: the body's modes with the boundary held (K_ii phi = w^2 M_ii phi),
  the lowest ones, by count or below a frequency cut-off.

With the constraint modes Psi = -K_ii^-1 K_ib (Craig and Bampton 1968) the displacements are
``u = T q``, ``T = [[I, 0], [Psi, Phi]]`` over (boundary, interior), and the reduced matrices
``K_r = T^T K T`` (block-diagonal: K_bb + K_bi Psi and diag(mu_j w_j^2)) and
``M_r = T^T M T``. Each fixed-interface mode is scaled to a largest displacement of 1 mm so
that every ROM coordinate is a displacement in mm (its modal mass mu_j in t). The ROM is
exact when every interior mode is kept; with fewer its stuck frequencies (the contact's
tangent springs, stick slope x area, added at the boundary) converge from above
(:func:`convergence`).

Each contact node then carries the full FE's own law (:func:`rom_structure`): with ``fixed``
normal contact a 2-D circular Coulomb (Jenkins) element on its two tangential dofs, stiffness
lambda A_i and slip force mu N_i at the clamping step's normal force, one
:class:`~microslip.dynamics.operators2d.CircularIwan` of one element per node (its
circular slip limit, REFERENCES.md 2-D Jenkins); with ``penalty`` normal contact the 3-D
element of :mod:`microslip.dynamics.operators3d` on its three dofs. :func:`write_rom` writes
either as a structure file (:mod:`microslip.dynamics.files`, SI: kg, N/m) with the
per-joint laws.

Units: N, mm, s, t (mass in tonnes, N s^2/mm) in the ROM; the structure file is SI.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray
from scipy.linalg import eigh

from ..blas import single_threaded_blas
from ..errors import ParameterError
from ..fe.builtin.meshmodel import MeshModel
from .modes import modal_mass, modal_stiffness, shift_inverse

if TYPE_CHECKING:
    from ..dynamics.files import MatrixFile
    from ..dynamics.structure import Structure

__all__ = ["Rom", "build_rom", "convergence", "full_mass", "rom_arrays", "rom_matrices",
           "rom_structure", "stuck_frequencies_full", "write_rom"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Tonnes per kg and N/m per N/mm: the ROM (t, N/mm) times this is SI (kg, N/m).
SI_FACTOR = 1e3


@dataclass(frozen=True, eq=False)
class Rom:
    """A Craig-Bampton reduced model of a clamped body with every contact node kept.

    Attributes
    ----------
    mass, stiffness : ndarray, shape (n, n)
        M_r (t) and K_r (N/mm) of the body without the contact springs; coordinates: the
        boundary dofs (``boundary`` in order), then the fixed-interface modal coordinates
        (mm: each mode's largest displacement is 1).
    boundary : ndarray of int, shape (n_b,)
        Free-dof positions (:attr:`MeshModel.free` order) of the boundary, node-major:
        e1, e2 (and e3 with penalty) of each contact node.
    per_node : int
        Boundary dofs per contact node: 2 (``fixed``) or 3 (``penalty``).
    interface_frequencies : ndarray, shape (n_m,)
        Fixed-interface natural frequencies, Hz.
    contact_stiffness, slip_force, normal_stiffness : ndarray, shape (n_c,)
        lambda A_i (N/mm), mu N_i (N) and k_n A_i (N/mm, zeros with ``fixed``) per node.
    friction : float
        mu (the preload of a node is its slip force / mu).
    output : ndarray, shape (3, n)
        Mean displacement of the response set along the global x, y, z per unit ROM
        coordinate (-); None if no response set was named.
    build_s : float
        Seconds to build.
    stick_force : ndarray, shape (n_c, 2)
        The tangential force the clamping step leaves at each contact node, along e1, e2
        (N; |t_i| <= mu N_i). With ``penalty`` normal contact the 3-D elements start their
        cycles from it (it does not shake down when N varies); with ``fixed`` it shakes down
        and is not used.
    preload : ndarray, shape (n_c,), or None
        The signed normal preload after clamping (:attr:`.meshmodel.MeshModel.preload`, N):
        N_i > 0 where the node is closed; with ``penalty`` contact minus k_n A_i times the
        gap where the clamping lifted it off (open: it carries nothing until it closes).
        None: every node closed at N_i = slip force / mu.
    outputs : dict of str to ndarray, shape (3, n)
        The same rows for every other set named in ``build_rom``'s ``output_sets`` (a load
        set, say), from the same build: one basis, no sign to align.
    """

    mass: FloatArray = field(repr=False)
    stiffness: FloatArray = field(repr=False)
    boundary: IntArray = field(repr=False)
    per_node: int
    interface_frequencies: FloatArray = field(repr=False)
    contact_stiffness: FloatArray = field(repr=False)
    slip_force: FloatArray = field(repr=False)
    normal_stiffness: FloatArray = field(repr=False)
    friction: float
    output: FloatArray | None = field(repr=False)
    build_s: float
    stick_force: FloatArray | None = field(default=None, repr=False)
    preload: FloatArray | None = field(default=None, repr=False)

    @property
    def closed(self) -> NDArray[np.bool_]:
        """(n_c,): the contact nodes closed after clamping (preload > 0); the open ones carry
        no stuck stiffness."""
        if self.preload is None:
            return np.asarray(self.slip_force > 0.0)
        return np.asarray(self.preload > 0.0)
    outputs: dict[str, FloatArray] = field(default_factory=dict, repr=False)

    @property
    def dofs(self) -> int:
        """ROM coordinates: boundary dofs plus modes."""
        return int(self.mass.shape[0])

    @property
    def modes(self) -> int:
        """Fixed-interface modes kept."""
        return int(self.interface_frequencies.size)

    def contact_springs(self) -> FloatArray:
        """The contact's stuck tangent on the ROM's coordinates (diagonal, N/mm): lambda A_i
        on each tangential boundary dof, k_n A_i on each normal one, of every node closed
        after clamping (:attr:`closed`; 0 on an open node's dofs), 0 on the modes."""
        d = np.zeros(self.dofs)
        nb = self.boundary.size
        closed = self.closed
        d[:nb].reshape(-1, self.per_node)[:, :2] = np.where(
            closed, self.contact_stiffness, 0.0)[:, None]
        if self.per_node == 3:
            d[:nb].reshape(-1, 3)[:, 2] = np.where(closed, self.normal_stiffness, 0.0)
        return d

    def response_motion(self, count: int) -> FloatArray:
        """(count, 3): the response set's mean displacement along global x, y, z in each of
        the lowest ``count`` stuck modes, per unit length (the direction it moves);
        needs :attr:`output`."""
        if self.output is None:
            raise ParameterError("the ROM has no response set (build it with one)")
        k = self.stiffness + np.diag(self.contact_springs())
        _, vec = eigh(k, self.mass, subset_by_index=[0, min(count, self.dofs) - 1])
        motion = (self.output @ vec).T
        size = np.linalg.norm(motion, axis=1, keepdims=True)
        return np.asarray(motion / np.where(size > 0.0, size, 1.0))

    def stuck_frequencies(self, count: int | None = None) -> FloatArray:
        """The ROM's linear natural frequencies with the contact stuck, Hz, ascending."""
        k = self.stiffness + np.diag(self.contact_springs())
        lam = eigh(k, self.mass, eigvals_only=True,
                   subset_by_index=None if count is None else [0, min(count, self.dofs) - 1])
        return np.asarray(np.sqrt(np.maximum(lam, 0.0)) / (2.0 * np.pi))


def full_mass(model: MeshModel, density_kg_m3: float) -> sp.csr_matrix:
    """Consistent mass of the model's free dofs (t): :func:`.modes.modal_mass`."""
    return modal_mass(model, density_kg_m3)


def _boundary(model: MeshModel) -> tuple[IntArray, int]:
    if model.normal is None:
        return model.contact_dofs.reshape(-1).astype(np.int64), 2
    nodes = model.model_nodes(model.contact_nodes)
    normal = model.index[3 * nodes + 2]
    return np.column_stack([model.contact_dofs, normal]).reshape(-1).astype(np.int64), 3


def _springs(model: MeshModel) -> FloatArray:
    """The contact's stuck tangent on the free dofs (diagonal, N/mm), the nodes closed after
    clamping only (:attr:`.meshmodel.MeshModel.closed`)."""
    d = np.zeros(model.dof)
    kc = np.where(model.closed, model.contact_stiffness, 0.0)
    d[model.contact_dofs[:, 0]] = kc
    d[model.contact_dofs[:, 1]] = kc
    if model.normal is not None:
        d[model.normal.dofs] += np.where(model.closed, model.normal.stiffness, 0.0)
    return d


def stuck_frequencies_full(model: MeshModel, mass: sp.csr_matrix, count: int) -> FloatArray:
    """The full FE's lowest ``count`` linear natural frequencies with the contact stuck
    (:func:`.modes.modal_stiffness`: stick slope x area tangentially, the normal held or its
    penalty), Hz."""
    k = modal_stiffness(model, "stuck")
    with single_threaded_blas():
        lam = spla.eigsh(k, k=count, M=mass, sigma=0.0, which="LM", OPinv=shift_inverse(k),
                         return_eigenvectors=False, v0=np.ones(k.shape[0]))
    return np.asarray(np.sort(np.sqrt(np.maximum(lam, 0.0))) / (2.0 * np.pi))


def _interface_modes(k_ii: sp.csc_matrix, m_ii: sp.csc_matrix, modes: int | None,
                     cutoff_hz: float | None, lu: spla.SuperLU
                     ) -> tuple[FloatArray, FloatArray]:
    n_i = k_ii.shape[0]
    limit = n_i - 2  # eigsh needs k < n
    if modes is not None:
        if not (isinstance(modes, (int, np.integer)) and 1 <= modes <= limit):
            raise ParameterError(f"modes must be an integer in [1, {limit}], got {modes!r}")
        count = int(modes)
    else:
        count = min(20, limit)
    op = spla.LinearOperator(k_ii.shape, matvec=lu.solve, dtype=np.float64)
    while True:
        # a fixed start vector: ARPACK's random one makes two builds of one ROM differ
        lam, vec = spla.eigsh(k_ii, k=count, M=m_ii, sigma=0.0, which="LM", OPinv=op,
                              v0=np.ones(n_i))
        order = np.argsort(lam)
        lam, vec = lam[order], vec[:, order]
        f = np.sqrt(np.maximum(lam, 0.0)) / (2.0 * np.pi)
        if modes is not None:
            return f, vec
        assert cutoff_hz is not None
        if f[-1] > cutoff_hz or count == limit:
            keep = f <= cutoff_hz
            return f[keep], vec[:, keep]
        count = min(2 * count, limit)


def build_rom(model: MeshModel, density_kg_m3: float, *, modes: int | None = None,
              cutoff_hz: float | None = None, response_set: str | None = None,
              mass: sp.csr_matrix | None = None, output_sets: Sequence[str] = ()) -> Rom:
    """Craig-Bampton ROM of ``model`` with every contact node's dofs kept.

    Parameters
    ----------
    model : MeshModel
        After the clamping step (its normal forces give the slip limits).
    density_kg_m3 : float
        Density, kg/m^3.
    modes : int, optional
        Fixed-interface modes kept (the lowest). Give this or ``cutoff_hz``.
    cutoff_hz : float, optional
        Keep every fixed-interface mode below this frequency, Hz.
    response_set : str, optional
        A node set whose mean displacement is the ROM's output rows.
    mass : sparse matrix, optional
        The full mass (:func:`full_mass`), if already built.
    output_sets : sequence of str, optional
        More node sets whose mean displacement rows the ROM carries (:attr:`Rom.outputs`),
        computed in the same pass as the response set's.

    Returns
    -------
    Rom
    """
    if model.free_free:
        raise ParameterError(
            "the contact-node ROM of a free-free assembly is not built yet (its Craig-Bampton "
            "basis would need the six rigid-body modes set aside; the reduced models and the "
            "whole joint build on it): the full FE's QSMA (--solver fe) is the answer here")
    t0 = time.perf_counter()
    if (modes is None) == (cutoff_hz is None):
        raise ParameterError("give the number of fixed-interface modes or a cut-off "
                             "frequency (Hz), one of them")
    if cutoff_hz is not None and not (math.isfinite(cutoff_hz) and cutoff_hz > 0.0):
        raise ParameterError(f"cut-off frequency must be > 0 Hz, got {cutoff_hz!r}")
    m_full = full_mass(model, density_kg_m3) if mass is None else mass
    k_full = model.stiffness.tocsr()
    b, per_node = _boundary(model)
    inner = np.setdiff1d(np.arange(model.dof), b)
    rows = None if response_set is None else _response_rows(model, response_set, b, inner)
    others = [s for s in dict.fromkeys(output_sets) if s != response_set]
    more = [_response_rows(model, s, b, inner) for s in others]
    k_ii = k_full[inner][:, inner].tocsc()
    m_ii = m_full[inner][:, inner].tocsc()
    k_ib = k_full[inner][:, b]
    m_ib = m_full[inner][:, b]
    # SuperLU's solves with many right-hand sides call the BLAS; a threaded BLAS only
    # fights for the cores there (24x6x2 on a loaded 2-core machine: 2 s a block, not 0.1)
    with single_threaded_blas():
        lu = spla.splu(k_ii, permc_spec="MMD_AT_PLUS_A")
        freq, phi = _interface_modes(k_ii, m_ii, modes, cutoff_hz, lu)
        if freq.size == 0:
            raise ParameterError(f"no fixed-interface mode below {cutoff_hz} Hz (the lowest "
                                 "is above it): raise the cut-off")
        phi = phi / np.max(np.abs(phi), axis=0) * np.sign(
            phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])])
        k_psi, m_psi, psi_m_psi, m_psi_phi, psi_rows, psi_more = _constraint_modes(
            lu, k_ib.tocsc(), m_ib.tocsc(), m_ii, phi, rows, more)
    mu = np.einsum("ij,ij->j", phi, m_ii @ phi)
    del lu, k_ii, m_ii  # the factor (on the 50k-DOF cantilever 0.8 GB) before the rest
    k_bb = k_full[b][:, b].toarray() + k_psi
    m_bb = m_full[b][:, b].toarray() + m_psi + m_psi.T + psi_m_psi
    m_bm = m_ib.T @ phi + m_psi_phi
    nb, nm = b.size, phi.shape[1]
    m_r = np.zeros((nb + nm, nb + nm))
    k_r = np.zeros_like(m_r)
    m_r[:nb, :nb] = 0.5 * (m_bb + m_bb.T)
    m_r[:nb, nb:] = m_bm
    m_r[nb:, :nb] = m_bm.T
    m_r[nb:, nb:] = np.diag(mu)
    k_r[:nb, :nb] = 0.5 * (k_bb + k_bb.T)
    k_r[nb:, nb:] = np.diag(mu * (2.0 * np.pi * freq) ** 2)
    out = None if rows is None else _output(model, rows, psi_rows, phi)
    outputs = {s: _output(model, r, sums, phi)
               for s, r, sums in zip(others, more, psi_more, strict=True)}
    kn = (np.zeros_like(model.contact_stiffness) if model.normal is None
          else np.asarray(model.normal.stiffness, dtype=float))
    return Rom(mass=m_r, stiffness=k_r, boundary=b, per_node=per_node,
               interface_frequencies=freq, contact_stiffness=model.contact_stiffness.copy(),
               slip_force=model.friction_limit.copy(), normal_stiffness=kn,
               friction=model.friction, output=out,
               build_s=time.perf_counter() - t0, stick_force=clamped_stick_force(model),
               preload=model.preload.copy(), outputs=outputs)


def clamped_stick_force(model: MeshModel) -> FloatArray:
    """(n_c, 2): each contact node's tangential force after the clamping step,
    lambda A_i (u0 - slip0) along e1, e2, N, on or inside its friction limit mu N_0
    (N_0 = max(preload, 0)).

    A node that ends the clamping step sliding is a legal state, but the FE's last pass
    slides it against the limit of the pass before (``clamping_step`` lags the limits by
    one pass and stops when the normal forces change by <= 1e-12 F_N), so its force can
    sit above mu N_0 by up to mu 1e-12 F_N: 4e-9 of the limit on a 0.14 N node of
    ``bolt_pad.inp`` under penalty 1e5, which the 3-D element refused ("stick force ...
    exceeds the friction limit"). Such a node starts on its limit circle, its slider
    pre-slipped there (the force scaled back to mu N_0 along its own direction); a node
    the clamping left open carries none."""
    u = np.asarray(model.u0, dtype=float)[model.contact_dofs]
    t0 = np.asarray(model.contact_stiffness[:, None] * (u - model.slip0))
    limit = model.friction * np.maximum(np.asarray(model.preload, dtype=float), 0.0)
    size = np.hypot(t0[:, 0], t0[:, 1])
    scale = np.where(size > limit, limit / np.where(size > 0.0, size, 1.0), 1.0)
    return np.asarray(t0 * scale[:, None])


#: Constraint modes solved and multiplied by the mass this many at a time: Psi (n_i x n_b;
#: on the 50k-DOF cantilever 0.64 GB) is never held whole, only ``BLOCK`` of its columns.
BLOCK = 256


@dataclass(frozen=True)
class _Rows:
    """The response set's dofs (:func:`_response_rows`): per global axis of the model frame
    c, the count of its nodes on each boundary dof and its interior rows (positions in the
    interior dofs, one per node that moves along c there); ``nodes`` of them in all."""

    boundary: FloatArray
    interior: tuple[IntArray, IntArray, IntArray]
    nodes: int


def _constraint_modes(lu: spla.SuperLU, k_ib: sp.csc_matrix, m_ib: sp.csc_matrix,
                      m_ii: sp.csc_matrix, phi: FloatArray, rows: _Rows | None,
                      more: Sequence[_Rows] = ()
                      ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray,
                                 list[FloatArray]]:
    """The constraint modes Psi = -K_ii^-1 K_ib (n_i, n_b) in the reduced matrices, ``BLOCK``
    columns of Psi at a time: K_bi Psi, M_bi Psi, Psi^T M_ii Psi (n_b, n_b), (M_ii Psi)^T
    Phi (n_b, n_m) and the sums of Psi's rows of the response set (3, n_b; zeros without
    one; ``more``: the same for each of more sets). Psi^T M_ii Psi is taken column block
    by column block as -K_bi K_ii^-1 (M_ii Psi_j) (K_ii symmetric), one more solve per
    block instead of holding all of Psi."""
    n_b = k_ib.shape[1]
    k_bi = k_ib.T.tocsr()
    m_bi = m_ib.T.tocsr()
    k_psi = np.empty((n_b, n_b))
    m_psi = np.empty((n_b, n_b))
    psi_m_psi = np.empty((n_b, n_b))
    m_psi_phi = np.empty((n_b, phi.shape[1]))
    sums = np.zeros((3, n_b))
    more_sums = [np.zeros((3, n_b)) for _ in more]
    for j in range(0, n_b, BLOCK):
        cols = slice(j, j + BLOCK)
        psi = -lu.solve(k_ib[:, cols].toarray())
        k_psi[:, cols] = k_bi @ psi
        m_psi[:, cols] = m_bi @ psi
        if rows is not None:
            for c in range(3):
                sums[c, cols] = psi[rows.interior[c]].sum(axis=0)
        for r, s in zip(more, more_sums, strict=True):
            for c in range(3):
                s[c, cols] = psi[r.interior[c]].sum(axis=0)
        mp = m_ii @ psi
        del psi
        m_psi_phi[cols] = mp.T @ phi
        psi_m_psi[:, cols] = -(k_bi @ lu.solve(mp))
    return k_psi, m_psi, psi_m_psi, m_psi_phi, sums, more_sums


def _response_rows(model: MeshModel, name: str, b: IntArray, inner: IntArray) -> _Rows:
    """The response set's boundary counts and interior rows (:class:`_Rows`), checked."""
    if name not in model.mesh.node_sets:
        raise ParameterError(f"{model.mesh.source}: no node set {name!r} for the response "
                             f"(sets: {', '.join(model.mesh.set_names()) or 'none'})")
    nodes = model.model_nodes(model.mesh.node_sets[name])
    where_b = np.full(model.dof, -1, dtype=np.int64)
    where_b[b] = np.arange(b.size)
    where_i = np.full(model.dof, -1, dtype=np.int64)
    where_i[inner] = np.arange(inner.size)
    counts = np.zeros((3, b.size))
    interior = []
    for c in range(3):
        pos = model.index[3 * nodes + c]
        pos = pos[pos >= 0]  # held dofs do not move
        ib = where_b[pos]
        np.add.at(counts[c], ib[ib >= 0], 1.0)
        interior.append(where_i[pos[ib < 0]])
    return _Rows(counts, (interior[0], interior[1], interior[2]), int(nodes.size))


def _output(model: MeshModel, rows: _Rows, psi_rows: FloatArray, phi: FloatArray
            ) -> FloatArray:
    """(3, n_rom): the response set's mean displacement along global x, y, z."""
    local = np.zeros((3, rows.boundary.shape[1] + phi.shape[1]))
    nb = rows.boundary.shape[1]
    for c in range(3):
        local[c, :nb] = rows.boundary[c] + psi_rows[c]
        local[c, nb:] = phi[rows.interior[c]].sum(axis=0)
    local /= rows.nodes
    return np.asarray(model.rotation.T @ local)  # u_global = R^T u_model


def convergence(model: MeshModel, density_kg_m3: float, counts: list[int],
                compare: int = 6, mass: sp.csr_matrix | None = None, rom: Rom | None = None
                ) -> dict[str, list[float] | list[int] | list[list[float]]]:
    """Relative error of the ROM's lowest ``compare`` stuck frequencies against the full FE,
    for each number of fixed-interface modes in ``counts``; ``rom``, if given, is the ROM
    of its own mode count (not built again)."""
    m = full_mass(model, density_kg_m3) if mass is None else mass
    full = stuck_frequencies_full(model, m, compare)
    errors = []
    for n in counts:
        r = rom if rom is not None and rom.modes == n else build_rom(
            model, density_kg_m3, modes=n, mass=m)
        errors.append(list((r.stuck_frequencies(compare) - full) / full))
    return {"modes": list(counts), "full_Hz": list(full), "relative_error": errors}


def _joints(rom: Rom, nodes: IntArray | None = None) -> IntArray:
    """(n, per_node, 2): each contact node's (of ``nodes``, default all) joint on its
    boundary ROM dofs (tangential e1, e2, and the normal with ``penalty``), to the ground."""
    first = (np.arange(rom.contact_stiffness.size) if nodes is None else nodes) * rom.per_node
    rows = first[:, None] + np.arange(rom.per_node)[None, :]
    return np.stack([rows, np.full_like(rows, -1)], axis=2).astype(np.int64)


def rom_matrices(rom: Rom) -> MatrixFile:
    """The ROM as the matrices of a structure file (SI: kg, N/m; no damping), its joints
    one per contact node with their own laws: lambda A_i and mu N_i (``fixed``: 2-D
    Jenkins), or lambda A_i, k_n A_i, N_i and mu (``penalty``: 3-D contact elements).

    A node the clamping step left open: with ``penalty`` its element has the signed preload
    (minus k_n A_i times its gap, :attr:`Rom.preload`) and may close during the vibration;
    with ``fixed`` normal contact it has no joint (it carries nothing)."""
    from ..dynamics.files import MatrixFile, check_matrices

    m, k, c = check_matrices("rom", rom.mass * SI_FACTOR, rom.stiffness * SI_FACTOR,
                             np.zeros_like(rom.mass))
    if rom.per_node == 3:
        n = rom.contact_stiffness.size
        preload = rom.slip_force / rom.friction if rom.preload is None else rom.preload
        contacts = np.column_stack([rom.contact_stiffness, rom.normal_stiffness,
                                    preload, np.full(n, rom.friction)])
        stick = np.zeros((n, 2)) if rom.stick_force is None else rom.stick_force
        return MatrixFile(mass=m, stiffness=k, damping=c, joints=_joints(rom), path="rom",
                          contacts=contacts, stick_forces=np.asarray(stick, dtype=float))
    closed = np.flatnonzero(rom.closed)
    return MatrixFile(mass=m, stiffness=k, damping=c, joints=_joints(rom, closed), path="rom",
                      laws=np.column_stack([rom.contact_stiffness, rom.slip_force])[closed])


def rom_structure(rom: Rom, output: FloatArray | None = None) -> Structure:
    """The ROM as a :class:`~microslip.dynamics.structure.Structure`: each contact node a
    2-D circular Jenkins element (stiffness lambda A_i, slip force mu N_i) on its tangential
    dofs, to the ground (``fixed`` normal contact), or the 3-D element of
    :mod:`microslip.dynamics.operators3d` on its three dofs (``penalty``: k_n A_i with
    lift-off, preload N_i, limit mu N(t)); the output coordinate ``output`` (n_rom,) or, by
    default, the response set's mean displacement along global y (the contact plane's
    in-plane bending of the cantilever), else the first coordinate. The same structure as
    :func:`write_rom`'s file read back (:func:`~microslip.dynamics.assemble.from_matrices`)."""
    from ..dynamics.assemble import from_matrices, with_output

    mats = rom_matrices(rom)
    s = from_matrices(mats, mats.joints, None, "circular")  # every joint has its own law
    if output is None:
        output = rom.output[1] if rom.output is not None else np.eye(rom.dofs)[0]
    return with_output(s, np.asarray(output, dtype=float))


def rom_arrays(rom: Rom) -> dict[str, FloatArray | IntArray]:
    """The arrays of the ROM's structure file (:mod:`microslip.dynamics.files`): ``M``
    (kg), ``K`` (N/m), ``joints`` and each joint's ``joint_stiffness`` (N/mm) with
    ``joint_slip_force`` (N; ``fixed``, joints (n_c, 2, 2)) or with
    ``joint_normal_stiffness`` (N/mm), ``joint_preload`` (N), ``joint_friction`` and
    ``joint_stick_force`` (N, (n_c, 2): the clamping step's tangential force) (``penalty``,
    joints (n_c, 3, 2))."""
    mats = rom_matrices(rom)
    out: dict[str, FloatArray | IntArray] = {"M": mats.mass, "K": mats.stiffness,
                                             "joints": mats.joints}
    if mats.contacts is not None:
        for j, name in enumerate(("joint_stiffness", "joint_normal_stiffness",
                                  "joint_preload", "joint_friction")):
            out[name] = mats.contacts[:, j]
        if mats.stick_forces is not None:
            out["joint_stick_force"] = mats.stick_forces
        return out
    assert mats.laws is not None
    out["joint_stiffness"] = mats.laws[:, 0]
    out["joint_slip_force"] = mats.laws[:, 1]
    return out


def write_rom(path: str, rom: Rom) -> None:
    """Write the ROM as a structure file (.npz, :func:`rom_arrays`). Written to a
    temporary name in the same directory and renamed, so a failure leaves no half-written
    file (and no temporary one)."""
    import os

    arrays = rom_arrays(rom)
    tmp = f"{path}.part"
    try:
        with open(tmp, "wb") as fh:
            np.savez(fh, **arrays)  # type: ignore[arg-type]
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
