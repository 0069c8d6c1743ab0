"""One case, one computation: what ``loop``, ``planar``, ``fe`` and ``report`` run.

A command's options arrive as a mapping from the option's argparse destination to its value:
the command line gives ``vars(args)`` (with ``--case`` the file's keys are its defaults,
:func:`microslip.case.options.parse_args`), the report gives :func:`case_options` (the same
case keys through the same table, :data:`~microslip.case.options.CASE_OPTIONS`, on the
command's defaults :data:`COMMAND_DEFAULTS`). The functions here turn that mapping into the
inputs of one computation (:class:`LoopInputs`, :class:`PlanarInputs`, :class:`FeInputs`),
run it (:func:`compute_loop`, :func:`compute_planar`, :func:`compute_fe`) and write its JSON
object (:func:`loop_json`, :func:`planar_json`, :func:`fe_json`), so that a case gives the
same numbers whichever of them runs it.

Every W_d, U and eta says which part of the clamp it belongs to (``clamp_portion``,
:data:`MODEL_PORTION`): the paper's tip model is one of two symmetric halves of the clamped
zone, each carrying the tip force it is given (Section 2.1); the centre model and the work of
a planar load are the whole clamp (docs/interpretation.md §8).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from ..conventions import DEFAULT_MESH, DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE, check_whole
from ..energy import DEFAULT_STRAIN_ENERGY, damping
from ..errors import MacroslipError, ParameterError
from ..models import Contact, check_increments, get_model, macroslip_force
from ..models.interface import PRESSURE_LAWS, PressureLaw, power_law, read_pressure_table
from ..models.validity import validity
from ..named import result
from ..options import ModelOptions
from ..params import PRESETS, ClampParams, preset
from ..planar import TIP_SYMMETRY, PlanarResult, paper_levels, planar_damping
from ..planar.loadpath import DEFAULT_WORK_STRAIN_ENERGY
from ..results import DampingResult
from .model import Case
from .options import CASE_OPTIONS, _reads
from .schema import CLAMP_KEYS
from .table import OPTIONS, SOLVERS

__all__ = [
    "CLAMP_FIELDS",
    "COMMAND_DEFAULTS",
    "MODEL_PORTION",
    "FeInputs",
    "LoopInputs",
    "LoopRun",
    "PlanarInputs",
    "PlanarRun",
    "case_options",
    "clamp_from_options",
    "clamp_overrides",
    "compute_fe",
    "compute_loop",
    "compute_planar",
    "contact_from_options",
    "fe_inputs",
    "fe_json",
    "law_from_text",
    "loop_inputs",
    "loop_json",
    "model_options_from",
    "planar_amplitudes",
    "planar_inputs",
    "planar_json",
    "planar_zones",
    "portion_text",
    "tip_portion",
    "validity_warnings",
    "with_portion",
]

#: The seven clamp values (ClampParams fields), in the order of the case file and the flags.
CLAMP_FIELDS = tuple(CLAMP_KEYS.values())

#: Which part of the clamp a 1-D model's (or its FE run's) W_d, U and loop belong to: the
#: paper's tip model is one of two symmetric halves acting in parallel, "each half accepts
#: half of the tip force" (Section 2.1), so its F0 is the force on one half; the centre load
#: has no line of symmetry and the centre model is the whole clamped zone.
MODEL_PORTION = {"tip": "half", "centre": "whole"}

#: The words of a clamp portion in text output (the JSON holds the key).
_PORTION_TEXT = {"half": "one symmetric half of the clamp", "whole": "the whole clamp",
                 "mixed": "tip half with the whole centre"}

def _table_defaults(*names: str) -> dict[str, Any]:
    """The option table's defaults of ``names`` (:attr:`~.table.Option.default`)."""
    return {name: OPTIONS[name].default for name in names}


#: The defaults of the options that loop, planar and fe read, as their command lines have
#: them: the option table's (one definition; tests/test_report_consistency.py holds them
#: equal to the parsers'), and where a command has its own, the library's constant it uses;
#: a case's keys and the report's settings are laid over them.
_MODEL_DEFAULTS: dict[str, Any] = {
    **_table_defaults("preset", "amplitude", "displacement_amplitude", *CLAMP_FIELDS),
    "strain_energy": DEFAULT_STRAIN_ENERGY}
