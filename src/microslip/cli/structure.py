"""The structure of ``microslip modal`` and ``microslip frf``: one mode (``--frequency``,
``--modal-mass``, ...) or a structure file with its joints (``--structure``, ``--joint-dof``,
``--mode``, ``--coupling``, a case file's ``[[joint]]`` tables), the options of harmonic
balance, and their JSON description.

Shared by both commands (and :mod:`.across`'s warnings need the joints' connectivity), so they
live here rather than inside one command.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np

from ..case.options import add_case_option
from ..case.table import MAX_MODE, MODE_STRUCTURE, add_option
from ..conventions import CLAMP_MODELS
from ..dynamics.assemble import (
    PlacedJoint,
    describe_matrices,
    from_joints,
    from_matrices,
    modal_output,
    with_output,
)
from ..dynamics.files import MatrixFile, check_joint_dofs, read_structure
from ..dynamics.harmonics import DEFAULT_TOLERANCE, HarmonicControl
from ..dynamics.hb import DEFAULT_HARMONICS, DEFAULT_HB_SAMPLES, check_balance
from ..dynamics.modal import ModalCurve
from ..dynamics.operators2d import PAIRINGS
from ..dynamics.operators3d import Contact3D
from ..dynamics.structure import Structure, free_frequency, one_mode
from ..errors import ParameterError
from .across import (
    across_from_args,
    across_joint,
    add_across_options,
    describe_across,
)
from .common import flagged
from .joint import add_joint_options, describe_joint, joint_from_args

__all__ = [
    "ACROSS_WARNING",
    "DEFAULT_HARMONICS",
    "across_warnings",
    "add_balance_options",
    "add_structure_options",
    "balance_from_args",
    "balance_json",
    "balance_text",
    "connectivity_from_args",
    "describe_contacts",
    "describe_structure",
    "harmonic_control",
    "headline",
    "mode_from_args",
    "placed_joints",
    "structure_from_args",
]

#: The warning for a two-directional tip or centre joint that is its own 1-D model across
#: (docs/dynamics.md, "The reduced bar against the FE").
ACROSS_WARNING = (
    "{who}: the {model} model is also the joint across (its second direction); a clamped "
    "bar loaded across bends in its plane, which no 1-D model describes (on the Table 1 bar "
    "such joints dissipate 53-79 % more than the coupled FE at R = 1, docs/dynamics.md): "
    "give {fix} to take the FE's first loading across")


#: The mode of ``modal`` and ``frf`` that a mesh of the user's own replaces: one mode, a
#: structure file, their joint and the box's geometry (:func:`add_structure_options`; with
#: ``--mesh`` these options are refused, :func:`~.meshstructure.check_mesh_structure`).
NOT_MESH = MODE_STRUCTURE


def add_structure_options(parser: argparse.ArgumentParser) -> None:
    """One mode (``--frequency`` or ``--stuck-frequency``, ``--modal-mass``, ``--damping-ratio``,
    ``--participation``) or ``--structure FILE`` with ``--joint-dof``, ``--mode``,
    ``--coupling`` and the joint across (``--transverse``, ``--pairing``, ``--fe-mesh``);
    and the joint's options."""
    g = parser.add_argument_group("structure: one mode (units Hz, kg)")
    given = g.add_mutually_exclusive_group()
    add_option(given, "frequency", mode=NOT_MESH)
    add_option(given, "stuck_frequency", mode=NOT_MESH)
    add_option(g, "modal_mass", mode=NOT_MESH)
    add_option(g, "damping_ratio", note="default 0; with --mesh FILE: a structural (modal) "
               "damping ratio given to every stuck mode of every model (the full FE's QSMA "
               "adds it to the friction's)")
    add_option(g, "participation", note="default 1", mode=NOT_MESH)
    f = parser.add_argument_group("structure: matrices from a file (SI: kg, N/m, N s/m)")
    add_option(f, "structure", note="see docs/dynamics.md", mode=NOT_MESH)
    add_option(f, "joint_dof", mode=NOT_MESH)
    add_option(f, "mode", note="default 1; with --mesh FILE the mode whose damping is studied")
    add_option(f, "coupling", note="default circular", mode=NOT_MESH)
    add_across_options(f, NOT_MESH)
    add_joint_options(parser, required=False, mode=NOT_MESH)
    add_case_option(parser, "a case file with [structure] file and [[joint]] tables: several "
                    "joints, each with its own model; or a clamp for --joint tip|centre; or "
                    "a [mesh] of your own part (docs/casefile.md); options given here win")


