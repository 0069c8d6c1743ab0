"""CalculiX on the user's own mesh: write the deck, run ccx, read the loops back.

:func:`run_mesh_calculix` writes :func:`~microslip.fe.calculix.meshdeck.build_mesh_deck` into
a job directory, runs ccx through :func:`~microslip.fe.calculix.runner.run_ccx` (time-out,
typed :class:`~microslip.fe.errors.SolverError` failures) and reads the ``.dat`` and ``.sta``
files into a :class:`MeshCalculixResult`.

Definitions (the built-in solver's, docs/solver.md "Planar paths"):

- the work-conjugate displacement of load l is delta_l = sum_i w_i (u_i . d_l), the
  force-weighted mean along its direction d_l over its set's nodes with the consistent shares
  w_i of :func:`~microslip.fe.hexmesh.face_load`, measured from the clamped state (end of
  step 1), so that F_l d(delta_l) is the work of load l's nodal forces;
- the dissipated energy W is the work of all loads over the last cycle,
  W = sum_l (closed integral of F_l d delta_l), trapezoidal over its increments
  (:func:`microslip.energy.loop_work`; Eq. 21 of the paper for one load);
- the peak displacement of a load is half the peak-to-peak delta_l over the last cycle;
- the contact status of every node of the contact faces at every state (open, stick, slip)
  comes from the ``.frd`` file's slips and tractions by the box's rule
  (:func:`~microslip.fe.calculix.collect.contact_status`, docs/validation.md Section 1); a
  last cycle in which no node slips has W = 0 with the reason (stick throughout, or
  shakedown), and states in which no node sticks are flagged as gross sliding, with the
  sentences of :mod:`microslip.fe.result`.

Units: N, mm, N·mm; time in cycles.
"""

from __future__ import annotations

import dataclasses
import math
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...energy import loop_work
from ...errors import ParameterError
from ...io import atomic_write
from ...named import result
from ..assembly import Assembly, as_assembly
from ..clamp import MeshClamp
from ..errors import ResultsError
from ..hexmesh import HexMesh, face_load
from ..meshload import MeshLoad
from ..result import (
    ContactHistory,
    column_lengths,
    gross_sliding_message,
    idle_loop_reason,
    join_message,
)
from .assemblydeck import resolve_assembly
from .collect import contact_status
from .meshdeck import (
    CLAMP_TIME,
    MESH_ELEMENTS,
    MeshLoadPlan,
    build_frequency_deck,
    build_mesh_deck,
    load_plan,
)
from .meshhistory import LoadHistory, load_history
from .readers import read_dat, read_frd, read_sta
from .runner import JOBNAME, find_ccx, run_ccx

