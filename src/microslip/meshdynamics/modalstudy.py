"""A mode's frequency and damping ratio against amplitude on the structure of a mesh, by the
full FE (quasi-static modal analysis, the truth), the contact-node ROM, the interface-reduced
model or the whole joint,
each on the same amplitude grid, and the models judged against the full FE.

:func:`modal_study` runs the solvers of :data:`MESH_SOLVERS` on one
:class:`~microslip.meshdynamics.case.StructureCase`; the ROM is built once for every solver
that needs it. :func:`study_output` and :func:`compare_output` are the JSON of one solver
and of several side by side (what ``modal --mesh --json`` prints). Units: Hz, mm, N,
kg/m^3; damping ratios dimensionless.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..dynamics.hb import DEFAULT_HARMONICS, DEFAULT_HB_SAMPLES, check_balance
from ..dynamics.modal import RESPONSE_SET_COORDINATE
from ..errors import MicroslipError, ParameterError
from .case import (
    MAX_AMPLITUDES,
    OnStructure,
    PreparedStructure,
    StructureCase,
    limited_grid,
    prepare_structure,
    structure_rom,
)
from .verdict_modal import modal_verdict

if TYPE_CHECKING:
    from .limits import GridLimit
    from .studyresult import StudyResult

__all__ = ["BASE_COLUMNS", "MESH_SOLVERS", "ROM_NODE_LIMIT", "SHARED", "STUCK_TOLERANCE",
           "TRUTH", "MeshCurve", "MeshSolver", "ModalSettings", "ModalStudy", "compare_all",
           "compare_output", "modal_study", "prepare_modal", "run_solvers", "stood_in",
           "stuck_check", "study_output"]

#: Keys of a solver's JSON that the study gives, the same for every solver: written once.
SHARED = ("mesh", "mode", "label", "density_kg_m3", "amplitude_coordinate",
          "linear_frequencies_Hz", "free_frequencies_Hz", "modes", "amplitude_limit",
          "model", "structural_damping_ratio")
#: The solver every other is judged against.
TRUTH = "fe"
#: Progress of the full FE's amplitudes: (done, total, seconds left).
Progress = Callable[[int, int, float], None]


@dataclass(frozen=True)
class ModalSettings:
    """The solvers' settings of a modal study: the amplitude grid (``amplitudes`` of them,
    first slip to near gross sliding, or log-uniform over ``amplitude_range``, mm), the
    harmonic balance of the ROM and the whole joint (``harmonics``, ``samples`` per period),
    where the full FE's independent amplitudes run (``workers`` local processes, or a
    Dask ``scheduler`` address) and a structural (modal) ``damping_ratio`` in [0, 1) added to
    every model (:func:`~.case.modal_damping`; the full FE's QSMA adds it to its friction's
    ratio, energy for energy)."""

    amplitudes: int = 8
    amplitude_range: tuple[float, float] | None = None
    harmonics: int = DEFAULT_HARMONICS
    samples: int = DEFAULT_HB_SAMPLES
    workers: int = 1
    scheduler: str | None = None
    damping_ratio: float = 0.0

    def __post_init__(self) -> None:
        from .case import check_damping_ratio

        object.__setattr__(self, "damping_ratio", check_damping_ratio(self.damping_ratio))
        n = self.amplitudes
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or not (
                1 <= n <= MAX_AMPLITUDES):
            raise ParameterError(f"amplitudes must be in [1, {MAX_AMPLITUDES}] with a mesh, "
                                 f"got {n}")
        if self.amplitude_range is not None:
            lo, hi = self.amplitude_range
            if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
                raise ParameterError(f"amplitude-range must satisfy 0 < MIN <= MAX (mm), got "
                                     f"{lo:g} {hi:g}")
        check_balance(self.harmonics, self.samples)
        if self.workers < 1:
            raise ParameterError(f"workers must be >= 1, got {self.workers}")


@dataclass(frozen=True)
class ModalStudy(OnStructure):
    """What every solver of a modal study shares: the prepared structure (clamped model,
    stuck and free modes, the mode studied), the settings, and the one amplitude grid.

    ``forces`` are the QSMA's modal forces q; ``amplitudes`` (mm) are the same levels mapped
    through the stuck mode (a = q r / omega^2, r the response set's motion per unit modal
    coordinate), or the settings' ``amplitude_range`` itself. ``limit`` is the grid's
    physical limit (:class:`~.limits.GridLimit`: small rotations, the elastic limit) and
    ``notes`` what it did to the automatic grid (issue 34 item 2)."""

    prepared: PreparedStructure
    settings: ModalSettings
    forces: np.ndarray = field(repr=False)
    amplitudes: np.ndarray = field(repr=False)
    limit: GridLimit | None = None
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class MeshCurve:
    """One solver's frequency and damping ratio against amplitude, with its own columns
    (``columns``: JSON key -> (table header, format)) and figures (``extra``)."""

    label: str
    columns: dict[str, tuple[str, str]]
    values: dict[str, list[float | None]]
    extra: dict[str, Any]
    warnings: list[str]
    #: Why amplitudes (or the whole solver) failed: each reason once, also in ``warnings``;
    #: the side-by-side verdict on the solver names them.
    failures: tuple[str, ...] = ()
    #: What the curve cost, wall s: the solver's run and, for a solver on the contact-node
    #: ROM, the ROM's build (shared, counted for each); None where not measured.
    cost_s: float | None = None


@dataclass(frozen=True)
class MeshSolver:
    """One solver of a modal study: what it is, the settings only it takes (their option
    names), whether it runs on the contact-node ROM, and the function that computes its
    curve from the study, the ROM (or None) and a progress callback."""

    help: str
    options: tuple[str, ...]
    needs_rom: bool | Callable[[ModalStudy], bool]
    run: Callable[[ModalStudy, Any, Progress | None], MeshCurve]

    def rom_needed(self, study: ModalStudy) -> bool:
        """Whether the solver runs on the study's contact-node ROM."""
        return bool(self.needs_rom(study) if callable(self.needs_rom) else self.needs_rom)


