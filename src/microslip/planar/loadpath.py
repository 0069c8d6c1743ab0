"""The work planar load paths do: the physically consistent alternative to Eqs 19-23.

A :class:`~microslip.loading.LoadPath` (:mod:`microslip.loading.path`, re-exported here) is
any sampled in-plane load history on the whole clamp: the force along the bar ("tip"
direction) and across it at mid-length ("centre" direction) at angles theta, with one closed
cycle at its end. A solver turns it into a :class:`PathResponse` (the
displacement of each load point along its own force); this module does so with the two
decoupled 1-D models and the extended Masing rules (:func:`analytical_response`), and a
coupled 2-D friction solver can return the same type. From a response:

* the energy dissipated per cycle is the work of the load,
  W = closed integral of (F_tip d delta_tip + F_centre d delta_centre) (:func:`cycle_work`);
* the strain energy U is the stored energy of the combined motion, one of
  :data:`WORK_STRAIN_ENERGY` (:func:`work_damping`);
* eta = W / (2 pi U), as Eq. 23.

For two *independent* 1-D models each force traverses its own closed loop whatever the phase
between them, so W = W_tip + W_centre at every phase; the phase matters only once the two
directions share one friction limit (a coupled model). Units: N, mm, N·mm, radians for theta.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..conventions import check_choice, check_whole
from ..energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY, loop_work, loss_factor, strain_energy
from ..errors import ParameterError
from ..hysteresis import VirginCurve, masing_loop, masing_response
from ..loading.path import LoadPath
from ..results import Backbone

__all__ = [
    "DEFAULT_WORK_STRAIN_ENERGY",
    "WORK_STRAIN_ENERGY",
    "ComponentEnergy",
    "LoadPath",
    "PathResponse",
    "WorkResult",
    "analytical_response",
    "closure_error",
    "cycle_work",
    "truncate_backbone",
    "work_damping",
]

FloatArray = NDArray[np.float64]


def _readonly(a: ArrayLike) -> FloatArray:
    arr = np.array(a, dtype=float)
    arr.setflags(write=False)
    return arr

@dataclass(frozen=True)
class PathResponse:
    """Displacements of the two load points along a :class:`LoadPath`.

    Attributes
    ----------
    path : LoadPath
    tip_displacement : ndarray, shape (K,)
        Displacement of the tip load point along the tip force, mm.
    centre_displacement : ndarray, shape (K,)
        Displacement of the mid-length section along the centre force, mm.
    source : str
        What computed it (``"masing"`` for the decoupled analytical models).
    meta : dict
    """

    path: LoadPath
    tip_displacement: FloatArray
    centre_displacement: FloatArray
    source: str = "masing"
    meta: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        dt = _readonly(self.tip_displacement)
        dc = _readonly(self.centre_displacement)
        if dt.shape != self.path.theta.shape or dc.shape != self.path.theta.shape:
            raise ParameterError(
                f"displacements must have the path's shape {self.path.theta.shape}, got "
                f"{dt.shape} and {dc.shape}"
            )
        object.__setattr__(self, "tip_displacement", dt)
        object.__setattr__(self, "centre_displacement", dc)


def analytical_response(path: LoadPath, tip: Backbone | VirginCurve,
                        centre: Backbone | VirginCurve, tip_symmetry: int = 2) -> PathResponse:
    """Each decoupled 1-D model follows its own force history (extended Masing rules).

    Parameters
    ----------
    path : LoadPath
        Total forces on the clamp.
    tip, centre : Backbone or VirginCurve
        Virgin curves of the tip and the centre model; each must reach the largest force
        its model sees (else :class:`~microslip.MacroslipError`).
    tip_symmetry : int
        Number of identical tip models in parallel: each carries F_tip / tip_symmetry
        (2 for the paper's half model, Section 2; 1 if ``tip`` describes the whole clamp).

    Returns
    -------
    PathResponse
        ``source="masing"``.
    """
    sym = _symmetry(tip_symmetry)
    dt = masing_response(tip, path.tip_force / sym)
    dc = masing_response(centre, path.centre_force)
    return PathResponse(path, dt, dc, source="masing", meta={"tip_symmetry": sym})


def _symmetry(tip_symmetry: Any) -> int:
    return check_whole("tip_symmetry", tip_symmetry, 1)


def cycle_work(response: PathResponse) -> tuple[float, float]:
    """Work of the tip and of the centre force over the closed cycle, N·mm (trapezoidal).

    Their sum is the energy dissipated per cycle, W = closed integral of
    (F_tip d delta_tip + F_centre d delta_centre), provided the response is periodic
    (see :func:`closure_error`).
    """
    p = response.path
    c = p.cycle
    return (loop_work(p.tip_force[c], response.tip_displacement[c]),
            loop_work(p.centre_force[c], response.centre_displacement[c]))


def closure_error(response: PathResponse) -> float:
    """Largest |delta(end) - delta(start)| of the cycle relative to that component's
    half peak-to-peak displacement (0 for a steady response); dimensionless."""
    c = response.path.cycle
    worst = 0.0
    for d in (response.tip_displacement[c], response.centre_displacement[c]):
        span = 0.5 * float(np.max(d) - np.min(d))
        if span > 0.0:
            worst = max(worst, abs(float(d[-1] - d[0])) / span)
    return worst


def truncate_backbone(backbone: Backbone, j: int) -> Backbone:
    """The first ``j`` increments of a backbone: exactly the model run to F_j in j increments
    (the models are incremental from rest with equal steps)."""
    n = backbone.increments
    if not 1 <= j <= n:
        raise ParameterError(f"truncation index must be in [1, {n}], got {j}")
    s = slice(0, j + 1)
    return Backbone(
        model=backbone.model, force=backbone.force[s], displacement=backbone.displacement[s],
        domains=backbone.domains, slip_length=backbone.slip_length[s],
        width=backbone.width[s], thickness=backbone.thickness[s],
        stored_energy=backbone.stored_energy[s], params=backbone.params,
        options=backbone.options,
    )


@dataclass(frozen=True)
class ComponentEnergy:
    """U_k(F): the strain energy of one load component at force amplitude |F|, N·mm.

    The named definition (:data:`microslip.STRAIN_ENERGY`) evaluated on the Masing loop of the
    component's own backbone truncated at amplitude |F| / copies, times ``copies`` (identical
    models in parallel). Exact at the backbone's peak; in between, U / F^3 (constant for a
    quadratic backbone) is interpolated monotonically between tabulated truncations.

    Parameters
    ----------
    backbone : Backbone
    kind : str
        Strain-energy definition.
    copies : int
        Models in parallel (the tip's symmetry factor); forces are whole-clamp forces.
    points : int
        Tabulated amplitudes (>= 2).
    """

    backbone: Backbone
    kind: str = DEFAULT_STRAIN_ENERGY
    copies: int = 1
    points: int = 33

    def __post_init__(self) -> None:
        check_choice("strain-energy definition", self.kind, STRAIN_ENERGY)
        _symmetry(self.copies)
        if self.backbone.increments < 1 or self.points < 2:
            raise ParameterError("a component energy needs >= 1 increment and >= 2 points")

    @property
    def amplitude(self) -> float:
        """Largest whole-clamp force of the table, N."""
        return self.copies * self.backbone.amplitude

    @functools.cached_property
    def peak(self) -> float:
        """U at the backbone's peak, N·mm (exact)."""
        bb = self.backbone
        return self.copies * strain_energy(masing_loop(bb), bb, self.kind)

    @functools.cached_property
    def _table(self) -> Any:  # scipy.interpolate.PchipInterpolator
        bb = self.backbone
        n = bb.increments
        js = np.unique(np.round(np.linspace(1, n, min(self.points, n))).astype(int))
        f = np.array([bb.force[j] for j in js], dtype=float)
        u = np.array([strain_energy(masing_loop(truncate_backbone(bb, int(j))),
                                    truncate_backbone(bb, int(j)), self.kind) for j in js])
        if f.size == 1:
            f = np.r_[0.5 * f[0], f]
            u = np.r_[u[0] / 8.0, u]
        from scipy.interpolate import PchipInterpolator

        return PchipInterpolator(f, u / f**3, extrapolate=True)

    def __call__(self, force: ArrayLike) -> FloatArray:
        """U at whole-clamp force amplitudes |force|, N·mm."""
        a = np.abs(np.asarray(force, dtype=float)) / self.copies
        top = self.backbone.amplitude
        if np.any(a > top * (1.0 + 1e-9)):
            raise ParameterError(
                f"force {float(np.max(a)) * self.copies:g} N is beyond the component's "
                f"backbone ({self.amplitude:g} N)"
            )
        a = np.minimum(a, top)
        at_peak = np.isclose(a, top, rtol=1e-12, atol=0.0)
        u = np.full(a.shape, self.peak if np.any(at_peak) else 0.0)
        if not np.all(at_peak):
            inner = a[~at_peak]
            ratio = self._table(np.maximum(inner, float(self.backbone.force[1])))
            u[~at_peak] = self.copies * ratio * inner**3
        return u


def _sum_of_peaks(path: LoadPath, tip: Callable[[ArrayLike], FloatArray],
                  centre: Callable[[ArrayLike], FloatArray]) -> tuple[float, float]:
    return float(tip(path.tip_amplitude)), float(centre(path.centre_amplitude))


def _simultaneous_peak(path: LoadPath, tip: Callable[[ArrayLike], FloatArray],
                       centre: Callable[[ArrayLike], FloatArray]) -> tuple[float, float]:
    c = path.cycle
    ut = tip(path.tip_force[c])
    uc = centre(path.centre_force[c])
    k = int(np.argmax(ut + uc))
    return float(ut[k]), float(uc[k])


#: How the strain energies of the two components combine into the U of the combined motion:
#: name -> (function(path, U_tip, U_centre) -> (U_tip part, U_centre part), meaning).
WORK_STRAIN_ENERGY: dict[str, tuple[Callable[..., tuple[float, float]], str]] = {
    "sum": (_sum_of_peaks,
            "sum of the component peaks, U_tip(max|F_tip|) + U_centre(max|F_centre|): "
            "independent of the phase; for linear springs twice the cycle-mean stored energy"),
    "peak": (_simultaneous_peak,
             "largest simultaneous stored energy, max over the cycle of "
             "U_tip(|F_tip|) + U_centre(|F_centre|)"),
}
DEFAULT_WORK_STRAIN_ENERGY = "sum"


@dataclass(frozen=True)
class WorkResult:
    """Work-based damping of a planar load cycle.

    Attributes
    ----------
    dissipated_energy : float
        W, work of the load over the closed cycle, N·mm.
    tip_dissipated_energy, centre_dissipated_energy : float
        The tip and the centre force's parts of W, N·mm.
    strain_energy : float
        U of the combined motion, N·mm.
    tip_strain_energy, centre_strain_energy : float
        The components' parts of U, N·mm.
    strain_energy_kind : str
        Definition of each component's U (:data:`microslip.STRAIN_ENERGY`).
    combination : str
        How they combine (:data:`WORK_STRAIN_ENERGY`).
    loss_factor : float
        eta = W / (2 pi U), dimensionless.
    closure_error : float
        See :func:`closure_error`.
    response : PathResponse
    """

    dissipated_energy: float
    tip_dissipated_energy: float
    centre_dissipated_energy: float
    strain_energy: float
    tip_strain_energy: float
    centre_strain_energy: float
    strain_energy_kind: str
    combination: str
    loss_factor: float
    closure_error: float
    response: PathResponse

    def summary(self) -> dict[str, float | str]:
        """Scalar results with units in the keys."""
        w = self.dissipated_energy
        return {
            "dissipated_energy_Nmm": w,
            "tip_dissipated_energy_Nmm": self.tip_dissipated_energy,
            "centre_dissipated_energy_Nmm": self.centre_dissipated_energy,
            "tip_share_of_dissipation": self.tip_dissipated_energy / w if w else math.nan,
            "centre_share_of_dissipation": self.centre_dissipated_energy / w if w else math.nan,
            "strain_energy_Nmm": self.strain_energy,
            "tip_strain_energy_Nmm": self.tip_strain_energy,
            "centre_strain_energy_Nmm": self.centre_strain_energy,
            "strain_energy_definition": self.strain_energy_kind,
            "strain_energy_combination": self.combination,
            "loss_factor": self.loss_factor,
            "closure_error": self.closure_error,
        }


def work_damping(response: PathResponse, tip_energy: Callable[[ArrayLike], FloatArray],
                 centre_energy: Callable[[ArrayLike], FloatArray],
                 combination: str = DEFAULT_WORK_STRAIN_ENERGY, kind: str = "") -> WorkResult:
    """W, U and eta of a planar cycle from any solver's response.

    Parameters
    ----------
    response : PathResponse
    tip_energy, centre_energy : callable
        U_k(F) for whole-clamp force amplitudes, N·mm (e.g. :class:`ComponentEnergy`).
    combination : str
        One of :data:`WORK_STRAIN_ENERGY`.
    kind : str
        Name of the component definition, recorded in the result (taken from
        ``tip_energy.kind`` when empty).
    """
    try:
        combine = WORK_STRAIN_ENERGY[combination][0]
    except (KeyError, TypeError):
        raise ParameterError(
            f"unknown work strain-energy combination {combination!r}; "
            f"choose one of {', '.join(WORK_STRAIN_ENERGY)}"
        ) from None
    wt, wc = cycle_work(response)
    ut, uc = combine(response.path, tip_energy, centre_energy)
    return WorkResult(
        dissipated_energy=wt + wc,
        tip_dissipated_energy=wt,
        centre_dissipated_energy=wc,
        strain_energy=ut + uc,
        tip_strain_energy=ut,
        centre_strain_energy=uc,
        strain_energy_kind=kind or str(getattr(tip_energy, "kind", "")),
        combination=combination,
        loss_factor=loss_factor(wt + wc, ut + uc),
        closure_error=closure_error(response),
        response=response,
    )