def structure_from_args(args: argparse.Namespace) -> Structure:
    """The structure with its joints that the options describe; for a file structure the
    output is the modal coordinate of ``--mode``."""
    if getattr(args, "case_joints", ()) and args.structure is None:
        raise ParameterError(f"case {args.case} has [[joint]] tables but no structure: give "
                             "[structure] file = \"FILE.npz\" in it or --structure FILE")
    if args.structure is None:
        _refuse(args, ("joint_dof", "--joint-dof"), ("mode", "--mode"),
                ("coupling", "--coupling"), ("excitation", "--excitation"),
                why="a one-mode structure (they need --structure)")
        across_from_args(args, None)
        stuck = getattr(args, "stuck_frequency", None)
        if (args.frequency is None and stuck is None) or args.modal_mass is None:
            raise ParameterError("give --frequency HZ (or --stuck-frequency HZ) and "
                                 "--modal-mass KG (one mode) or --structure FILE")
        joint = joint_from_args(args)
        p = 1.0 if args.participation is None else args.participation
        f = args.frequency if stuck is None else free_frequency(stuck, args.modal_mass, joint, p)
        return one_mode(f, args.modal_mass,
                        0.0 if args.damping_ratio is None else args.damping_ratio, joint, p)
    _refuse(args, ("frequency", "--frequency"), ("stuck_frequency", "--stuck-frequency"),
            ("modal_mass", "--modal-mass"),
            ("damping_ratio", "--damping-ratio"), ("participation", "--participation"),
            why="--structure (the file's matrices give them)")
    matrices = read_structure(args.structure)
    if getattr(args, "case_joints", ()):
        structure = from_joints(matrices, placed_joints(args, matrices))
        return with_output(structure, modal_output(structure, mode_from_args(args)))
    joints = connectivity_from_args(args, matrices)
    if args.coupling is not None and not np.any(np.asarray(joints).shape[1:2] == (2,)):
        raise ParameterError("--coupling applies to two-directional joints only (give "
                             "--joint-dof twice or a (n, 2, 2) joints array)")
    across = across_from_args(args, np.asarray(joints))
    own = (matrices.laws is not None or matrices.contacts is not None) and \
        np.array_equal(np.asarray(joints), matrices.joints)
    if own:
        _refuse_own_law(args)
    given = None if own else joint_from_args(args)
    structure = from_matrices(matrices, np.asarray(joints), given,
                              args.coupling or "circular", across, args.pairing)
    return with_output(structure, modal_output(structure, mode_from_args(args)))


#: Options of the joint that a structure file's own joint laws replace (refused with them).
JOINT_LAW_OPTIONS = ("joint", "joint_stiffness", "slip_force", "chi", "beta", "elements",
                     "stick_slope", "transverse", "pairing", "fe_mesh", "coupling")


def _refuse_own_law(args: argparse.Namespace) -> None:
    """The joints of a structure file that carry their own law (``reduce``'s ROM: a circular
    Jenkins element or a 3-D contact element per contact node) take no joint, no coupling and
    no joint across: such an option would change nothing, so it is refused in one line."""
    given: frozenset[str] = getattr(args, "given_options", frozenset())
    bad = [f"--{d.replace('_', '-')}" for d in JOINT_LAW_OPTIONS if d in given]
    if not bad and args.coupling is not None:
        bad = [f"[structure] coupling of case {args.case}"]
    if bad:
        raise ParameterError(f"{', '.join(bad)} changes nothing here: the joints of "
                             f"{args.structure} carry their own law (each contact node's "
                             "circular Coulomb element); remove it")


