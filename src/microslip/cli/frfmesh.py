"""``microslip frf --mesh FILE``: the forced response of the structure of the user's own mesh
with its clamp, at the force levels the user gives (issue 23, item 5).

The load is a force F cos(2 pi f t) of amplitude F (N, each ``--force``) on a node set
(``--load-set``), spread equally over its nodes along ``--load-direction`` (default: the
response set along the mode's direction). The response, ``amplitude_mm``, is the first
harmonic of the response set's mean displacement along the mode's direction (as in ``modal
--mesh``). Each solver of :data:`FRF_MESH_SOLVERS` gives a
:class:`~microslip.dynamics.structure.Structure` with that output and the load on its
coordinates; the curves are :func:`microslip.dynamics.response.frequency_response` (harmonic
balance and arclength continuation).

The peak's equivalent damping ratio (:func:`equivalent_damping`): a linear mode driven at
resonance has a_peak = F_modal / (2 zeta m omega^2), so zeta = F_modal / (2 m omega^2
a_peak) with the stuck mode's modal force and mass and omega the peak's frequency. The
half-power width is ill-defined on a nonlinear peak (the curve leans, its two sides belong to
different amplitudes); this definition needs the peak only. Parses and delegates; units N, mm,
Hz, kg/m^3.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError
from .common import check_plot, print_json
from .meshstructure import (
    DEFAULT_ROM_MODES,
    MeshModes,
    add_mesh_structure_options,
    add_reduced_model_options,
    check_mesh_structure,
    mesh_model,
    mesh_modes,
)
from .ownmesh import given, verb

__all__ = ["DEFAULT_MESH_HARMONICS", "FRF_MESH_SOLVERS", "MESH_RANGE", "ForcedModel",
           "FrfMeshSolver", "FrfStudy", "add_frf_mesh_options", "check_range",
           "equivalent_damping", "refuse_frf_mesh_options", "run_frf_mesh", "stuck_response"]

#: Harmonics of the balance with --mesh unless --harmonics says. On the 12x3x1 cantilever's
#: mode 2 at 10 N the peak with 3 harmonics is within 0.4 % (frequency) and 1 % (amplitude)
#: of the peak with 7, seven times faster (the ROM has no linear damping, so the balance is
#: not condensed onto the contact dofs and costs (dofs x (2H + 1))^3 per step; with odd
#: joint forces, ``fixed`` normal contact, on the odd harmonics only, (dofs x (H + 1))^3).
#: On 24x6x2, mode 2 at 3 N (186 ROM DOF, odd harmonics), the whole command with one force
#: level: 3 harmonics 8 s (31 s on every harmonic), 5 take 18 s, 7 take 43 s; the peak
#: frequency moves by -0.14 % from 3 to 5 harmonics, and with 7 an internal resonance of the
#: undamped ROM (a dip near 1590 Hz) shifts the located peak by +0.5 %: 3 stays the default
#: (7 would cost more than the old default did), --harmonics 7 resolves such features.
DEFAULT_MESH_HARMONICS = 3
#: Default sweep: these fractions of the mode's stuck frequency (the friction softens the
#: peak below the stuck frequency; the range keeps it inside).
MESH_RANGE = (0.8, 1.05)
#: Options of frf --mesh only (destinations).
FRF_MESH_ONLY = ("contact_set", "clamp_set", "normal_contact", "normal_slope", "density",
                 "response_set", "solver", "rom_modes", "backbone", "load_set",
                 "load_direction")
#: Options of frf's structure file that do nothing with a mesh.
NOT_WITH_FRF_MESH = ("excitation",)
DAMPING_DEFINITION = ("zeta = F_modal / (2 m omega^2 a_peak): the linear single-mode peak "
                      "a_peak = F_modal / (2 zeta m omega^2) solved for zeta, with the stuck "
                      "mode's modal force F_modal and mass m (mass-normalised: m = 1) "
                      "referred to the response set's motion, omega = 2 pi x the peak's "
                      "frequency")


def add_frf_mesh_options(p: argparse.ArgumentParser) -> None:
    """The mesh structure's options (:mod:`.meshstructure`), the load and the solver."""
    g = p.add_argument_group("the structure of your own mesh (--mesh FILE; docs/ownmesh.md)")
    add_mesh_structure_options(g)
    g.add_argument("--load-set", metavar="NAME", default=None,
                   help="--mesh: node set that carries the force F (N, each --force), spread "
                        "equally over its nodes (default: the response set)")
    g.add_argument("--load-direction", metavar="DX,DY,DZ", default=None,
                   help="--mesh: direction of the force, global axes (default: the "
                        "response set's motion in the mode)")
    g.add_argument("--solver", choices=[*FRF_MESH_SOLVERS, ALL], default=None,
                   help="--mesh: " + "; ".join(f"{k}: {v.help}"
                                               for k, v in FRF_MESH_SOLVERS.items())
                   + f"; {ALL}: both on the same forces and frequencies, the whole joint's "
                   "peaks against the ROM's"
                   + f" (default rom; --harmonics defaults to {DEFAULT_MESH_HARMONICS} "
                   "with --mesh)")
    add_reduced_model_options(g)


