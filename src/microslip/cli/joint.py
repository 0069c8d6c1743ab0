"""``microslip joint``: a joint's stiffness and damping versus vibration amplitude.

Also the joint options every dynamics command shares (:func:`add_joint_options`,
:func:`joint_from_args`): ``--joint jenkins|iwan|tip|centre`` and its parameters.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np

from ..case.table import add_option
from ..dynamics.describing import (
    DEFAULT_SAMPLES,
    DescribingFunction,
    amplitude_for_force,
    describing_function,
)
from ..dynamics.distributions import DEFAULT_ELEMENTS
from ..dynamics.operators import IwanOperator
from ..errors import ParameterError
from ..jointspec import JOINT_USES, JointSpec, joint_spec, series_stiffness
from ..meshdynamics.spec import joint_operator
from ..models import MODELS
from ..params import ClampParams
from .common import add_model_options, add_params, model_options, params_from_args

__all__ = ["JOINTS", "add_joint_options", "add_parser", "clamp_from_args", "describe_joint",
           "elements_from_args", "joint_from_args", "run", "spec_from_args"]

def clamp_from_args(args: argparse.Namespace) -> tuple[ClampParams, float, float | None]:
    """The clamp of a tip or centre joint, its series spring (N/mm) and the stick slope it
    comes from (N/mm^3; None if --joint-stiffness is given)."""
    params, stiffness, slope = _clamp_args(args)
    if stiffness is None:
        assert slope is not None  # exactly one of the two (checked)
        return params, series_stiffness(params, slope), slope
    return params, stiffness, None


def _clamp_args(args: argparse.Namespace) -> tuple[ClampParams, float | None, float | None]:
    """The clamp of a tip or centre joint and --joint-stiffness or --stick-slope (the
    other None), checked."""
    params, _ = params_from_args(args, fallback_amplitude=1.0)
    if args.amplitude is not None:
        raise ParameterError("--amplitude (a load amplitude) does not apply to a joint; give "
                             "--amplitude-range or --force-range")
    if (args.joint_stiffness is None) == (args.stick_slope is None):
        raise ParameterError(
            f"the {args.joint} joint needs exactly one of --joint-stiffness N/MM (a series "
            "spring) or --stick-slope N/MM3 (series spring = stick slope x width x length): "
            "a bar on a rigid Coulomb foundation has no finite stiffness at zero "
            "displacement (F ~ sqrt(d))")
    if args.stick_slope is not None:
        return params, None, _positive(args.stick_slope, "--stick-slope", "N/mm^3")
    return params, args.joint_stiffness, None


#: Joint option dest -> the key of a ``[[joint]]`` table (:class:`JointSpec` values).
_KEYS = {"joint_stiffness": "stiffness", "slip_force": "slip_force", "chi": "chi",
         "beta": "beta", "elements": "elements"}

#: Joint name -> the joint options it uses (the others are refused): those of
#: :data:`~microslip.jointspec.JOINT_USES`, and the stick slope of a tip or centre joint.
JOINTS: dict[str, frozenset[str]] = {
    model: frozenset({dest for dest, key in _KEYS.items() if key in uses}
                     | ({"stick_slope"} if model in MODELS else set()))
    for model, uses in JOINT_USES.items()}

#: Joint option dest -> flag.
_FLAGS = {"joint_stiffness": "--joint-stiffness", "slip_force": "--slip-force", "chi": "--chi",
          "beta": "--beta", "stick_slope": "--stick-slope", "elements": "--elements"}


def add_joint_options(parser: argparse.ArgumentParser, required: bool = True,
                      mode: str | None = None) -> None:
    """``--joint`` and its parameters, with the clamp's options for the tip and centre joints;
    ``required=False`` where another source may give the joint (``modal --mesh``), ``mode``
    the mode of the command the joint belongs to (the clamp's material, friction and force
    serve a mesh as well)."""
    g = parser.add_argument_group("joint (units N, mm, N/mm)")
    add_option(g, "joint", required=required, choices=list(JOINTS), mode=mode,
               **({} if required else {"note": "required but with --mesh"}))
    for name in ("joint_stiffness", "slip_force", "chi", "beta"):
        add_option(g, name, mode=mode)
    add_option(g, "stick_slope", note="tip, centre: series spring = slope x width x length "
               "(instead of --joint-stiffness)")
    add_option(g, "elements", mode=mode)
    before = len(parser._actions)
    add_params(parser, mode=mode)
    add_model_options(parser)
    clamp = []
    for action in parser._actions[before:]:
        if action.dest == "amplitude":  # the clamp's load amplitude is not a joint option
            action.help = argparse.SUPPRESS
        clamp.append((action.dest, action.default, action.option_strings[0]))
    parser.set_defaults(clamp_options=tuple(clamp))


def spec_from_args(args: argparse.Namespace) -> JointSpec:
    """The joint specification the options describe (as a ``[[joint]]`` table gives it);
    options of another joint are refused."""
    if getattr(args, "joint", None) is None:
        raise ParameterError(f"give --joint {' | '.join(JOINTS)}")
    uses = JOINTS[args.joint]
    # with --case, a value the case file gives but this joint does not use is not an error
    # (the case describes the clamp for every command); only options given here are
    given: frozenset[str] = getattr(args, "given_options", frozenset())
    from_case = getattr(args, "case", None) is not None and hasattr(args, "given_options")
    extra = [flag for dest, flag in _FLAGS.items()
             if dest not in uses and getattr(args, dest, None) is not None
             and (not from_case or dest in given)]
    if args.joint not in MODELS and getattr(args, "case", None) is None:
        extra += [flag for dest, default, flag in getattr(args, "clamp_options", ())
                  if getattr(args, dest, default) != default]
    if extra:
        raise ParameterError(f"{', '.join(extra)} not used by --joint {args.joint}")
    values: dict[str, Any] = {}
    clamp, stiffness, slope = None, None, None
    if args.joint in MODELS:
        clamp, stiffness, slope = _clamp_args(args)
    else:
        values = {key: _need(args, dest) for dest, key in _KEYS.items()
                  if dest in uses and dest != "elements"}
    if "elements" in uses:
        values["elements"] = elements_from_args(args)
    return joint_spec(args.joint, values, clamp=clamp, stiffness=stiffness, stick_slope=slope,
                      coupling=getattr(args, "coupling", None),
                      transverse=getattr(args, "transverse", None),
                      pairing=getattr(args, "pairing", None),
                      fe_mesh=getattr(args, "fe_mesh", None))


def joint_from_args(args: argparse.Namespace) -> IwanOperator:
    """The joint operator the options describe (:func:`spec_from_args`, built by the
    dynamics as a case file's joint is)."""
    return joint_operator(spec_from_args(args), model_options(args))


def describe_joint(joint: IwanOperator) -> dict[str, Any]:
    """JSON description of a joint operator (keys carry units)."""
    return {"name": joint.name, "elements": int(joint.stiffness.size),
            "initial_stiffness_N_per_mm": joint.initial_stiffness,
            "macroslip_force_N": joint.slip_force}


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "joint", help="describing function of a joint: stiffness, damping, loss factor",
        description="Equivalent stiffness K_eq, damping D_eq (f_1 = K_eq x + D_eq/w dx/dt), "
        "dissipated energy W_d and loss factor eta = D_eq/K_eq of a joint under harmonic "
        "relative displacement, versus displacement or force amplitude.")
    add_joint_options(p)
    r = p.add_argument_group("amplitudes (one of)")
    add_option(r, "amplitude_range", help="displacement amplitudes, mm (geometric spacing)")
    add_option(r, "force_range")
    add_option(p, "amplitudes")
    add_option(p, "samples", default=DEFAULT_SAMPLES, note="of the quadrature")
    add_option(p, "json")
    add_option(p, "plot", help="write a figure of K_eq, D_eq and eta")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from .common import check_plot, print_json

    check_plot(args.plot)
    joint = joint_from_args(args)
    result = describing_function(joint, _amplitudes(args, joint), args.samples)
    out = result_json(joint, result)
    if args.plot:
        from ..plot.dynamics import plot_describing_function

        plot_describing_function(result, args.plot)
    if args.json:
        print_json(out)
        return 0
    print(f"joint {joint.name}: {joint.stiffness.size} Jenkins element(s), initial stiffness "
          f"{joint.initial_stiffness:.6g} N/mm, macroslip force {joint.slip_force:.6g} N")
    print(f"{'A (mm)':>12} {'F (N)':>12} {'K_eq (N/mm)':>13} {'D_eq (N/mm)':>13} "
          f"{'W_d (N·mm)':>12} {'eta (-)':>10}")
    for row in zip(result.amplitude, result.force, result.stiffness, result.damping,
                   result.dissipated_energy, result.loss_factor, strict=True):
        print("{:12.5g} {:12.5g} {:13.6g} {:13.6g} {:12.5g} {:10.5g}".format(*row))
    return 0