def placed_joints(args: argparse.Namespace, matrices: MatrixFile) -> list[PlacedJoint]:
    """The joints of the case file's [[joint]] tables, placed on ``matrices``; a joint's own
    coupling wins over --coupling (or [structure] coupling), which wins over circular."""
    from ..meshdynamics.spec import joint_operator, transverse_operator
    from .common import model_options

    specs = args.case_joints
    if args.coupling is not None and all(s.directions == 1 for s in specs):
        raise ParameterError("--coupling ([structure] coupling) applies to two-directional "
                             "joints only; the case's joints all have one direction")
    out = []
    for spec in specs:
        where = f"case {args.case}: joint {spec.number}"
        dofs = check_joint_dofs(f"{where}: dofs", np.array(spec.dofs, dtype=np.int64),
                                matrices.mass.shape[0])
        coupling = spec.coupling or args.coupling or "circular"
        if spec.pairing is not None and coupling == "decoupled":
            raise ParameterError(f"{where}: joint.pairing ({' | '.join(PAIRINGS)}) applies "
                                 "to coupling circular only, and this joint's coupling is "
                                 "decoupled ([structure] coupling or --coupling): its "
                                 "directions are independent")
        opts = model_options(args)
        out.append(PlacedJoint(dofs, joint_operator(spec, opts), coupling,
                               transverse_operator(spec, opts), spec.pairing))
    return out


def mode_from_args(args: argparse.Namespace) -> int:
    """The followed mode, 0-based (``--mode`` is 1-based, in the option table's range)."""
    mode = 1 if getattr(args, "mode", None) is None else args.mode
    if not 1 <= mode <= MAX_MODE:
        raise ParameterError(f"--mode must be in [1, {MAX_MODE}], got {mode}")
    return int(mode) - 1


def connectivity_from_args(args: argparse.Namespace, matrices: MatrixFile
                           ) -> np.ndarray | list[np.ndarray]:
    """The joints' [i, j] per direction ((n, d, 2), or one (d, 2) array per joint of a case
    file): the case's [[joint]] tables, --joint-dof, else the file's."""
    if getattr(args, "case_joints", ()):
        return [np.array(spec.dofs, dtype=np.int64) for spec in args.case_joints]
    if args.joint_dof is None:
        return np.asarray(matrices.joints)
    rows = args.joint_dof
    if len(rows) > 2 or any(len(r) > 2 for r in rows):
        raise ParameterError("--joint-dof takes I or I J, at most twice (two directions), "
                             f"got {rows}")
    pairs = [[r[0], r[1] if len(r) == 2 else -1] for r in rows]
    return check_joint_dofs("--joint-dof", np.array([pairs], dtype=np.int64),
                            matrices.mass.shape[0])


def _refuse(args: argparse.Namespace, *flags: tuple[str, str], why: str) -> None:
    given = [flag for dest, flag in flags if getattr(args, dest, None) is not None]
    if given:
        raise ParameterError(f"{', '.join(given)} not used with {why}")