def refuse_frf_mesh_options(args: argparse.Namespace) -> None:
    """Without --mesh, the mesh's options given on the command line are refused."""
    bad = [f"--{d.replace('_', '-')}" for d in FRF_MESH_ONLY if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to frf --mesh FILE only; remove "
                             "them")


def check_range(lo: float, hi: float) -> tuple[float, float]:
    """A checked --frequency-range MIN MAX, Hz."""
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise ParameterError(f"--frequency-range must satisfy 0 < MIN < MAX (Hz), got "
                             f"{lo:g} {hi:g}")
    return float(lo), float(hi)


@dataclass(frozen=True)
class FrfStudy(MeshModes):
    """What every solver of ``frf --mesh`` shares: the clamped model, its stuck and free
    modes, the mode studied and the load.

    ``load_nodes`` (mesh node indices) carry F / n each along ``load_direction`` (unit,
    global axes); ``modal_force`` is the stuck mode's modal force per N of F and
    ``response_motion`` the response set's motion along the mode per unit modal coordinate
    (mass-normalised mode; their product over omega^2 is the single-mode receptance)."""

    load_set: str
    load_nodes: np.ndarray = field(repr=False)
    load_direction: np.ndarray = field(repr=False)
    modal_force: float
    response_motion: float


@dataclass(frozen=True)
class ForcedModel:
    """A solver's structure for the forced response: ``structure`` (its output coordinate
    the response set's mean displacement along the mode, mm), ``load`` its force per N of
    --force (N/N), ``mode`` the studied mode's index in it (0-based, by stuck frequency),
    ``odd`` whether its joint forces are odd (the forced response and the backbone's EPMC
    then run on the odd harmonics), a ``label`` and JSON ``extra`` figures."""

    structure: Any
    load: np.ndarray = field(repr=False)
    mode: int
    odd: bool
    label: str
    extra: dict[str, Any]


@dataclass(frozen=True)
class FrfMeshSolver:
    """One ``--solver`` of ``frf --mesh``: what it is, the options only it takes and the
    function that builds its :class:`ForcedModel`."""

    help: str
    options: tuple[str, ...]
    build: Callable[[FrfStudy], ForcedModel]


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


def _load_direction(args: argparse.Namespace, mode: Any) -> np.ndarray:
    if args.load_direction is None:
        return np.asarray(mode.direction, dtype=float)
    try:
        d = np.array([float(v) for v in str(args.load_direction).split(",")])
    except ValueError:
        d = np.zeros(0)
    if d.size != 3 or not np.all(np.isfinite(d)) or float(np.linalg.norm(d)) == 0.0:
        raise ParameterError(f"--load-direction must be three finite numbers DX,DY,DZ, not "
                             f"all 0, got {args.load_direction!r}")
    return np.asarray(d / np.linalg.norm(d))


