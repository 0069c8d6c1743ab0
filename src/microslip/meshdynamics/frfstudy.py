"""The forced response of the structure of a mesh with its clamp, at the force levels given
(issue 23, item 5): :func:`frf_study`.

The load is a force F cos(2 pi f t) of amplitude F (N) on a node set, spread equally over
its nodes along a direction (default: the response set along the mode's direction). The
response, ``amplitude_mm``, is the first harmonic of the response set's mean displacement
along the mode's direction. Each solver of :data:`FRF_MESH_SOLVERS` gives a
:class:`~microslip.dynamics.structure.Structure` with that output and the load on its
coordinates; the curves are :func:`microslip.dynamics.response.frequency_response`
(harmonic balance and arclength continuation). The contact-node ROM is built once per study
with the rows of the response set and of the load set.

The peak's equivalent damping ratio (:func:`equivalent_damping`): a linear mode driven at
resonance has a_peak = F_modal / (2 zeta m omega^2), so zeta = F_modal / (2 m omega^2
a_peak) with the stuck mode's modal force and mass and omega the peak's frequency. The
half-power width is ill-defined on a nonlinear peak (the curve leans, its two sides belong
to different amplitudes); this definition needs the peak only. Units N, mm, Hz, kg/m^3.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics.hb import DEFAULT_HB_SAMPLES, check_balance
from ..errors import ParameterError
from .case import (
    OnStructure,
    PreparedStructure,
    StructureCase,
    prepare_structure,
    set_rows,
    structure_rom,
)

if TYPE_CHECKING:
    from .studyresult import StudyResult

__all__ = ["DAMPING_DEFINITION", "DEFAULT_MESH_HARMONICS", "FRF_MESH_SOLVERS", "MESH_RANGE",
           "REFERENCE", "ForcedModel", "FrfMeshSolver", "FrfSettings", "FrfStudy",
           "curve_json", "curve_warnings", "equivalent_damping", "frf_output", "frf_study",
           "peak_comparison", "prepare_frf", "run_forced", "stuck_response"]

#: Harmonics of the balance with a mesh unless the study says. On the 12x3x1 cantilever's
#: mode 2 at 10 N the peak with 3 harmonics is within 0.4 % (frequency) and 1 % (amplitude)
#: of the peak with 7, seven times faster (the ROM has no linear damping, so the balance is
#: not condensed onto the contact dofs and costs (dofs x (2H + 1))^3 per step; with odd
#: joint forces, ``fixed`` normal contact, on the odd harmonics only, (dofs x (H + 1))^3).
#: On 24x6x2, mode 2 at 3 N (186 ROM DOF, odd harmonics), the whole command with one force
#: level: 3 harmonics 8 s (31 s on every harmonic), 5 take 18 s, 7 take 43 s; the peak
#: frequency moves by -0.14 % from 3 to 5 harmonics, and with 7 an internal resonance of the
#: undamped ROM (a dip near 1590 Hz) shifts the located peak by +0.5 %: 3 stays the default
#: (7 would cost more than the old default did), 7 resolves such features.
DEFAULT_MESH_HARMONICS = 3
#: Default sweep: these fractions of the mode's stuck frequency (the friction softens the
#: peak below the stuck frequency; the range keeps it inside).
MESH_RANGE = (0.8, 1.05)
DAMPING_DEFINITION = ("zeta = F_modal / (2 m omega^2 a_peak): the linear single-mode peak "
                      "a_peak = F_modal / (2 zeta m omega^2) solved for zeta, with the stuck "
                      "mode's modal force F_modal and mass m (mass-normalised: m = 1) "
                      "referred to the response set's motion, omega = 2 pi x the peak's "
                      "frequency")
#: The solver the others are judged against when several run (no dynamic full FE exists:
#: the contact-node ROM is the reference; the modal study checks it against the full FE).
REFERENCE = "rom"


@dataclass(frozen=True)
class FrfSettings:
    """The forced response's settings: the balance (``harmonics``, ``samples`` per period),
    the sweep (``frequency_range`` in Hz, default :data:`MESH_RANGE` times the mode's stuck
    frequency), the continuation ``step`` (None: the continuation's default) and a structural
    (modal) ``damping_ratio`` in [0, 1) given to every stuck mode of the solver's model
    (:func:`~.case.modal_damping`)."""

    harmonics: int = DEFAULT_MESH_HARMONICS
    samples: int = DEFAULT_HB_SAMPLES
    frequency_range: tuple[float, float] | None = None
    step: float | None = None
    damping_ratio: float = 0.0

    def __post_init__(self) -> None:
        from .case import check_damping_ratio

        object.__setattr__(self, "damping_ratio", check_damping_ratio(self.damping_ratio))
        check_balance(self.harmonics, self.samples)
        if self.frequency_range is not None:
            lo, hi = self.frequency_range
            if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
                raise ParameterError(f"frequency-range must satisfy 0 < MIN < MAX (Hz), got "
                                     f"{lo:g} {hi:g}")
            object.__setattr__(self, "frequency_range", (float(lo), float(hi)))


@dataclass(frozen=True)
class FrfStudy(OnStructure):
    """What every solver of a forced response shares: the prepared structure (clamped model,
    stuck and free modes, the mode studied) and the load.

    ``load_nodes`` (mesh node indices) carry F / n each along ``load_direction`` (unit,
    global axes); ``modal_force`` is the stuck mode's modal force per N of F and
    ``response_motion`` the response set's motion along the mode per unit modal coordinate
    (mass-normalised mode; their product over omega^2 is the single-mode receptance)."""

    prepared: PreparedStructure
    load_set: str
    load_nodes: np.ndarray = field(repr=False)
    load_direction: np.ndarray = field(repr=False)
    modal_force: float
    response_motion: float


@dataclass(frozen=True)
class ForcedModel:
    """A solver's structure for the forced response: ``structure`` (its output coordinate
    the response set's mean displacement along the mode, mm), ``load`` its force per N of
    F (N/N), ``mode`` the studied mode's index in it (0-based, by stuck frequency), ``odd``
    whether its joint forces are odd (the forced response and the backbone's EPMC then run
    on the odd harmonics), a ``label`` and JSON ``extra`` figures."""

    structure: Any
    load: np.ndarray = field(repr=False)
    mode: int
    odd: bool
    label: str
    extra: dict[str, Any]


@dataclass(frozen=True)
class FrfMeshSolver:
    """One solver of the forced response: what it is, the settings only it takes (their
    option names) and the function that builds its :class:`ForcedModel` from the study and
    the contact-node ROM (every solver runs on it)."""

    help: str
    options: tuple[str, ...]
    build: Callable[[FrfStudy, Any], ForcedModel]


def equivalent_damping(force: float, modal_force: float, response_motion: float,
                       peak_frequency_Hz: float, peak_amplitude_mm: float) -> float:
    """The peak's equivalent damping ratio zeta = F_modal / (2 m omega^2 q_peak) (-).

    Notes
    -----
    A linear mode m q'' + 2 zeta m omega q' + m omega^2 q = F_modal cos(omega t) peaks at
    q = F_modal / (2 zeta m omega^2). Here the mode is mass-normalised (m = 1), F_modal =
    ``force * modal_force`` and q_peak = a_peak / ``response_motion`` (the response set's
    motion per unit modal coordinate), omega = 2 pi ``peak_frequency_Hz``:
    zeta = F modal_force response_motion / (2 omega^2 a_peak).
    """
    omega = 2.0 * math.pi * peak_frequency_Hz
    return float(force * abs(modal_force) * response_motion
                 / (2.0 * omega**2 * peak_amplitude_mm))


def stuck_response(structure: Any, load: np.ndarray, force: float,
                   frequencies_Hz: np.ndarray) -> np.ndarray:
    """The exact forced response with every joint stuck: |output . (K_stuck - omega^2 M +
    i omega C)^-1 F load| at each frequency, mm (the small-force limit of the curves)."""
    from ..dynamics.hb import SI_PER_MM

    k = structure.stuck_stiffness() * SI_PER_MM
    m = structure.mass * SI_PER_MM
    c = structure.damping * SI_PER_MM
    out = []
    for f in np.asarray(frequencies_Hz, dtype=float):
        w = 2.0 * math.pi * f
        x = np.linalg.solve(k - w**2 * m + 1j * w * c, force * np.asarray(load, dtype=complex))
        out.append(abs(structure.output @ x))
    return np.asarray(out)


def prepare_frf(case: StructureCase, load_set: str | None = None,
                load_direction: Sequence[float] | None = None) -> FrfStudy:
    """Clamp the case's mesh, compute its stuck and free modes and the load's modal force:
    ``load_set`` (default the response set) along ``load_direction`` (global axes, default
    the response set's motion in the mode)."""
    if case.response_set is None:
        raise ParameterError(f"the forced response of {case.mesh_name} needs a response set "
                             "(the amplitude is its mean displacement along the mode)")
    direction = None
    if load_direction is not None:
        d = np.asarray(load_direction, dtype=float).ravel()
        if d.size != 3 or not np.all(np.isfinite(d)) or float(np.linalg.norm(d)) == 0.0:
            raise ParameterError(f"load-direction must be three finite numbers DX,DY,DZ, not "
                                 f"all 0, got {load_direction!r}")
        direction = np.asarray(d / np.linalg.norm(d))
    name = load_set or case.response_set
    prepared = prepare_structure(case, (name,) if load_set else ())
    mode = prepared.mode
    sets = prepared.model.mesh.node_sets
    if name not in sets:
        raise ParameterError(f"load-set must name a node set of {prepared.model.mesh.source}, "
                             f"got {name!r} (node sets: {', '.join(sorted(sets)) or 'none'})")
    nodes = np.asarray(sets[name], dtype=np.int64)
    if direction is None:
        direction = np.asarray(mode.direction, dtype=float)
    i = prepared.number - 1
    stuck = prepared.stuck
    modal_force = float(np.mean(stuck.shapes[i, nodes] @ direction))
    peak = float(np.max(np.linalg.norm(stuck.shapes[i], axis=1)))
    if abs(modal_force) <= 1e-6 * peak:
        along = ", ".join(f"{v:.3g}" for v in direction)
        raise ParameterError(f"the load on {name!r} along ({along}) does not excite mode "
                             f"{prepared.number} ({mode.label}); choose another --load-set "
                             "or --load-direction")
    return FrfStudy(prepared=prepared, load_set=name, load_nodes=nodes,
                    load_direction=direction, modal_force=modal_force,
                    response_motion=float(np.linalg.norm(stuck.response_motion[i])))


def study_rom(study: FrfStudy) -> Any:
    """The contact-node ROM of the study, built once with the response set's and the load
    set's rows."""
    return structure_rom(study.prepared, (study.load_set,))


def _load_rows(study: FrfStudy, rom: Any) -> np.ndarray:
    """The load set's mean displacement rows (3, n_rom) on the ROM's coordinates."""
    return set_rows(rom, study.load_set, study.case.response_set)


def _rom(study: FrfStudy, rom: Any) -> ForcedModel:
    """The contact-node ROM (:func:`microslip.meshdynamics.reduce.build_rom`), its load
    F d . mean(T_node) over the load set's nodes (T the Craig-Bampton basis)."""
    from .reduce import rom_structure

    mode = study.mode
    output = mode.direction @ rom.output
    return ForcedModel(
        structure=rom_structure(rom, output),
        load=np.asarray(study.load_direction @ _load_rows(study, rom)),
        mode=study.number - 1, odd=rom.per_node == 2,
        label=f"harmonic balance on the contact-node ROM ({rom.dofs} DOF, "
              f"{len(rom.slip_force)} contact nodes)",
        extra={"rom": {"dofs": rom.dofs, "fixed_interface_modes": study.case.rom_modes,
                       "contact_nodes": len(rom.slip_force),
                       "stuck_frequencies_Hz": [float(f) for f in rom.stuck_frequencies(
                           len(study.prepared.stuck.frequencies_Hz))]}})


def _joint(study: FrfStudy, rom: Any) -> ForcedModel:
    """The whole-joint model (:func:`microslip.meshdynamics.wholejoint.build_whole_joint`)
    on the contact-node ROM: its load is the ROM's carried through the interface reduction
    T (T^T f), its mode the stuck one nearest the full FE's."""
    from .wholejoint import build_whole_joint

    mode = study.mode
    joint = build_whole_joint(rom, study.prepared.model, mode, mode.direction @ rom.output,
                              backbone=study.case.backbone)
    index = joint.mode_index(mode.frequency_Hz)
    stuck = float(joint.stuck_frequencies()[index])
    return ForcedModel(
        structure=joint.structure,
        load=np.asarray(study.load_direction @ _load_rows(study, rom) @ joint.transform),
        mode=index, odd=True,
        label=f"harmonic balance on the whole-joint model ({joint.structure.dofs} DOF; stuck "
              f"{stuck:.6g} Hz, {100 * (stuck / mode.frequency_Hz - 1):+.2f} % against the "
              "full FE)",
        extra={"joint": {**joint.backbone.summary(), "torsion": joint.torsion,
                         "stuck_frequency_Hz": stuck}})


#: The solvers of the forced response on a mesh.
FRF_MESH_SOLVERS: dict[str, FrfMeshSolver] = {
    "rom": FrfMeshSolver("harmonic balance on the Craig-Bampton model that keeps every "
                         "contact node with the FE's own contact law (--rom-modes "
                         "fixed-interface modes)", ("rom_modes",), _rom),
    "joint": FrfMeshSolver("harmonic balance on the whole-joint model: the interface rigid "
                           "in its plane, one joint whose backbone is the FE's first loading "
                           "by the mode (--backbone)", ("rom_modes", "backbone"), _joint),
}


def frequency_range(study: FrfStudy, settings: FrfSettings) -> tuple[float, float]:
    """The settings' range, or :data:`MESH_RANGE` times the mode's stuck frequency (Hz)."""
    if settings.frequency_range is not None:
        return settings.frequency_range
    stuck_hz = float(study.prepared.stuck.frequencies_Hz[study.number - 1])
    return MESH_RANGE[0] * stuck_hz, MESH_RANGE[1] * stuck_hz


def run_forced(study: FrfStudy, forces: Sequence[float], settings: FrfSettings,
               solvers: Sequence[str] = (REFERENCE,),
               each: Callable[[str, Iterable[float]], Iterable[float]] | None = None
               ) -> dict[str, tuple[ForcedModel, list[Any]]]:
    """Each named solver's model and its curves, one per force (N); the ROM is built once.
    ``each(name, forces)`` may wrap the forces' iteration (a progress bar)."""
    from ..dynamics.response import DEFAULT_STEP, frequency_response

    bad = [s for s in solvers if s not in FRF_MESH_SOLVERS]
    if bad or not solvers:
        raise ParameterError(f"unknown frf solver {bad[0] if bad else None!r}; choose from "
                             f"{', '.join(FRF_MESH_SOLVERS)}")
    frange = frequency_range(study, settings)
    step = DEFAULT_STEP if settings.step is None else settings.step
    rom = study_rom(study)
    runs = {}
    for name in solvers:
        forced = FRF_MESH_SOLVERS[name].build(study, rom)
        if settings.damping_ratio:
            from dataclasses import replace

            from .case import modal_damping

            forced = replace(forced, structure=modal_damping(forced.structure,
                                                             settings.damping_ratio),
                             label=f"{forced.label} + structural damping ratio "
                                   f"{settings.damping_ratio:g} on every mode")
        levels = forces if each is None else each(name, forces)
        runs[name] = (forced, [
            frequency_response(forced.structure, f, forced.load, frange, settings.harmonics,
                               settings.samples, step, odd=forced.odd)
            for f in levels])
    return runs


def curve_json(c: Any, study: FrfStudy) -> dict[str, Any]:
    """One force level's curve as JSON, with its peak's equivalent damping ratio (None, and
    ``peak_in_range`` False, when the largest amplitude is at an end of the range: no peak,
    its ``peak_*`` then the largest point's)."""
    inside = bool(c.frequency.size > 2 and c.frequency[0] < c.peak_frequency
                  < c.frequency[-1])
    zeta = (equivalent_damping(c.force, study.modal_force, study.response_motion,
                               c.peak_frequency, c.peak_amplitude) if inside else None)
    return {"force_N": c.force, "frequency_Hz": c.frequency, "amplitude_mm": c.amplitude,
            "peak_amplitude_mm": c.peak_amplitude, "peak_frequency_Hz": c.peak_frequency,
            "peak_in_range": inside, "damping_ratio": zeta,
            "points": int(c.frequency.size), "success": c.success,
            "message": c.message}


def curve_warnings(curves: list[Any], study: FrfStudy | None = None) -> list[str]:
    """A curve that stopped early, or whose largest amplitude is not a peak; with the
    ``study``, a peak's equivalent damping ratio above 10 % (:func:`~.limits.damping_warning`:
    near gross sliding, outside the model's validity)."""
    from .limits import VALIDITY_DAMPING, damping_warning

    out = []
    for c in curves:
        if study is not None:
            zeta = curve_json(c, study)["damping_ratio"]
            if zeta is not None and zeta > VALIDITY_DAMPING:
                out.append(f"curve at {c.force:g} N: " + damping_warning(
                    zeta, f"the peak at {c.peak_amplitude:.4g} mm",
                    len(getattr(study.case.clamp, "shanks", ()))))
        if not c.success:
            out.append(f"curve at {c.force:g} N stopped early: {c.message}")
        if not (c.frequency.size > 2 and c.frequency[0] < c.peak_frequency
                < c.frequency[-1]):
            out.append(f"curve at {c.force:g} N: the largest amplitude is at an end of the "
                       "frequency range, not a peak (no damping ratio); widen "
                       "--frequency-range")
    return out


def peak_comparison(reference: dict[str, Any], other: dict[str, Any]) -> dict[str, Any]:
    """One force level's peak of ``other`` against ``reference`` (their curve JSON): the
    relative differences of peak amplitude, peak frequency and equivalent damping ratio
    (None where either has none)."""
    def rel(key: str) -> float | None:
        a, b = other[key], reference[key]
        return None if a is None or b is None else float(a / b - 1.0)

    return {"force_N": reference["force_N"],
            "peak_amplitude_difference": rel("peak_amplitude_mm"),
            "peak_frequency_difference": rel("peak_frequency_Hz"),
            "damping_ratio_difference": rel("damping_ratio")}


def _head(study: FrfStudy) -> dict[str, Any]:
    prepared = study.prepared
    return {"mesh": study.case.mesh_name, "mode": study.number, "label": study.mode.label,
            "density_kg_m3": study.case.density,
            "linear_frequencies_Hz": [float(f) for f in prepared.stuck.frequencies_Hz],
            "free_frequencies_Hz": [float(f) for f in prepared.free.frequencies_Hz],
            "response_set": study.case.response_set,
            "model": prepared.model.describe()}


def _load(study: FrfStudy) -> dict[str, Any]:
    return {"set": study.load_set, "nodes": int(study.load_nodes.size),
            "direction": [float(v) for v in study.load_direction]}


def frf_output(study: FrfStudy, runs: dict[str, tuple[ForcedModel, list[Any]]],
               settings: FrfSettings, compare: bool = False) -> dict[str, Any]:
    """The JSON of the forced response: one solver's curves (``compare`` False, one run),
    or every solver's side by side with each one's peaks against :data:`REFERENCE`'s."""
    harmonics, samples = settings.harmonics, settings.samples
    frange = list(frequency_range(study, settings))
    if not compare:
        ((solver, (forced, curves)),) = runs.items()
        head = _head(study)
        return {"mesh": head["mesh"], "solver": solver,
                **{k: v for k, v in head.items() if k != "mesh"},
                "response_direction": [float(v) for v in study.mode.direction],
                "load": _load(study), "harmonics": harmonics, "samples": samples,
                "frequency_range_Hz": frange,
                "structural_damping_ratio": settings.damping_ratio, **forced.extra,
                "curves": [curve_json(c, study) for c in curves],
                "damping_ratio_definition": DAMPING_DEFINITION,
                "warnings": curve_warnings(curves, study)}
    solvers = {name: {**forced.extra, "label": forced.label,
                      "curves": [curve_json(c, study) for c in curves],
                      "warnings": curve_warnings(curves, study)}
               for name, (forced, curves) in runs.items()}
    ref = solvers[REFERENCE]["curves"]
    comparison = {name: [peak_comparison(r, o) for r, o in zip(ref, s["curves"], strict=True)]
                  for name, s in solvers.items() if name != REFERENCE}
    head = _head(study)
    return {"mesh": head["mesh"], "solver": "all",
            **{k: v for k, v in head.items() if k != "mesh"},
            "load": _load(study), "harmonics": harmonics, "samples": samples,
            "frequency_range_Hz": frange,
            "structural_damping_ratio": settings.damping_ratio, "solvers": solvers,
            "reference": REFERENCE,
            "comparison": comparison, "damping_ratio_definition": DAMPING_DEFINITION,
            "warnings": [f"{n}: {w}" for n, s in solvers.items() for w in s["warnings"]]}


def frf_study(case: StructureCase, forces: Sequence[float],
              settings: FrfSettings | None = None, solvers: Sequence[str] = (REFERENCE,),
              load_set: str | None = None, load_direction: Sequence[float] | None = None
              ) -> StudyResult:
    """The forced response of the case's structure at each force (N) by each named solver:
    :func:`frf_output` (several solvers: side by side, peaks against the ROM's), as a named
    :class:`~.studyresult.StudyResult` (``["curves"]``, ``.solvers``, ``.to_json()``)."""
    from .studyresult import StudyResult

    settings = FrfSettings() if settings is None else settings
    levels = [float(f) for f in forces]
    bad = [f for f in levels if not (math.isfinite(f) and f > 0.0)]
    if bad or not levels:
        raise ParameterError(f"force must be finite and > 0 N, got "
                             f"{bad[0] if bad else None!r}")
    study = prepare_frf(case, load_set, load_direction)
    runs = run_forced(study, levels, settings, solvers)
    return StudyResult("frf", frf_output(study, runs, settings,
                                         compare=len(runs) > 1 or REFERENCE not in runs))
