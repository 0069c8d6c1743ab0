"""Named results of the built-in frictional FE solver.

Loops arrive as :class:`microslip.results.HysteresisLoop` with ``source="builtin"``, so that
:func:`microslip.energy.damping_from_loop` and every comparison treat them like any other
loop. Units: force N, displacement mm, energy N·mm, time s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ...named import result
from ...results import HysteresisLoop
from ..result import ContactHistory, gross_sliding_message, join_message

if TYPE_CHECKING:
    from .clamping import ClampingPressure
    from .meshmodel import MeshModel

__all__ = [
    "BuiltinDetails",
    "CouplingResult",
    "CycleWork",
    "LoadPathResult",
    "SolverStats",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]


@dataclass(frozen=True)
class SolverStats:
    """Size and cost of a run.

    Attributes
    ----------
    dof : int
        Unknowns (free dofs: 3 per node less u_z of the bottom face).
    total_dof : int
        3 x nodes.
    half_bandwidth : int or None
        Of the tangent in the banded backend (None for the sparse backends).
    mesh : dict
        Element counts and sizes.
    element : str
    linear_solver : str
    stick_slope : float
        lambda, N/mm^3.
    increments : int
        Load increments solved.
    iterations : int
        Newton iterations, all increments.
    factorisations : int
        Tangent factorisations (<= iterations: factorisations are reused, see NewtonOptions).
    max_iterations : int
        Largest number of iterations of one increment.
    setup_s, wall_s : float
        Assembly and clamping; total including setup, s.
    """

    dof: int
    total_dof: int
    half_bandwidth: int | None
    mesh: dict[str, Any]
    element: str
    linear_solver: str
    stick_slope: float
    increments: int
    iterations: int
    factorisations: int
    max_iterations: int
    setup_s: float
    wall_s: float

    def summary(self) -> dict[str, Any]:
        return {"dof": self.dof, "total_dof": self.total_dof,
                "half_bandwidth": self.half_bandwidth, "mesh": self.mesh,
                "element": self.element, "linear_solver": self.linear_solver,
                "stick_slope_N_per_mm3": self.stick_slope, "increments": self.increments,
                "newton_iterations": self.iterations, "factorisations": self.factorisations,
                "max_iterations_per_increment": self.max_iterations,
                "setup_s": self.setup_s, "wall_s": self.wall_s}


@result
class BuiltinDetails:
    """What the built-in solver adds to its :class:`~microslip.fe.result.FELoopResult`.

    Attributes
    ----------
    stats : SolverStats
    centre_direction : str
        Direction of the centre load (``axial`` for the paper's centre model).
    friction_dissipation : float
        Energy dissipated by friction over the loop, sum tau . Delta s, N·mm. Exact in time for
        1-D loading (the slipping nodes are at the limit mu N_i); the loop area converges to it
        as the increments are refined.
    model : MeshModel or None
        The assembled box (:func:`~microslip.fe.builtin.box.box_model`), kept with ``u``
        (``record=True``) for the VTU export.
    u : ndarray, shape (n + 1, dof) or None
        Free-dof displacements after every increment, mm (``record=True``).
    pressure_law : str
        Name of the clamping pressure law (``uniform``: the paper's).
    clamping : ClampingPressure or None
        The interface pressure after the clamping step (:mod:`~microslip.fe.builtin.clamping`).
    normal_contact : str
        ``fixed`` (the paper's reading) or ``penalty`` (:mod:`~microslip.fe.builtin.normal`).
    normal_slope : float or None
        k_n of the penalty, N/mm^3 (None when fixed).
    normal_force : ndarray, shape (n + 1, n_c) or None
        Normal forces N_i after every increment, N (penalty only).
    """

    stats: SolverStats
    centre_direction: str
    friction_dissipation: float
    model: MeshModel | None = None
    u: FloatArray | None = None
    pressure_law: str = "uniform"
    clamping: ClampingPressure | None = None
    normal_contact: str = "fixed"
    normal_slope: float | None = None
    normal_force: FloatArray | None = None

    def options(self) -> dict[str, Any]:
        s = self.stats
        return {"mesh": dict(s.mesh), "element": s.element, "stick_slope": s.stick_slope,
                "linear_solver": s.linear_solver, "centre_direction": self.centre_direction,
                "pressure_law": self.pressure_law, "normal_contact": self.normal_contact,
                "normal_slope": self.normal_slope}

    def summary(self) -> dict[str, Any]:
        return {"friction_dissipation_Nmm": self.friction_dissipation}


@dataclass(frozen=True, eq=False)
class CycleWork:
    """Energy per load cycle, cycle by cycle, and how well it settled.

    Attributes
    ----------
    work : ndarray, shape (n_cycles,)
        W_k = closed integral over cycle k of (F_tip d delta_tip + F_centre d delta_centre),
        trapezoidal, N·mm.
    tip, centre : ndarray, shape (n_cycles,)
        The two terms of W_k, N·mm.
    friction : ndarray, shape (n_cycles,)
        Friction dissipation sum tau . Delta s over cycle k, N·mm (equal to W_k in a periodic
        state up to the time discretisation).
    tolerance : float
        Requested relative change |W_k - W_(k-1)| / W_k at which the cycles stop.
    """

    work: FloatArray
    tip: FloatArray
    centre: FloatArray
    friction: FloatArray
    tolerance: float

    @property
    def cycles(self) -> int:
        return int(self.work.size)

    @property
    def relative_change(self) -> FloatArray:
        """|W_k - W_(k-1)| / |W_k| (NaN for the first cycle)."""
        w = self.work
        out = np.full(w.size, np.nan)
        if w.size > 1:
            out[1:] = np.abs(np.diff(w)) / np.maximum(np.abs(w[1:]), 1e-300)
        return out

    @property
    def reached(self) -> float:
        """Relative change of the last cycle (the tolerance reached), NaN after one cycle."""
        return float(self.relative_change[-1])

    @property
    def settled(self) -> bool:
        return bool(self.cycles > 1 and self.reached <= self.tolerance)

    def summary(self) -> dict[str, Any]:
        return {"cycles": self.cycles, "work_per_cycle_Nmm": self.work.tolist(),
                "tip_work_per_cycle_Nmm": self.tip.tolist(),
                "centre_work_per_cycle_Nmm": self.centre.tolist(),
                "friction_dissipation_per_cycle_Nmm": self.friction.tolist(),
                "relative_change_per_cycle": [None if np.isnan(x) else float(x)
                                              for x in self.relative_change],
                "cycle_tolerance": self.tolerance, "tolerance_reached": self.reached,
                "settled": self.settled}


@dataclass(frozen=True, eq=False)
class LoadPathResult:
    """Response to a planar cyclic load path, cycle after cycle until W per cycle settles.

    Attributes
    ----------
    theta : ndarray, shape (n,)
        Load parameter of each increment (start-up, then the cycles).
    f_tip, f_centre : ndarray, shape (n,)
        Applied forces, N.
    tip_displacement, centre_displacement : ndarray, shape (n,)
        Work-conjugate displacements along each force, relative to the clamped state, mm.
    cycle_start : int
        First sample of the first cycle.
    samples_per_cycle : int
    centre_direction : str
    cycle_work : CycleWork
    loops : dict of str -> HysteresisLoop
        ``tip`` and ``centre`` force-displacement curves of the last cycle (``source="builtin"``).
    contact : ContactHistory
    stats : SolverStats
    converged : bool
        Every increment converged.
    success : bool
        Converged and W per cycle settled to the tolerance.
    message : str
    """

    theta: FloatArray
    f_tip: FloatArray
    f_centre: FloatArray
    tip_displacement: FloatArray
    centre_displacement: FloatArray
    cycle_start: int
    samples_per_cycle: int
    centre_direction: str
    cycle_work: CycleWork
    loops: dict[str, HysteresisLoop]
    contact: ContactHistory
    stats: SolverStats
    converged: bool
    success: bool
    message: str
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def dissipated_energy(self) -> float:
        """W of the last cycle, N·mm."""
        return float(self.cycle_work.work[-1])

    @property
    def tip_work(self) -> float:
        """Tip term of W (last cycle), N·mm."""
        return float(self.cycle_work.tip[-1])

    @property
    def centre_work(self) -> float:
        """Centre term of W (last cycle), N·mm."""
        return float(self.cycle_work.centre[-1])

    @property
    def tip_share(self) -> float:
        """Tip term over W (last cycle), dimensionless."""
        return self.tip_work / self.dissipated_energy if self.dissipated_energy else float("nan")

    @property
    def centre_share(self) -> float:
        """Centre term over W (last cycle), dimensionless."""
        return (self.centre_work / self.dissipated_energy if self.dissipated_energy
                else float("nan"))

    @property
    def gross_sliding(self) -> bool:
        """Some increment has no sticking contact point: the body slides as a whole
        (:func:`~microslip.fe.result.gross_sliding_states`); the W per cycle is then that of
        gross sliding, not of microslip."""
        return gross_sliding_message(self.contact) is not None

    def last_cycle(self) -> slice:
        """Samples of the last cycle."""
        n = self.samples_per_cycle
        end = self.theta.size
        return slice(end - n - 1, end)

    def path_response(self) -> tuple[FloatArray, FloatArray]:
        """Displacements (tip, centre), mm, at the samples of the path as given: its start-up
        from the first pass, its closed cycle from the last (settled) cycle. Samples the solver
        prepended (a ramp from zero load, ``meta["prepended_samples"]``) are left out, so the
        arrays match a planar ``LoadPath`` sample for sample, for its ``PathResponse``."""
        k0 = self.cycle_start
        skip = int(self.meta.get("prepended_samples", 0))
        c = self.last_cycle()
        return (np.r_[self.tip_displacement[skip:k0], self.tip_displacement[c]],
                np.r_[self.centre_displacement[skip:k0], self.centre_displacement[c]])

    def summary(self) -> dict[str, Any]:
        return {"solver": "builtin", "centre_direction": self.centre_direction,
                "dissipated_energy_Nmm": self.dissipated_energy,
                "tip_work_Nmm": self.tip_work, "centre_work_Nmm": self.centre_work,
                "tip_share": self.tip_share, "centre_share": self.centre_share,
                "converged": self.converged, "success": self.success,
                "gross_sliding": self.gross_sliding,
                "message": join_message(self.message, gross_sliding_message(self.contact)),
                **self.cycle_work.summary(), **self.stats.summary()}


@dataclass(frozen=True, eq=False)
class CouplingResult:
    """Coupled planar loading against the sum of its two uni-axial parts.

    Attributes
    ----------
    tip_amplitude, centre_amplitude : float
        A_t, A_c, N.
    phase_deg : float
        Phase of the centre force ahead of the tip force, degrees.
    coupled : LoadPathResult
        Both forces together (one interface, one circular friction limit per node).
    tip_only, centre_only : LoadPathResult
        Each force alone, same samples and cycles.
    """

    tip_amplitude: float
    centre_amplitude: float
    phase_deg: float
    coupled: LoadPathResult
    tip_only: LoadPathResult
    centre_only: LoadPathResult

    @property
    def force_ratio(self) -> float:
        """R = A_t / A_c (Eq. 1 applied to the forces on the bar), inf when A_c = 0."""
        return self.tip_amplitude / self.centre_amplitude if self.centre_amplitude else np.inf

    @property
    def dissipated_energy(self) -> float:
        """W of the coupled cycle, N·mm."""
        return self.coupled.dissipated_energy

    @property
    def decoupled_dissipated_energy(self) -> float:
        """W_tip-only + W_centre-only, N·mm (the paper's decoupling)."""
        return self.tip_only.dissipated_energy + self.centre_only.dissipated_energy

    @property
    def coupling_ratio(self) -> float:
        """W_coupled / W_decoupled, dimensionless (1: the decoupling is exact)."""
        d = self.decoupled_dissipated_energy
        return self.dissipated_energy / d if d else float("nan")

    @property
    def tip_share(self) -> float:
        return self.coupled.tip_share

    @property
    def centre_share(self) -> float:
        return self.coupled.centre_share

    @property
    def converged(self) -> bool:
        return all(r.converged for r in (self.coupled, self.tip_only, self.centre_only))

    @property
    def success(self) -> bool:
        return all(r.success for r in (self.coupled, self.tip_only, self.centre_only))

    @property
    def gross_sliding(self) -> bool:
        """The coupled run slides as a whole at some increment (not microslip)."""
        return self.coupled.gross_sliding

    @property
    def message(self) -> str:
        bad = [f"{name}: {r.message}" for name, r in self.runs().items() if not r.success]
        sliding = [f"{name}: {gross_sliding_message(r.contact)}"
                   for name, r in self.runs().items() if r.gross_sliding]
        return join_message(
            "; ".join(bad) if bad else "converged; W per cycle settled in all three runs",
            *sliding)

    def runs(self) -> dict[str, LoadPathResult]:
        return {"coupled": self.coupled, "tip_only": self.tip_only,
                "centre_only": self.centre_only}

    @property
    def wall_s(self) -> float:
        return float(sum(r.stats.wall_s for r in self.runs().values()))

    def summary(self) -> dict[str, Any]:
        """The JSON of ``microslip planar --solver fe`` (units in the keys)."""
        return {
            "solver": "builtin",
            "tip_amplitude_N": self.tip_amplitude,
            "centre_amplitude_N": self.centre_amplitude,
            "force_ratio": self.force_ratio if np.isfinite(self.force_ratio) else None,
            "phase_deg": self.phase_deg,
            "dissipated_energy_Nmm": self.dissipated_energy,
            "decoupled_dissipated_energy_Nmm": self.decoupled_dissipated_energy,
            "coupling_ratio": self.coupling_ratio,
            "tip_share": self.tip_share, "centre_share": self.centre_share,
            "tip_work_Nmm": self.coupled.tip_work, "centre_work_Nmm": self.coupled.centre_work,
            "tip_only_dissipated_energy_Nmm": self.tip_only.dissipated_energy,
            "centre_only_dissipated_energy_Nmm": self.centre_only.dissipated_energy,
            "centre_direction": self.coupled.centre_direction,
            "converged": self.converged, "success": self.success,
            "gross_sliding": self.gross_sliding, "message": self.message,
            "warnings": [f"{name}: {gross_sliding_message(r.contact)}"
                         for name, r in self.runs().items() if r.gross_sliding],
            "dof": self.coupled.stats.dof, "wall_s": self.wall_s,
            "cycles": {name: r.cycle_work.summary() for name, r in self.runs().items()},
        }