def _check(args: argparse.Namespace) -> None:
    check_mesh_structure(args, NOT_WITH_FRF_MESH)
    if args.response_set is None:
        raise ParameterError(f"--mesh {args.mesh} needs --response-set NAME (the amplitude is "
                             "its mean displacement along the mode)")
    solver = args.solver or "rom"
    for dest in dict.fromkeys(o for s in FRF_MESH_SOLVERS.values() for o in s.options):
        if given(args, dest) and solver != ALL and dest not in FRF_MESH_SOLVERS[solver].options:
            owners = [n for n, s in FRF_MESH_SOLVERS.items() if dest in s.options]
            raise ParameterError(f"--{dest.replace('_', '-')} applies to --solver "
                                 f"{' or '.join(owners)} only")
    if solver == ALL and (args.plot or args.csv):
        raise ParameterError("--plot and --csv draw and write one solver's curves; give "
                             "--solver rom or joint with them (--solver all compares the "
                             "peaks)")
    if args.rom_modes is not None and args.rom_modes < 1:
        raise ParameterError(f"--rom-modes must be >= 1, got {args.rom_modes}")


def frf_study(args: argparse.Namespace) -> FrfStudy:
    """Check the command line, read the mesh, clamp it, compute the stuck and free modes and
    the load's modal force."""
    _check(args)
    load_set = args.load_set or args.response_set
    model = mesh_model(args, (load_set,) if args.load_set else ())
    number, stuck, free = mesh_modes(args, model)
    mode = stuck.select(number)
    sets = model.mesh.node_sets
    if load_set not in sets:
        raise ParameterError(f"{model.mesh.source}: --load-set must name a node set, got "
                             f"{load_set!r} (node sets: {', '.join(sorted(sets)) or 'none'})")
    nodes = np.asarray(sets[load_set], dtype=np.int64)
    direction = _load_direction(args, mode)
    i = number - 1
    modal_force = float(np.mean(stuck.shapes[i, nodes] @ direction))
    peak = float(np.max(np.linalg.norm(stuck.shapes[i], axis=1)))
    if abs(modal_force) <= 1e-6 * peak:
        along = ", ".join(f"{v:.3g}" for v in direction)
        raise ParameterError(f"the load on {load_set!r} along ({along}) does not excite mode "
                             f"{number} ({mode.label}); choose another --load-set or "
                             "--load-direction")
    return FrfStudy(args=args, model=model, stuck=stuck, free=free, number=number,
                    load_set=load_set, load_nodes=nodes, load_direction=direction,
                    modal_force=modal_force,
                    response_motion=float(np.linalg.norm(stuck.response_motion[i])))


def _rom(study: FrfStudy) -> ForcedModel:
    """The contact-node ROM (:func:`microslip.fe.builtin.reduce.build_rom`), its load F d .
    mean(T_node) over the load set's nodes (T the Craig-Bampton basis)."""
    from ..fe.builtin.reduce import build_rom, rom_structure

    args, mode = study.args, study.mode
    modes = args.rom_modes or DEFAULT_ROM_MODES
    rom = build_rom(study.model, args.density, modes=modes, response_set=args.response_set)
    output = mode.direction @ rom.output
    rows = rom.output if study.load_set == args.response_set else _load_rows(study, rom, modes)
    return ForcedModel(
        structure=rom_structure(rom, output), load=np.asarray(study.load_direction @ rows),
        mode=study.number - 1, odd=rom.per_node == 2,
        label=f"harmonic balance on the contact-node ROM ({rom.dofs} DOF, "
              f"{len(rom.slip_force)} contact nodes)",
        extra={"rom": {"dofs": rom.dofs, "fixed_interface_modes": modes,
                       "contact_nodes": len(rom.slip_force),
                       "stuck_frequencies_Hz": [float(f) for f in rom.stuck_frequencies(
                           len(study.stuck.frequencies_Hz))]}})


