"""The joint across a two-directional tip or centre joint on the command line of ``modal``
and ``frf``: ``--transverse tip|centre|fe``, ``--pairing``, ``--fe-mesh`` (the keys
``transverse``, ``pairing``, ``fe_mesh`` of a case file's ``[[joint]]``, docs/casefile.md).

Without ``--transverse`` a two-directional joint is its own 1-D model in both directions;
with it, the joint's model (``--joint``) is along the first direction (the first
``--joint-dof``) and the joint across along the second, coupled by ``--coupling``.
"""

from __future__ import annotations

import argparse
from typing import Any

import numpy as np

from ..case.schema import DEFAULT_FE_MESH
from ..case.table import add_option
from ..conventions import CLAMP_MODELS, TRANSVERSE
from ..dynamics.operators import IwanOperator
from ..dynamics.operators2d import DEFAULT_PAIRING, PAIRINGS
from ..meshdynamics.spec import across_operator
from .common import model_options
from .joint import clamp_from_args, describe_joint, elements_from_args

__all__ = ["across_from_args", "across_joint", "add_across_options", "describe_across"]


def add_across_options(group: Any, mode: str | None = None) -> None:
    """``--transverse``, ``--pairing`` and ``--fe-mesh`` in the argument group ``group`` (in
    ``mode`` only, if given)."""
    add_option(group, "transverse", note="the second --joint-dof; default: --joint in both",
               mode=mode)
    add_option(group, "pairing", mode=mode)
    add_option(group, "fe_mesh", mode=mode)


def _usage(message: str) -> Exception:
    from .main import UsageError

    return UsageError(message)


def _check(args: argparse.Namespace, two_directions: bool) -> None:
    """The refusals: each option only where it does something."""
    transverse = getattr(args, "transverse", None)
    if transverse is not None:
        if args.joint not in CLAMP_MODELS:
            raise _usage(f"--transverse ({' | '.join(TRANSVERSE)}) applies to --joint tip "
                         f"or centre, not --joint {args.joint}")
        if not two_directions:
            raise _usage(f"--transverse ({' | '.join(TRANSVERSE)}) applies to two-directional "
                         "joints only (--structure with --joint-dof given twice or a "
                         "(n, 2, 2) joints array)")
    if getattr(args, "pairing", None) is not None:
        if transverse is None:
            raise _usage(f"--pairing ({' | '.join(PAIRINGS)}) needs --transverse "
                         f"({' | '.join(TRANSVERSE)}): it matches the elements along with "
                         "those across")
        if args.coupling == "decoupled":
            raise _usage(f"--pairing ({' | '.join(PAIRINGS)}) applies to --coupling circular "
                         "only: the decoupled directions are independent")
    if getattr(args, "fe_mesh", None) is not None and transverse != "fe":
        raise _usage("--fe-mesh LEVEL needs --transverse fe (the FE mesh of the joint "
                     "across)")
    if transverse == "fe" and args.stick_slope is None:
        raise _usage("--transverse fe needs --stick-slope N/MM3 (the FE's contact "
                     "stiffness), not --joint-stiffness")


def across_from_args(args: argparse.Namespace, joints: np.ndarray | None
                     ) -> IwanOperator | None:
    """The 1-D joint across (None without --transverse), the options checked against the
    joints' connectivity ``joints`` ((n, d, 2); None: a one-mode structure)."""
    two = joints is not None and joints.ndim == 3 and joints.shape[1] == 2
    _check(args, two)
    return across_joint(args)


def across_joint(args: argparse.Namespace) -> IwanOperator | None:
    """The 1-D joint across of checked options (the FE's is cached: built once)."""
    if getattr(args, "transverse", None) is None:
        return None
    params, series, slope = clamp_from_args(args)
    return across_operator(args.transverse, params, series,
                           elements=elements_from_args(args), options=model_options(args),
                           stick_slope=slope, fe_mesh=args.fe_mesh)


def describe_across(transverse: str | None, pairing: str | None, coupling: str,
                    across: IwanOperator | None, fe_mesh: str | None = None
                    ) -> dict[str, Any]:
    """JSON of the joint across: ``transverse`` (its name, the FE mesh of ``fe``, the
    joint), ``pairing`` (circular coupling: the one used); empty without a joint across."""
    if transverse is None or across is None:
        return {}
    mesh = {"fe_mesh": DEFAULT_FE_MESH if fe_mesh is None else fe_mesh} \
        if transverse == "fe" else {}
    out: dict[str, Any] = {"transverse": {"model": transverse, **mesh,
                                          **describe_joint(across)}}
    if coupling == "circular":
        out["pairing"] = DEFAULT_PAIRING if pairing is None else pairing
    return out