def describe_structure(structure: Structure, args: argparse.Namespace | None = None
                       ) -> dict[str, Any]:
    """JSON description of the structure and its joint (keys carry units)."""
    if args is not None and args.structure is not None:
        out = {"file": args.structure, "mode": mode_from_args(args) + 1,
               **describe_matrices(structure)}
        specs = getattr(args, "case_joints", ())
        if not specs and getattr(args, "transverse", None) is not None:
            return {**out, "joint": {**describe_joint(joint_from_args(args)), **describe_across(
                args.transverse, args.pairing, args.coupling or "circular",
                across_joint(args), args.fe_mesh)}}
        if not specs and isinstance(structure.joints[0].operator, Contact3D):
            return {**out, "joint": describe_contacts(structure)}
        if not specs:
            return {**out, "joint": describe_joint(structure.joints[0].operator)}  # type: ignore[arg-type]
        from ..meshdynamics.spec import joint_operator, transverse_operator
        from .common import model_options

        opts = model_options(args)
        return {**out, "case_joints": [
            {"number": s.number, "model": s.model, "dofs": [list(d) for d in s.dofs],
             "coupling": (s.coupling or args.coupling or "circular") if s.directions == 2
             else None, **describe_joint(joint_operator(s, opts)),
             **describe_across(s.transverse, s.pairing, s.coupling or args.coupling
                               or "circular", transverse_operator(s, opts), s.fe_mesh)}
            for s in specs]}
    m = float(structure.mass[0, 0])
    k = float(structure.stiffness[0, 0])
    link = structure.joints[0]
    return {"modal_mass_kg": m,
            "frequency_Hz": math.sqrt(k / m) / (2.0 * math.pi),
            "damping_ratio": float(structure.damping[0, 0]) / (2.0 * math.sqrt(k * m)),
            "participation": float(link.participation[0]),
            "stuck_frequency_Hz": float(structure.linear_frequencies(stuck=True)[0]),
            "joint": describe_joint(link.operator)}  # type: ignore[arg-type]


def describe_contacts(structure: Structure) -> dict[str, Any]:
    """JSON description of a structure file's 3-D contact joints (each its own law)."""
    ops = [link.operator for link in structure.joints if isinstance(link.operator, Contact3D)]
    return {"name": "contact3d", "elements": len(ops),
            "tangential_stiffness_N_per_mm": [op.tangential_stiffness for op in ops],
            "normal_stiffness_N_per_mm": [op.normal_stiffness for op in ops],
            "preload_N": [op.preload for op in ops], "friction": [op.friction for op in ops]}


def add_balance_options(parser: argparse.ArgumentParser, auto: bool = False) -> None:
    """``--harmonics``, ``--harmonic-tolerance`` and ``--samples``; ``auto``: whether the
    command's default is ``--harmonics auto`` (else :data:`DEFAULT_HARMONICS`)."""
    g = parser.add_argument_group("harmonic balance")
    add_option(g, "harmonics", note=f"default {'auto' if auto else DEFAULT_HARMONICS}")
    add_option(g, "harmonic_tolerance", note=f"default {DEFAULT_TOLERANCE:g}")
    add_option(g, "samples", default=None,
               note=f"of the alternating frequency-time scheme with fixed harmonics (default "
                    f"{DEFAULT_HB_SAMPLES}; auto takes 16 (H + 1) rounded up to a power of two)")


def harmonic_control(args: argparse.Namespace, auto: bool = False) -> HarmonicControl | None:
    """The control of ``--harmonics auto`` (or of no --harmonics where ``auto`` is the
    command's default), checked, or None for fixed harmonics (then
    :func:`balance_from_args`). --samples with auto and --harmonic-tolerance with fixed
    harmonics are refused (they would do nothing)."""
    chosen = args.harmonics == "auto" or (args.harmonics is None and auto)
    tol = getattr(args, "harmonic_tolerance", None)
    if not chosen:
        if tol is not None:
            raise ParameterError("--harmonic-tolerance is used by --harmonics auto only; "
                                 f"leave it out with --harmonics {args.harmonics}")
        return None
    if args.samples is not None:
        raise ParameterError("--samples is not used with --harmonics auto (the samples follow "
                             "the harmonics); leave it out or give --harmonics H")
    tol = DEFAULT_TOLERANCE if tol is None else tol
    if not (math.isfinite(tol) and 0.0 < tol < 0.5):
        raise ParameterError(f"--harmonic-tolerance must be in (0, 0.5), got {tol!r}")
    return HarmonicControl(tolerance=float(tol))