def _load_rows(study: FrfStudy, rom: Any, modes: int) -> np.ndarray:
    """The load set's mean displacement rows (3, n_rom) on ``rom``'s coordinates.

    :func:`~microslip.fe.builtin.reduce.build_rom` gives the rows of one set, so the ROM is
    built again with the load set as its response set; the fixed-interface modes are unique
    up to sign, so each modal coordinate's sign is aligned on the first build's mass
    coupling, and the two builds' matrices must then agree to 1e-8."""
    from ..fe.builtin.reduce import build_rom

    other = build_rom(study.model, study.args.density, modes=modes,
                      response_set=study.load_set)
    nb = rom.boundary.size
    sign = np.ones(rom.dofs)
    coupling = np.einsum("ij,ij->j", rom.mass[:nb, nb:], other.mass[:nb, nb:])
    sign[nb:] = np.where(coupling < 0.0, -1.0, 1.0)
    flipped = sign[:, None] * other.mass * sign[None, :]
    if not (np.allclose(flipped, rom.mass, rtol=0.0, atol=1e-8 * np.abs(rom.mass).max())
            and np.allclose(other.stiffness, rom.stiffness, rtol=1e-8, atol=0.0)):
        raise ParameterError("the reduced model's fixed-interface modes differ between two "
                             "builds (repeated frequencies); load the response set (leave "
                             "out --load-set)")
    return np.asarray(other.output * sign[None, :])


#: What ``frf --mesh ... --solver`` builds. The whole-joint model (fe.builtin.wholejoint,
#: a function returning a dynamics Structure) is one more line here: its ForcedModel needs
#: the Structure with its output set to the response set's motion along the mode, its load
#: per N (the load set's force on its coordinates), the mode's index in it and odd=True for
#: an Iwan joint, e.g. ``"joint": FrfMeshSolver("harmonic balance on the whole-joint model
#: ...", (), _joint)``.
def _joint(study: FrfStudy) -> ForcedModel:
    """The whole-joint model (:func:`microslip.fe.builtin.wholejoint.build_whole_joint`) on
    the contact-node ROM: its load is the ROM's carried through the interface reduction T
    (T^T f), its mode the stuck one nearest the full FE's."""
    from ..fe.builtin.reduce import build_rom
    from ..fe.builtin.wholejoint import build_whole_joint

    args, mode = study.args, study.mode
    modes = args.rom_modes or DEFAULT_ROM_MODES
    rom = build_rom(study.model, args.density, modes=modes, response_set=args.response_set)
    rows = rom.output if study.load_set == args.response_set else _load_rows(study, rom, modes)
    joint = build_whole_joint(rom, study.model, mode, mode.direction @ rom.output,
                              backbone=args.backbone or "fe")
    index = joint.mode_index(mode.frequency_Hz)
    stuck = float(joint.stuck_frequencies()[index])
    return ForcedModel(
        structure=joint.structure,
        load=np.asarray(study.load_direction @ rows @ joint.transform), mode=index, odd=True,
        label=f"harmonic balance on the whole-joint model ({joint.structure.dofs} DOF; stuck "
              f"{stuck:.6g} Hz, {100 * (stuck / mode.frequency_Hz - 1):+.2f} % against the "
              "full FE)",
        extra={"joint": {**joint.backbone.summary(), "torsion": joint.torsion,
                         "stuck_frequency_Hz": stuck}})


FRF_MESH_SOLVERS: dict[str, FrfMeshSolver] = {
    "rom": FrfMeshSolver("harmonic balance on the Craig-Bampton model that keeps every "
                         "contact node with the FE's own contact law (--rom-modes "
                         "fixed-interface modes)", ("rom_modes",), _rom),
    "joint": FrfMeshSolver("harmonic balance on the whole-joint model: the interface rigid "
                           "in its plane, one joint whose backbone is the FE's first loading "
                           "by the mode (--backbone)", ("rom_modes", "backbone"), _joint),
}


def _curve_json(c: Any, study: FrfStudy) -> dict[str, Any]:
    inside = bool(c.frequency[0] < c.peak_frequency < c.frequency[-1])
    zeta = (equivalent_damping(c.force, study.modal_force, study.response_motion,
                               c.peak_frequency, c.peak_amplitude) if inside else None)
    return {"force_N": c.force, "frequency_Hz": c.frequency, "amplitude_mm": c.amplitude,
            "peak_amplitude_mm": c.peak_amplitude, "peak_frequency_Hz": c.peak_frequency,
            "damping_ratio": zeta, "points": int(c.frequency.size), "success": c.success,
            "message": c.message}


