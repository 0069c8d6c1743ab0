"""Damping of planar (circular and elliptical) loading: the paper's coupling and the work.

:func:`planar_damping` runs the tip and centre models to their amplitudes, couples their
loops as the paper does (Eqs 19-23, :mod:`~microslip.planar.coupling`) and, side by side,
computes the work done by the load over a cycle with any phase between the components
(:mod:`~microslip.planar.loadpath`). :func:`loss_factor_vs_ratio` does it for a set of force
ratios R (the paper's Fig. 12). Units: N, mm, N·mm.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Sequence
from dataclasses import field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..conventions import check_choice
from ..energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY, damping_from_backbone
from ..errors import MicroslipError, ParameterError
from ..models import Contact, check_increments, first_loading
from ..models.contact import check_strain_energy, energy_defined
from ..named import result
from ..options import ModelOptions
from ..params import ClampParams, check_amplitude, preset
from ..results import Backbone, DampingResult
from .coupling import paper_coupling, paper_loss_factors
from .loadpath import (
    DEFAULT_WORK_STRAIN_ENERGY,
    WORK_STRAIN_ENERGY,
    ComponentEnergy,
    LoadPath,
    WorkResult,
    analytical_response,
    work_damping,
)
from .trajectories import (
    LEVEL_SCHEMES,
    PAPER_RATIOS,
    TIP_SYMMETRY,
    eccentricity,
    force_ratio,
    paper_level_pair,
    paper_levels,
)

__all__ = [
    "PAPER_STRAIN_ENERGY",
    "PlanarResult",
    "RatioCase",
    "RatioSweep",
    "loss_factor_vs_ratio",
    "planar_damping",
]

#: The strain-energy definition read from the paper's Eq. 22 for its figures.
PAPER_STRAIN_ENERGY = "branch"


@functools.lru_cache(maxsize=32)
def _backbone(model: str, params: ClampParams, amplitude: float, increments: int,
              options: ModelOptions, contact: Contact | None = None) -> Backbone:
    """:func:`~microslip.first_loading`, remembered: sweeps over R reuse the same amplitudes
    (a Backbone's arrays are read-only, so sharing it is safe)."""
    return first_loading(model, params, amplitude, increments, options, contact)


@result
class PlanarResult:
    """Damping of one planar load case by the paper's coupling and by the work of the load.

    Attributes
    ----------
    ratio : float
        R = tip_symmetry x tip_amplitude / centre_amplitude (Eq. 1, normalised forces).
    eccentricity : float
        epsilon of R.
    phase_deg : float
        Phase of the centre force relative to the tip force in the work-based cycle, degrees
        (the paper's coupling is always at zero phase).
    tip_amplitude, centre_amplitude : float
        Amplitudes of the tip model (one symmetric half) and of the centre model, N.
    tip_symmetry : int
        Tip models in parallel in the whole clamp.
    tip, centre : DampingResult
        Each 1-D model's own Masing loop, W_d, U, eta.
    paper : DampingResult
        The paper's resultant loop (Eqs 19-20) and its W_d, U, eta (Eqs 21-23).
    paper_loss_factors : dict
        eta of the resultant loop under every strain-energy definition.
    work : WorkResult
        The work-based result in full (load path, displacements, parts).
    work_dissipated_energy : float
        W, work of the load over one cycle on the whole clamp, N·mm.
    work_strain_energy : float
        U of the combined motion, N·mm.
    work_loss_factor : float
        W / (2 pi U), dimensionless.
    work_loss_factors : dict
        Work-based eta under every strain-energy definition (same combination).
    strain_energy_kind : str
        Definition of U used for ``paper`` and ``work``.
    work_energy : str
        Combination of the component energies (:data:`WORK_STRAIN_ENERGY`).
    """

    ratio: float
    eccentricity: float
    phase_deg: float
    tip_amplitude: float
    centre_amplitude: float
    tip_symmetry: int
    tip: DampingResult
    centre: DampingResult
    paper: DampingResult
    paper_loss_factors: dict[str, float]
    work: WorkResult
    work_dissipated_energy: float
    work_strain_energy: float
    work_loss_factor: float
    work_loss_factors: dict[str, float]
    strain_energy_kind: str
    work_energy: str

    def summary(self) -> dict[str, Any]:
        """Scalar results with units in the keys (the ``microslip planar --json`` object)."""
        w = self.work
        return {
            "ratio": self.ratio,
            "eccentricity": self.eccentricity,
            "phase_deg": self.phase_deg,
            "tip_amplitude_N": self.tip_amplitude,
            "centre_amplitude_N": self.centre_amplitude,
            "tip_symmetry": self.tip_symmetry,
            "strain_energy_definition": self.strain_energy_kind,
            "work_strain_energy_combination": self.work_energy,
            "dissipated_energy_Nmm": self.work_dissipated_energy,
            "strain_energy_Nmm": self.work_strain_energy,
            "loss_factor": self.work_loss_factor,
            "work_dissipated_energy_Nmm": self.work_dissipated_energy,
            "work_strain_energy_Nmm": self.work_strain_energy,
            "work_loss_factor": self.work_loss_factor,
            "work_loss_factor_by_definition": dict(self.work_loss_factors),
            "work_tip_dissipated_energy_Nmm": w.tip_dissipated_energy,
            "work_centre_dissipated_energy_Nmm": w.centre_dissipated_energy,
            "tip_share_of_dissipation": _share(w.tip_dissipated_energy, w.dissipated_energy),
            "centre_share_of_dissipation": _share(w.centre_dissipated_energy,
                                                  w.dissipated_energy),
            "work_tip_strain_energy_Nmm": w.tip_strain_energy,
            "work_centre_strain_energy_Nmm": w.centre_strain_energy,
            "work_closure_error": w.closure_error,
            "paper_dissipated_energy_Nmm": self.paper.dissipated_energy,
            "paper_strain_energy_Nmm": self.paper.strain_energy,
            "paper_loss_factor": self.paper.loss_factor,
            "paper_loss_factor_by_definition": dict(self.paper_loss_factors),
            "paper_peak_force_N": self.paper.amplitude,
            "paper_peak_displacement_mm": self.paper.peak_displacement,
            "tip": self.tip.summary(),
            "centre": self.centre.summary(),
        }


def _share(part: float, whole: float) -> float:
    return part / whole if whole else math.nan


def _check_kind(kind: str) -> str:
    return check_choice("strain-energy definition", kind, STRAIN_ENERGY)


def planar_damping(tip_params: ClampParams, centre_params: ClampParams, tip_amplitude: float,
                   centre_amplitude: float, *, increments: int = 1000,
                   options: ModelOptions | None = None,
                   centre_options: ModelOptions | None = None,
                   strain_energy: str = DEFAULT_STRAIN_ENERGY, phase_deg: float = 0.0,
                   work_energy: str = DEFAULT_WORK_STRAIN_ENERGY,
                   tip_symmetry: int = TIP_SYMMETRY,
                   samples_per_cycle: int = 2048,
                   contact: Contact | None = None) -> PlanarResult:
    """Damping of a planar load case: the paper's coupling and the work-based result.

    Parameters
    ----------
    tip_params, centre_params : ClampParams
        The tip model (one symmetric half, Section 2.1) and the centre model (Section 2.2),
        e.g. ``preset("table2-tip")`` and ``preset("table2-centre")``.
    tip_amplitude, centre_amplitude : float
        Force amplitudes of the tip model and of the centre model, N.
    increments : int
        Force increments of each first loading; both loops then share their load fractions.
    options : ModelOptions, optional
        Reading of the tip model (and of the centre model when ``centre_options`` is None).
    centre_options : ModelOptions, optional
        Reading of the centre model; defaults to ``options``.
    strain_energy : str
        Definition of U (:data:`microslip.STRAIN_ENERGY`), default secant as for loop and sweep;
        ``branch`` (:data:`PAPER_STRAIN_ENERGY`) is the paper's Eq. 22.
    phase_deg : float
        Phase phi of the centre force in the work-based cycle, degrees:
        F_tip = A sin(theta), F_centre = A_c sin(theta + phi).
    work_energy : str
        How the components' strain energies combine (:data:`WORK_STRAIN_ENERGY`).
    tip_symmetry : int
        Tip models in parallel (2: the paper's tip model is half the clamp). Scales the tip's
        share of the work and of U, and R.
    samples_per_cycle : int
        Samples of the work-based cycle.
    contact : Contact, optional
        The interface under both models (stick slope, shear lag, pressure law); default the
        paper's rigid foundation. The ``stored`` strain energy is refused on any other.

    Returns
    -------
    PlanarResult

    Examples
    --------
    >>> from microslip import ModelOptions, preset
    >>> r = planar_damping(preset("table2-tip"), preset("table2-centre"), 8000.0, 4000.0,
    ...                    increments=200, options=ModelOptions.uncorrected())
    >>> r.ratio, round(r.eccentricity, 3)
    (4.0, 0.968)
    >>> round(r.paper.loss_factor / r.tip.loss_factor, 12)  # a scaled copy of each loop
    1.0
    >>> round(r.work_loss_factor * 3 * math.pi / 4, 4)  # secant U: 4/(3 pi), to the
    ...                                                   # discretisation error
    1.0
    """
    n = check_increments(increments)
    at = check_amplitude(tip_amplitude)
    ac = check_amplitude(centre_amplitude)
    kind = _check_kind(strain_energy)
    if work_energy not in WORK_STRAIN_ENERGY:
        raise ParameterError(
            f"unknown work strain-energy combination {work_energy!r}; "
            f"choose one of {', '.join(WORK_STRAIN_ENERGY)}"
        )
    phi = float(phase_deg)
    if not math.isfinite(phi):
        raise ParameterError(f"phase must be a finite angle in degrees, got {phase_deg!r}")
    opt = options if options is not None else ModelOptions()
    copt = centre_options if centre_options is not None else opt
    ratio = force_ratio(at, ac, tip_symmetry)

    check_strain_energy(contact, kind)
    tip_bb = _backbone("tip", tip_params, at, n, opt, contact)
    centre_bb = _backbone("centre", centre_params, ac, n, copt, contact)
    tip = damping_from_backbone(tip_bb, kind)
    centre = damping_from_backbone(centre_bb, kind)
    paper = paper_coupling(tip_bb, centre_bb, kind)

    path = LoadPath.harmonic(tip_symmetry * at, ac, phi, samples_per_cycle)
    response = analytical_response(path, tip_bb, centre_bb, tip_symmetry)
    works = {}
    for k in (k for k in STRAIN_ENERGY if energy_defined(contact, k)):
        works[k] = work_damping(response, ComponentEnergy(tip_bb, k, tip_symmetry),
                                ComponentEnergy(centre_bb, k, 1), work_energy, k)
    work = works[kind]
    return PlanarResult(
        ratio=ratio,
        eccentricity=float(eccentricity(ratio)),
        phase_deg=phi,
        tip_amplitude=at,
        centre_amplitude=ac,
        tip_symmetry=int(tip_symmetry),
        tip=tip,
        centre=centre,
        paper=paper,
        paper_loss_factors={k: v for k, v in paper_loss_factors(paper).items()
                            if energy_defined(contact, k)},
        work=work,
        work_dissipated_energy=work.dissipated_energy,
        work_strain_energy=work.strain_energy,
        work_loss_factor=work.loss_factor,
        work_loss_factors={k: w.loss_factor for k, w in works.items()},
        strain_energy_kind=kind,
        work_energy=work_energy,
    )


@result
class RatioCase:
    """One force ratio of a sweep: its levels, amplitudes and result (or why there is none).

    Attributes
    ----------
    ratio, eccentricity : float
    tip_level, centre_level : float
        Normalised forces (paper levels).
    tip_amplitude, centre_amplitude : float
        Model amplitudes, N.
    result : PlanarResult or None
        None when the case cannot be computed in the reading in force.
    error : str
        Why not (empty when computed).
    """

    ratio: float
    eccentricity: float
    tip_level: float
    centre_level: float
    tip_amplitude: float
    centre_amplitude: float
    result: PlanarResult | None
    error: str = ""


@result
class RatioSweep:
    """Loss factor against force ratio R (the paper's Fig. 12), case by case.

    Loss factors of cases that could not be computed are NaN. Normalised loss factors are
    divided by the value at R = 1 (the circle); NaN when R = 1 is absent or not computed.
    """

    cases: tuple[RatioCase, ...]
    levels: str
    strain_energy_kind: str
    work_energy: str
    phase_deg: float
    increments: int
    options: ModelOptions
    centre_options: ModelOptions
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def ratios(self) -> NDArray[np.float64]:
        return np.array([c.ratio for c in self.cases], dtype=float)

    @property
    def eccentricities(self) -> NDArray[np.float64]:
        return np.array([c.eccentricity for c in self.cases], dtype=float)

    def _values(self, get: Any) -> NDArray[np.float64]:
        return np.array([get(c.result) if c.result is not None else math.nan
                         for c in self.cases], dtype=float)

    def loss_factor(self, coupling: str = "paper", kind: str | None = None
                    ) -> NDArray[np.float64]:
        """eta per case: ``coupling`` ``paper`` (Eqs 19-23) or ``work``; ``kind`` a
        strain-energy definition (default: the sweep's)."""
        k = _check_kind(kind or self.strain_energy_kind)
        if coupling == "paper":
            return self._values(lambda r: r.paper_loss_factors[k])
        if coupling == "work":
            return self._values(lambda r: r.work_loss_factors[k])
        raise ParameterError(f"coupling must be 'paper' or 'work', got {coupling!r}")

    def normalised_loss_factor(self, coupling: str = "paper", kind: str | None = None
                               ) -> NDArray[np.float64]:
        """eta / eta(R = 1), dimensionless."""
        eta = self.loss_factor(coupling, kind)
        ref = eta[np.isclose(self.ratios, 1.0, rtol=1e-12, atol=0.0)]
        base = float(ref[0]) if ref.size and np.isfinite(ref[0]) else math.nan
        return np.asarray(eta / base, dtype=float)

    def columns(self) -> dict[str, Any]:
        """The table behind Fig. 12, one row per R, column names with units."""
        k = self.strain_energy_kind
        col: dict[str, Any] = {
            "R": self.ratios,
            "eccentricity": self.eccentricities,
            "tip_level": [c.tip_level for c in self.cases],
            "centre_level": [c.centre_level for c in self.cases],
            "tip_amplitude_N": [c.tip_amplitude for c in self.cases],
            "centre_amplitude_N": [c.centre_amplitude for c in self.cases],
            "paper_dissipated_energy_Nmm": self._values(lambda r: r.paper.dissipated_energy),
            "paper_strain_energy_Nmm": self._values(lambda r: r.paper.strain_energy),
            "paper_loss_factor": self.loss_factor("paper"),
            "paper_normalised_loss_factor": self.normalised_loss_factor("paper"),
        }
        if k != "secant":
            col["paper_loss_factor_secant"] = self.loss_factor("paper", "secant")
            col["paper_normalised_loss_factor_secant"] = self.normalised_loss_factor(
                "paper", "secant")
        col.update({
            "work_dissipated_energy_Nmm": self._values(lambda r: r.work_dissipated_energy),
            "work_strain_energy_Nmm": self._values(lambda r: r.work_strain_energy),
            "work_loss_factor": self.loss_factor("work"),
            "work_normalised_loss_factor": self.normalised_loss_factor("work"),
        })
        if k != "secant":
            col["work_loss_factor_secant"] = self.loss_factor("work", "secant")
        col.update({
            "work_tip_share_of_dissipation": self._values(
                lambda r: r.work.tip_dissipated_energy / r.work_dissipated_energy),
            "tip_peak_displacement_mm": self._values(lambda r: r.tip.peak_displacement),
            "centre_peak_displacement_mm": self._values(lambda r: r.centre.peak_displacement),
            "tip_secant_stiffness_N_per_mm": self._values(
                lambda r: r.tip.amplitude / r.tip.peak_displacement),
            "centre_secant_stiffness_N_per_mm": self._values(
                lambda r: r.centre.amplitude / r.centre.peak_displacement),
            "tip_loss_factor": self._values(lambda r: r.tip.loss_factor),
            "centre_loss_factor": self._values(lambda r: r.centre.loss_factor),
            "computed": [c.result is not None for c in self.cases],
        })
        return col


def loss_factor_vs_ratio(ratios: Iterable[float] = PAPER_RATIOS, *,
                         tip_params: ClampParams | None = None,
                         centre_params: ClampParams | None = None,
                         levels: str = "base", increments: int = 1000,
                         options: ModelOptions | None = None,
                         centre_options: ModelOptions | None = None,
                         strain_energy: str = DEFAULT_STRAIN_ENERGY, phase_deg: float = 0.0,
                         work_energy: str = DEFAULT_WORK_STRAIN_ENERGY,
                         tip_symmetry: int = TIP_SYMMETRY, samples_per_cycle: int = 2048,
                         skip_errors: bool = True, progress: Any = None,
                         contact: Contact | None = None) -> RatioSweep:
    """The loss factor of each force ratio R at the paper's levels (Fig. 12).

    Parameters
    ----------
    ratios : iterable of float
        Force ratios R (default the paper's seven, :data:`PAPER_RATIOS`).
    tip_params, centre_params : ClampParams, optional
        Default: the Table 2 presets ``table2-tip`` and ``table2-centre``.
    levels : str
        Level scheme mapping R to amplitudes (:data:`LEVEL_SCHEMES`).
    skip_errors : bool
        Record a case the reading in force cannot compute (e.g. a centre amplitude at the
        macroslip limit) with its reason and NaN results, instead of raising.
    progress : callable, optional
        ``progress(iterable, desc, total)`` wrapper (e.g. :func:`microslip.progress.progress`).
    Other parameters are those of :func:`planar_damping`.

    Returns
    -------
    RatioSweep

    Examples
    --------
    >>> from microslip import ModelOptions
    >>> s = loss_factor_vs_ratio((1.0, 4.0), increments=100,
    ...                          options=ModelOptions.uncorrected(), samples_per_cycle=256)
    >>> s.normalised_loss_factor("paper").round(9).tolist()
    [1.0, 1.0]
    """
    if levels not in LEVEL_SCHEMES:
        raise ParameterError(
            f"unknown level scheme {levels!r}; choose one of {', '.join(LEVEL_SCHEMES)}"
        )
    tp = tip_params if tip_params is not None else preset("table2-tip")
    cp = centre_params if centre_params is not None else preset("table2-centre")
    opt = options if options is not None else ModelOptions()
    copt = centre_options if centre_options is not None else opt
    rs: Sequence[float] = [float(r) for r in ratios]
    if not rs:
        raise ParameterError("give at least one force ratio R > 0")
    it: Iterable[float] = rs
    if progress is not None:
        it = progress(rs, "force ratios", len(rs))
    cases = []
    for r in it:
        lt, lc = paper_level_pair(r, levels)
        at, ac = paper_levels(r, levels)
        try:
            res: PlanarResult | None = planar_damping(
                tp, cp, at, ac, increments=increments, options=opt, centre_options=copt,
                strain_energy=strain_energy, phase_deg=phase_deg, work_energy=work_energy,
                tip_symmetry=tip_symmetry, samples_per_cycle=samples_per_cycle, contact=contact)
            err = ""
        except MicroslipError as exc:
            if not skip_errors:
                raise
            res, err = None, " ".join(str(exc).split())
        cases.append(RatioCase(r, float(eccentricity(r)), lt, lc, at, ac, res, err))
    return RatioSweep(tuple(cases), levels, _check_kind(strain_energy), work_energy,
                      float(phase_deg), check_increments(increments), opt, copt,
                      meta={"tip_params": tp, "centre_params": cp,
                            "tip_symmetry": tip_symmetry})
