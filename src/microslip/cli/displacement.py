"""``--displacement-amplitude MM``: the force amplitude from a displacement amplitude.

The option of ``loop``, ``fe`` and ``sweep`` (and, with two values, ``planar``); the inversion
itself is :mod:`microslip.displacement`. Given with ``--amplitude`` it is a usage error.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import Any

from ..case.table import OPTIONS, add_option

__all__ = ["DISPLACEMENT_HELP", "add_displacement_option", "check_exclusive"]

#: The shared help of ``--displacement-amplitude`` (the option table's).
DISPLACEMENT_HELP = OPTIONS["displacement_amplitude"].help


def add_displacement_option(parser: Any, help: str | None = None, nargs: Any = None,
                            metavar: Any = None, note: str = "", mode: str | None = None
                            ) -> None:
    """Add ``--displacement-amplitude`` to a parser or argument group (``help``: another
    meaning, ``note``: a sentence of this command after the shared help, ``mode``: the mode
    of the command it belongs to)."""
    add_option(parser, "displacement_amplitude", help=help, note=note, mode=mode,
               **({} if nargs is None else {"nargs": nargs}),
               **({} if metavar is None else {"metavar": metavar}))


def check_exclusive(args: argparse.Namespace, *others: str) -> bool:
    """True if ``--displacement-amplitude`` was given; a usage error if one of the options
    ``others`` (argparse destinations) was given too."""
    from .main import UsageError

    if getattr(args, "displacement_amplitude", None) is None:
        return False
    for dest in others:
        if getattr(args, dest, None) is not None:
            flag = "--" + dest.replace("_", "-")
            raise UsageError(f"argument --displacement-amplitude: not allowed with argument "
                             f"{flag}")
    return True


def displacement_force(args: argparse.Namespace, model: str, params: Any, increments: int,
                       options: Any, contact: Any = None) -> float | None:
    """The force amplitude (N) of ``--displacement-amplitude`` for a 1-D model (on
    ``contact``), or None."""
    if not check_exclusive(args, "amplitude"):
        return None
    from ..displacement import force_for_displacement

    return force_for_displacement(model, params, args.displacement_amplitude, increments,
                                  options, contact)


#: The finite-element inversion stays this far (relative) below the macroslip force.
FE_MARGIN = 1e-3


def fe_displacement_force(args: argparse.Namespace, load: str, params: Any,
                          run: Callable[[float], Any]) -> float | None:
    """The force amplitude (N) at which the FE runs ``run(F0)`` (returning an FELoopResult)
    reach ``--displacement-amplitude``, or None when it was not given.

    A root-find on the force (:func:`microslip.displacement.force_for_fe_displacement`),
    started from the 1-D model of the same load case, up to (1 - FE_MARGIN) mu F_N.
    """
    if not check_exclusive(args, "amplitude"):
        return None
    from ..displacement import force_for_displacement, force_for_fe_displacement
    from ..errors import MicroslipError
    from ..models import MODELS

    model = next(name for name, spec in MODELS.items() if spec.load_case == load)
    upper = (1.0 - FE_MARGIN) * params.macroslip_force
    try:
        guess = force_for_displacement(model, params, args.displacement_amplitude)
    except MicroslipError:  # beyond the 1-D model's range: the FE bar may still reach it
        guess = upper

    def peak(force: float) -> float:
        result = run(force)
        if not result.converged:
            raise MicroslipError(f"the FE run at F0 = {force:.6g} N did not converge while "
                                 "searching the force of --displacement-amplitude")
        return float(result.loop.peak_displacement)

    return force_for_fe_displacement(peak, args.displacement_amplitude, guess, upper)


PLANAR_HELP = ("displacement amplitudes of the tip and centre models, mm (instead of the force "
               "amplitudes or --ratio): each force amplitude is the one whose first loading "
               "reaches its displacement; --solver analytical only")


def planar_displacement_forces(args: argparse.Namespace, increments: int, options: Any,
                               zones: tuple[Any, Any], contact: Any = None
                               ) -> tuple[float, float] | None:
    """(tip, centre) force amplitudes (N) of ``planar --displacement-amplitude TIP CENTRE``
    for the (tip, centre) clamp ``zones`` on ``contact``."""
    if not check_exclusive(args, "tip_amplitude", "centre_amplitude", "ratio"):
        return None
    from ..displacement import force_for_displacement
    from ..errors import ParameterError

    if args.solver != "analytical":
        raise ParameterError(f"--displacement-amplitude applies to --solver analytical, not "
                             f"{args.solver}; give --tip-amplitude N and --centre-amplitude N")
    tip, centre = args.displacement_amplitude
    return (force_for_displacement("tip", zones[0], tip, increments, options, contact),
            force_for_displacement("centre", zones[1], centre, increments, options, contact))


def sweep_displacement_force(args: argparse.Namespace, swept: set[str], params: Any,
                             increments: int, options: Any, contact: Any = None
                             ) -> float | None:
    """The force amplitude (N) of ``sweep --displacement-amplitude`` for the base clamp, or
    None. The inversion holds for one clamp: swept or sampled parameters are refused."""
    if not check_exclusive(args, "amplitude", "amplitude_range"):
        return None
    from ..errors import ParameterError

    if swept:
        raise ParameterError(f"--displacement-amplitude fixes one force amplitude for the base "
                             f"clamp; it cannot be combined with sweeping or sampling "
                             f"{', '.join(sorted(swept))}")
    return displacement_force(args, args.model, params, increments, options, contact)