#: The amplitude column: the response set's mean displacement along the mode (its header
#: says so: ``amplitude_coordinate`` = ``response_set``).
BASE_COLUMNS = {"amplitude_mm": ("a_resp (mm)", "{:12.5g}"),
                "frequency_Hz": ("f (Hz)", "{:12.7g}"),
                "damping_ratio": ("zeta (-)", "{:12.5g}")}


def nulls(values: Any) -> list[float | None]:
    """A column for JSON: NaN (an amplitude that failed; its reason is in ``warnings``) as
    null."""
    return [None if v is None or math.isnan(v) else float(v) for v in values]


def _fe(study: ModalStudy, rom: Any, progress: Progress | None) -> MeshCurve:
    """Quasi-static modal analysis of the full frictional FE at the grid's modal forces."""
    from .qsma import qsma

    model = study.prepared.model
    curve = qsma(model, study.mode, cast(Any, study.forces), workers=study.settings.workers,
                 scheduler=study.settings.scheduler, progress=progress)
    s = curve.summary()
    zeta0 = study.settings.damping_ratio  # structural damping: W_s = 4 pi zeta0 U, added
    s["damping_ratio"] = [z + zeta0 if z is not None and math.isfinite(z) else z
                          for z in s["damping_ratio"]]
    columns = {"amplitude_mm": BASE_COLUMNS["amplitude_mm"],
               "frequency_Hz": BASE_COLUMNS["frequency_Hz"],
               "secant_frequency_Hz": ("f_sec (Hz)", "{:12.7g}"),
               "damping_ratio": BASE_COLUMNS["damping_ratio"],
               "slip_fraction": ("slip (-)", "{:9.3f}")}
    values = {k: nulls(s[k]) for k in (*columns, "dissipated_energy_Nmm")}
    # the slip pattern: the contact nodes in the contact plane (mm), slipped or not per amplitude
    xy = model.mesh.nodes[model.contact_nodes] @ model.rotation.T
    pattern = {"x_mm": xy[:, 0].tolist(), "y_mm": xy[:, 1].tolist(),
               "slipped": [p.node_slipped.tolist() for p in curve.points],
               "open": [(p.node_open if p.node_open.size else
                         np.zeros(xy.shape[0], dtype=bool)).tolist() for p in curve.points]}
    return MeshCurve(label="quasi-static modal analysis of the full FE" + _damped(study),
                     columns=columns,
                     values=values, extra={"modal_force": s["force"], "slip_pattern": pattern},
                     warnings=list(s["warnings"]))