_READING_DEFAULTS: dict[str, Any] = _table_defaults(
    "no_corrections", "poisson", "no_length_update", "centre_reading", "paper_literal",
    "stick_slope", "pressure_law", "no_shear_lag")
COMMAND_DEFAULTS: dict[str, dict[str, Any]] = {
    "loop": {**_MODEL_DEFAULTS, **_READING_DEFAULTS, **_table_defaults("increments")},
    "planar": {**{k: v for k, v in _MODEL_DEFAULTS.items() if k != "amplitude"},
               **_READING_DEFAULTS,
               **_table_defaults("increments", "tip_amplitude", "centre_amplitude", "ratio",
                                 "levels", "phase", "tip_preset", "centre_preset",
                                 "samples_per_cycle"),
               "tip_symmetry": TIP_SYMMETRY, "work_energy": DEFAULT_WORK_STRAIN_ENERGY,
               "solver": next(iter(SOLVERS["planar"]))},
    "fe": {**_MODEL_DEFAULTS, "mesh": DEFAULT_MESH, "stick_slope": DEFAULT_STICK_SLOPE,
           "normal_slope": DEFAULT_NORMAL_SLOPE,
           **_table_defaults("normal_contact", "pressure_law", "clamping_csv", "element",
                             "substeps", "timeout", "threads", "reuse"),
           "solver": next(iter(SOLVERS["fe"]))},
}


def portion_text(portion: str) -> str:
    """The words of a clamp portion (``half``, ``whole``, ``1/K``, ``mixed``) in text output."""
    if portion in _PORTION_TEXT:
        return _PORTION_TEXT[portion]
    return f"{portion} of the clamp"


def tip_portion(tip_symmetry: int) -> str:
    """The clamp portion of one of ``tip_symmetry`` tip models in parallel."""
    return {1: "whole", 2: "half"}.get(tip_symmetry, f"1/{tip_symmetry}")


def with_portion(out: dict[str, Any], portion: str) -> dict[str, Any]:
    """``out`` with ``clamp_portion`` placed just before ``dissipated_energy_Nmm``."""
    new: dict[str, Any] = {}
    for key, value in out.items():
        if key == "dissipated_energy_Nmm":
            new["clamp_portion"] = portion
        new[key] = value
    new.setdefault("clamp_portion", portion)
    return new


# -- a case as a command's options ----------------------------------------------------------


def case_options(case: Case, command: str) -> dict[str, Any]:
    """The options ``microslip COMMAND --case FILE`` runs with when nothing else is given.

    The command's defaults (:data:`COMMAND_DEFAULTS`), the case's keys through
    :data:`~microslip.case.options.CASE_OPTIONS` (the table ``--case`` reads), no preset when
    the case gives the whole clamp, and F0 from ``load.amplitude`` or its fraction of
    mu F_N (:meth:`Case.amplitude`).
    """
    if command not in COMMAND_DEFAULTS:
        raise ParameterError(f"unknown command {command!r}; choose one of "
                             f"{', '.join(COMMAND_DEFAULTS)}")
    out = dict(COMMAND_DEFAULTS[command])
    for key, (dest, scope) in CASE_OPTIONS.items():
        if key in case.values and _reads(command, scope) and dest != "amplitude":
            out[dest] = case.values[key]
    if case.params is not None:
        out["preset"] = None
    if "amplitude" in out:
        out["amplitude"] = case.amplitude()
    return out


# -- the clamp, the reading, the contact -----------------------------------------------------


def clamp_from_options(opts: Mapping[str, Any], fallback_amplitude: float | None = None
                       ) -> tuple[ClampParams, float]:
    """ClampParams (``preset`` overridden by the seven clamp values given) and the amplitude
    F0 (``amplitude``, else the preset's, else ``fallback_amplitude``), validated."""
    name = opts.get("preset")
    if name is not None:
        values = preset(name).as_dict()
        amplitude = PRESETS[name][1]
    else:
        values = {}
        amplitude = None
    values.update({f: opts[f] for f in CLAMP_FIELDS if opts.get(f) is not None})
    missing = [f"--{f.replace('_', '-')}" for f in CLAMP_FIELDS if f not in values]
    if missing:
        raise ParameterError(f"give --preset or all of {', '.join(missing)}")
    params = ClampParams(**values)
    if opts.get("amplitude") is not None:
        amplitude = opts["amplitude"]
    if amplitude is None:
        amplitude = fallback_amplitude
    if amplitude is None:
        raise ParameterError("give --amplitude N (the load amplitude, > 0)")
    if not (math.isfinite(amplitude) and amplitude > 0):
        raise ParameterError(f"amplitude must be finite and > 0 N, got {amplitude!r}")
    return params, float(amplitude)