def result_json(joint: IwanOperator, result: DescribingFunction) -> dict[str, Any]:
    return {
        "joint": describe_joint(joint),
        "units": {"displacement": "mm", "force": "N", "stiffness": "N/mm", "energy": "N·mm"},
        "samples": result.samples,
        "amplitude_mm": result.amplitude,
        "force_N": result.force,
        "stiffness_N_per_mm": result.stiffness,
        "damping_N_per_mm": result.damping,
        "dissipated_energy_Nmm": result.dissipated_energy,
        "loss_factor": result.loss_factor,
    }


def _amplitudes(args: argparse.Namespace, joint: IwanOperator) -> np.ndarray:
    n = args.amplitudes
    if not 1 <= n <= 100_000:
        raise ParameterError(f"--amplitudes must be in [1, 100000], got {n}")
    if (args.amplitude_range is None) == (args.force_range is None):
        raise ParameterError("give exactly one of --amplitude-range MIN MAX (mm) or "
                             "--force-range MIN MAX (N)")
    if args.amplitude_range is not None:
        lo, hi = (_positive(v, "--amplitude-range", "mm") for v in args.amplitude_range)
        return _spaced(lo, hi, n, "--amplitude-range")
    lo, hi = (_positive(v, "--force-range", "N") for v in args.force_range)
    return amplitude_for_force(joint, _spaced(lo, hi, n, "--force-range"))


def _spaced(lo: float, hi: float, n: int, flag: str) -> np.ndarray:
    if lo > hi:
        raise ParameterError(f"{flag} must have MIN <= MAX, got {lo:g} > {hi:g}")
    return np.geomspace(lo, hi, n) if n > 1 else np.array([lo])


def _positive(value: float, flag: str, unit: str) -> float:
    if not (math.isfinite(value) and value > 0.0):
        raise ParameterError(f"{flag} must be finite and > 0 {unit}, got {value!r}")
    return float(value)


def _need(args: argparse.Namespace, dest: str) -> float:
    value = getattr(args, dest)
    if value is None:
        raise ParameterError(f"--joint {args.joint} needs {_FLAGS[dest]}")
    return float(value)


def elements_from_args(args: argparse.Namespace) -> int:
    """--elements, checked (default :data:`DEFAULT_ELEMENTS`)."""
    n = DEFAULT_ELEMENTS if args.elements is None else args.elements
    if not 2 <= n <= 100_000:
        raise ParameterError(f"--elements must be in [2, 100000], got {n}")
    return int(n)
