"""``microslip modal --mesh FILE``: a mode's frequency and damping ratio against amplitude,
on the structure of the user's own mesh.

``--solver fe`` is the truth: quasi-static modal analysis of the full frictional FE
(:func:`microslip.fe.builtin.qsma.qsma`, Lacayo and Allen 2019); the stuck and free linear
modes come first (:func:`microslip.fe.builtin.modes.linear_modes`). This module parses and
prints. Units: Hz, mm, N, kg/m^3.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

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

__all__ = ["MESH_SOLVERS", "add_modal_mesh_options", "run_modal_mesh"]

# The mesh structure's options, checks, model and modes: cli.meshstructure (shared with
# frf --mesh).
#: Options of --mesh only.
MESH_ONLY = ("contact_set", "clamp_set", "normal_contact", "normal_slope", "density",
             "response_set", "solver", "workers", "rom_modes", "backbone")
#: ``--solver`` that runs every solver of :data:`MESH_SOLVERS` (:mod:`.modalcompare`).
ALL = "all"


def add_modal_mesh_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("the structure of your own mesh (--mesh FILE; docs/ownmesh.md)")
    add_mesh_structure_options(g)
    g.add_argument("--solver", choices=[*MESH_SOLVERS, ALL], default=None,
                   help="; ".join(f"{k}: {v.help}" for k, v in MESH_SOLVERS.items())
                   + f"; {ALL}: every one of them side by side, with a verdict on each "
                   "against the full FE (default fe)")
    add_reduced_model_options(g)
    g.add_argument("--workers", type=int, default=None, metavar="N",
                   help="local processes for the amplitudes (independent runs; default 1)")
    g.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="a Dask scheduler (tcp://HOST:8786) to run the amplitudes on")


def _nulls(values: Any) -> list[float | None]:
    """A column for JSON: NaN (an amplitude that failed; its reason is in ``warnings``) as
    null."""
    return [None if v is None or math.isnan(v) else float(v) for v in values]



def refuse_mesh_options(args: argparse.Namespace) -> None:
    """Without --mesh, the mesh's options given on the command line are refused."""
    bad = [f"--{d.replace('_', '-')}" for d in (*MESH_ONLY, "scheduler") if given(args, d)]
    if bad:
        raise ParameterError(f"{', '.join(bad)} {verb(bad)} to modal --mesh FILE only; remove "
                             "them")


def _check(args: argparse.Namespace) -> None:
    check_mesh_structure(args)
    solver = args.solver or "fe"
    for dest in dict.fromkeys(o for s in MESH_SOLVERS.values() for o in s.options):
        if given(args, dest) and solver != ALL and dest not in MESH_SOLVERS[solver].options:
            owners = [n for n, s in MESH_SOLVERS.items() if dest in s.options]
            raise ParameterError(f"--{dest.replace('_', '-')} applies to --solver "
                                 f"{' or '.join(owners)} only")
    if not 1 <= args.amplitudes <= 200:
        raise ParameterError(f"--amplitudes must be in [1, 200] with --mesh, got "
                             f"{args.amplitudes}")


def _grid(args: argparse.Namespace, model: Any, modes: Any, number: int) -> tuple[Any, Any]:
    """The modal forces q and the amplitudes (mm) of the one grid: from first slip to near
    gross sliding, or --amplitude-range; linear through the stuck mode, the response set's
    amplitude is a = q r / omega^2 at modal force q (r its motion per unit modal
    coordinate)."""
    import numpy as np

    from ..fe.builtin.qsma import qsma_amplitudes

    mode = modes.select(number)
    scale = float(np.linalg.norm(modes.response_motion[number - 1])) / (
        2 * math.pi * mode.frequency_Hz) ** 2
    if args.amplitude_range is None:
        forces = qsma_amplitudes(model, mode, args.amplitudes)
        return forces, forces * scale
    lo, hi = args.amplitude_range
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ParameterError(f"--amplitude-range must satisfy 0 < MIN <= MAX (mm), got "
                             f"{lo:g} {hi:g}")
    amplitudes = np.geomspace(lo, hi, args.amplitudes)
    return amplitudes / scale, amplitudes


def mesh_study(args: argparse.Namespace) -> MeshStudy:
    """Check the command line, read the mesh, clamp it, compute the stuck and free modes and
    the amplitude grid: everything the solvers share."""
    _check(args)
    check_plot(args.plot)
    model = mesh_model(args)
    number, stuck, free = mesh_modes(args, model)
    forces, amplitudes = _grid(args, model, stuck, number)
    return MeshStudy(args=args, model=model, stuck=stuck, free=free, number=number,
                     forces=forces, amplitudes=amplitudes)


def study_output(study: MeshStudy, solver: str, curve: MeshCurve) -> dict[str, Any]:
    """The JSON of one solver's curve on the study."""
    args = study.args
    return {"mesh": args.mesh, "solver": solver, "mode": study.number,
            "label": study.mode.label, "density_kg_m3": args.density,
            "linear_frequencies_Hz": [float(f) for f in study.stuck.frequencies_Hz],
            "free_frequencies_Hz": [float(f) for f in study.free.frequencies_Hz],
            "modes": study.stuck.summary(), **curve.values, **curve.extra,
            "warnings": curve.warnings}


