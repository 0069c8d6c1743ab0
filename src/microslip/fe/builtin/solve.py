"""The frictional finite-element model (built here, held in :mod:`.model`) and its
semi-smooth Newton solver (one increment: :mod:`.stepper`).

An elastic box (the clamped zone) rests on a rigid base: the bottom face is held at
u_z = 0 and each bottom node carries the Coulomb friction of :mod:`.contact`. Step 1
(*clamping*) applies the uniform pressure F_N / (L w) on the top face with the friction
active from a zero slip; the z-reactions of the bottom nodes are the nodal normal forces N_i
(all positive; they differ from plain area shares at edges and corners because the stuck
interface restrains the Poisson expansion) and stay fixed afterwards. Step 2 applies the
tangential loads increment by increment:

* *tip*: force along the bar (x) on the end face x = L, spread like a uniform traction;
* *centre*: force on the mid-length section x = L/2, spread like a uniform traction over the
  section, along the bar (``axial``, the paper's 1-D centre model) or across it in the plane
  of the interface (``transverse``, y: the second in-plane component of the planar study).

The displacement reported for a load is the force-weighted mean of the nodal displacements
of its section along the load (the work-conjugate displacement: F delta is the work done).

Each increment solves r(u) = f - K u - C^T tau(u) = 0 by semi-smooth Newton: the tangent
K + C^T D C (D the consistent 2 x 2 friction tangents) is factorised (banded Cholesky by
default), and a backtracking line search on |r| guards the step. Units: N, mm, MPa, N·mm.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...blas import single_threaded_blas
from ...conventions import DEFAULT_MESH
from ...errors import MacroslipError, ParameterError
from ...models.interface import PressureLaw
from ...params import ClampParams, check_positive
from ..constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from .clamping import clamp_forces
from .contact import FrictionResponse
from .element import assemble_stiffness
from .linalg import Backend, make_backend
from .mesh import BoxMesh, mesh_from_spec
from .model import CENTRE_DIRECTIONS, FrictionModel, NewtonOptions
from .normal import PenaltyNormal, check_normal_contact
from .stepper import Increment, _Stepper, load_increment, runaway_reason

__all__ = [
    "CENTRE_DIRECTIONS",
    "FrictionModel",
    "History",
    "Increment",
    "NewtonOptions",
    "Simulation",
    "build_model",
    "clamping_step",
    "load_increment",
    "run_history",
    "runaway_reason",
    "single_threaded_blas",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]



def _unit_load(mesh: BoxMesh, face: str, component: int, index: IntArray, n_free: int
               ) -> FloatArray:
    """Nodal forces of a uniform traction of total 1 N on a face, on the free dofs."""
    nodes = mesh.face_nodes(face)
    w = mesh.face_weights(face)
    out = np.zeros(n_free)
    out[index[3 * nodes + component]] = w / w.sum()
    return out


def build_model(params: ClampParams, mesh: Any = DEFAULT_MESH, *, stick_slope: float =
                DEFAULT_STICK_SLOPE, element: str = "C3D8I", linear_solver: str = "banded",
                newton: NewtonOptions | None = None,
                pressure_law: PressureLaw | None = None, normal_contact: str = "fixed",
                normal_slope: float = DEFAULT_NORMAL_SLOPE) -> FrictionModel:
    """Assemble the clamped zone and solve the clamping step.

    Parameters
    ----------
    params : ClampParams
        Geometry, material, friction and clamping force.
    mesh : str, (nx, ny, nz) or BoxMesh
        See :func:`~microslip.fe.builtin.mesh.mesh_from_spec`; nx must be even (mid-length section).
    stick_slope : float
        lambda, N/mm^3 (default 1e4, CalculiX's).
    element : str
        ``C3D8`` or ``C3D8I``.
    linear_solver : str
        ``banded`` (default), ``splu`` or ``cholmod``.
    newton : NewtonOptions, optional
    pressure_law : PressureLaw, optional
        Shape of the clamping traction along the length
        (:mod:`microslip.models.interface`; default uniform, the paper's; see
        :func:`~microslip.fe.builtin.clamping.clamp_forces`).
    normal_contact : {"fixed", "penalty"}
        :data:`~microslip.fe.builtin.normal.NORMAL_CONTACTS` (default ``fixed``, the paper's).
    normal_slope : float
        k_n of the penalty, N/mm^3 (``penalty`` only; default 1e5, as the CalculiX model's).

    Returns
    -------
    FrictionModel

    Examples
    --------
    >>> from microslip import preset
    >>> m = build_model(preset("table1"), (8, 2, 1))
    >>> m.dof, round(float(m.normal_force.sum()), 6), bool(np.all(m.normal_force > 0))
    (135, 445.0, True)
    """
    t0 = time.perf_counter()
    if not isinstance(params, ClampParams):
        raise ParameterError(f"params must be a ClampParams, got {type(params).__name__}")
    lam = check_positive("stick_slope", stick_slope, "N/mm^3")
    penalty = check_normal_contact(normal_contact) == "penalty"
    k_n = check_positive("normal_slope", normal_slope, "N/mm^3")
    newton = NewtonOptions() if newton is None else newton
    box = mesh_from_spec(params, mesh)
    box.face_nodes("mid")  # even nx required
    k_all = assemble_stiffness(box, params.modulus, params.poisson_ratio, element)
    bottom = box.face_nodes("bottom")
    area = box.face_weights("bottom")
    free, index, k_ff, k_rf, cdofs, kc, springs = contact_partition(
        k_all, bottom, area, lam, k_n, penalty)
    backend = make_backend(linear_solver, k_ff, cdofs[:, 0], cdofs[:, 1], kc,
                           None if springs is None else springs.stiffness)

    # Clamping pressure on the top face: consistent nodal forces of the traction.
    if pressure_law is not None and pressure_law.name == "uniform":
        pressure_law = None
    top = box.face_nodes("top")
    clamp = np.zeros(free.size)
    clamp[index[3 * top + 2]] = -clamp_forces(box, params, pressure_law)
    loads = {
        "tip": _unit_load(box, "end", 0, index, free.size),
        "centre-axial": _unit_load(box, "mid", 0, index, free.size),
        "centre-transverse": _unit_load(box, "mid", 1, index, free.size),
    }

    normal, limit, u, resp, iters = clamping_step(
        k_ff, k_rf, backend, cdofs, kc, springs, clamp, newton, params.friction,
        params.normal_force)
    slip = resp.slip
    return FrictionModel(
        params=params, mesh=box, element=element, stick_slope=lam,
        pressure_law=pressure_law, normal=springs, free=free,
        stiffness=k_ff, contact_nodes=bottom, contact_dofs=cdofs, contact_area=area,
        contact_stiffness=kc, normal_force=normal, friction_limit=limit, loads=loads,
        clamp_load=clamp, u0=u, slip0=slip, clamp_iterations=iters, backend=backend,
        setup_s=time.perf_counter() - t0, newton=newton,
    )


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


@dataclass(frozen=True, eq=False)
class History:
    """Raw response to a sampled load history (one row per load sample).

    Attributes
    ----------
    f_tip, f_centre : ndarray, shape (n,)
        Applied forces, N.
    tip_displacement, centre_displacement : ndarray, shape (n,)
        Work-conjugate displacements along each load, relative to the clamped state, mm.
    iterations : ndarray of int, shape (n,)
        Newton iterations of each increment (of all its sub-increments if it was cut).
    slipping : ndarray of bool, shape (n, n_c)
        Contact status after each increment: True = slip, False = stick.
    friction_work : ndarray, shape (n,)
        Energy dissipated by friction in each increment, N·mm (0 for the first sample).
    converged : bool
    completed : int
        Number of samples solved (all of them unless an increment failed).
    message : str
    wall_s : float
        Wall time of the stepping, s (setup excluded: see :attr:`FrictionModel.setup_s`).
    factorisations : int
    u : ndarray, shape (n, dof) or None
        Free-dof displacements after each increment, mm (with ``record=True``).
    slip : ndarray, shape (n, n_c, 2) or None
        Slips of the contact nodes after each increment, mm (with ``record=True``).
    normal_force : ndarray, shape (n, n_c) or None
        Normal forces N_i after each increment, N (penalty normal contact; None when they
        are fixed: :attr:`FrictionModel.normal_force`).
    """

    f_tip: FloatArray
    f_centre: FloatArray
    tip_displacement: FloatArray
    centre_displacement: FloatArray
    iterations: IntArray
    slipping: BoolArray
    friction_work: FloatArray
    converged: bool
    completed: int
    message: str
    wall_s: float
    factorisations: int
    u: FloatArray | None = None
    slip: FloatArray | None = None
    normal_force: FloatArray | None = None

    def displacement(self, component: str) -> FloatArray:
        """Work-conjugate displacement of the ``tip`` or ``centre`` load, mm."""
        return {"tip": self.tip_displacement, "centre": self.centre_displacement}[component]


class Simulation:
    """Tangential loading of a :class:`FrictionModel`, continued chunk after chunk.

    The state (displacements, slips, the last factorisation) is kept between calls of
    :meth:`advance`, so a cyclic run can stop as soon as the energy per cycle settles.
    """

    def __init__(self, model: FrictionModel, centre_direction: str = "transverse") -> None:
        self.model = model
        self.p_tip = model.loads["tip"]
        self.p_cen = model.loads[model.centre_load(centre_direction)]
        self.stepper = _Stepper(model.stiffness, model.backend, model.contact_dofs,
                                model.contact_stiffness, model.friction_limit, model.newton,
                                model.force_scale, model.normal,
                                None if model.normal is None else model.params.friction)
        self.u, self.slip = model.u0.copy(), model.slip0.copy()
        self.base_tip = float(self.p_tip @ self.u)
        self.base_cen = float(self.p_cen @ self.u)
        self.increments = 0
        self.failed = False
        self.last_force = (0.0, 0.0)

    def _increment(self, ft: float, fc: float) -> tuple[bool, int, float, FrictionResponse]:
        """One increment to (ft, fc) (:func:`load_increment`). Returns (converged,
        iterations, friction work, last response)."""
        step = load_increment(self.stepper, self.model.clamp_load, (self.p_tip, self.p_cen),
                              self.last_force, (ft, fc), self.u, self.slip,
                              self.model.newton.max_cuts)
        if step.converged:
            self.u, self.slip, self.last_force = step.u, step.slip, (ft, fc)
        return step.converged, step.iterations, step.work, step.response

    def _runaway(self) -> str | None:
        """Why the state just reached is no static equilibrium, or None. With unilateral
        normal contact a block whose load moment exceeds the clamping's tips over: the
        displacements then run away (here: beyond 1 % of the body's largest size)."""
        p = self.model.params
        return runaway_reason(self.model.normal, self.u, max(p.length, p.width, p.thickness))

    def advance(self, f_tip: Any, f_centre: Any, *, record: bool = False) -> History:
        """Apply the next samples of the force history (one increment each).

        Parameters
        ----------
        f_tip, f_centre : array_like, shape (n,)
            Forces at each sample, N.
        record : bool
            Keep the displacements and slips after each increment (for a VTU export).

        Returns
        -------
        History
            Of these samples only; after a failed increment, the samples solved so far and
            ``converged=False`` (further calls raise).
        """
        model = self.model
        if self.failed:
            raise MacroslipError("the simulation stopped at a failed increment")
        ft = np.asarray(f_tip, dtype=float)
        fc = np.asarray(f_centre, dtype=float)
        if ft.ndim != 1 or ft.shape != fc.shape:
            raise ParameterError("tip and centre force histories must be 1-D arrays of equal "
                                 "length")
        if not (np.all(np.isfinite(ft)) and np.all(np.isfinite(fc))):
            raise ParameterError("force histories must be finite")
        peak = float(np.max(np.hypot(ft, fc))) if ft.size else 0.0
        if peak >= model.params.macroslip_force:
            raise MacroslipError(
                f"the resultant tangential load reaches {peak:g} N >= mu F_N = "
                f"{model.params.macroslip_force:g} N (macroslip: no static equilibrium)")
        n = ft.size
        d_tip, d_cen, fwork = np.zeros(n), np.zeros(n), np.zeros(n)
        its = np.zeros(n, dtype=np.int64)
        slipping = np.zeros((n, model.contact_nodes.size), dtype=bool)
        u_rec = np.zeros((n, model.dof)) if record else None
        s_rec = np.zeros((n, model.contact_nodes.size, 2)) if record else None
        springs = model.normal
        n_rec = None if springs is None else np.zeros((n, model.contact_nodes.size))
        f0 = self.stepper.factorisations
        t0 = time.perf_counter()
        converged, message, done = True, "converged", n
        with single_threaded_blas():
            for i in range(n):
                ok, it, fw, resp = self._increment(ft[i], fc[i])
                its[i] = it
                runaway = self._runaway() if ok else None
                if not ok or runaway:
                    converged, done, self.failed = False, i, True
                    message = (f"increment {self.increments + i} (F_tip {ft[i]:g} N, F_centre "
                               f"{fc[i]:g} N) " + (runaway or
                               f"did not converge in {model.newton.max_iterations} Newton "
                               f"iterations, even cut into {model.newton.max_cuts} "
                               "sub-increments"))
                    break
                fwork[i] = fw
                d_tip[i] = float(self.p_tip @ self.u) - self.base_tip
                d_cen[i] = float(self.p_cen @ self.u) - self.base_cen
                slipping[i] = resp.slipping
                if springs is not None and n_rec is not None:
                    n_rec[i] = springs.forces(self.u)
                if u_rec is not None and s_rec is not None:
                    u_rec[i], s_rec[i] = self.u, self.slip
        self.increments += done
        return History(
            f_tip=ft[:done], f_centre=fc[:done], tip_displacement=d_tip[:done],
            centre_displacement=d_cen[:done],
            iterations=its[:done], slipping=slipping[:done], friction_work=fwork[:done],
            converged=converged, completed=done, message=message,
            wall_s=time.perf_counter() - t0, factorisations=self.stepper.factorisations - f0,
            u=None if u_rec is None else u_rec[:done],
            slip=None if s_rec is None else s_rec[:done],
            normal_force=None if n_rec is None else n_rec[:done])


def run_history(model: FrictionModel, f_tip: Any, f_centre: Any, *,
                centre_direction: str = "transverse") -> History:
    """Apply a sampled history of tip and centre forces from the clamped state.

    Each sample is one increment, solved to convergence from the previous one; sample 0 is
    applied from the clamped, unloaded state. A failed increment stops the run: the result
    then has ``converged=False`` and the samples solved so far.

    Parameters
    ----------
    model : FrictionModel
    f_tip, f_centre : array_like, shape (n,)
        Forces at each sample, N.
    centre_direction : {"transverse", "axial"}
        Direction of the centre load (across the bar in the interface plane, or along it).

    Returns
    -------
    History
    """
    return Simulation(model, centre_direction).advance(f_tip, f_centre)
