"""Mesh convergence as a result: the given mesh and its refinements, Richardson's estimate.

:func:`richardson` is the kernel: values on meshes of size h, h/r, h/r^2 (r = 2 here) give
the observed order p = log((v1 - v0) / (v2 - v1)) / log r and the estimate
v* = v_last + (v_last - v_prev) / (r^p - 1); from two levels the element's theoretical order
(:data:`THEORETICAL_ORDER`) is assumed and the result says so. The discretisation error of
the given (coarsest) mesh is v0 / v* - 1. The uncertainty of the estimate is Roache's grid
convergence index, F_s |v* - v_last| / |v*| with the safety factor F_s = 1.25 for an observed
order and 3 for an assumed one (Roache 1998, *Verification and Validation in Computational
Science and Engineering*, ch. 5). Three levels outside the asymptotic range (oscillating, or
changing more on the finer pair, or an observed order outside :data:`ORDER_RANGE`) are not
extrapolated: the estimate is the finest value, its uncertainty 3 x the largest change between
levels, and ``order_source`` is ``none``.

:func:`converge_own_mesh` runs an own-mesh case (:mod:`.ownmesh`) on the given mesh and one
or two refinements x2 (:mod:`.refine`) and estimates W (N·mm) and the peak displacement (mm);
:func:`converge_frequencies` does the same for the stuck linear frequencies (Hz) of a clamped
mesh. Interpretation: docs/interpretation.md, "Mesh convergence as a result".
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import ParameterError
from .hexmesh import HexMesh

__all__ = [
    "LEVEL_CHOICES",
    "REFINEMENT_RATIO",
    "THEORETICAL_ORDER",
    "WARN_ERROR",
    "Estimate",
    "FrequencyConvergence",
    "Level",
    "MeshConvergence",
    "converge_frequencies",
    "converge_own_mesh",
    "richardson",
]

#: Refinement ratio between levels (each level subdivides the last one's elements x2).
REFINEMENT_RATIO = 2
#: How many meshes a convergence study runs: the given one and one or two refinements.
LEVEL_CHOICES = (2, 3)
#: The relative distance of the given mesh from the estimate above which a warning is given.
WARN_ERROR = 0.05
#: Orders of convergence assumed from two levels, for 8-node hexahedra (C3D8I), by quantity.
#: The loop area W: 1, the conservative end of what is measured. Friction acts at the nodes,
#: so the slip front is placed to O(h) and, once the slip zone spans many nodes, the loop area
#: converges as h^2 (2.1 on the tip bar at R = 0.75, tests/test_fe_builtin_convergence.py);
#: in microslip the zone spans a few nodes and the measured rate is 1.2 (the tip bar at
#: R = 0.05, tests/test_fe_small_slip.py), and coarse meshes are not yet in the asymptotic
#: range at all (the cantilever's W: 24x6x2 -> 96x24x8, docs/interpretation.md §15).
#: Displacements and eigenvalues of linear elements converge as h^2 (Strang & Fix), the
#: frequencies too.
THEORETICAL_ORDER = {"dissipated_energy": 1.0, "peak_displacement": 2.0, "frequency": 2.0}
#: An observed order outside this range is not trusted: the assumed order is used instead.
ORDER_RANGE = (0.5, 6.0)
#: Roache's safety factors of the grid convergence index, by the order's source: observed,
#: assumed (two levels), none (three levels outside the asymptotic range: no extrapolation).
SAFETY = {"observed": 1.25, "assumed": 3.0, "none": 3.0}


@dataclass(frozen=True)
class Estimate:
    """Richardson's estimate of one quantity from its values on successive meshes.

    Attributes
    ----------
    values : tuple of float
        The quantity on each level, coarsest (the given mesh) first.
    value : float
        The estimate of the converged value.
    order : float
        The order of convergence used.
    order_source : str
        ``observed`` (from three levels), ``assumed`` (two levels: the element's theoretical
        order) or ``none`` (three levels not in the asymptotic range, ``note`` says why: the
        value is the finest level's, not extrapolated; ``order`` is the theoretical one).
    relative_error : float
        The given mesh's discretisation error, values[0] / value - 1.
    uncertainty : float
        Relative uncertainty of the estimate (grid convergence index).
    note : str
        Why the observed order was not used, empty otherwise.
    """

    values: tuple[float, ...]
    value: float
    order: float
    order_source: str
    relative_error: float
    uncertainty: float
    note: str = ""

    @property
    def how(self) -> str:
        """How the estimate was made, in words."""
        if self.order_source == "none":
            return "the finest level: not in the asymptotic range, not extrapolated"
        return f"{self.order_source} order {self.order:.3g}"

    def summary(self) -> dict[str, Any]:
        return {"value": self.value, "order": self.order, "order_source": self.order_source,
                "relative_error": self.relative_error, "uncertainty": self.uncertainty,
                "note": self.note}


def richardson(values: Sequence[float], assumed_order: float,
               ratio: float = REFINEMENT_RATIO) -> Estimate:
    """Richardson's extrapolation of ``values`` on meshes h, h/ratio (, h/ratio^2).

    Three values that converge monotonically (successive differences of one sign, shrinking)
    give the observed order, if it lies in :data:`ORDER_RANGE`; otherwise the finest value is
    the estimate (``order_source`` ``none``). From two values ``assumed_order`` extrapolates.

    >>> e = richardson([1.25, 1.0625, 1.015625], 2.0)   # 1 + h^2, h = 1/2, 1/4, 1/8
    >>> round(e.value, 12), round(e.order, 12), e.order_source
    (1.0, 2.0, 'observed')
    """
    v = [float(x) for x in values]
    if len(v) not in LEVEL_CHOICES or not all(math.isfinite(x) for x in v):
        raise ParameterError(f"richardson needs 2 or 3 finite values, got {values!r}")
    if not (math.isfinite(assumed_order) and assumed_order > 0 and ratio > 1):
        raise ParameterError(f"richardson needs an order > 0 and a ratio > 1, got "
                             f"{assumed_order!r}, {ratio!r}")
    order, source, note = assumed_order, "assumed", ""
    if len(v) == 3:
        d0, d1 = v[1] - v[0], v[2] - v[1]
        if d1 == 0.0 or d0 == 0.0:
            note = "two levels give the same value"
        elif d0 * d1 < 0:
            note = "the values oscillate: not in the asymptotic range"
        elif abs(d1) >= abs(d0):
            note = "the differences do not shrink: not in the asymptotic range"
        else:
            p = math.log(d0 / d1) / math.log(ratio)
            if ORDER_RANGE[0] <= p <= ORDER_RANGE[1]:
                order, source = p, "observed"
            else:
                note = (f"observed order {p:.3g} outside [{ORDER_RANGE[0]:g}, "
                        f"{ORDER_RANGE[1]:g}]")
    else:
        note = "two levels: the element's theoretical order is assumed"
    last, prev = v[-1], v[-2]
    if len(v) == 3 and source != "observed":
        # outside the asymptotic range no extrapolation is trusted: the finest value, and
        # the largest change between levels as its error
        source, value = "none", last
        change = max(abs(a - b) for a, b in zip(v[1:], v[:-1], strict=True))
    else:
        value = last + (last - prev) / (ratio ** order - 1.0)
        change = abs(value - last)
    error = v[0] / value - 1.0 if value else math.nan
    spread = change / abs(value) if value else math.nan
    return Estimate(tuple(v), value, order, source, error, SAFETY[source] * spread, note)


@dataclass(frozen=True)
class Level:
    """One mesh of a convergence study: its subdivision of the given mesh, size and result."""

    refine: int
    nodes: int
    elements: int
    dof: int
    dissipated_energy_Nmm: float
    peak_displacement_mm: float
    wall_s: float
    solver_converged: bool = True

    def summary(self) -> dict[str, Any]:
        return {"refine": self.refine, "nodes": self.nodes, "elements": self.elements,
                "dof": self.dof, "dissipated_energy_Nmm": self.dissipated_energy_Nmm,
                "peak_displacement_mm": self.peak_displacement_mm, "wall_s": self.wall_s,
                "solver_converged": self.solver_converged}


@dataclass(frozen=True)
class MeshConvergence:
    """W and the peak displacement on each level, their estimates, the given mesh's error."""

    levels: tuple[Level, ...]
    dissipated_energy: Estimate
    peak_displacement: Estimate
    first: Any  # the given mesh's run (:class:`~microslip.fe.ownmesh.OwnMeshRun`)

    @property
    def error(self) -> float:
        """The given mesh's relative discretisation error of W."""
        return self.dissipated_energy.relative_error

    def warnings(self) -> list[str]:
        """One line when the given mesh's W or displacement is more than
        :data:`WARN_ERROR` from the estimate."""
        out = []
        for name, unit, est in (("W", "N·mm", self.dissipated_energy),
                                ("the peak displacement", "mm", self.peak_displacement)):
            if abs(est.relative_error) > WARN_ERROR:
                out.append(f"the given mesh's {name} ({est.values[0]:.6g} {unit}) is "
                           f"{100 * est.relative_error:+.1f} % from the converged estimate "
                           f"{est.value:.6g} {unit} ({est.how}): refine the mesh "
                           "(--refine 2) or use the estimate")
        return out

    def summary(self) -> dict[str, Any]:
        """The ``converged`` object of ``fe --mesh --convergence --json``."""
        w, d = self.dissipated_energy, self.peak_displacement
        return {"dissipated_energy_Nmm": w.value, "peak_displacement_mm": d.value,
                "order": w.order, "order_source": w.order_source,
                "peak_displacement_order": d.order,
                "peak_displacement_order_source": d.order_source,
                "uncertainty": w.uncertainty,
                "peak_displacement_uncertainty": d.uncertainty,
                "peak_displacement_error_estimate": d.relative_error,
                "refinement_ratio": REFINEMENT_RATIO,
                "note": w.note, "levels": [lv.summary() for lv in self.levels]}


def _check_levels(levels: int) -> int:
    if isinstance(levels, bool) or levels not in LEVEL_CHOICES:
        raise ParameterError(f"--levels must be 2 or 3, got {levels!r}")
    return int(levels)


def converge_own_mesh(case: Any, levels: int = 2, solver: str = "builtin",
                      progress: Callable[[str], None] | None = None) -> MeshConvergence:
    """Run ``case`` (an :class:`~microslip.fe.ownmesh.OwnMeshCase`) on its mesh and on
    ``levels`` - 1 refinements x2, and estimate the converged W and peak displacement.

    ``progress`` is called with a line before each level. Raises
    :class:`~microslip.errors.ParameterError` for ``levels`` not 2 or 3, or a refinement
    beyond :data:`~microslip.fe.refine.MAX_REFINE`.
    """
    from .ownmesh import run_own_mesh
    from .refine import MAX_REFINE

    n = _check_levels(levels)
    top = case.refine * REFINEMENT_RATIO ** (n - 1)
    if top > MAX_REFINE:
        raise ParameterError(f"--refine {case.refine} with --convergence --levels {n} would "
                             f"subdivide {top} times (at most {MAX_REFINE})")
    runs, out = [], []
    for k in range(n):
        factor = case.refine * REFINEMENT_RATIO ** k
        if progress is not None:
            progress(f"level {k + 1}/{n}: refine x{factor}")
        start = time.perf_counter()
        run = run_own_mesh(replace(case, refine=factor), solver)
        s = run.summary
        runs.append(run)
        out.append(Level(factor, int(s["nodes"]), int(s["elements"]), int(s.get("dof", 0)),
                         float(s["dissipated_energy_Nmm"]), float(s["peak_displacement_mm"]),
                         time.perf_counter() - start, bool(s.get("converged", True))))
    return MeshConvergence(
        tuple(out),
        richardson([lv.dissipated_energy_Nmm for lv in out],
                   THEORETICAL_ORDER["dissipated_energy"]),
        richardson([lv.peak_displacement_mm for lv in out],
                   THEORETICAL_ORDER["peak_displacement"]),
        runs[0])


@dataclass(frozen=True)
class FrequencyConvergence:
    """The stuck linear frequencies (Hz) on each level and their estimates, mode by mode."""

    refine: tuple[int, ...]
    dof: tuple[int, ...]
    frequencies_Hz: tuple[tuple[float, ...], ...]  # per level
    estimates: tuple[Estimate, ...]  # per mode

    def summary(self) -> dict[str, Any]:
        return {"converged_linear_frequencies_Hz": [e.value for e in self.estimates],
                "frequency_convergence": {
                    "order": [e.order for e in self.estimates],
                    "order_source": [e.order_source for e in self.estimates],
                    "error_estimate": [e.relative_error for e in self.estimates],
                    "uncertainty": [e.uncertainty for e in self.estimates],
                    "refinement_ratio": REFINEMENT_RATIO,
                    "levels": [{"refine": r, "dof": d, "linear_frequencies_Hz": list(f)}
                               for r, d, f in zip(self.refine, self.dof,
                                                  self.frequencies_Hz, strict=True)]}}

    def warnings(self) -> list[str]:
        bad = [k + 1 for k, e in enumerate(self.estimates)
               if abs(e.relative_error) > WARN_ERROR]
        if not bad:
            return []
        worst = max(self.estimates, key=lambda e: abs(e.relative_error))
        return [f"the given mesh's stuck frequencies of modes {', '.join(map(str, bad))} are "
                f"more than {100 * WARN_ERROR:g} % from the converged estimate (up to "
                f"{100 * worst.relative_error:+.1f} %): refine the mesh"]


def converge_frequencies(mesh: HexMesh, frequencies: Callable[[HexMesh], tuple[int, Any]],
                         levels: int = 2) -> FrequencyConvergence:
    """The stuck frequencies of ``mesh`` and ``levels`` - 1 refinements x2, estimated.

    ``frequencies(mesh)`` returns (DOF, the lowest stuck linear frequencies in Hz) of a mesh
    (the caller clamps it: :func:`~microslip.fe.builtin.meshmodel.build_mesh_model` and
    :func:`~microslip.meshdynamics.modes.linear_modes`). The modes are matched by their rank.
    """
    from .refine import refine_mesh

    n = _check_levels(levels)
    factors = tuple(REFINEMENT_RATIO ** k for k in range(n))
    dofs, freqs = [], []
    for f in factors:
        dof, values = frequencies(refine_mesh(mesh, f))
        dofs.append(int(dof))
        freqs.append(tuple(float(x) for x in np.asarray(values, dtype=float)))
    count = min(len(f) for f in freqs)
    estimates = tuple(richardson([f[k] for f in freqs], THEORETICAL_ORDER["frequency"])
                      for k in range(count))
    return FrequencyConvergence(factors, tuple(dofs), tuple(freqs), estimates)
