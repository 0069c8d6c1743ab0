"""The clamping step of a body on its rigid base: its dof partition and the normal forces the
clamping (preload) step leaves, for :func:`~microslip.fe.builtin.meshmodel.build_mesh_model`
(the paper's box included, :mod:`.box`).

Step 1 (*clamping*) applies the preloads with the friction active from a zero slip; the
normal reactions of the contact nodes are their normal forces N_i (all positive; they differ
from plain area shares at edges and corners because the stuck interface restrains the
Poisson expansion) and stay fixed afterwards (``fixed`` normal contact), or follow the load
(the ``penalty`` normal contact of :mod:`.normal`). Each solve is the semi-smooth Newton of
:mod:`.stepper`. Units: N, mm, MPa.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...blas import single_threaded_blas
from ...errors import MacroslipError, ParameterError
from .contact import FrictionResponse
from .linalg import Backend
from .model import NewtonOptions
from .normal import PenaltyNormal
from .stepper import _Stepper

__all__ = ["clamping_step", "contact_partition"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]


def contact_partition(k_all: sp.csr_matrix, contact: IntArray, area: FloatArray, lam: float,
                      k_n: float, penalty: bool, released: BoolArray | None = None,
                      fixed: IntArray | None = None, gap: FloatArray | None = None
                      ) -> tuple[IntArray, IntArray, sp.csr_matrix, sp.csr_matrix, IntArray,
                                 FloatArray, PenaltyNormal | None]:
    """The dofs of a body on its rigid base (any mesh), its contact nodes ``contact`` (with
    their areas, mm^2) on the plane normal to z (the model frame).

    Returns ``free`` (the free dofs: all but the contact nodes' u_z under ``fixed`` normal
    contact, every dof under ``penalty``), ``index`` (dof -> free position, -1 if held),
    ``k_ff`` and ``k_rf`` (the stiffness on the free dofs, and from them to the contact
    nodes' u_z), ``cdofs`` (the contact nodes' free x, y positions), ``kc`` (the stick
    springs lambda A_i, N/mm) and the penalty normal springs (None under ``fixed``).
    ``released`` (``fixed`` only): contact nodes the clamping step lifted off, whose u_z is
    free too (``k_rf`` then has the held nodes' rows only). ``fixed``: further dofs held
    at zero (an assembly's supports); ``gap`` (``penalty``): the nodes' initial gaps to the
    base, mm.
    """
    n_all = k_all.shape[0]
    held = 3 * (contact if released is None else contact[~released]) + 2
    mask = np.ones(n_all, dtype=bool)
    if not penalty:
        mask[held] = False
    if fixed is not None:  # supports: held at 0, their reactions not needed
        mask[fixed] = False
    free = np.flatnonzero(mask).astype(np.int64)
    index = np.full(n_all, -1, dtype=np.int64)
    index[free] = np.arange(free.size)
    k_ff = k_all[free][:, free].tocsr()
    k_rf = k_all[held][:, free].tocsr()
    cdofs = np.stack([index[3 * contact], index[3 * contact + 1]], axis=1)
    kc = lam * area
    springs = PenaltyNormal(k_n * area, index[3 * contact + 2], k_n, gap) if penalty else None
    return free, index, k_ff, k_rf, cdofs, kc, springs


def clamping_step(k_ff: sp.csr_matrix, k_rf: sp.csr_matrix, backend: Backend,
                  cdofs: IntArray, kc: FloatArray, springs: PenaltyNormal | None,
                  clamp: FloatArray, newton: NewtonOptions, friction: float,
                  normal_force: float, clamp_fixed: FloatArray | None = None,
                  released: BoolArray | None = None, settle_first: bool = False
                  ) -> tuple[FloatArray, FloatArray, FloatArray, FrictionResponse, int]:
    """Solve the clamping step of a body on its rigid base (any mesh).

    The first pass has no friction limit (all nodes stick); N_i are the normal reactions
    (``k_rf @ u`` minus the clamping load ``clamp_fixed`` on the held normal dofs, if any; the
    penalty forces with ``springs``). If a node's stick force then exceeds mu N_i, the step is
    solved again with the limits mu N_i until the normal forces stop changing (they depend on
    the slip).

    ``released`` (``fixed`` normal contact, :func:`contact_partition`'s): the nodes whose u_z
    is free carry N_i = 0, and a held node in tension (N_i <= 0) returns at once with its
    normal force (the caller releases it:
    :func:`~.meshmodel.build_mesh_model`'s active set) instead of refusing. With
    ``settle_first`` it returns only once the friction has settled (the held nodes in tension
    get no friction meanwhile): a node in tension when all stick may press once the others
    slip (:mod:`.curved`: a ring at a curved face's contact edge, nu = 0.3, mu = 0.1, else
    released and pressed back pass after pass).

    Returns
    -------
    normal : ndarray, shape (n_c,)
        N_i, N.
    limit : ndarray, shape (n_c,)
        mu N_i, N.
    u : ndarray
        Free-dof displacements after clamping, mm.
    resp : FrictionResponse
        The contact response of the last pass (its ``slip`` is the slip after clamping).
    iterations : int
        Newton iterations of all passes.
    """
    n_c = cdofs.shape[0]
    limit = np.full(n_c, np.inf)
    normal = np.zeros(n_c)
    iters = 0
    for attempt in range(20):
        stepper = _Stepper(k_ff, backend, cdofs, kc, limit, newton, friction * normal_force,
                           springs)
        with single_threaded_blas():
            ok, it, u, resp = stepper.solve(np.zeros(k_ff.shape[0]), np.zeros((n_c, 2)),
                                            clamp)
        iters += it
        if stepper.singular:  # nothing holds the body: the callers say so in one line
            raise np.linalg.LinAlgError("singular tangent stiffness")
        if not ok:
            raise MacroslipError("the clamping step did not converge")
        new_normal = np.asarray(k_rf @ u) if springs is None else springs.forces(u)
        if springs is None and clamp_fixed is not None:
            new_normal = new_normal - clamp_fixed
        if released is not None:
            held, new_normal = new_normal, np.zeros(n_c)
            new_normal[~released] = held
            if np.any(held <= 0.0) and not settle_first:  # tension: the caller releases them
                return new_normal, friction * new_normal, u, resp, iters
        # penalty normal contact: a node may lift off (N_i = 0); fixed: N_i must be > 0
        bad = (new_normal <= 0.0 if springs is None and released is None else
               np.array([np.all(new_normal <= 0.0)]))
        if np.any(bad):
            raise ParameterError(
                f"the clamping step gave a non-positive normal force at {int(bad.sum())} of "
                f"{n_c} contact nodes (the clamp pulls them off the base); use the penalty "
                "normal contact, which lets them lift off, or refine the mesh through the "
                "thickness" if springs is None and released is None else
                "the clamping step left no contact node pressed onto the base")
        change = float(np.max(np.abs(new_normal - normal)))
        normal = new_normal
        limit_new = friction * (np.maximum(normal, 0.0) if settle_first else normal)
        admissible = bool(np.all(np.hypot(*resp.force.T) <= limit_new))
        limit = limit_new
        if (attempt == 0 and admissible) or change <= 1e-12 * normal_force:
            break
    else:
        raise MacroslipError("the normal forces of the clamping step did not settle")
    return normal, limit, u, resp, iters
