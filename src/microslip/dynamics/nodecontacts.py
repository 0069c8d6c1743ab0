"""Every contact node's friction law on a few generalised coordinates: the joint of an
interface-reduced model (issue 28, item 4).

A reduced model whose interface moves in a few shapes, the boundary displacements
``u_b = G eta`` (G: (n_c d, n) node-major, d = 2 tangential dofs per node with ``fixed``
normal contact, 3 with ``penalty``), still carries the full FE's contact law at every node:
:class:`NodeContacts` is one joint of n directions (the coordinates eta) whose force is

    F(eta) = G^T f(G eta) - G^T K_c G eta,

f the nodes' own elements (a circular Jenkins element of stiffness k_i and slip force s_i
per node, :class:`~.operators2d.CircularIwan` of one element; or the 3-D contact element of
:mod:`.operators3d`), K_c = diag(k_t, k_t[, k_n]) their stuck slopes. The stuck part
``G^T K_c G`` is linear and belongs in the structure's stiffness (:attr:`stuck_stiffness`),
so the joint's own force is zero to first order and its :attr:`initial_stiffness` is 0:
:meth:`~.structure.Structure.stuck_stiffness` and the EPMC's stuck start are then those of
the reduced model with every node stuck, exactly.

Harmonic balance (:meth:`periodic_harmonics`, the compiled-AFT entry point that
:class:`~.hb.HarmonicBalance` calls with its own transforms): the nodes' displacement
harmonics ``U = G X``, each node's periodic force and its time-domain Jacobian by the
node's own kernel (the same compiled code as the contact-node ROM's joints, called in one
compiled loop), the force harmonics and the per-node harmonic Jacobian
``dF_i = P J_i E`` (d h x d h), and then the projection ``sum_i G_i^T dF_i G_i``, per
harmonic block a product of (n, n_c d) by (n_c d, h^2 n): the balance's size is n h, the
AFT's cost linear in the contact nodes. With every boundary dof kept (G invertible) the
balance is the contact-node ROM's in other coordinates.

Units: displacement mm, force N, stiffness N/mm.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

from ..errors import ParameterError
from ..named import readonly, result
from .kernels2d import circular_periodic_kernel
from .operators3d import _periodic as _contact3d_periodic

__all__ = ["NodeContacts"]

Array = NDArray[np.float64]


@njit(cache=True, nogil=True)
def _circular_nodes(u: Array, k: Array, phi: Array, basis: Array, f: Array, jb: Array
                    ) -> int:  # pragma: no cover - compiled
    """Each node's one-element circular Jenkins joint: u (n_c, N, 2) mm, k (n_c,) N/mm, phi
    (n_c,) mm, basis (N, h); fills f (n_c, N, 2) and jb (n_c, N, 2, 2, h) as
    :meth:`~.operators2d.CircularIwan.periodic_force_projected` does node by node (the
    same start sample, the largest |u|). Returns the nodes that did not converge."""
    failed = 0
    kk = np.empty(1)
    pp = np.empty(1)
    for i in range(u.shape[0]):
        best = -1.0
        start = 0
        for t in range(u.shape[1]):
            r = math.hypot(u[i, t, 0], u[i, t, 1])
            if r > best:
                best = r
                start = t
        if phi[i] <= 0.0:  # an open node (no normal force): it carries nothing
            continue
        kk[0] = k[i]
        pp[0] = phi[i]
        failed += circular_periodic_kernel(u[i], kk, kk, pp, start, basis, f[i], jb[i])
    return failed


@njit(cache=True, nogil=True)
def _contact3d_nodes(u: Array, kt: Array, kn: Array, n0: Array, mu: float, t0: Array,
                     basis: Array, f: Array, jb: Array) -> int:  # pragma: no cover - compiled
    """Each node's 3-D contact element (:mod:`.operators3d`), node by node; returns the
    nodes whose cycle did not close (they give their last period, as the element does)."""
    open_ = 0
    for i in range(u.shape[0]):
        if _contact3d_periodic(u[i], basis, kt[i], kn[i], n0[i], mu, t0[i], f[i], jb[i]) < 0:
            open_ += 1
    return open_


@result
class NodeContacts:
    """Every contact node's own law seen through the interface shapes G.

    Parameters
    ----------
    shapes : ndarray, shape (n_c d, n)
        G: the boundary dofs (node-major: e1, e2 (, e3) of each node) per unit generalised
        coordinate, mm/mm.
    tangential_stiffness : ndarray, shape (n_c,)
        k_t = lambda A_i, N/mm, > 0.
    slip_force : ndarray, shape (n_c,)
        mu N_i, N, >= 0 (the clamping step's normal force); 0: an open node, which carries
        nothing (``fixed``) or only the penalty law with separation (``penalty``).
    normal_stiffness : ndarray, shape (n_c,), optional
        k_n A_i, N/mm: with it each node carries the 3-D element (``penalty``), its preload
        ``slip_force / friction``.
    friction : float
        mu (used with ``normal_stiffness``).
    stick_force : ndarray, shape (n_c, 2), optional
        The clamping step's tangential force per node (3-D elements only), N.
    preload : ndarray, shape (n_c,), optional
        The signed normal preload per node (3-D elements only, N; :attr:`~microslip.
        meshdynamics.reduce.Rom.preload`): N_0 > 0 where closed, minus k_n A_i times the gap
        where the clamping left it open, which then carries nothing until the gap closes.
        Default ``slip_force / friction`` (an open node at a zero gap).
    """

    shapes: np.ndarray
    tangential_stiffness: np.ndarray
    slip_force: np.ndarray
    normal_stiffness: np.ndarray | None = None
    friction: float = 0.0
    stick_force: np.ndarray | None = None
    preload: np.ndarray | None = None

    def __post_init__(self) -> None:
        g = np.asarray(self.shapes, dtype=np.float64)
        kt = np.asarray(self.tangential_stiffness, dtype=np.float64).reshape(-1)
        s = np.asarray(self.slip_force, dtype=np.float64).reshape(-1)
        d = 2 if self.normal_stiffness is None else 3
        n_c = kt.size
        if g.ndim != 2 or g.shape[0] != d * n_c or not np.all(np.isfinite(g)):
            raise ParameterError(f"shapes must be finite of shape ({d * n_c}, n) for {n_c} "
                                 f"nodes of {d} dofs, got {g.shape}")
        if s.shape != kt.shape or not (np.all(kt > 0.0) and np.all(s >= 0.0)):
            raise ParameterError("each node needs a stiffness > 0 N/mm and a slip force "
                                 ">= 0 N")
        object.__setattr__(self, "shapes", readonly(np.ascontiguousarray(g)))
        object.__setattr__(self, "tangential_stiffness", readonly(kt))
        object.__setattr__(self, "slip_force", readonly(s))
        if self.normal_stiffness is not None:
            kn = np.asarray(self.normal_stiffness, dtype=np.float64).reshape(-1)
            if kn.shape != kt.shape or not np.all(kn > 0.0):
                raise ParameterError("each node needs a normal stiffness > 0 N/mm")
            if not (math.isfinite(self.friction) and self.friction > 0.0):
                raise ParameterError(f"friction must be > 0, got {self.friction!r}")
            t0 = (np.zeros((n_c, 2)) if self.stick_force is None
                  else np.asarray(self.stick_force, dtype=np.float64))
            if t0.shape != (n_c, 2) or not np.all(np.isfinite(t0)):
                raise ParameterError(f"stick force must be finite of shape ({n_c}, 2)")
            n0 = (s / self.friction if self.preload is None
                  else np.asarray(self.preload, dtype=np.float64).reshape(-1))
            if n0.shape != kt.shape or not np.all(np.isfinite(n0)):
                raise ParameterError(f"preload must be {n_c} finite numbers (N)")
            if np.any((n0 > 0.0) != (s > 0.0)):
                raise ParameterError("a node's preload is > 0 exactly where its slip force "
                                     "is (closed after clamping)")
            object.__setattr__(self, "normal_stiffness", readonly(kn))
            object.__setattr__(self, "stick_force", readonly(np.ascontiguousarray(t0)))
            object.__setattr__(self, "preload", readonly(np.ascontiguousarray(n0)))

    @property
    def directions(self) -> int:
        """The generalised coordinates the joint takes (its columns of G)."""
        return int(self.shapes.shape[1])

    @property
    def per_node(self) -> int:
        """Dofs per node: 2 (circular Jenkins) or 3 (3-D contact element)."""
        return 2 if self.normal_stiffness is None else 3

    @property
    def odd(self) -> bool:
        """Whether the force is odd in the displacement (no normal preload): the
        odd-harmonic balance applies."""
        return self.normal_stiffness is None

    #: The joint's own slope from the virgin state, N/mm: 0, its stuck slope is in
    #: :attr:`stuck_stiffness`, which the structure carries.
    initial_stiffness = 0.0

    def node_springs(self) -> Array:
        """The stuck slopes on the boundary dofs, diagonal of K_c (n_c d,), N/mm; zero at an
        open node (slip force 0: no normal force after clamping), which carries nothing at
        rest (with ``penalty`` its element closes if the node is pressed back)."""
        d = np.repeat(self.tangential_stiffness[:, None], self.per_node, axis=1)
        if self.normal_stiffness is not None:
            d[:, 2] = self.normal_stiffness
        d[self.slip_force <= 0.0] = 0.0
        return np.asarray(d.reshape(-1))

    @property
    def stuck_stiffness(self) -> Array:
        """G^T K_c G (n, n), N/mm: the nodes stuck, on the generalised coordinates."""
        g = self.shapes
        return np.asarray(g.T @ (self.node_springs()[:, None] * g))

    def periodic_harmonics(self, u: Array, synth: Array, analysis: Array
                           ) -> tuple[Array, Array]:
        """The joint's force harmonics (N, (n h,), coordinate-major) and their derivative in
        the coordinates' harmonics ``u`` (mm, (n h,)), N/mm, (n h, n h), with the balance's
        synthesis (N, h) and analysis (h, N) matrices; see the module notes."""
        g = self.shapes
        n, d = self.directions, self.per_node
        n_c = self.tangential_stiffness.size
        h = synth.shape[1]
        x = np.asarray(u, dtype=np.float64).reshape(n, h)
        synth = np.ascontiguousarray(synth, dtype=np.float64)
        # node samples (n_c, N, d)
        samples = np.ascontiguousarray(
            ((g @ x) @ synth.T).reshape(n_c, d, -1).transpose(0, 2, 1))
        if not np.all(np.isfinite(samples)):
            raise ParameterError("contact node displacements must be finite (mm)")
        f = np.zeros(samples.shape)
        jb = np.zeros((n_c, synth.shape[0], d, d, h))
        if self.normal_stiffness is None:
            failed = _circular_nodes(samples, self.tangential_stiffness,
                                     self.slip_force / self.tangential_stiffness, synth, f, jb)
            if failed:
                raise ParameterError(f"the periodic state of {failed} contact node(s) did not "
                                     "converge")
        else:
            assert self.stick_force is not None and self.preload is not None
            _contact3d_nodes(samples, self.tangential_stiffness, self.normal_stiffness,
                             self.preload, float(self.friction),
                             self.stick_force, synth, f, jb)
        # force harmonics per node dof (n_c d, h), projected; the stuck part taken off
        fh = np.einsum("at,itb->iba", analysis, f).reshape(n_c * d, h)
        stuck = self.stuck_stiffness
        force = g.T @ fh - stuck @ x
        # harmonic Jacobian per node: dF[i, a, alpha, b, beta]; G_i^T dF_i G_i summed
        df = np.einsum("ft,itabg->iafbg", analysis, jb)
        w = g.reshape(n_c, d, n)
        t = np.einsum("iafbg,ibl->iafgl", df, w).reshape(n_c * d, h * h * n)
        jac = (g.T @ t).reshape(n, h, h, n).transpose(0, 1, 3, 2).reshape(n * h, n * h)
        jac -= np.kron(stuck, np.eye(h))
        return np.asarray(force.reshape(-1)), np.asarray(jac)
