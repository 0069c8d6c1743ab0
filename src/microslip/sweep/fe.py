"""Finite-element amplitude sweeps: one FE run per amplitude, saved as it completes, resumable.

An FE run takes seconds to minutes, so a sweep over amplitudes is a long job. Every finished
point is appended to the output CSV at once (one complete line, flushed), after a first line
that records the sweep's settings as JSON (``# microslip fe-sweep {...}``). Running the same
sweep again with the same file reads the finished points and computes only the others; a file
of a different sweep is refused (never overwritten). Before computing, :func:`estimate`
gives the expected wall time from the saved points' own times or, for a new file, from the
first point.

Units: N, mm, N·mm, s; the column names carry them (:data:`FE_COLUMNS`).
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..conventions import DEFAULT_MESH
from ..errors import ParameterError
from ..fe.constants import DEFAULT_STICK_SLOPE
from ..named import result
from ..params import ClampParams
from ..progress import progress_bar

__all__ = [
    "FE_COLUMNS",
    "FESweepResult",
    "FESweepSpec",
    "amplitudes",
    "estimate",
    "read_finished",
    "run_fe_sweep",
]

#: Columns of an FE sweep CSV, in order.
FE_COLUMNS = ("amplitude_N", "peak_displacement_mm", "dissipated_energy_Nmm",
              "strain_energy_Nmm", "loss_factor", "converged", "wall_s")
#: First characters of the settings line of an FE sweep CSV.
HEADER = "# microslip fe-sweep "


@dataclass(frozen=True)
class FESweepSpec:
    """One FE amplitude sweep: the load case, the clamp, the amplitudes (N) and the solver's
    settings (those of :func:`microslip.fe.run_loop`)."""

    load: str
    params: ClampParams
    amplitudes: tuple[float, ...]
    solver: str = "builtin"
    mesh: str = DEFAULT_MESH
    substeps: int = 50
    strain_energy: str = "secant"
    stick_slope: float = DEFAULT_STICK_SLOPE

    def settings(self) -> dict[str, Any]:
        """What identifies the sweep in its file (JSON-able)."""
        out = asdict(self)
        out["params"] = self.params.as_dict()
        out["amplitudes"] = list(self.amplitudes)
        return out


@result
class FESweepResult:
    """The rows of a finished (or partly finished) FE sweep, in amplitude order.

    ``table`` has one row per point and the columns :data:`FE_COLUMNS`; ``computed`` counts
    the points run by this call (the others were read from the file).
    """

    spec: FESweepSpec
    table: np.ndarray
    computed: int

    def column(self, name: str) -> np.ndarray:
        return np.asarray(self.table[:, FE_COLUMNS.index(name)])


def _row(values: Any) -> str:
    return ",".join(repr(float(v)) for v in values) + "\n"


def read_finished(path: str | os.PathLike[str], spec: FESweepSpec
                  ) -> dict[float, tuple[float, ...]]:
    """The finished points saved in ``path`` by the same sweep, by amplitude (N).

    A missing file has none; a file of another sweep (or not of an FE sweep) is refused; an
    incomplete last line (a run killed while writing) is ignored.
    """
    p = Path(path)
    if not p.exists():
        return {}
    lines = p.read_text(encoding="utf-8").splitlines(keepends=True)
    if not lines or not lines[0].startswith(HEADER):
        raise ParameterError(f"{p} exists and is not an FE sweep file; remove it or choose "
                             "another --out")
    if json.loads(lines[0][len(HEADER):]) != spec.settings():
        raise ParameterError(f"{p} holds a different FE sweep (other settings); remove it or "
                             "choose another --out")
    rows: dict[float, tuple[float, ...]] = {}
    for line in lines[2:]:
        fields = line.rstrip("\n").split(",")
        if not line.endswith("\n") or len(fields) != len(FE_COLUMNS):
            continue
        values = tuple(float(x) for x in fields)
        rows[values[0]] = values
    return rows


def estimate(seconds_per_point: float, points: int) -> str:
    """One line: the expected wall time of ``points`` more points."""
    total = seconds_per_point * points
    when = f"{total / 60:.3g} min" if total >= 120 else f"{total:.3g} s"
    return (f"estimated time: {points} point(s) x {seconds_per_point:.3g} s = {when} "
            "(resumable: Ctrl-C keeps the finished points)")


def _open(path: Path, spec: FESweepSpec) -> Any:
    if path.exists():
        return path.open("a", encoding="utf-8")
    f = path.open("w", encoding="utf-8")
    f.write(HEADER + json.dumps(spec.settings()) + "\n")
    f.write(",".join(FE_COLUMNS) + "\n")
    f.flush()
    return f


def _point(run: Callable[[float], Any], amplitude: float) -> tuple[float, ...]:
    start = time.perf_counter()
    res = run(amplitude)
    wall = time.perf_counter() - start
    d = res.damping
    return (amplitude, res.peak_displacement, d.dissipated_energy, d.strain_energy,
            d.loss_factor, float(res.converged), wall)


def _runner(spec: FESweepSpec) -> Callable[[float], Any]:
    from ..fe import run_loop

    def run(amplitude: float) -> Any:
        return run_loop(spec.load, spec.params, amplitude, solver=spec.solver, mesh=spec.mesh,
                        substeps=spec.substeps, strain_energy_kind=spec.strain_energy,
                        stick_slope=spec.stick_slope)[0]

    return run


def _todo(spec: FESweepSpec, done: dict[float, tuple[float, ...]]) -> Iterator[float]:
    return (a for a in spec.amplitudes if a not in done)


def run_fe_sweep(spec: FESweepSpec, out: str | os.PathLike[str], *, progress: bool = True,
                 say: Callable[[str], None] = print,
                 on_point: Callable[[int, tuple[float, ...]], None] | None = None
                 ) -> FESweepResult:
    """Run the points of ``spec`` not yet in ``out``, appending each to ``out`` as it finishes.

    ``say`` receives the estimate line before the long part of the run; ``on_point`` (if
    given) each finished row with the number of points done. A KeyboardInterrupt leaves every
    finished point in ``out``: the same call resumes after them.
    """
    path = Path(out)
    done = read_finished(path, spec)
    left = list(_todo(spec, done))
    run = _runner(spec)
    computed = 0
    with _open(path, spec) as f, progress_bar(len(spec.amplitudes), "FE sweep",
                                               enabled=progress, unit="point") as bar:
        bar.update(len(spec.amplitudes) - len(left))
        if done and left:
            say(estimate(float(np.mean([r[-1] for r in done.values()])), len(left)))
        for i, amplitude in enumerate(left):
            row = _point(run, amplitude)
            f.write(_row(row))
            f.flush()
            done[amplitude] = row
            computed += 1
            bar.update(1)
            if on_point is not None:
                on_point(len(done), row)
            if i == 0 and len(left) > 1 and computed == len(done):
                say(estimate(row[-1], len(left) - 1))
    table = np.array([done[a] for a in spec.amplitudes], dtype=float)
    return FESweepResult(spec=spec, table=table, computed=computed)


def amplitudes(a: float, b: float, cases: int) -> tuple[float, ...]:
    """``cases`` amplitudes evenly spaced from a to b N (both included), each finite > 0."""
    for v in (a, b):
        if not (math.isfinite(v) and v > 0):
            raise ParameterError(f"--amplitude-range ends must be finite and > 0 N, got {v!r}")
    return tuple(float(x) for x in np.linspace(a, b, cases))
