"""Options shared by several subcommands: parameters, model readings, output."""

from __future__ import annotations

import argparse
import dataclasses
import json
import re
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from ..case import run
from ..case.run import planar_zones
from ..case.table import OPTIONS, add_option, number
from ..energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY
from ..errors import ParameterError
from ..io import check_writable, to_jsonable
from ..models import check_increments
from ..options import CENTRE_READINGS, POISSON_MODES, ModelOptions
from ..params import PRESETS, ClampParams

__all__ = [
    "add_clamp_flags",
    "add_model_options",
    "add_params",
    "add_strain_energy",
    "check_output_dir",
    "check_plot",
    "clamp_overrides",
    "flagged",
    "increments_option",
    "model_options",
    "number",
    "params_from_args",
    "planar_zones",
    "print_json",
    "refuse_inapplicable",
    "warn_cost",
]

#: Command-line name, ClampParams field, unit: the clamp's seven options of the option table.
PARAM_FLAGS = tuple((OPTIONS[f.name].flag[2:], f.name, OPTIONS[f.name].unit)
                    for f in dataclasses.fields(ClampParams))


#: The clamp's values a mesh of the user's own gives itself (its geometry).
GEOMETRY = ("length", "width", "thickness")


def add_params(parser: argparse.ArgumentParser,
               default_preset: str | None = OPTIONS["preset"].default,
               mode: str | None = None) -> None:
    """``--preset``, the seven clamp flags and ``--amplitude``; with ``mode`` the preset, the
    geometry and the amplitude belong to that mode only (:func:`~microslip.case.table.
    add_option`): the box's, which a mesh of the user's own replaces."""
    g = parser.add_argument_group("clamped zone (override the preset's values)")
    add_option(g, "preset", choices=sorted(PRESETS), default=default_preset, mode=mode)
    add_clamp_flags(g, mode)
    add_option(g, "amplitude", note="default: the preset's", mode=mode)


def add_clamp_flags(group: Any, geometry_mode: str | None = None) -> None:
    """The seven clamp flags of :data:`PARAM_FLAGS` (without --preset and --amplitude); the
    geometry's in ``geometry_mode`` only, if given."""
    for _, field, _ in PARAM_FLAGS:
        add_option(group, field, mode=geometry_mode if field in GEOMETRY else None)


def clamp_overrides(args: argparse.Namespace) -> dict[str, float]:
    """The clamp values given by the flags of :func:`add_clamp_flags` (field -> value)."""
    return run.clamp_overrides(vars(args))


def params_from_args(args: argparse.Namespace, fallback_amplitude: float | None = None
                     ) -> tuple[ClampParams, float]:
    """ClampParams (preset overridden by explicit flags) and the amplitude, validated
    (:func:`microslip.case.run.clamp_from_options`)."""
    return run.clamp_from_options(vars(args), fallback_amplitude)


def add_model_options(parser: argparse.ArgumentParser,
                      centre_default: str = OPTIONS["centre_reading"].default,
                      centre_why: str = "") -> None:
    """Flags of :class:`ModelOptions`; ``centre_why`` explains a non-default centre reading."""
    g = parser.add_argument_group("reading of the paper (docs/interpretation.md)")
    add_option(g, "no_corrections")
    add_option(g, "poisson", choices=POISSON_MODES)
    add_option(g, "no_length_update")
    add_option(g, "centre_reading", choices=CENTRE_READINGS, default=centre_default,
               note=centre_why.lstrip(",; ") if centre_why else "")
    add_option(g, "paper_literal")


def model_options(args: argparse.Namespace) -> ModelOptions:
    return run.model_options_from(vars(args))


def add_strain_energy(parser: argparse.ArgumentParser,
                      default: str = DEFAULT_STRAIN_ENERGY,
                      why: str = "", mode: str | None = None) -> None:
    add_option(parser, "strain_energy", choices=list(STRAIN_ENERGY), default=default, mode=mode,
               help="definition of U in eta = W_d/(2 pi U): "
               + "; ".join(f"{k}: {v[1]}" for k, v in STRAIN_ENERGY.items()),
               note=why.lstrip(",; ") if why else "")


def check_plot(path: str | None) -> None:
    """Before the work: a figure file ``path`` (if given) has a known format, can be written,
    and matplotlib is installed."""
    if path is None:
        return
    from ..plot.core import PLOT_FORMATS, pyplot

    check_writable(path, PLOT_FORMATS, "plot file")
    pyplot()