def _rom(study: ModalStudy, rom: Any, progress: Progress | None) -> MeshCurve:
    """EPMC on the contact-node ROM at the grid's amplitudes."""
    from ..dynamics.modal import epmc
    from ..dynamics.modal_odd import epmc_odd
    from .case import modal_damping
    from .reduce import rom_structure

    mode, s = study.mode, study.settings
    structure = modal_damping(rom_structure(rom, mode.direction @ _output(rom)),
                              s.damping_ratio)
    method = epmc if rom.per_node == 3 else epmc_odd  # odd joint forces: odd harmonics only
    failures: list[str] = []  # an amplitude not reached is NaN, its reason a warning
    curve = method(structure, np.asarray(study.amplitudes), s.harmonics, s.samples,
                   study.number - 1, failures=failures)
    count = len(study.prepared.stuck.frequencies_Hz)
    freqs = [float(f) for f in rom.stuck_frequencies(count + 2)]
    stuck, warn = stuck_check(study, freqs, "contact-node ROM")
    return MeshCurve(
        label=f"EPMC on the contact-node ROM ({rom.dofs} DOF, {curve.harmonics} harmonics)"
              + _damped(study),
        columns=dict(BASE_COLUMNS),
        values={"amplitude_mm": nulls(np.where(np.isnan(curve.frequency), np.nan,
                                               curve.amplitude)),
                "frequency_Hz": nulls(curve.frequency),
                "damping_ratio": nulls(curve.damping_ratio)},
        extra={"rom_frequencies_Hz": freqs[:count],
               "rom": {"dofs": rom.dofs, "fixed_interface_modes": study.case.rom_modes,
                       "contact_nodes": len(rom.slip_force), "harmonics": curve.harmonics,
                       "samples": curve.samples, **stuck}},
        warnings=warn + failures, failures=tuple(failures))


#: A reduced model's stuck frequency of the studied mode must be the full FE's within this
#: (relative) at zero amplitude (issue 35, item 1), or it says why not and does not stand in
#: for the contact-node ROM.
STUCK_TOLERANCE = 1e-3


def stuck_check(study: ModalStudy, frequencies: Any, name: str) -> tuple[dict[str, float],
                                                                      list[str]]:
    """The model's stuck frequency nearest the studied mode's (Hz, of ``frequencies``) and
    its relative error against the full FE's, and a warning when it is beyond
    :data:`STUCK_TOLERANCE`."""
    f_fe = float(study.mode.frequency_Hz)
    f = np.asarray(frequencies, dtype=float)
    nearest = float(f[np.argmin(np.abs(f - f_fe))])
    error = nearest / f_fe - 1.0
    warn = ([] if abs(error) <= STUCK_TOLERANCE else
            [f"the {name}'s stuck frequency {nearest:.6g} Hz is {100 * error:+.2f} % off the "
             f"full FE's {f_fe:.6g} Hz at zero amplitude (more than "
             f"{100 * STUCK_TOLERANCE:g} %)"])
    return {"stuck_frequency_Hz": nearest, "stuck_frequency_error": error}, warn


def _damped(study: ModalStudy) -> str:
    """The label's note of a structural damping ratio (none: nothing)."""
    zeta = study.settings.damping_ratio
    return f" + structural damping ratio {zeta:g} on every mode" if zeta else ""