def run_frf_mesh(args: argparse.Namespace, levels: list[float]) -> int:
    """``frf --mesh``: one curve per force level (N, checked by the caller)."""
    from ..dynamics.response import frequency_response
    from ..io import check_writable, write_csv
    from ..progress import progress
    from .structure import balance_from_args, harmonic_control

    check_plot(args.plot)
    if args.csv:
        check_writable(args.csv)
    study = frf_study(args)
    if args.harmonics == "auto":
        raise ParameterError("--harmonics auto is not available with frf --mesh (each level "
                             "a whole continuation on the ROM); give a number, default "
                             f"{DEFAULT_MESH_HARMONICS}")
    if args.harmonics is None:
        args.harmonics = DEFAULT_MESH_HARMONICS
    harmonic_control(args, auto=False)  # refuses --harmonic-tolerance with fixed harmonics
    harmonics, samples = balance_from_args(args)
    stuck_hz = float(study.stuck.frequencies_Hz[study.number - 1])
    frange = (check_range(*args.frequency_range) if args.frequency_range is not None
              else (MESH_RANGE[0] * stuck_hz, MESH_RANGE[1] * stuck_hz))
    solver = args.solver or "rom"
    if solver == ALL:
        runs = {}
        for name, each in FRF_MESH_SOLVERS.items():
            forced = each.build(study)
            runs[name] = (forced, [
                frequency_response(forced.structure, f, forced.load, frange, harmonics,
                                   samples, args.step, odd=forced.odd)
                for f in progress(levels, desc=f"frf {name}", total=len(levels))])
        return _print_all(args, study, runs, harmonics, samples, frange)
    forced = FRF_MESH_SOLVERS[solver].build(study)
    curves = [frequency_response(forced.structure, f, forced.load, frange, harmonics, samples,
                                 args.step, odd=forced.odd)
              for f in progress(levels, desc="frf", total=len(levels))]
    out = {"mesh": args.mesh, "solver": solver, "mode": study.number,
           "label": study.mode.label, "density_kg_m3": args.density,
           "linear_frequencies_Hz": [float(f) for f in study.stuck.frequencies_Hz],
           "free_frequencies_Hz": [float(f) for f in study.free.frequencies_Hz],
           "response_set": args.response_set,
           "response_direction": [float(v) for v in study.mode.direction],
           "load": {"set": study.load_set, "nodes": int(study.load_nodes.size),
                    "direction": [float(v) for v in study.load_direction]},
           "harmonics": harmonics, "samples": samples, "frequency_range_Hz": list(frange),
           **forced.extra, "curves": [_curve_json(c, study) for c in curves],
           "damping_ratio_definition": DAMPING_DEFINITION, "warnings": _warnings(curves)}
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.csv:
        write_csv(args.csv, {
            "force_N": np.concatenate([np.full(c.frequency.size, c.force) for c in curves]),
            "frequency_Hz": np.concatenate([c.frequency for c in curves]),
            "amplitude_mm": np.concatenate([c.amplitude for c in curves])})
    if args.plot:
        _plot(forced, curves, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(f"mesh {args.mesh}: mode {study.number} ({out['label']}), stuck {stuck_hz:.6g} Hz, "
          f"free {out['free_frequencies_Hz'][study.number - 1]:.6g} Hz; {forced.label}, "
          f"{harmonics} harmonic(s); load on {study.load_set!r}, "
          f"{frange[0]:.6g} to {frange[1]:.6g} Hz")
    print(f"{'force (N)':>12} {'peak a (mm)':>14} {'peak f (Hz)':>14} {'zeta (-)':>12} "
          f"{'points':>7}")
    for c in out["curves"]:
        zeta = "n/a" if c["damping_ratio"] is None else f"{c['damping_ratio']:.5g}"
        print(f"{c['force_N']:12.6g} {c['peak_amplitude_mm']:14.7g} "
              f"{c['peak_frequency_Hz']:14.8g} {zeta:>12} {c['points']:7d}")
    return 0


#: ``--solver`` that runs every solver of :data:`FRF_MESH_SOLVERS` on the same forces.
ALL = "all"
#: The solver the others are judged against in ``--solver all`` (no dynamic full FE exists:
#: the contact-node ROM is the reference, modal --mesh --solver all checks it against the
#: full FE's QSMA).
REFERENCE = "rom"


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


def _print_all(args: argparse.Namespace, study: FrfStudy,
               runs: dict[str, tuple[ForcedModel, list[Any]]], harmonics: int, samples: int,
               frange: tuple[float, float]) -> int:
    """``frf --mesh --solver all``: every solver's curves on the same forces and range, and
    each one's peaks against the ROM's."""
    solvers = {name: {**forced.extra, "label": forced.label,
                      "curves": [_curve_json(c, study) for c in curves],
                      "warnings": _warnings(curves)}
               for name, (forced, curves) in runs.items()}
    ref = solvers[REFERENCE]["curves"]
    comparison = {name: [peak_comparison(r, o) for r, o in zip(ref, s["curves"], strict=True)]
                  for name, s in solvers.items() if name != REFERENCE}
    out = {"mesh": args.mesh, "solver": ALL, "mode": study.number, "label": study.mode.label,
           "density_kg_m3": args.density,
           "linear_frequencies_Hz": [float(f) for f in study.stuck.frequencies_Hz],
           "free_frequencies_Hz": [float(f) for f in study.free.frequencies_Hz],
           "response_set": args.response_set,
           "load": {"set": study.load_set, "nodes": int(study.load_nodes.size),
                    "direction": [float(v) for v in study.load_direction]},
           "harmonics": harmonics, "samples": samples, "frequency_range_Hz": list(frange),
           "solvers": solvers, "reference": REFERENCE, "comparison": comparison,
           "damping_ratio_definition": DAMPING_DEFINITION,
           "warnings": [f"{n}: {w}" for n, s in solvers.items() for w in s["warnings"]]}
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.json:
        print_json(out)
        return 0
    print(f"mesh {args.mesh}: mode {study.number} ({out['label']}); load on "
          f"{study.load_set!r}, {frange[0]:.6g} to {frange[1]:.6g} Hz, {harmonics} harmonic(s)")
    print(f"{'solver':>8} {'force (N)':>10} {'peak a (mm)':>13} {'peak f (Hz)':>13} "
          f"{'zeta (-)':>10}")
    for name, s in solvers.items():
        for c in s["curves"]:
            zeta = "n/a" if c["damping_ratio"] is None else f"{c['damping_ratio']:.5g}"
            print(f"{name:>8} {c['force_N']:10.6g} {c['peak_amplitude_mm']:13.6g} "
                  f"{c['peak_frequency_Hz']:13.7g} {zeta:>10}")
    for name, rows in comparison.items():
        for r in rows:
            parts = [f"{label} {100 * r[key]:+.2g} %" for key, label in (
                ("peak_amplitude_difference", "peak amplitude"),
                ("peak_frequency_difference", "peak frequency"),
                ("damping_ratio_difference", "damping ratio")) if r[key] is not None]
            print(f"  {name} against {REFERENCE} at {r['force_N']:g} N: {', '.join(parts)}")
    return 0


def _warnings(curves: list[Any]) -> list[str]:
    out = []
    for c in curves:
        if not c.success:
            out.append(f"curve at {c.force:g} N stopped early: {c.message}")
        if not c.frequency[0] < c.peak_frequency < c.frequency[-1]:
            out.append(f"curve at {c.force:g} N: the largest amplitude is at an end of the "
                       "frequency range, not a peak (no damping ratio); widen "
                       "--frequency-range")
    return out


def _plot(forced: ForcedModel, curves: list[Any], path: str) -> None:
    """The curves with the structure's backbone (EPMC up to 1.05 times the highest peak)."""
    from ..dynamics.modal import epmc
    from ..dynamics.modal_odd import epmc_odd
    from ..plot.dynamics import plot_frequency_response

    top = max(float(c.amplitude.max()) for c in curves)
    method = epmc_odd if forced.odd else epmc
    backbone = method(forced.structure, np.geomspace(top * 1e-2, top * 1.05, 20),
                      curves[0].harmonics, curves[0].samples, forced.mode)
    plot_frequency_response(curves, backbone, [[] for _ in curves], path)