def run_modal_mesh(args: argparse.Namespace) -> int:
    """One solver's curve (``--solver all``: :func:`.modalcompare.run_modal_all`, which
    :mod:`.modal` dispatches to)."""
    study = mesh_study(args)
    solver = args.solver or "fe"
    curve = MESH_SOLVERS[solver].run(study)
    out = study_output(study, solver, curve)
    for w in out["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    if args.plot:
        from ..plot.ownmesh import plot_qsma

        plot_qsma(out, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(headline(study, out, curve.label))
    print("\n".join(curve_table(out, curve)))
    return 0


def headline(study: MeshStudy, out: dict[str, Any], what: str) -> str:
    """The first line of the text output: the mesh, the mode, its stuck and free
    frequencies (Hz) and ``what`` was computed."""
    number = study.number
    return (f"mesh {study.args.mesh}: mode {number} ({out['label']}), stuck "
            f"{out['linear_frequencies_Hz'][number - 1]:.6g} Hz, free "
            f"{out['free_frequencies_Hz'][number - 1]:.6g} Hz; {what}")


def curve_table(values: dict[str, Any], curve: MeshCurve) -> list[str]:
    """One solver's rows under its own column headers (units in the headers)."""
    lines = [" ".join(f"{h:>12}" if f.startswith("{:12") else f"{h:>9}"
                      for h, f in curve.columns.values())]
    for row in zip(*(values[k] for k in curve.columns), strict=True):
        if row[0] is None:
            lines.append(f"{'failed':>12} (see the warnings)")
            continue
        lines.append(" ".join(fmt.format(v) for v, (_, fmt)
                              in zip(row, curve.columns.values(), strict=True)))
    return lines


@dataclass(frozen=True)
class MeshStudy(MeshModes):
    """What every solver of ``modal --mesh`` shares: the clamped model, its stuck and free
    modes, the mode studied, and the one amplitude grid.

    ``forces`` are the QSMA's modal forces q; ``amplitudes`` (mm) are the same levels mapped
    through the stuck mode (a = q r / omega^2, r the response set's motion per unit modal
    coordinate), or ``--amplitude-range`` itself: the grid every solver runs on."""

    forces: Any
    amplitudes: Any


@dataclass(frozen=True)
class MeshCurve:
    """One solver's frequency and damping ratio against amplitude, with its own columns
    (``columns``: JSON key -> (table header, format)) and figures (``extra``)."""

    label: str
    columns: dict[str, tuple[str, str]]
    values: dict[str, list[float | None]]
    extra: dict[str, Any]
    warnings: list[str]


@dataclass(frozen=True)
class MeshSolver:
    """One ``--solver`` of ``modal --mesh``: what it is, the options only it takes and the
    function that computes its curve."""

    help: str
    options: tuple[str, ...]
    run: Callable[[MeshStudy], MeshCurve]


BASE_COLUMNS = {"amplitude_mm": ("a (mm)", "{:12.5g}"), "frequency_Hz": ("f (Hz)", "{:12.7g}"),
                "damping_ratio": ("zeta (-)", "{:12.5g}")}


def _fe(study: MeshStudy) -> MeshCurve:
    """Quasi-static modal analysis of the full frictional FE at the grid's modal forces."""
    from ..fe.builtin.qsma import qsma

    args = study.args

    def progress(done: int, total: int, eta: float) -> None:
        if not args.json:
            print(f"\r  amplitude {done}/{total}, about {eta:.0f} s left", end="",
                  file=sys.stderr, flush=True)

    curve = qsma(study.model, study.mode, study.forces, workers=args.workers or 1,
                 scheduler=args.scheduler, progress=progress)
    if not args.json:
        print(file=sys.stderr)
    s = curve.summary()
    columns = {"amplitude_mm": BASE_COLUMNS["amplitude_mm"],
               "frequency_Hz": BASE_COLUMNS["frequency_Hz"],
               "secant_frequency_Hz": ("f_sec (Hz)", "{:12.7g}"),
               "damping_ratio": BASE_COLUMNS["damping_ratio"],
               "slip_fraction": ("slip (-)", "{:9.3f}")}
    values = {k: _nulls(s[k]) for k in (*columns, "dissipated_energy_Nmm")}
    # the slip pattern: the contact nodes in the contact plane (mm), slipped or not per amplitude
    xy = study.model.mesh.nodes[study.model.contact_nodes] @ study.model.rotation.T
    pattern = {"x_mm": xy[:, 0].tolist(), "y_mm": xy[:, 1].tolist(),
               "slipped": [p.node_slipped.tolist() for p in curve.points]}
    return MeshCurve(label="quasi-static modal analysis of the full FE", columns=columns,
                     values=values, extra={"modal_force": s["force"], "slip_pattern": pattern},
                     warnings=list(s["warnings"]))


def _rom(study: MeshStudy) -> MeshCurve:
    """EPMC on the contact-node ROM at the grid's amplitudes."""
    import numpy as np

    from ..dynamics.harmonics import adaptive_epmc, cap_warning
    from ..dynamics.modal import epmc
    from ..dynamics.modal_odd import epmc_odd
    from ..fe.builtin.reduce import build_rom, rom_structure
    from .structure import balance_from_args, balance_json, balance_text, harmonic_control

    args, mode = study.args, study.mode
    control = harmonic_control(args)
    if control is None:
        harmonics, samples = balance_from_args(args)
    modes = args.rom_modes or DEFAULT_ROM_MODES
    rom = build_rom(study.model, args.density, modes=modes, response_set=args.response_set)
    structure = rom_structure(rom, mode.direction @ rom.output)
    odd = rom.per_node != 3  # odd joint forces: odd harmonics only
    if control is not None:
        curve = adaptive_epmc(structure, np.asarray(study.amplitudes), control,
                              study.number - 1, odd=odd)
    else:
        curve = (epmc_odd if odd else epmc)(structure, np.asarray(study.amplitudes),
                                            harmonics, samples, study.number - 1)
    capped = (None if control is None else
              cap_warning(curve.harmonic_error_estimate, curve.harmonics, control))
    count = len(study.stuck.frequencies_Hz)
    return MeshCurve(
        label=f"EPMC on the contact-node ROM ({rom.dofs} DOF, {balance_text(curve)})"
        if control is not None else
        f"EPMC on the contact-node ROM ({rom.dofs} DOF, {curve.harmonics} harmonics)",
        columns=dict(BASE_COLUMNS),
        values={"amplitude_mm": [float(a) for a in curve.amplitude],
                "frequency_Hz": [float(f) for f in curve.frequency],
                "damping_ratio": [float(z) for z in curve.damping_ratio]},
        extra={"rom_frequencies_Hz": [float(f) for f in rom.stuck_frequencies(count)],
               "rom": {"dofs": rom.dofs, "fixed_interface_modes": modes,
                       "contact_nodes": len(rom.slip_force),
                       **balance_json(curve, control)}},
        warnings=[capped] if capped else [])


def _joint(study: MeshStudy) -> MeshCurve:
    """EPMC on the whole-joint model (:mod:`microslip.fe.builtin.wholejoint`) at the grid's
    amplitudes: the ROM reduced to the interface's rigid motion, one joint from the FE's
    first loading."""
    import numpy as np

    from ..fe.builtin.reduce import build_rom
    from ..fe.builtin.wholejoint import build_whole_joint, whole_joint_epmc
    from .structure import balance_from_args

    args, mode = study.args, study.mode
    harmonics, samples = balance_from_args(args)
    modes = args.rom_modes or DEFAULT_ROM_MODES
    rom = build_rom(study.model, args.density, modes=modes, response_set=args.response_set)
    assert rom.output is not None
    joint = build_whole_joint(rom, study.model, mode, mode.direction @ rom.output,
                              backbone=args.backbone or "fe")
    curve, failed = whole_joint_epmc(joint, np.asarray(study.amplitudes), harmonics,
                                     samples, mode.frequency_Hz)
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
        label=f"EPMC on the whole-joint model ({joint.structure.dofs} DOF, "
              f"{curve.harmonics} harmonics; stuck {stuck:.6g} Hz, "
              f"{100 * (stuck / mode.frequency_Hz - 1):+.2f} % against the full FE)",
        columns=dict(BASE_COLUMNS),
        values={"amplitude_mm": _nulls(np.where(np.isnan(curve.frequency), np.nan,
                                                curve.amplitude)),
                "frequency_Hz": _nulls(curve.frequency),
                "damping_ratio": _nulls(curve.damping_ratio)},
        extra={"joint": {**bb.summary(), "torsion": joint.torsion,
                         "rigid_work_share": share,
                         "stuck_frequency_Hz": stuck,
                         "stuck_frequency_error": stuck / mode.frequency_Hz - 1.0,
                         "dofs": joint.structure.dofs, "fixed_interface_modes": modes,
                         "harmonics": curve.harmonics, "samples": curve.samples}},
        warnings=warnings)


#: What ``modal --mesh ... --solver`` computes, each on the same amplitude grid.
MESH_SOLVERS: dict[str, MeshSolver] = {
    "fe": MeshSolver("quasi-static modal analysis of the full frictional FE (the truth)",
                     ("workers", "scheduler"), _fe),
    "rom": MeshSolver("EPMC by harmonic balance on a Craig-Bampton model that keeps every "
                      "contact node with the FE's own contact law (--rom-modes "
                      "fixed-interface modes)", ("harmonics", "rom_modes"), _rom),
    "joint": MeshSolver("EPMC by harmonic balance on the whole-joint model: the contact "
                        "reduced to its rigid motion in its plane, one joint whose backbone "
                        "is the FE's first loading by the mode (or --backbone tip|centre)",
                        ("harmonics", "rom_modes", "backbone"), _joint),
}