def _output(rom: Any) -> Any:
    """The ROM's output rows (3, n): the response set's mean displacement; one line without
    a response set."""
    if rom.output is None:
        raise ParameterError("the reduced models (rom, interface, joint) measure the amplitude "
                             "on a node set: give the response set (--response-set NAME)")
    return rom.output


def _interface(study: ModalStudy, rom: Any, progress: Progress | None) -> MeshCurve:
    """EPMC on the interface-reduced model (:mod:`microslip.meshdynamics.interfacerom`): a
    few interface modes for the contact, the friction law at every contact node."""
    from .interfacerom import interface_epmc

    s, case = study.settings, study.case
    model, curve = interface_epmc(
        study.prepared.model, case.density, study.mode, study.amplitudes, s.harmonics,
        s.samples, response_set=case.response_set, rom_modes=case.rom_modes,
        interface_modes=case.interface_modes, rom=rom, damping_ratio=s.damping_ratio)
    count = len(study.prepared.stuck.frequencies_Hz)
    freqs = [float(f) for f in model.stuck_frequencies(count + 2)]
    stuck, warn = stuck_check(study, freqs, "interface model")
    return MeshCurve(
        label=f"EPMC on the interface-reduced ROM ({model.dofs} DOF: "
              f"{model.interface_modes} interface modes for {model.contact_nodes} "
              f"contact nodes, {curve.harmonics} harmonics)" + _damped(study),
        columns=dict(BASE_COLUMNS),
        values={"amplitude_mm": [float(a) for a in curve.amplitude],
                "frequency_Hz": [float(f) for f in curve.frequency],
                "damping_ratio": [float(z) for z in curve.damping_ratio]},
        extra={"interface_frequencies_Hz": freqs[:count],
               "interface": {"dofs": model.dofs, "interface_modes": model.interface_modes,
                             "characteristic_modes": model.characteristic_modes,
                             "basis": model.basis,
                             "fixed_interface_modes": model.fixed_interface_modes,
                             "contact_nodes": model.contact_nodes,
                             "harmonics": curve.harmonics, "samples": curve.samples,
                             **stuck}},
        warnings=warn)


def _joint(study: ModalStudy, rom: Any, progress: Progress | None) -> MeshCurve:
    """EPMC on the whole-joint model (:mod:`microslip.meshdynamics.wholejoint`) at the grid's
    amplitudes: the ROM reduced to the interface's rigid motion, one joint from the FE's
    first loading."""
    from .wholejoint import build_whole_joint, whole_joint_epmc

    mode, s = study.mode, study.settings
    from .case import modal_damping

    joint = build_whole_joint(rom, study.prepared.model, mode, mode.direction @ _output(rom),
                              backbone=study.case.backbone)
    joint = replace(joint, structure=modal_damping(joint.structure, s.damping_ratio))
    curve, failed = whole_joint_epmc(joint, np.asarray(study.amplitudes), s.harmonics,
                                     s.samples, mode.frequency_Hz)
    stuck = float(joint.stuck_frequencies()[joint.mode_index(mode.frequency_Hz)])
    bb = joint.backbone
    warnings = list(failed)
    if bb.source == "pull":
        warnings.append(f"mode {study.number} does not load the interface as a whole (its "
                        "contact resultant does not follow its mean displacement): the joint "
                        "is the interface's pull test, and the whole-joint model misses the "
                        "damping of the interface's distortion")
    loading = bb.loading
    share = (float(loading.rigid_work[-1] / loading.work[-1])
             if loading is not None and loading.work[-1] > 0 else None)
    return MeshCurve(
        label=f"EPMC on the whole-joint (pull-test) model ({joint.structure.dofs} DOF, "
              f"{curve.harmonics} harmonics; stuck {stuck:.6g} Hz, "
              f"{100 * (stuck / mode.frequency_Hz - 1):+.2f} % against the full FE)"
              + _damped(study),
        columns=dict(BASE_COLUMNS),
        values={"amplitude_mm": nulls(np.where(np.isnan(curve.frequency), np.nan,
                                               curve.amplitude)),
                "frequency_Hz": nulls(curve.frequency),
                "damping_ratio": nulls(curve.damping_ratio)},
        extra={"joint": {**bb.summary(), "torsion": joint.torsion,
                         "rigid_work_share": share,
                         "stuck_frequency_Hz": stuck,
                         "stuck_frequency_error": stuck / mode.frequency_Hz - 1.0,
                         "dofs": joint.structure.dofs,
                         "fixed_interface_modes": study.case.rom_modes,
                         "harmonics": curve.harmonics, "samples": curve.samples}},
        warnings=warnings)