def balance_from_args(args: argparse.Namespace) -> tuple[int, int]:
    """(harmonics, samples) of fixed harmonics, checked; --harmonics defaults to
    :data:`DEFAULT_HARMONICS` (also where ``auto`` has no adaptive method: the whole-joint
    model), --samples to the AFT's default."""
    h = DEFAULT_HARMONICS if args.harmonics in (None, "auto") else args.harmonics
    n = DEFAULT_HB_SAMPLES if args.samples is None else args.samples
    with flagged():
        return check_balance(h, n)


def balance_json(curve: ModalCurve, control: HarmonicControl | None) -> dict[str, Any]:
    """The JSON of a modal curve's balance: ``harmonics`` and ``samples`` (numbers when
    fixed; per point with ``harmonic_error_estimate`` and ``harmonic_tolerance`` when
    chosen)."""
    if control is None or curve.point_harmonics is None:
        return {"harmonics": curve.harmonics, "samples": curve.samples}
    assert curve.harmonic_error_estimate is not None
    return {"harmonics": [int(h) for h in curve.point_harmonics],
            "samples": [HarmonicControl.samples(int(h)) for h in curve.point_harmonics],
            "harmonic_error_estimate": [float(e) if math.isfinite(e) else None
                                        for e in curve.harmonic_error_estimate],
            "harmonic_tolerance": control.tolerance}


def balance_text(curve: ModalCurve) -> str:
    """'H harmonic(s), N samples' of fixed harmonics, or 'auto: H1-H2 harmonic(s) (largest
    estimate E %)'."""
    if curve.point_harmonics is None or curve.harmonic_error_estimate is None:
        return f"{curve.harmonics} harmonic(s), {curve.samples} samples"
    lo, hi = int(curve.point_harmonics.min()), int(curve.point_harmonics.max())
    span = f"{lo}" if lo == hi else f"{lo} to {hi}"
    est = curve.harmonic_error_estimate[np.isfinite(curve.harmonic_error_estimate)]
    top = f"{100 * float(est.max()):.3g} %" if est.size else "none"
    return f"harmonics auto: {span} harmonic(s), largest error estimate {top}"


def headline(structure: Structure, mode: int) -> str:
    """'mode F Hz with the joint removed, F Hz stuck'; for a file structure the linear
    modes (stuck and joint-free) on a line before it."""
    free = structure.linear_frequencies(stuck=False)[mode]
    stuck = structure.linear_frequencies(stuck=True)[mode]
    label = "mode" if structure.dofs == 1 else f"{structure.dofs} DOFs, mode {mode + 1}:"
    joints = "the joint" if len(structure.joints) == 1 else "the joints"
    line = f"{label} {free:.6g} Hz with {joints} removed, {stuck:.6g} Hz stuck"
    if structure.dofs == 1:
        return line
    modes = ("linear modes (Hz), stuck: "
             + ", ".join(f"{f:.6g}" for f in structure.linear_frequencies(stuck=True))
             + "; joints removed: "
             + ", ".join(f"{f:.6g}" for f in structure.linear_frequencies(stuck=False)))
    return f"{modes}\n{line}"


def across_warnings(args: argparse.Namespace) -> list[str]:
    """Warnings (sentences) for the two-directional tip or centre joints that are their own
    model across: each [[joint]] table of a case, or the command line's joint where its
    connectivity (``--joint-dof`` or the structure file's) has two directions."""
    specs = getattr(args, "case_joints", ())
    if specs:
        return [ACROSS_WARNING.format(who=f"joint {s.number}", model=s.model,
                                      fix='transverse = "fe"')
                for s in specs if s.directions == 2 and s.model in CLAMP_MODELS
                and s.transverse is None]
    if args.structure is None or args.joint not in CLAMP_MODELS or \
            getattr(args, "transverse", None) is not None:
        return []
    joints = np.asarray(connectivity_from_args(args, read_structure(args.structure)))
    if joints.ndim != 3 or joints.shape[1] != 2:
        return []
    return [ACROSS_WARNING.format(who=f"--joint {args.joint}", model=args.joint,
                                  fix="--transverse fe --stick-slope N/MM3")]