def clamp_overrides(opts: Mapping[str, Any]) -> dict[str, float]:
    """The clamp values given (field -> value), over whatever preset they change."""
    return {f: float(v) for f in CLAMP_FIELDS if (v := opts.get(f)) is not None}


def model_options_from(opts: Mapping[str, Any]) -> ModelOptions:
    """The reading of the paper the options ask for (:class:`ModelOptions`)."""
    if opts.get("paper_literal"):
        return ModelOptions.paper()
    centre = opts.get("centre_reading", "physical")
    if opts.get("no_corrections"):
        return ModelOptions(poisson="off", length_update=False, centre=centre)
    return ModelOptions(poisson=opts.get("poisson", "consistent"),
                        length_update=not opts.get("no_length_update"), centre=centre)


def law_from_text(text: str | None, params: ClampParams) -> PressureLaw | None:
    """The pressure law of a ``--pressure-law`` value; None for the uniform (paper's) law."""
    if text is None or text == "uniform":
        return None
    if text in PRESSURE_LAWS:
        return PRESSURE_LAWS[text]()
    kind, _, rest = text.partition(":")
    if kind == "table" and rest:
        return read_pressure_table(rest, params.length)
    if kind == "power" and rest:
        try:
            numbers = [float(x) for x in rest.split(":")]
        except ValueError:
            numbers = []
        if len(numbers) in (1, 2):
            return power_law(*numbers)
    raise ParameterError(f"--pressure-law {text!r}: use one of {', '.join(PRESSURE_LAWS)}, "
                         "power:N[:EDGE] or table:FILE.csv")


def contact_from_options(opts: Mapping[str, Any], params: ClampParams) -> Contact | None:
    """The contact the options ask for; None when they leave the paper's foundation."""
    slope = opts.get("stick_slope")
    law = law_from_text(opts.get("pressure_law"), params)
    if opts.get("no_shear_lag") and slope is None:
        raise ParameterError("--no-shear-lag needs --stick-slope (the rigid foundation has no "
                             "shear layer to leave out)")
    if slope is None and law is None:
        return None
    slope = math.inf if slope is None else slope
    contact = Contact(slope, shear_lag=not opts.get("no_shear_lag") and math.isfinite(slope),
                      law=law)
    return None if contact.is_rigid else contact


def validity_warnings(model: str, params: ClampParams, amplitude: float,
                      contact: Contact | None) -> list[str]:
    """The validity warnings of a 1-D result (sentences; empty within the model's range)."""
    c = contact or Contact()
    return list(validity(get_model(model).load_case, params, amplitude,
                         stick_slope=c.stick_slope, law=c.law).warnings)


def _contact_json(contact: Contact | None) -> dict[str, Any]:
    return (contact or Contact()).summary()


# -- loop -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class LoopInputs:
    """One 1-D loop: model, clamp, F0 (N), increments, reading, U definition, contact."""

    model: str
    params: ClampParams
    amplitude: float
    increments: int = 1000
    options: ModelOptions = field(default_factory=ModelOptions)
    strain_energy: str = DEFAULT_STRAIN_ENERGY
    contact: Contact | None = None

    @property
    def macroslip(self) -> float:
        """The force at which the whole interface slips, N."""
        return macroslip_force(self.model, self.params, self.options)


@result
class LoopRun:
    """A loop computed from its inputs, with the validity warnings of its amplitude."""

    inputs: LoopInputs
    result: DampingResult
    warnings: tuple[str, ...]


def loop_inputs(opts: Mapping[str, Any], fallback_amplitude: float | None = None
                ) -> LoopInputs:
    """The loop ``microslip loop`` runs with the options ``opts`` (argparse destinations)."""
    params, amplitude = clamp_from_options(opts, fallback_amplitude)
    return LoopInputs(model=opts["model"], params=params, amplitude=amplitude,
                      increments=check_increments(opts.get("increments", 1000)),
                      options=model_options_from(opts),
                      strain_energy=opts.get("strain_energy", DEFAULT_STRAIN_ENERGY),
                      contact=contact_from_options(opts, params))


