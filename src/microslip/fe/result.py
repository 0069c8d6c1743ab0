"""The one result of a finite-element loop, whichever solver ran it.

Both solvers (:mod:`microslip.fe.builtin`, the built-in one, and CalculiX) return a
:class:`FELoopResult`: the paper's load step (Section 4, :class:`~microslip.loading.PaperSine`)
with the loop t = 0.25 .. 1.25 s as a :class:`~microslip.results.HysteresisLoop`, its damping
(an attribute, :func:`microslip.energy.damping_from_loop`), the contact status history and
the solver's own figures (``details``, a named result with ``options()`` and ``summary()``).

Conventions (docs/validation.md, docs/solver.md):

- The loop displacement is the work-conjugate displacement of the loaded section measured
  from the clamped state; its amplitude is half the peak-to-peak displacement.
- Loop closure: |delta(1.25 s) - delta(0.25 s)| over that amplitude (dimensionless, >= 0).
- Slip length of a domain: the slipping length along x, each contact point standing for its
  share ``length`` of the column of points it belongs to; a column exactly on a domain
  boundary (the loaded section of the centre case) counts half to each side.
- A loop during which no contact point slips encloses no area: W_d and eta are then exactly 0
  (not the rounding noise of the trapezoidal area) and ``message`` says why
  (:func:`loop_damping`: stick throughout, or shakedown after the first loading).
- Gross sliding: a state in which no contact point sticks (:func:`gross_sliding_states`). No
  stuck region anchors the body, so the joint slides as a whole: not microslip.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from ..energy import damping_from_loop
from ..loading import load_case
from ..named import result
from ..params import ClampParams
from ..results import DampingResult, HysteresisLoop

__all__ = ["OPEN", "SLIP", "STATUS", "STICK", "ContactHistory", "FELoopResult",
           "SolverDetails", "column_lengths", "gross_sliding_message", "gross_sliding_states",
           "idle_loop_reason", "join_message", "loop_damping"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Contact status codes: index in this tuple.
STATUS = ("open", "stick", "slip")
OPEN, STICK, SLIP = 0, 1, 2

UNITS = {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm", "time": "s",
         "stick_slope": "N/mm^3"}


def column_lengths(x: FloatArray, weight: FloatArray | None = None) -> FloatArray:
    """Length along x that each point stands for: its column's width (half the spacing to the
    neighbouring columns on each side) shared among the column's points in proportion to
    ``weight`` (default equal shares), mm."""
    xr = np.round(np.asarray(x, dtype=float), 9)
    cols, which = np.unique(xr, return_inverse=True)
    edges = np.concatenate([[cols[0]], 0.5 * (cols[1:] + cols[:-1]), [cols[-1]]])
    w = np.ones(xr.size) if weight is None else np.asarray(weight, dtype=float)
    total = np.bincount(which, weights=w)
    return np.asarray(np.diff(edges)[which] * w / total[which], dtype=float)


@result
class ContactHistory:
    """Contact state of every contact point (node of the bar's lower face) at every state.

    Attributes
    ----------
    nodes : ndarray of int, shape (m,)
        Indices of the contact points among the mesh's nodes (0-based).
    coords : ndarray, shape (m, 3)
        Reference coordinates, mm (z = 0).
    time : ndarray, shape (k,)
        Time of each state, s: 0 is the clamped state, then every increment to 1.25 s.
    status : ndarray of int8, shape (k, m)
        Codes into :data:`STATUS` (0 open, 1 stick, 2 slip).
    length : ndarray, shape (m,)
        Length along x each point stands for in slip lengths, mm (:func:`column_lengths`).
    slip : ndarray, shape (k, m, 2) or None
        Tangential relative displacement (x, y), mm, where the solver reports it.
    """

    nodes: IntArray
    coords: FloatArray
    time: FloatArray
    status: NDArray[np.int8]
    length: FloatArray
    slip: FloatArray | None = None

    def index(self, t: float) -> int:
        """Index of the state at time ``t`` (s); raises if there is none within 1e-9 s."""
        k = int(np.argmin(np.abs(self.time - t)))
        if abs(self.time[k] - t) > 1e-9:
            raise ValueError(f"no contact state at t = {t:g} s")
        return k

    def slip_length(self, x_min: float = -math.inf, x_max: float = math.inf) -> FloatArray:
        """Slipping length along x in x_min <= x <= x_max at every state, mm; points exactly on
        a finite bound (within 1e-6 mm) count half."""
        x = self.coords[:, 0]
        share = ((x >= x_min - 1e-6) & (x <= x_max + 1e-6)).astype(float)
        share[np.isclose(x, x_min, rtol=0.0, atol=1e-6) | np.isclose(x, x_max, rtol=0.0,
                                                                      atol=1e-6)] = 0.5
        return np.asarray((self.status == SLIP) @ (share * self.length), dtype=float)

    @property
    def slip_area_fraction(self) -> FloatArray:
        """Share of the contact length slipping at every state (dimensionless)."""
        return self.slip_length() / float(np.sum(self.length))


def idle_loop_reason(contact: ContactHistory, loop_states: int) -> str | None:
    """Why a loop of the last ``loop_states`` states encloses no area, or None if it may not.

    The loop dissipates only if some contact point slips in one of its increments (the states
    after its first). None of them slipping: ``stick throughout`` if no point slipped at any
    state, ``shakedown`` if points slipped only before the loop (the first loading).
    """
    status = contact.status
    inside = status[max(status.shape[0] - loop_states + 1, 0):]
    if np.any(inside == SLIP):
        return None
    if np.any(status == SLIP):
        return ("shakedown: contact points slipped only during the first loading, none during "
                "the loop, so it encloses no area and W_d = 0")
    return ("stick throughout: no contact point slipped at any increment, so the loop "
            "encloses no area and W_d = 0")


def gross_sliding_states(contact: ContactHistory) -> IntArray:
    """Indices of the states in which no contact point sticks and some slip (gross sliding)."""
    status = contact.status
    sliding = ~np.any(status == STICK, axis=1) & np.any(status == SLIP, axis=1)
    return np.flatnonzero(sliding).astype(np.int64)


def loop_damping(loop: HysteresisLoop, contact: ContactHistory, strain_energy_kind: str
                 ) -> tuple[DampingResult, str | None]:
    """W_d, U and eta of an FE loop (:func:`~microslip.energy.damping_from_loop`), with W_d and
    eta exactly 0 when no contact point slips during the loop; the reason, or None. A loop cut
    short before it began (fewer than 2 points: the run failed) has NaN figures."""
    if loop.force.size < 2:
        nan = math.nan
        return DampingResult(nan, nan, strain_energy_kind, nan, nan, nan, loop), None
    damping = damping_from_loop(loop, None, strain_energy_kind)
    reason = idle_loop_reason(contact, loop.force.size)
    if reason is None:
        return damping, None
    return dataclasses.replace(damping, dissipated_energy=0.0, loss_factor=0.0), reason


def gross_sliding_message(contact: ContactHistory) -> str | None:
    """One sentence if some state is gross sliding (see :func:`gross_sliding_states`)."""
    k = gross_sliding_states(contact)
    if k.size == 0:
        return None
    return (f"gross sliding (full slip), not microslip: no contact point sticks in {k.size} "
            f"of {contact.status.shape[0]} states (the first is state {int(k[0])}), so no stuck "
            "region anchors the joint and the 1-D microslip models do not apply")


def join_message(*parts: str | None) -> str:
    """The sentences given (None skipped), joined by semicolons."""
    return "; ".join(p for p in parts if p)


class SolverDetails(Protocol):
    """What a solver adds to an :class:`FELoopResult`: its set-up and its own figures."""

    def options(self) -> dict[str, Any]: ...

    def summary(self) -> dict[str, Any]: ...


@result
class FELoopResult:
    """One finite-element loop of the clamped bar (either solver).

    Attributes
    ----------
    solver : str
        Name in :data:`microslip.fe.SOLVERS`.
    load_case : str
        Name in :data:`microslip.loading.LOAD_CASES`.
    params : ClampParams
    amplitude : float
        F0, N.
    time, force, displacement : ndarray, shape (n + 1,)
        Time (s; 0 is the clamped state), applied force (N) and work-conjugate displacement of
        the loaded section from the clamped state (mm) after every increment.
    loop : HysteresisLoop
        The closed loop t = 0.25 .. 1.25 s (``source`` is the solver).
    damping : DampingResult
        W_d, U and eta of ``loop``.
    contact : ContactHistory
    dof : int
        Free degrees of freedom.
    iterations : ndarray of int
        Equilibrium iterations of each increment.
    wall_s : float
        Wall time of the solver, s.
    converged : bool
        Every increment converged.
    message : str
    details : SolverDetails
        The solver's set-up (``options()``) and own figures (``summary()``).
    job_dir : Path or None
        Where the solver's files are (CalculiX), or None.
    """

    solver: str
    load_case: str
    params: ClampParams
    amplitude: float
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
    message: str
    details: SolverDetails
    job_dir: Path | None = None

    @property
    def peak_displacement(self) -> float:
        """Half the peak-to-peak displacement of the loop, mm."""
        return self.loop.peak_displacement

    @property
    def dissipated_energy(self) -> float:
        """W_d, the loop area (Eq. 21), N·mm."""
        return self.damping.dissipated_energy

    @property
    def closure(self) -> float:
        """|delta(1.25 s) - delta(0.25 s)| over the loop's amplitude (dimensionless)."""
        d = self.loop.displacement
        return float(abs(d[-1] - d[0]) / max(self.peak_displacement, 1e-300))

    @property
    def offset(self) -> float:
        """Mid-point of the loop's displacement extremes, mm (0 for a point-symmetric loop)."""
        d = self.loop.displacement
        return float(0.5 * (np.max(d) + np.min(d)))

    @property
    def total_iterations(self) -> int:
        return int(np.sum(self.iterations))

    def slip_lengths(self, t: float = 0.25) -> dict[str, float]:
        """Slip length of each domain of the load case at time ``t`` (default the first peak),
        mm (:attr:`~microslip.loading.LoadCase.domains`)."""
        k = self.contact.index(t)
        length = self.params.length
        return {name: float(self.contact.slip_length(lo * length, hi * length)[k])
                for name, lo, hi in load_case(self.load_case).domains}

    @property
    def gross_sliding(self) -> bool:
        """Some state has no sticking contact point (:func:`gross_sliding_states`)."""
        return bool(gross_sliding_states(self.contact).size)

    @property
    def warnings(self) -> list[str]:
        """Sentences on what the figures do not mean (gross sliding); empty if none."""
        message = gross_sliding_message(self.contact)
        return [] if message is None else [message]

    def with_strain_energy(self, kind: str) -> FELoopResult:
        """The same result with U (and eta) by another definition."""
        return dataclasses.replace(self, damping=loop_damping(self.loop, self.contact, kind)[0])

    def summary(self) -> dict[str, Any]:
        """The JSON object of ``microslip fe``: the keys of ``microslip loop --json`` plus the
        FE set-up and figures (units in the keys). A run that did not converge has no figures
        of its loop (None: displacement, energies, loss factor, slip lengths, closure)."""
        if self.converged:
            loop = self.damping.loop_json(self.slip_lengths())
            closure: float | None = self.closure
            offset: float | None = self.offset
        else:
            loop = {key: None for key in ("peak_displacement_mm", "dissipated_energy_Nmm",
                                          "strain_energy_Nmm", "strain_energy_definition",
                                          "loss_factor", "slip_length_mm")}
            loop.update(strain_energy_definition=self.damping.strain_energy_kind,
                        slip_length_by_domain_mm={},
                        loop={"force_N": self.loop.force,
                              "displacement_mm": self.loop.displacement})
            closure = offset = None
        return {
            "model": self.load_case, "solver": self.solver, "units": dict(UNITS),
            "params": self.params.as_dict(), "options": self.details.options(),
            "increments": int(self.time.size - 1), "amplitude_N": self.amplitude,
            "macroslip_force_N": self.params.macroslip_force,
            **loop,
            "dof": self.dof, "wall_s": self.wall_s, "converged": self.converged,
            "iterations": self.total_iterations, "loop_closure": closure,
            "loop_offset_mm": offset, "message": self.message, **self.details.summary(),
            "job_dir": None if self.job_dir is None else str(self.job_dir),
            "gross_sliding": self.gross_sliding, "warnings": self.warnings,
        }

