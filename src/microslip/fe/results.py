"""Named results of a CalculiX run: the loop, the contact status history, solver figures.

The FE loop arrives as a :class:`~microslip.results.HysteresisLoop` (``source="calculix"``)
and its damping as a :class:`~microslip.results.DampingResult` from
:func:`microslip.energy.damping_from_loop`, exactly as the analytical models deliver theirs, so
comparison code never cares where a loop came from.

Conventions (docs/validation.md):

- The loop displacement is the work-conjugate displacement of the loaded section, the
  force-weighted mean sum_i w_i u_x,i of its nodes with the consistent-load shares w_i (sum 1),
  measured from the clamped state (end of step 1). The clamping pressure itself moves the
  section by a Poisson expansion of order 1e-6 mm; it is reported as ``clamp_displacement``.
- The closed loop is t = 0.25 .. 1.25 s (force peak to force peak). Its amplitude is half the
  peak-to-peak displacement (``HysteresisLoop.peak_displacement``): residual tractions of the
  clamping step can shift the loop by a small ``offset`` (mid-point of the extremes), which
  half peak-to-peak does not see.
- Contact status of a contact point (a slave node of the lower face) at a substep: ``open``
  if its pressure is zero; ``slip`` if its shear traction is at the friction limit
  (|tau| >= (1 - ratio_tol) mu p, ratio_tol = 0.5 by default: nodal tractions are smeared
  over an element next to the stick-slip boundary) *and* it slipped irreversibly during the
  substep (|delta s - delta tau / lambda| > slip_tol); ``stick`` otherwise. The second condition
  separates a point that slips from one that is locked at the limit traction after a load
  reversal (which ANSYS, and the paper's Fig. 8, count as sticking).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..energy import DEFAULT_STRAIN_ENERGY, damping_from_loop
from ..results import DampingResult, HysteresisLoop
from .case import FECase
from .errors import ResultsError
from .mesh import BarMesh
from .readers import read_dat, read_frd, read_sta

__all__ = [
    "STATUS",
    "ContactHistory",
    "FEResult",
    "contact_status",
    "read_results",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Contact status codes: index in this tuple.
STATUS = ("open", "stick", "slip")
OPEN, STICK, SLIP = 0, 1, 2


def contact_status(pressure: FloatArray, shear: FloatArray, slip: FloatArray, friction: float,
                   stick_slope: float, *, ratio_tol: float = 0.5,
                   slip_tol: float | None = None) -> NDArray[np.int8]:
    """Stick/slip/open status of every contact point at every state.

    Parameters
    ----------
    pressure : ndarray, shape (k, m)
        Contact pressure p, MPa, at k states (the first is the reference for increments).
    shear : ndarray, shape (k, m, 2)
        Shear traction tau, MPa.
    slip : ndarray, shape (k, m, 2)
        Total tangential relative displacement s, mm.
    friction, stick_slope : float
        mu and lambda (N/mm^3) of the friction law.
    ratio_tol : float
        A point may slip only when |tau| >= (1 - ratio_tol) mu p. The irreversible slip is the
        discriminating test (a stuck point has delta s = delta tau / lambda exactly, also in
        the nodal values, which are linear extrapolations of integration-point values); this
        one only guards against rounding noise far from the limit. Nodal tractions next to
        the stick-slip boundary are smeared over an element, hence the generous default.
    slip_tol : float, optional
        Irreversible slip per substep above which a point at the limit counts as slipping, mm.
        Default: 1 % of the elastic slip at the limit, mu p_mean / lambda, plus twice the
        resolution of the ``.frd`` file's five-digit slips (2e-5 max |s|).

    Returns
    -------
    ndarray of int8, shape (k, m)
        Codes into :data:`STATUS` (0 open, 1 stick, 2 slip). The first state's increment is
        taken from the unloaded, unclamped state (s = 0, tau = 0).

    Examples
    --------
    >>> p = np.full((2, 3), 0.07); tau = np.zeros((2, 3, 2)); s = np.zeros((2, 3, 2))
    >>> tau[1, :2, 0] = 0.056; s[1, 0, 0] = 1e-4; s[1, 1, 0] = 0.056 / 1e4
    >>> contact_status(p, tau, s, 0.8, 1e4).tolist()   # slipping, locked at the limit, stuck
    [[1, 1, 1], [2, 1, 1]]
    """
    p = np.asarray(pressure, dtype=float)
    tau = np.asarray(shear, dtype=float)
    s = np.asarray(slip, dtype=float)
    if tau.shape != (*p.shape, 2) or s.shape != tau.shape:
        raise ValueError("pressure (k, m), shear and slip (k, m, 2) shapes do not match")
    if slip_tol is None:
        closed = p > 0.0
        p_mean = float(np.mean(p[closed])) if np.any(closed) else 0.0
        s_max = float(np.max(np.abs(s))) if s.size else 0.0
        slip_tol = 0.01 * friction * p_mean / stick_slope + 2e-5 * s_max
    ds = np.diff(s, axis=0, prepend=0.0)
    dtau = np.diff(tau, axis=0, prepend=0.0)
    plastic = np.linalg.norm(ds - dtau / stick_slope, axis=-1)
    at_limit = np.linalg.norm(tau, axis=-1) >= (1.0 - ratio_tol) * friction * p
    status = np.full(p.shape, STICK, dtype=np.int8)
    status[at_limit & (plastic > slip_tol)] = SLIP
    status[p <= 0.0] = OPEN
    return status


@dataclass(frozen=True)
class ContactHistory:
    """Contact state of every contact point (slave node of the lower face) at every state.

    Attributes
    ----------
    nodes : ndarray of int, shape (m,)
        Node ids.
    coords : ndarray, shape (m, 3)
        Reference coordinates, mm (z = 0).
    time : ndarray, shape (k,)
        Step time of each state, s: 0 is the clamped state, then the substeps to 1.25 s.
    pressure : ndarray, shape (k, m)
        Contact pressure, MPa.
    shear : ndarray, shape (k, m, 2)
        Shear traction in the face's two tangent directions (here x and y), MPa.
    slip : ndarray, shape (k, m, 2)
        Total tangential relative displacement, mm.
    status : ndarray of int8, shape (k, m)
        Codes into :data:`STATUS`.
    column_width : ndarray, shape (m,)
        Length along x that each point stands for (half the spacing to its neighbours), mm;
        used to turn status into slip lengths.
    """

    nodes: IntArray
    coords: FloatArray
    time: FloatArray
    pressure: FloatArray
    shear: FloatArray
    slip: FloatArray
    status: NDArray[np.int8]
    column_width: FloatArray

    def index(self, t: float) -> int:
        """Index of the state at step time ``t`` (s); raises if there is none within 1e-9 s."""
        k = int(np.argmin(np.abs(self.time - t)))
        if abs(self.time[k] - t) > 1e-9:
            raise ValueError(f"no contact state at t = {t:g} s")
        return k

    def slip_length(self, x_min: float = -math.inf, x_max: float = math.inf) -> FloatArray:
        """Slipping length along x at every state, mm: slipping share of each x-column of
        points (over the width) times the column width, summed over x_min <= x <= x_max."""
        x = self.coords[:, 0]
        sel = (x >= x_min) & (x <= x_max)
        cols = np.unique(np.round(x[sel], 9))
        out = np.zeros(self.time.shape[0])
        for c in cols:
            k = sel & (np.abs(x - c) < 1e-6)
            share = np.mean(self.status[:, k] == SLIP, axis=1)
            out += share * float(self.column_width[k][0])
        return out


@dataclass(frozen=True)
class FEResult:
    """One finite-element run of the clamped bar.

    Attributes
    ----------
    case : FECase
    time : ndarray, shape (n + 1,)
        Step time, s: 0 (clamped) and the n substep ends up to 1.25 s.
    force : ndarray, shape (n + 1,)
        Applied tangential force F_T(t), N.
    displacement : ndarray, shape (n + 1,)
        Work-conjugate displacement of the loaded section from the clamped state, mm.
    loop : HysteresisLoop
        The closed loop t = 0.25 .. 1.25 s, ``source="calculix"``.
    damping : DampingResult
        W_d, U and eta of ``loop`` (:func:`microslip.energy.damping_from_loop`).
    contact : ContactHistory
    dof : int
        Free degrees of freedom of the bar.
    iterations : ndarray of int, shape (n,)
        Equilibrium iterations of each substep.
    wall_s : float
        Wall time of the solver, s.
    converged : bool
        Every substep converged (a run that does not converge raises instead of returning).
    clamp_displacement : float
        Work-conjugate displacement caused by the clamping step alone, mm.
    job_dir : Path or None
        Where the deck and result files are.
    """

    case: FECase
    time: FloatArray
    force: FloatArray
    displacement: FloatArray
    loop: HysteresisLoop
    damping: DampingResult
    contact: ContactHistory
    dof: int
    iterations: IntArray
    wall_s: float
    converged: bool
    clamp_displacement: float
    job_dir: Path | None = None

    @property
    def closure(self) -> float:
        """(delta(1.25 s) - delta(0.25 s)) / delta(0.25 s): how far the loop is from closed."""
        d = self.loop.displacement
        return float((d[-1] - d[0]) / d[0])

    @property
    def offset(self) -> float:
        """Mid-point of the loop's displacement extremes, mm (0 for a point-symmetric loop)."""
        d = self.loop.displacement
        return float(0.5 * (np.max(d) + np.min(d)))

    @property
    def total_iterations(self) -> int:
        return int(np.sum(self.iterations))

    def slip_lengths(self, t: float = 0.25) -> dict[str, float]:
        """Slip length of each domain at step time ``t`` (default the first peak), mm.

        Tip: the slipping length measured from the loaded end. Centre: the slipping length
        in the tension half (x > L/2) and in the compression half (x < L/2).
        """
        k = self.contact.index(t)
        half = 0.5 * self.case.params.length
        if self.case.model == "tip":
            return {"tip": float(self.contact.slip_length()[k])}
        return {"tension": float(self.contact.slip_length(x_min=half)[k]),
                "compression": float(self.contact.slip_length(x_max=half)[k])}

    def summary(self) -> dict[str, Any]:
        """The JSON object of ``microslip fe``: the keys of ``microslip loop --json`` plus
        ``dof``, ``wall_s``, ``converged`` and the FE set-up."""
        c = self.case
        return {
            "model": c.model,
            "solver": "calculix",
            "units": {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm",
                      "time": "s", "stick_slope": "N/mm^3"},
            "params": c.params.as_dict(),
            "options": {"mesh": c.spec.label(), "element": c.element,
                        "stick_slope": c.stick_slope, "normal_slope": c.normal_slope,
                        "max_iterations": c.max_iterations, "nlgeom": c.nlgeom},
            "increments": c.substeps,
            "amplitude_N": c.amplitude,
            "macroslip_force_N": c.params.macroslip_force,
            **self.damping.loop_json(self.slip_lengths()),
            "dof": self.dof,
            "wall_s": self.wall_s,
            "converged": self.converged,
            "iterations": self.total_iterations,
            "loop_closure": self.closure,
            "loop_offset_mm": self.offset,
            "clamp_displacement_mm": self.clamp_displacement,
            "job_dir": None if self.job_dir is None else str(self.job_dir),
        }

    def with_strain_energy(self, kind: str) -> FEResult:
        """The same result with U (and eta) by another definition."""
        from dataclasses import replace

        return replace(self, damping=damping_from_loop(self.loop, None, kind))