def compute_loop(inputs: LoopInputs, amplitude: float | None = None) -> LoopRun:
    """The loop of ``inputs`` (at ``amplitude`` N instead of its own, if given):
    :func:`microslip.damping` on its contact, and its validity warnings."""
    if amplitude is not None:
        inputs = replace(inputs, amplitude=float(amplitude))
    r = damping(inputs.model, inputs.params, inputs.amplitude, inputs.increments,
                inputs.options, inputs.strain_energy, inputs.contact)
    warnings = validity_warnings(inputs.model, inputs.params, inputs.amplitude, inputs.contact)
    return LoopRun(inputs, r, tuple(warnings))


def loop_json(run: LoopRun) -> dict[str, Any]:
    """The JSON object of a loop (``microslip loop --json``); keys carry their units."""
    i, r = run.inputs, run.result
    bb = r.backbone
    if bb is None:  # pragma: no cover - microslip.damping always keeps the backbone
        raise ValueError("a loop result from microslip.damping carries its backbone")
    slip = {name: float(bb.slip_length[-1, k]) for k, name in enumerate(bb.domains)}
    out = {
        "model": i.model,
        "units": {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm"},
        "params": i.params.as_dict(),
        "options": {"poisson": i.options.poisson, "length_update": i.options.length_update,
                    "centre_reading": i.options.centre},
        "contact": _contact_json(i.contact),
        "increments": i.increments,
        "amplitude_N": r.amplitude,
        "macroslip_force_N": i.macroslip,
    }
    return with_portion(out | r.loop_json(slip), MODEL_PORTION[i.model]) | {
        "warnings": list(run.warnings)}


# -- planar ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class PlanarInputs:
    """One planar load case of the paper's decoupled models (units N, mm, degrees)."""

    tip_params: ClampParams
    centre_params: ClampParams
    tip_amplitude: float
    centre_amplitude: float
    increments: int = 1000
    options: ModelOptions = field(default_factory=ModelOptions)
    strain_energy: str = DEFAULT_STRAIN_ENERGY
    phase_deg: float = 0.0
    work_energy: str = DEFAULT_WORK_STRAIN_ENERGY
    tip_symmetry: int = TIP_SYMMETRY
    samples_per_cycle: int = 2048
    contact: Contact | None = None
    tip_preset: str = "table2-tip"
    centre_preset: str = "table2-centre"
    own_clamp: tuple[tuple[str, float], ...] = ()


@result
class PlanarRun:
    """A planar case computed from its inputs, with the validity warnings of both models."""

    inputs: PlanarInputs
    result: PlanarResult
    warnings: tuple[str, ...]


def planar_zones(tip: ClampParams, centre: ClampParams, overrides: Mapping[str, float],
                 tip_symmetry: int = TIP_SYMMETRY) -> tuple[ClampParams, ClampParams]:
    """The tip and centre zones of the planar case with the clamp values ``overrides``.

    The values describe the whole clamp: the centre model is the whole clamp; the tip model is
    one of ``tip_symmetry`` symmetric parts of the contact width, so it takes width
    w / ``tip_symmetry`` (as the Table 2 presets in the reading of docs/interpretation.md §6:
    tip w = 25 mm, centre w = 50 mm) and every other value as given.
    """
    check_whole("tip_symmetry", tip_symmetry, 1)
    tip_values = dict(overrides)
    if "width" in overrides:
        tip_values["width"] = overrides["width"] / tip_symmetry
    return tip.replace(**tip_values), centre.replace(**overrides)


def planar_amplitudes(opts: Mapping[str, Any]) -> tuple[float, float]:
    """(tip, centre) amplitudes in N from ``tip_amplitude`` and ``centre_amplitude`` or
    ``ratio`` (on the paper's ``levels``)."""
    tip, centre = opts.get("tip_amplitude"), opts.get("centre_amplitude")
    if opts.get("ratio") is not None:
        if tip is not None or centre is not None:
            raise ParameterError("give either --ratio or --tip-amplitude and "
                                 "--centre-amplitude, not both")
        return paper_levels(opts["ratio"], opts.get("levels", "base"))
    if tip is None or centre is None:
        raise ParameterError("give --tip-amplitude N and --centre-amplitude N, or --ratio R")
    return float(tip), float(centre)


def planar_zones_from(opts: Mapping[str, Any]) -> tuple[ClampParams, ClampParams]:
    """The (tip, centre) zones of the options: the presets with the clamp values over them."""
    return planar_zones(preset(opts.get("tip_preset", "table2-tip")),
                        preset(opts.get("centre_preset", "table2-centre")),
                        clamp_overrides(opts), opts.get("tip_symmetry", TIP_SYMMETRY))


def planar_inputs(opts: Mapping[str, Any], amplitudes: tuple[float, float] | None = None
                  ) -> PlanarInputs:
    """The planar case ``microslip planar`` runs with the options ``opts``; ``amplitudes``
    (tip, centre, N) replace those of the options (``--displacement-amplitude``)."""
    tip, centre = planar_zones_from(opts)
    at, ac = amplitudes if amplitudes is not None else planar_amplitudes(opts)
    return PlanarInputs(
        tip_params=tip, centre_params=centre, tip_amplitude=at, centre_amplitude=ac,
        increments=check_increments(opts.get("increments", 1000)),
        options=model_options_from(opts),
        strain_energy=opts.get("strain_energy", DEFAULT_STRAIN_ENERGY),
        phase_deg=float(opts.get("phase", 0.0)),
        work_energy=opts.get("work_energy", DEFAULT_WORK_STRAIN_ENERGY),
        tip_symmetry=opts.get("tip_symmetry", TIP_SYMMETRY),
        samples_per_cycle=opts.get("samples_per_cycle", 2048),
        contact=contact_from_options(opts, tip),
        tip_preset=opts.get("tip_preset", "table2-tip"),
        centre_preset=opts.get("centre_preset", "table2-centre"),
        own_clamp=tuple(clamp_overrides(opts).items()))


def compute_planar(inputs: PlanarInputs) -> PlanarRun:
    """:func:`microslip.planar.planar_damping` of ``inputs`` and the validity warnings of
    both models."""
    i = inputs
    try:
        r = planar_damping(
            i.tip_params, i.centre_params, i.tip_amplitude, i.centre_amplitude,
            increments=i.increments, options=i.options, strain_energy=i.strain_energy,
            phase_deg=i.phase_deg, work_energy=i.work_energy, tip_symmetry=i.tip_symmetry,
            samples_per_cycle=i.samples_per_cycle, contact=i.contact)
    except MacroslipError as exc:
        if "centre model" in str(exc) and i.options.centre == "physical":
            raise MacroslipError(f"{exc}; the paper's reading of Eq. 11 "
                                 "(--centre-reading paper) reaches 2 mu F_N") from None
        raise
    warnings = [f"tip model: {w}" for w in validity_warnings(
        "tip", i.tip_params, i.tip_amplitude, i.contact)]
    warnings += [f"centre model: {w}" for w in validity_warnings(
        "centre", i.centre_params, i.centre_amplitude, i.contact)]
    return PlanarRun(i, r, tuple(warnings))


def planar_json(run: PlanarRun) -> dict[str, Any]:
    """The JSON object of a planar case (``microslip planar --json``); keys carry units.

    ``clamp_portion`` is the whole clamp (the work of the load); the ``tip`` and ``centre``
    objects carry their own, and ``paper_clamp_portion`` is ``mixed`` (the paper's resultant
    combines the tip half's loop with the whole centre's, Eqs 19-20).
    """
    i = run.inputs
    out: dict[str, Any] = {
        "solver": "analytical",
        "units": {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm",
                  "angle": "degrees"},
        "tip_preset": i.tip_preset,
        "centre_preset": i.centre_preset,
        "options": {"poisson": i.options.poisson, "length_update": i.options.length_update,
                    "centre_reading": i.options.centre},
        "increments": i.increments,
        "samples_per_cycle": i.samples_per_cycle,
    }
    if i.own_clamp:
        out["tip_params"], out["centre_params"] = (i.tip_params.as_dict(),
                                                   i.centre_params.as_dict())
    summary = with_portion(run.result.summary(), "whole")
    summary["paper_clamp_portion"] = "mixed"
    summary["tip"] = with_portion(summary["tip"], tip_portion(i.tip_symmetry))
    summary["centre"] = with_portion(summary["centre"], MODEL_PORTION["centre"])
    out.update(summary)
    return out | {"contact": _contact_json(i.contact), "warnings": list(run.warnings)}


# -- fe -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class FeInputs:
    """One finite-element run: load case, clamp, F0 (N) and the keywords of
    :func:`microslip.fe.run_loop` (solver, mesh, element, stick slope, substeps, U and the
    solver's own options)."""

    model: str
    params: ClampParams
    amplitude: float
    run_options: tuple[tuple[str, Any], ...]

    @property
    def options(self) -> dict[str, Any]:
        return dict(self.run_options)


def _check_run_options(opts: Mapping[str, Any]) -> None:
    timeout, threads = opts.get("timeout"), opts.get("threads", 1)
    if timeout is not None and not (math.isfinite(timeout) and timeout > 0):
        raise ParameterError(f"--timeout must be > 0 s, got {timeout!r}")
    if not 1 <= threads <= 256:
        raise ParameterError(f"--threads must be in [1, 256], got {threads}")


def _solver_options(opts: Mapping[str, Any], params: ClampParams) -> dict[str, Any]:
    """The solver's own options given; one line for one the solver does not take."""
    from ..fe import SOLVERS

    solver = opts.get("solver", "builtin")
    entry = SOLVERS[solver]
    threads = opts.get("threads", 1)
    normal_slope = opts.get("normal_slope")
    given = {"timeout": opts.get("timeout"), "threads": threads if threads != 1 else None,
             "reuse": opts.get("reuse") or None,
             "pressure_law": law_from_text(opts.get("pressure_law"), params),
             "normal_contact": opts.get("normal_contact"),
             "normal_slope": (normal_slope if normal_slope not in (None, DEFAULT_NORMAL_SLOPE)
                              else None)}
    given = {k: v for k, v in given.items() if v is not None}
    if (solver == "builtin" and "normal_slope" in given
            and opts.get("normal_contact") != "penalty"):
        raise ParameterError("--normal-slope with --solver builtin needs --normal-contact "
                             "penalty (the fixed normal contact has no normal stiffness)")
    if opts.get("clamping_csv") is not None and solver != "builtin":
        given["clamping_csv"] = opts["clamping_csv"]
    bad = [f"--{k.replace('_', '-')}" for k in given if k not in entry.options]
    if bad:
        raise ParameterError(f"{', '.join(bad)} do(es) not apply to --solver {solver}")
    if "threads" in entry.options:
        given.setdefault("threads", threads)
    return given


def fe_inputs(opts: Mapping[str, Any], fallback_amplitude: float | None = None) -> FeInputs:
    """The run ``microslip fe`` makes with the options ``opts`` (argparse destinations)."""
    _check_run_options(opts)
    params, amplitude = clamp_from_options(opts, fallback_amplitude)
    slope = opts.get("stick_slope")
    run = {"solver": opts.get("solver", "builtin"), "mesh": opts.get("mesh", "coarse"),
           "element": opts.get("element"),
           "stick_slope": DEFAULT_STICK_SLOPE if slope is None else slope,
           "substeps": opts.get("substeps", 50),
           "strain_energy_kind": opts.get("strain_energy", DEFAULT_STRAIN_ENERGY),
           **_solver_options(opts, params)}
    return FeInputs(opts["model"], params, amplitude, tuple(run.items()))


def compute_fe(inputs: FeInputs, amplitude: float | None = None, **io: Any) -> Any:
    """:func:`microslip.fe.run_loop` of ``inputs`` (at ``amplitude`` N instead of its own, if
    given); ``io`` are its ``out`` and ``vtu``. Returns (FELoopResult, files)."""
    from ..fe import run_loop

    f0 = inputs.amplitude if amplitude is None else float(amplitude)
    return run_loop(inputs.model, inputs.params, f0, **io, **inputs.options)


def fe_json(result: Any) -> dict[str, Any]:
    """The JSON object of an FE run (``microslip fe --json``): the result's summary with its
    ``clamp_portion``, the same as the 1-D model of its load case."""
    return with_portion(result.summary(), MODEL_PORTION[result.load_case])