def check_output_dir(path: str | None) -> None:
    """Before the work: an output directory ``path`` (if given) can be created or written."""
    if path is not None:
        check_writable(path, what="--out", directory=True)


#: The flags of :func:`add_model_options` (the analytical models' reading of the paper).
MODEL_OPTION_DESTS = ("no_corrections", "poisson", "no_length_update", "centre_reading",
                      "paper_literal")


def refuse_inapplicable(args: argparse.Namespace, mode: str,
                        applies: dict[str, tuple[str, ...]]) -> None:
    """Refuse an option given on the command line for a mode it does nothing in.

    ``mode`` is the destination that selects the mode (``"solver"``); ``applies`` maps an
    option's destination to the modes where it applies. Options not given explicitly
    (``args.given_options``, from :func:`microslip.case.options.parse_args`) pass.
    """
    value = getattr(args, mode)
    given: frozenset[str] = getattr(args, "given_options", frozenset())
    for dest, modes in applies.items():
        if dest in given and value not in modes:
            flag = "--" + dest.replace("_", "-")
            raise ParameterError(f"{flag} does not apply to --{mode} {value} (only to "
                                 f"--{mode} {' or '.join(modes)}); remove it")


#: Fewest useful force increments: eta of the piecewise-linear loop is low by 1/n^2 (exactly,
#: for the quadratic backbones), so 1 increment gives eta = 0 and 10 give 1 %.
MIN_INCREMENTS = 10

#: Cost of one increment of one first loading with its loop, measured on the CLI: kept loops
#: (``loop --increments 1000000``: 2.6 s, 0.3 GB) and the compiled batch of a sweep (1e9
#: case-increments in 6.4 s on two cores, results only). A run estimated above WARN_SECONDS
#: or WARN_BYTES is announced with its cost.
BYTES_PER_INCREMENT = 250.0
SECONDS_PER_INCREMENT = 2.5e-6
BATCH_SECONDS_PER_INCREMENT = 1e-8
WARN_SECONDS = 10.0
WARN_BYTES = 1e9


def increments_option(n: Any, loops: int = 1, batch: bool = False) -> int:
    """A checked ``--increments``: at least :data:`MIN_INCREMENTS`, with the cost warning of
    :func:`warn_cost` for ``loops`` first loadings."""
    n = check_increments(n)
    if n < MIN_INCREMENTS:
        raise ParameterError(
            f"--increments must be >= {MIN_INCREMENTS}, got {n}: eta of the discretised loop "
            f"is low by 1/n^2 (n = 1 gives eta = 0, n = {MIN_INCREMENTS} is 1 % low, "
            "n = 1000 is 1e-6 low)")
    warn_cost(n, loops, batch)
    return n


def warn_cost(n: int, loops: int, batch: bool = False) -> None:
    """A warning with the estimated time and memory when ``loops`` first loadings of ``n``
    increments are costly (``batch``: a compiled sweep, which keeps only each case's results).
    """
    total = float(n) * loops
    seconds = total * (BATCH_SECONDS_PER_INCREMENT if batch else SECONDS_PER_INCREMENT)
    memory = 0.0 if batch else total * BYTES_PER_INCREMENT
    if seconds > WARN_SECONDS or memory > WARN_BYTES:
        from ..case.options import warn

        size = f" and {memory / 1e9:.2g} GB of memory" if memory else ""
        warn(f"--increments {n} for {loops} loading(s) takes about {seconds:.2g} s{size}; "
             "eta is within 1e-6 at 1000 increments (its error is 1/n^2)")


def print_json(obj: Any) -> None:
    from ..case.options import annotate_json

    json.dump(to_jsonable(annotate_json(obj)), sys.stdout, indent=2)
    sys.stdout.write("\n")


@contextmanager
def flagged() -> Iterator[None]:
    """Re-raise a library's ParameterError about a named value (``harmonics must be in [1,
    256], got 0``) as the command line's option (``--harmonics must be ...``): the library
    checks a value once, the command line names the flag."""
    try:
        yield
    except ParameterError as exc:
        text = str(exc)
        m = re.match(r"([a-z][a-z_-]*) (must|needs) ", text)
        if m is None:
            raise
        raise ParameterError(f"--{m.group(1).replace('_', '-')}{text[len(m.group(1)):]}"
                             ) from None