__all__ = ["MeshCalculixResult", "contact_values", "mesh_timeout", "read_contact",
           "read_frequencies", "read_mesh_results", "run_frequency_calculix",
           "run_mesh_calculix"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

_RESULT_SUFFIXES = (".dat", ".frd", ".sta", ".cvg", ".12d")


@result
class MeshCalculixResult:
    """A CalculiX run of the user's mesh: every load's loop and the work of the last cycle.

    Attributes
    ----------
    loads : tuple of MeshLoad
    time : ndarray, shape (k + 1,)
        Increment ends of the load step, cycles (the first sample is the clamped state; a
        ``ramp`` start-up has negative times, :data:`~.meshhistory.STARTUPS`).
    force : ndarray, shape (k + 1, loads)
        F_l(t), N.
    displacement : ndarray, shape (k + 1, loads)
        Work-conjugate displacement delta_l from the clamped state, mm.
    work : ndarray, shape (loads,)
        Work of each load over the last cycle, N·mm.
    dissipated_energy : float
        W = sum of ``work``, N·mm.
    cycle_work : ndarray, shape (cycles,)
        The work of all loads over each full cycle, N·mm (the last is W before a stick or
        shakedown verdict sets it to 0): whether the cycles have settled.
    peak_displacement : ndarray, shape (loads,)
        Half the peak-to-peak delta_l over the last cycle, mm.
    clamp_displacement : ndarray, shape (loads,)
        delta_l caused by the clamping step alone, mm.
    increments_per_cycle, cycles : int
    iterations : ndarray of int, shape (k,)
        Equilibrium iterations of each increment of the load step.
    converged : bool
        Every increment converged at its first attempt (``DIRECT`` increments, no cut-back).
    message : str
    element : str
        C3D8I or C3D20R.
    dof : int
        3 per node of the body (the base is fixed).
    wall_s : float
        Wall time of ccx, s.
    contact : ContactHistory or None
        Status (0 open, 1 stick, 2 slip) and slip of every node of the contact faces at every
        state (None when read without the contact set).
    job_dir : Path or None
        Where the deck and the solver's files are (None: a removed temporary directory).
    """

    loads: tuple[MeshLoad, ...]
    time: FloatArray
    force: FloatArray
    displacement: FloatArray
    work: FloatArray
    dissipated_energy: float
    cycle_work: FloatArray
    peak_displacement: FloatArray
    clamp_displacement: FloatArray
    increments_per_cycle: int
    cycles: int
    iterations: IntArray
    converged: bool
    message: str
    element: str
    dof: int
    wall_s: float
    contact: ContactHistory | None
    job_dir: Path | None

    @property
    def last_cycle(self) -> slice:
        """Rows of the last (settled) cycle, both ends included."""
        return slice(self.time.size - 1 - self.increments_per_cycle, self.time.size)

    def summary(self) -> dict[str, Any]:
        """The JSON keys of ``microslip fe --solver calculix`` on a mesh (issue 22)."""
        return {
            "solver": "calculix", "element": self.element, "dof": self.dof,
            "dissipated_energy_Nmm": self.dissipated_energy,
            "peak_displacement_mm": float(self.peak_displacement[0]),
            "loads": [{"set": ld.set, "direction": list(ld.direction),
                       "amplitude_N": ld.amplitude, "phase_deg": ld.phase_deg,
                       "work_Nmm": float(w), "peak_displacement_mm": float(d)}
                      for ld, w, d in zip(self.loads, self.work, self.peak_displacement,
                                          strict=True)],
            "increments_per_cycle": self.increments_per_cycle, "cycles": self.cycles,
            "cycle_work_Nmm": [float(w) for w in self.cycle_work],
            "iterations": int(self.iterations.sum()), "converged": self.converged,
            "wall_s": self.wall_s, "message": self.message, "warnings": self.warnings(),
        }

    def warnings(self) -> list[str]:
        """What the user should know about the run: not converged, gross sliding."""
        out = []
        if not self.converged:
            out.append("an increment was cut back: the loop is not at the stated increments")
        if self.contact is not None:
            gross = gross_sliding_message(self.contact)
            if gross:
                out.append(gross)
        return out


def mesh_timeout(mesh: HexMesh, increments: int = 50) -> float:
    """A generous time-out, s: 120 s plus 0.15 s per degree of freedom (the box's rule,
    :func:`~microslip.fe.calculix.runner.default_timeout`) for every 50 increments or fewer
    (a run of several cycles, or of many increments per cycle, takes proportionally longer:
    the post's 3 cycles of 160 increments took 282 s on a loaded machine).

    >>> from microslip.fe.examples import cantilever_mesh
    >>> m = cantilever_mesh(12, 3, 1)
    >>> round(mesh_timeout(m), 6), round(mesh_timeout(m, 200), 6)
    (166.8, 307.2)
    """
    dof = 3 * int(np.unique(mesh.elements).size)
    return 120.0 + 0.15 * dof * max(1.0, increments / 50.0)


def _states(blocks: list[Any], n: int, what: str, job_dir: Path) -> list[Any]:
    """The clamped state and the load step's increments: blocks from the end of step 1 on
    (step 1 may have taken more than one increment)."""
    kept = [b for b in blocks if b.time >= CLAMP_TIME - 1e-9]
    if len(kept) != n + 1:
        raise ResultsError(f"{what} holds {len(kept)} result blocks from the clamped state on, "
                           f"expected {n + 1} (clamped state and {n} increments): the run "
                           "stopped early", job_dir)
    return kept


def contact_values(frd: str | Path, nodes: IntArray, n: int) -> FloatArray:
    """The ``.frd`` file's CONTACT values (CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2 in columns
    1..5) of ``nodes`` (0-based) at the clamped state and the ``n`` increments of the load
    step, shape (n + 1, nodes, 6); a node missing from a block has no contact element there
    (zeros: open)."""
    frd = Path(frd)
    blocks = _states(read_frd(frd, names=("CONTACT",)).select("CONTACT"), n, frd.name,
                     frd.parent)
    ids = np.asarray(nodes, dtype=np.int64) + 1
    values = np.zeros((n + 1, ids.size, 6))
    for k, cb in enumerate(blocks):
        if cb.nodes.size == 0:
            continue
        order = np.argsort(cb.nodes, kind="stable")
        sorted_ids = cb.nodes[order]
        pos = np.minimum(np.searchsorted(sorted_ids, ids), sorted_ids.size - 1)
        found = sorted_ids[pos] == ids
        values[k, found] = cb.values[order][pos[found]]
    return values


def read_contact(frd: str | Path, nodes: IntArray, coords: FloatArray, times: FloatArray,
                 friction: float, stick_slope: float) -> ContactHistory:
    """The contact status and slip of ``nodes`` (0-based) at every state, from the ``.frd``
    file's CONTACT blocks (CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2); a node missing from a
    block has no contact element there (open)."""
    values = contact_values(frd, nodes, int(times.size - 1))
    status = contact_status(values[:, :, 3], values[:, :, 4:6], values[:, :, 1:3], friction,
                            stick_slope)
    return ContactHistory(np.asarray(nodes, dtype=np.int64), np.asarray(coords, dtype=float),
                          np.asarray(times, dtype=float).copy(), status,
                          column_lengths(np.asarray(coords, dtype=float)[:, 0]),
                          values[:, :, 1:3].copy())


def read_mesh_results(plan: MeshLoadPlan, history: LoadHistory, job_dir: str | Path,
                      jobname: str = JOBNAME, *, element: str = "",
                      dof: int = 0, wall_s: float = math.nan,
                      contact: tuple[HexMesh, IntArray, float, float] | None = None
                      ) -> MeshCalculixResult:
    """Read a finished run's ``.dat`` and ``.sta`` files into a :class:`MeshCalculixResult`;
    with ``contact = (mesh, contact faces, friction, stick_slope)`` also the contact status
    from the ``.frd`` file.

    Raises
    ------
    ResultsError
        A file is missing or truncated, or it does not hold the clamped state and every
        increment of the load step (a partial loop is never returned).
    """
    job_dir = Path(job_dir)
    times = history.time
    increments_per_cycle = history.increments_per_cycle
    n = int(times.size - 1)
    blocks = _states(read_dat(job_dir / f"{jobname}.dat", "displacements",
                              expected_rows=plan.loaded.size), n, f"{jobname}.dat", job_dir)
    expected = CLAMP_TIME + history.step_time
    got = np.array([b.time for b in blocks])
    if not np.allclose(got, expected, rtol=0.0, atol=2e-6 * (1.0 + expected)):
        raise ResultsError(f"{jobname}.dat: increment times do not match the {n} equal "
                           "increments (cut-back?)", job_dir)
    u = np.empty((n + 1, plan.loaded.size, 3))
    for k, b in enumerate(blocks):
        if not np.array_equal(b.nodes, plan.loaded + 1) or b.values.shape[1] < 3:
            raise ResultsError(f"{jobname}.dat: the printed node set is not the loaded nodes",
                               job_dir)
        u[k] = b.values[:, :3]
    absolute = plan.conjugate(u)
    displacement = absolute - absolute[0]
    sta = read_sta(job_dir / f"{jobname}.sta").in_step(2)
    if sta.iterations.size != n:
        raise ResultsError(f"{jobname}.sta lists {sta.iterations.size} converged increments "
                           f"of the load step, expected {n}", job_dir)
    converged = bool(np.all(sta.attempts == 1))
    force = history.factors * np.array([ld.amplitude for ld in plan.loads])[None, :]
    last = slice(n - increments_per_cycle, n + 1)
    work = np.array([loop_work(force[last, j], displacement[last, j])
                     for j in range(len(plan.loads))])
    peak = 0.5 * np.ptp(displacement[last], axis=0)
    start = history.first_cycle
    cycle_work = np.array([
        sum(loop_work(force[a:a + increments_per_cycle + 1, j],
                      displacement[a:a + increments_per_cycle + 1, j])
            for j in range(len(plan.loads)))
        for a in range(start, n, increments_per_cycle)])
    states = None
    idle = gross = None
    if contact is not None:
        mesh, faces, friction, stick_slope = contact
        nodes = face_load(mesh, faces)[0]
        states = read_contact(job_dir / f"{jobname}.frd", nodes, mesh.nodes[nodes], times,
                              friction, stick_slope)
        idle = idle_loop_reason(states, increments_per_cycle + 1)
        gross = gross_sliding_message(states)
        if idle is not None:
            work = np.zeros_like(work)
    total = float(work.sum())
    message = (join_message("converged", idle, gross) if converged
               else "cut back: an increment needed more than one attempt")
    return MeshCalculixResult(
        loads=plan.loads, time=np.asarray(times, dtype=float).copy(), force=force,
        displacement=displacement, work=work, dissipated_energy=total, cycle_work=cycle_work,
        peak_displacement=peak,
        clamp_displacement=np.asarray(absolute[0], dtype=float).copy(),
        increments_per_cycle=int(increments_per_cycle),
        cycles=history.cycles,
        iterations=np.asarray(sta.iterations, dtype=np.int64).copy(),
        converged=converged, message=message, element=element, dof=int(dof),
        wall_s=float(wall_s), contact=states, job_dir=job_dir)


def run_mesh_calculix(mesh: HexMesh, assembly: Assembly | MeshClamp, *,
                      loads: Sequence[MeshLoad], increments_per_cycle: int = 40,
                      cycles: int = 1, max_iterations: int = 26, startup: str = "quarter",
                      job_dir: str | Path | None = None, timeout: float | None = None,
                      threads: int = 1, executable: str | None = None,
                      formulation: str = "face-to-face",
                      progress: Callable[[int], None] | None = None) -> MeshCalculixResult:
    """Write the deck of the user's mesh and its assembly (:func:`build_mesh_deck`, same
    parameters), run ccx and read each load's loop and the work of the last cycle.

    Parameters
    ----------
    assembly : Assembly or MeshClamp
        The contacts, preloads, supports, materials and contact law
        (:func:`~microslip.fe.assembly.as_assembly`); the status is read at every contact's
        face nodes.
    job_dir : path, optional
        Created if needed; holds ``job.inp``, the solver's files and ``ccx.log``. None: a
        temporary directory, removed afterwards (``result.job_dir`` is then None).
    timeout : float, optional
        Seconds (default :func:`mesh_timeout`).
    threads : int
        ``OMP_NUM_THREADS`` of the solver.
    executable : str, optional
        Solver name or path (default ``ccx`` on PATH).
    formulation : str
        The contact (:data:`~.meshdeck.CONTACT_FORMULATIONS`): ``"face-to-face"`` (default)
        or ``"node-to-surface"`` (the built-in solver's nodal law).
    progress : callable, optional
        Called while ccx runs with the increments it has finished (both steps; the total is
        ``len(history.time) + 1``: :func:`~.runner.run_ccx`'s ``watch``).

    Raises
    ------
    ParameterError
        A bad input (before anything is written).
    SolverError
        Solver missing, time-out, killed, not converged, results missing or truncated; nothing
        partial is returned.
    """
    a = as_assembly(assembly)
    deck = build_mesh_deck(mesh, a, loads=loads, increments_per_cycle=increments_per_cycle,
                           cycles=cycles, max_iterations=max_iterations, startup=startup,
                           formulation=formulation)
    faces = resolve_assembly(mesh, a).contact_faces
    plan = load_plan(mesh, loads)
    history = load_history(loads, increments_per_cycle, cycles, startup)
    exe = find_ccx(executable)  # fail before touching the directory
    if timeout is not None and not (isinstance(timeout, (int, float)) and timeout > 0):
        raise ParameterError(f"timeout must be > 0 s, got {timeout!r}")
    dof = 3 * int(np.unique(mesh.elements).size)
    element = MESH_ELEMENTS[mesh.nodes_per_element]

    def run_in(d: Path) -> MeshCalculixResult:
        d.mkdir(parents=True, exist_ok=True)
        for suffix in _RESULT_SUFFIXES:
            (d / f"{JOBNAME}{suffix}").unlink(missing_ok=True)
        with atomic_write(d / f"{JOBNAME}.inp") as fh:
            fh.write(deck)
        run = run_ccx(d, JOBNAME, timeout=timeout or mesh_timeout(mesh, history.time.size),
                      threads=threads, executable=exe, watch=progress)
        try:
            return read_mesh_results(plan, history, d, JOBNAME,
                                     element=element, dof=dof, wall_s=run.wall_s,
                                     contact=(mesh, faces, a.friction, a.stick_slope))
        except ResultsError as exc:
            raise type(exc)(exc.message, d, run.log_tail) from None

    if job_dir is not None:
        return run_in(Path(job_dir))
    with tempfile.TemporaryDirectory(prefix="microslip-ccx-mesh-") as tmp:
        r = run_in(Path(tmp))
    return dataclasses.replace(r, job_dir=None)


def read_frequencies(dat: str | Path) -> FloatArray:
    """The frequencies (Hz: cycles per time, the time in s) of the last
    ``E I G E N V A L U E   O U T P U T`` table of a ``.dat`` file."""
    text = Path(dat).read_text(errors="replace")
    marker = "E I G E N V A L U E   O U T P U T"
    if marker not in text:
        raise ResultsError(f"{dat}: no eigenvalue output (did the frequency step run?)")
    block = text.rsplit(marker, 1)[1]
    out = []
    started = False
    for line in block.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[0].isdigit():
            try:
                out.append(float(parts[2]))
            except ValueError:
                break
            started = True
        elif started and parts:
            break
    if not out:
        raise ResultsError(f"{dat}: the eigenvalue table is empty")
    return np.array(out)


def run_frequency_calculix(mesh: HexMesh, assembly: Assembly | MeshClamp, *,
                           density_kg_m3: float | None = None, modes: int = 10,
                           element: str | None = None, job_dir: str | Path | None = None,
                           timeout: float | None = None, executable: str | None = None
                           ) -> FloatArray:
    """Write :func:`~microslip.fe.calculix.meshdeck.build_frequency_deck` (same parameters),
    run ccx and return the linear frequencies about the clamped state, Hz (issue 23)."""
    deck = build_frequency_deck(mesh, assembly, density_kg_m3=density_kg_m3, modes=modes,
                                element=element)
    exe = find_ccx(executable)

    def run_in(d: Path) -> FloatArray:
        d.mkdir(parents=True, exist_ok=True)
        for suffix in _RESULT_SUFFIXES:
            (d / f"{JOBNAME}{suffix}").unlink(missing_ok=True)
        with atomic_write(d / f"{JOBNAME}.inp") as fh:
            fh.write(deck)
        run_ccx(d, JOBNAME, timeout=timeout or mesh_timeout(mesh), threads=1, executable=exe)
        return read_frequencies(d / f"{JOBNAME}.dat")

    if job_dir is not None:
        return run_in(Path(job_dir))
    with tempfile.TemporaryDirectory(prefix="microslip-ccx-modes-") as tmp:
        return run_in(Path(tmp))