def _column_widths(x: FloatArray) -> FloatArray:
    cols = np.unique(np.round(x, 9))
    edges = np.concatenate([[cols[0]], 0.5 * (cols[1:] + cols[:-1]), [cols[-1]]])
    width = np.diff(edges)
    return np.asarray(width[np.searchsorted(cols, np.round(x, 9))], dtype=float)


def read_results(case: FECase, mesh: BarMesh, job_dir: str | Path, jobname: str = "job", *,
                 wall_s: float = math.nan,
                 strain_energy_kind: str = DEFAULT_STRAIN_ENERGY) -> FEResult:
    """Assemble the :class:`FEResult` of a finished run from its ``.dat``, ``.sta``, ``.frd``.

    Raises
    ------
    ResultsError
        A file is missing or truncated, or it does not hold the clamped state and every
        substep of the load step (a partial loop is never returned).
    """
    job_dir = Path(job_dir)
    n = case.substeps
    clamp_time = 1.0  # step 1 has period 1 s
    load_ids, weights = mesh.load_weights(case.model)

    blocks = read_dat(job_dir / f"{jobname}.dat", "displacements", expected_rows=load_ids.size)
    if len(blocks) != n + 1:
        raise ResultsError(f"{jobname}.dat holds {len(blocks)} displacement blocks, expected "
                           f"{n + 1} (clamped state and {n} substeps): the run stopped early",
                           job_dir)
    expected = clamp_time + case.times
    got = np.array([b.time for b in blocks])
    if not np.allclose(got, expected, rtol=0.0, atol=2e-6 * (1.0 + expected)):
        raise ResultsError(f"{jobname}.dat: increment times do not match the {n} equal "
                           "substeps (cut-back?)", job_dir)
    u = np.empty((n + 1, load_ids.size))
    for k, b in enumerate(blocks):
        if not np.array_equal(b.nodes, load_ids):
            raise ResultsError(f"{jobname}.dat: the printed node set is not the loaded "
                               "section", job_dir)
        u[k] = b.values[:, 0]
    absolute = u @ weights
    displacement = absolute - absolute[0]

    sta = read_sta(job_dir / f"{jobname}.sta").in_step(2)
    if sta.iterations.size != n:
        raise ResultsError(f"{jobname}.sta lists {sta.iterations.size} converged substeps of "
                           f"the load step, expected {n}", job_dir)
    converged = bool(np.all(sta.attempts == 1))

    frd = read_frd(job_dir / f"{jobname}.frd", names=("CONTACT",))
    cblocks = frd.select("CONTACT")
    if len(cblocks) != n + 1:
        raise ResultsError(f"{jobname}.frd holds {len(cblocks)} contact blocks, expected "
                           f"{n + 1}", job_dir)
    ids, _, _ = mesh.contact_lattice()
    values = np.empty((n + 1, ids.size, 6))
    for k, cb in enumerate(cblocks):
        order = np.argsort(cb.nodes, kind="stable")
        pos = np.minimum(np.searchsorted(cb.nodes[order], ids), cb.nodes.size - 1)
        if not np.array_equal(cb.nodes[order][pos], ids):
            raise ResultsError(f"{jobname}.frd: contact block at time {cb.time:g} misses "
                               "contact nodes", job_dir)
        values[k] = cb.values[order][pos]
    pressure = values[:, :, 3]
    shear = values[:, :, 4:6]
    slip = values[:, :, 1:3]
    status = contact_status(pressure, shear, slip, case.params.friction, case.stick_slope)
    coords = mesh.nodes[ids - 1]
    contact = ContactHistory(ids, coords, case.times.copy(), pressure, shear, slip, status,
                             _column_widths(coords[:, 0]))

    force = case.force(case.times)
    q = case.quarter
    loop = HysteresisLoop(
        force=force[q:].copy(), displacement=displacement[q:].copy(), source="calculix",
        meta={"model": case.model, "amplitude_N": case.amplitude, "mesh": case.spec.label(),
              "stick_slope": case.stick_slope, "dof": case.spec.dof,
              "time_s": case.times[q:].copy()})
    return FEResult(
        case=case, time=case.times.copy(), force=force, displacement=displacement, loop=loop,
        damping=damping_from_loop(loop, None, strain_energy_kind), contact=contact,
        dof=case.spec.dof, iterations=sta.iterations.copy(), wall_s=float(wall_s),
        converged=converged, clamp_displacement=float(absolute[0]), job_dir=job_dir)