#: The solvers of a modal study, each on the same amplitude grid.
MESH_SOLVERS: dict[str, MeshSolver] = {
    "fe": MeshSolver("quasi-static modal analysis of the full frictional FE (the truth)",
                     ("workers", "scheduler"), False, _fe),
    "rom": MeshSolver("EPMC by harmonic balance on a Craig-Bampton model that keeps every "
                      "contact node with the FE's own contact law (--rom-modes "
                      "fixed-interface modes)", ("harmonics", "rom_modes"), True, _rom),
    "interface": MeshSolver("EPMC by harmonic balance on the ROM with its contact reduced "
                            "to a few interface modes (--interface-modes characteristic "
                            "constraint modes and the mode's first-loading shapes), every "
                            "contact node keeping its own law",
                            ("harmonics", "rom_modes", "interface_modes"),
                            # the ROM route where the body is not condensed (small meshes)
                            lambda study: study.prepared.model.reduced is None, _interface),
    "joint": MeshSolver("EPMC by harmonic balance on the whole-joint model, the pull-test "
                        "model (cheap, wrong by design where the contact's own distortion "
                        "does the friction work): the contact "
                        "reduced to its rigid motion in its plane, one joint whose backbone "
                        "is the FE's first loading by the mode (or --backbone tip|centre)",
                        ("harmonics", "rom_modes", "backbone"), True, _joint),
}


def check_solvers(solvers: Sequence[str]) -> tuple[str, ...]:
    """``solvers`` if each is a key of :data:`MESH_SOLVERS` (at least one)."""
    bad = [s for s in solvers if s not in MESH_SOLVERS]
    if bad or not solvers:
        raise ParameterError(f"unknown modal solver {bad[0] if bad else None!r}; choose from "
                             f"{', '.join(MESH_SOLVERS)}")
    return tuple(solvers)


#: Contact nodes above which the side-by-side study leaves the contact-node ROM's EPMC out
#: (its dense balance grows with their cube: 50 s on 221 nodes) and the interface model,
#: within 0.2 % / 2 % of it where measured (docs/interpretation.md), stands in.
ROM_NODE_LIMIT = 300


def stood_in(study: ModalStudy) -> dict[str, str]:
    """The solvers the side-by-side study leaves out on ``study``, each with why (``rom`` on a
    contact of more than :data:`ROM_NODE_LIMIT` nodes with ``fixed`` normal contact)."""
    model = study.prepared.model
    nodes = len(model.contact_nodes)
    if nodes <= ROM_NODE_LIMIT or model.normal is not None:
        return {}
    return {"rom": f"left out on {nodes} contact nodes (more than {ROM_NODE_LIMIT}): its "
                   "harmonic balance grows with their cube; the interface model stands in "
                   "for it (--solver rom runs it)"}


def compare_all(study: ModalStudy, progress: Progress | None = None,
                echo: Callable[[str], None] | None = None
                ) -> tuple[dict[str, MeshCurve], dict[str, Any]]:
    """Every solver of :data:`MESH_SOLVERS` on ``study`` but those :func:`stood_in` leaves
    out (named in the warnings), and :func:`compare_output` of them."""
    skip = stood_in(study)
    curves = run_solvers(study, tuple(n for n in MESH_SOLVERS if n not in skip), progress,
                         echo)
    out = compare_output(study, curves)
    out["warnings"] += [f"{name}: {why}" for name, why in skip.items()]
    stand_in = out["solvers"].get("interface", {}).get("interface", {})
    error = stand_in.get("stuck_frequency_error")
    if "rom" in skip and error is not None and abs(error) > STUCK_TOLERANCE:
        why = (f"does not stand in for the contact-node ROM: its stuck frequency is "
               f"{100 * error:+.2f} % off the full FE's at zero amplitude (more than "
               f"{100 * STUCK_TOLERANCE:g} %)")
        out["warnings"].append(f"interface: {why}")
        verdict = out["verdicts"].get("interface")
        if verdict is not None:
            verdict["verdict"] += f"; {why}"
            verdict["meets_targets"] = False
    return curves, out


def prepare_modal(case: StructureCase, settings: ModalSettings | None = None) -> ModalStudy:
    """Clamp the case's mesh, compute its stuck and free modes and the amplitude grid:
    everything the solvers share."""
    settings = ModalSettings() if settings is None else settings
    prepared = prepare_structure(case)
    forces, amplitudes, limit, notes = limited_grid(prepared, settings.amplitudes,
                                                    settings.amplitude_range)
    return ModalStudy(prepared=prepared, settings=settings, forces=forces,
                      amplitudes=amplitudes, limit=limit, notes=notes)


def run_solvers(study: ModalStudy, solvers: Sequence[str] = tuple(MESH_SOLVERS),
                progress: Progress | None = None,
                echo: Callable[[str], None] | None = None) -> dict[str, MeshCurve]:
    """Each named solver's curve on ``study`` (in the order given); the contact-node ROM is
    built once, before the first solver that needs it. ``echo`` hears each solver's name
    as it starts (``solver k/n: name``)."""
    names = check_solvers(solvers)
    rom = None
    curves: dict[str, MeshCurve] = {}
    for k, name in enumerate(names):
        solver = MESH_SOLVERS[name]
        if echo is not None:
            echo(f"solver {k + 1}/{len(names)}: {name}")
        start = time.perf_counter()
        try:
            needs = solver.rom_needed(study)
            if needs and rom is None:
                rom = structure_rom(study.prepared)
                start += rom.build_s  # counted below with the ROM's own build time
            curve = solver.run(study, rom, progress)
        except MicroslipError as exc:
            if name == TRUTH or len(names) == 1:  # nothing to judge, or nothing else to show
                raise
            curve = _failed(study, str(exc))
            needs = False
        cost = time.perf_counter() - start + (rom.build_s if needs and rom is not None else 0.0)
        curves[name] = replace(curve, cost_s=cost)
    return curves


def _failed(study: ModalStudy, why: str) -> MeshCurve:
    """The curve of a solver that stopped: every amplitude failed, ``why`` its reason."""
    empty: list[float | None] = [None] * len(study.amplitudes)
    return MeshCurve(label=f"failed: {why}", columns=dict(BASE_COLUMNS),
                     values={k: list(empty) for k in BASE_COLUMNS}, extra={},
                     warnings=[why], failures=(why,))


def study_output(study: ModalStudy, solver: str, curve: MeshCurve,
                 notes: bool = True) -> dict[str, Any]:
    """The JSON of one solver's curve on the study: its warnings with the validity ones
    (:func:`~.limits.result_warnings`) and, with ``notes``, what the grid's limit did."""
    from .limits import result_warnings

    prepared = study.prepared
    warnings = list(curve.warnings)
    if study.limit is not None:
        warnings += result_warnings(study.limit, curve.values["amplitude_mm"],
                                    curve.values["damping_ratio"],
                                    len(getattr(study.case.clamp, "shanks", ())))
    return {"mesh": study.case.mesh_name, "solver": solver, "mode": study.number,
            "label": study.mode.label, "density_kg_m3": study.case.density,
            "amplitude_coordinate": RESPONSE_SET_COORDINATE,
            "linear_frequencies_Hz": [float(f) for f in prepared.stuck.frequencies_Hz],
            "free_frequencies_Hz": [float(f) for f in prepared.free.frequencies_Hz],
            "modes": prepared.stuck.summary(),
            "amplitude_limit": None if study.limit is None else study.limit.summary(),
            "model": prepared.model.describe(),
            "structural_damping_ratio": study.settings.damping_ratio,
            **curve.values, **curve.extra,
            "cost_s": curve.cost_s,
            "warnings": [*(study.notes if notes else ()), *warnings]}


def compare_output(study: ModalStudy, curves: dict[str, MeshCurve]) -> dict[str, Any]:
    """The JSON of every solver's curve on ``study``: the shared keys once, ``solvers``
    (name -> that solver's own keys, as one solver's JSON has them), ``verdicts`` (name ->
    :meth:`~microslip.meshdynamics.verdict_modal.ModalVerdict.summary`, every solver but the
    full FE) and ``warnings`` (every solver's, each line led by its name)."""
    outputs = {name: study_output(study, name, curve, notes=False)
               for name, curve in curves.items()}
    first = next(iter(outputs.values()))
    out: dict[str, Any] = {k: first[k] for k in SHARED}
    out["solvers"] = {name: {k: v for k, v in o.items() if k not in (*SHARED, "solver")}
                      for name, o in outputs.items()}
    truth = out["solvers"].get(TRUTH)
    out["verdicts"] = ({} if truth is None else
                       {name: _verdict(name, truth, o, curves[name].failures)
                        for name, o in out["solvers"].items() if name != TRUTH})
    out["warnings"] = [*study.notes, *(f"{name}: {w}" for name, o in out["solvers"].items()
                                       for w in o["warnings"])]
    return out


def _verdict(name: str, truth: dict[str, Any], curve: dict[str, Any],
             failures: tuple[str, ...]) -> dict[str, Any]:
    """The model's verdict against the full FE; a model that failed at some amplitudes (or
    as a whole) says so in its line, and one with nothing left to compare does not meet its
    targets."""
    v = modal_verdict(name, truth, curve).summary()
    cost, truth_cost = curve.get("cost_s"), truth.get("cost_s")
    v["cost_s"] = cost
    if cost is not None:  # what the model buys: its error (above) for its cost
        v["verdict"] += (f"; cost {cost:.3g} s" + (f" ({cost / truth_cost:.2g}x the full FE's)"
                                                   if truth_cost else ""))
    if failures:
        v["verdict"] = (f"{name}: {failures[0]}" if not v["points"] else
                        f"{v['verdict']}; {failures[0]}")
        if len(failures) > 1:
            v["verdict"] += f" (and {len(failures) - 1} more amplitudes)"
        if not v["points"]:
            v["meets_targets"] = False
    return v


def modal_study(case: StructureCase, settings: ModalSettings | None = None,
                solvers: Sequence[str] = tuple(MESH_SOLVERS),
                progress: Progress | None = None,
                echo: Callable[[str], None] | None = None) -> StudyResult:
    """Every named solver on one structure and one amplitude grid, side by side with the
    verdicts against the full FE (when ``fe`` is among them): :func:`compare_output`, as a
    named :class:`~.studyresult.StudyResult` (``.solvers``, ``.verdicts``, ``.to_json()``).

    Examples
    --------
    >>> from microslip.fe.clamp import MeshClamp
    >>> from microslip.meshdynamics import StructureCase, modal_study
    >>> clamp = MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
    ...                   poisson_ratio=0.33, friction=0.5, stick_slope=1e4)
    >>> case = StructureCase("examples/cantilever.inp", clamp, density=2700.0, mode=2,
    ...                      response_set="response")
    >>> out = modal_study(case, ModalSettings(amplitudes=3), ("fe", "rom"))  # doctest: +SKIP
    """
    from .studyresult import StudyResult

    study = prepare_modal(case, settings)
    if tuple(solvers) == tuple(MESH_SOLVERS):
        return StudyResult("modal", compare_all(study, progress, echo)[1])
    return StudyResult("modal", compare_output(study, run_solvers(study, solvers, progress,
                                                                    echo)))
