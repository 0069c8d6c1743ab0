"""``microslip sweep``: parameter studies of the tip and centre models, and R for planar."""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np

from ..case.options import add_case_option
from ..case.runflags import positive_int
from ..case.table import add_option
from ..conventions import CLAMP_MODELS
from ..errors import ParameterError
from ..models import MODELS
from ..params import preset
from .common import (
    PARAM_FLAGS,
    add_model_options,
    add_params,
    add_strain_energy,
    check_plot,
    clamp_overrides,
    increments_option,
    model_options,
    params_from_args,
    planar_zones,
    refuse_inapplicable,
    warn_cost,
)
from .contact import add_contact_options, contact_from_args
from .displacement import add_displacement_option, sweep_displacement_force
from .sweep_fe import RUNNERS as FE_RUNNERS
from .sweep_fe import add_options as add_fe_sweep_options

__all__ = ["add_parser", "run"]

EPILOG = """\
examples:
  microslip sweep --model tip --preset table2-tip --amplitude-range 100 8000 \\
      --cases 1000000 --increments 1000 --out eta.csv
  microslip sweep --model centre --preset table2-centre --amplitude-range 1000 15000 \\
      --grid mu=0.4:0.8:5 --out eta.nc --plot eta.png
  microslip sweep --model tip --preset table2-tip --amplitude-range 1000 8000 --cases 50 \\
      --sample friction=normal:0.8:0.05 --samples 2000 --seed 1 --plot bands.png
  microslip sweep --model planar --ratio-range 0.25 4 --cases 50 --out r.csv
grid values: NAME=START:STOP:COUNT (evenly spaced, both ends included),
  NAME=START:STOP:COUNT:log (geometric) or NAME=V1,V2,...; NAME is one of amplitude,
  friction, normal_force, length, width, thickness, modulus, poisson_ratio
  (or F0, mu, F_N, L, w, t, E, nu). Rows of the CSV are in C order over the axes
  (--amplitude-range first, then the --grid axes as given, then the samples).
distributions: normal:MEAN:SD, lognormal:MEAN:SD (of the quantity, always > 0),
  uniform:LOW:HIGH; every grid point uses the same draws (common random numbers).
"""


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "sweep", help="parameter study: damping over grids and random samples",
        description="Damping of many cases at once (compiled batch engine): grids over the "
        "amplitude, friction, normal force, geometry and modulus, random samples of uncertain "
        "parameters, or the force ratio R of the planar model. Writes CSV or NetCDF (by the "
        "extension) and a summary plot; runs locally or on a Dask cluster (--scheduler).",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_option(p, "model", choices=[*MODELS, "planar"], required=True,
               note="planar: the paper's planar coupling over the force ratio R")
    add_params(p, default_preset=None)
    for action in p._actions:
        if action.dest == "preset":
            action.help = ("paper parameter set (default table1; --model planar uses "
                           "table2-tip and table2-centre)")
    g = p.add_argument_group("what to sweep")
    add_option(g, "amplitude_range", metavar=("A", "B"),
               help="--cases amplitudes evenly spaced from A to B N, both included (the first "
                    "axis)")
    add_option(g, "ratio_range")
    add_option(g, "cases", note="default 100")
    add_option(g, "grid", default=[])
    add_option(g, "sample", default=[])
    add_option(g, "samples", type=positive_int, default=1000, metavar="M",
               help="draws per grid point with --sample")
    add_option(g, "seed", note="default: a fresh seed, printed")
    add_option(g, "levels",
               note="planar: how R maps to the amplitudes (microslip.planar.LEVEL_SCHEMES)")
    add_displacement_option(g, note="for the base clamp (no swept clamp parameters)")
    add_option(p, "increments")
    add_model_options(p)
    add_contact_options(p)
    add_strain_energy(p)
    o = p.add_argument_group("output and execution")
    add_option(o, "out", metavar="FILE", help="write FILE.csv or FILE.nc (NetCDF)")
    add_option(o, "plot", help="summary plot of eta against the swept parameter")
    add_option(o, "scheduler")
    add_option(o, "chunk_size")
    add_option(o, "threads", type=positive_int, default=None, help="threads of a local run",
               note="default: all cores")
    add_option(o, "retries")
    add_option(o, "no_progress")
    add_fe_sweep_options(p)
    add_case_option(p)
    p.set_defaults(func=run)


def _check_outputs(args: argparse.Namespace) -> None:
    from ..io import check_writable
    from ..sweep import check_output

    if args.out:
        check_output(args.out)
        check_writable(args.out)
    check_plot(args.plot)


#: Options that apply to some models only (the others are refused, not silently ignored).
MODEL_OPTIONS: dict[str, tuple[str, ...]] = {
    **{dest: CLAMP_MODELS for dest in (
        "amplitude_range", "grid", "sample", "samples", "seed", "scheduler", "amplitude",
        "chunk_size", "threads", "retries", "preset")},
    **{dest: ("planar",) for dest in ("ratio_range", "levels")},
}


def _cases(args: argparse.Namespace) -> int:
    return 100 if args.cases is None else int(args.cases)


def run(args: argparse.Namespace) -> int:
    if args.solver in FE_RUNNERS:
        return FE_RUNNERS[args.solver](args)
    refuse_inapplicable(args, "model", MODEL_OPTIONS)
    if args.model == "planar":
        return _run_planar(args)
    from ..plot.sweep import plot_sweep
    from ..sweep import make_sweep, parse_grid, parse_sample, run_sweep, write_sweep

    if args.cases is not None and args.amplitude_range is None:
        raise ParameterError("--cases sets the number of points of --amplitude-range "
                             "(use --samples for random draws, --grid for other axes)")
    if args.retries < 0:
        raise ParameterError(f"--retries must be >= 0, got {args.retries}")
    n = increments_option(args.increments, loops=0)  # the cost follows from the spec below
    _check_outputs(args)
    grid = []
    if args.amplitude_range is not None:
        a, b = args.amplitude_range
        for v in (a, b):
            if not (math.isfinite(v) and v > 0):
                raise ParameterError(f"--amplitude-range ends must be finite and > 0 N, got {v!r}")
        grid.append(("amplitude", np.linspace(a, b, _cases(args))))
    grid.extend(parse_grid(t) for t in args.grid)
    samples = [parse_sample(t) for t in args.sample]
    if args.preset is None and any(getattr(args, f) is None for _, f, _ in PARAM_FLAGS):
        args.preset = "table1"
    swept = {name for name, _ in grid} | {name for name, _ in samples}
    fallback = None
    if "amplitude" in swept:
        if args.amplitude is not None:
            raise ParameterError("--amplitude conflicts with sweeping or sampling the amplitude")
        fallback = 1.0  # only to satisfy params_from_args: the amplitude varies
    if args.displacement_amplitude is not None:
        fallback = 1.0  # replaced by the force of the displacement amplitude
    params, amplitude = params_from_args(args, fallback_amplitude=fallback)
    opt = model_options(args)
    contact = contact_from_args(args, params)
    forced = sweep_displacement_force(args, swept, params, n, opt, contact)
    amplitude = amplitude if forced is None else forced
    spec = make_sweep(args.model, params, amplitude=None if "amplitude" in swept else amplitude,
                      grid=grid, samples=samples, n_samples=args.samples, seed=args.seed,
                      increments=n, options=opt, strain_energy=args.strain_energy,
                      contact=contact, check_draws=False)
    _warn_implausible(spec)
    warn_cost(n, spec.size, batch=True)
    result = run_sweep(spec, chunk_size=args.chunk_size, scheduler=args.scheduler,
                       threads=args.threads, retries=args.retries,
                       progress=not args.no_progress,
                       failures="record" if spec.samples else "raise")
    if len(result.failures) == spec.size:
        raise ParameterError(f"no case can be computed: {_failure_summary(spec, result)}")
    if args.out:
        write_sweep(result, args.out, chunk_size=args.chunk_size)
    if args.plot:
        plot_sweep(result, args.plot)
    _print_summary(args, spec, result)
    return 0


def _print_summary(args: argparse.Namespace, spec: Any, result: Any) -> None:
    opt = spec.options
    print(f"{spec.model} model ({MODELS[spec.model].equations}), {spec.size} cases x "
          f"{spec.increments} increments, poisson={opt.poisson}, "
          f"length_update={opt.length_update}"
          + (f", centre reading={opt.centre}" if spec.model == "centre" else "")
          + f"; U: {spec.strain_energy}")
    if args.preset:
        print(f"  base parameters        preset {args.preset} (with the flags given)")
    for line in spec.describe():
        print(f"  {line}")
    eta = result.loss_factor
    if np.isfinite(eta).any():
        q = np.nanpercentile(eta, [0, 5, 50, 95, 100])
        print(f"  loss factor eta        min {q[0]:.6g}, 5% {q[1]:.6g}, median {q[2]:.6g}, "
              f"95% {q[3]:.6g}, max {q[4]:.6g} (dimensionless"
              + (", computed cases" if result.failures else "") + ")")
    rate = spec.size * spec.increments / result.elapsed if result.elapsed > 0 else math.inf
    where = f"Dask scheduler {result.scheduler}" if result.scheduler else "this machine"
    print(f"  computed in            {result.elapsed:.3g} s on {where} ({result.backend}), "
          f"{rate:.3g} case-increments/s")
    if args.out:
        what = (f"{spec.size} rows" if args.out.lower().endswith(".csv") else
                f"{spec.size} cases, dimensions {', '.join(spec.dims) or 'none'}")
        print(f"  wrote                  {args.out} ({what})")
    if args.plot:
        print(f"  figure                 {args.plot}")
    if result.failures:
        from ..case.options import warn

        warn(_failure_summary(spec, result))


def _warn_implausible(spec: Any) -> None:
    """The unit plausibility check of the options, for grid values and sample medians."""
    from ..case.options import warn
    from ..case.units import plausibility_warnings

    values = [(f"--grid {a.name}: ", a.name, v) for a in spec.grid
              for v in (float(np.min(a.values)), float(np.max(a.values)))]
    values += [(f"--sample {s.name} (median): ", s.name, float(np.median(s.values)))
               for s in spec.samples]
    for where, name, v in values:
        for line in plausibility_warnings({name: v}, where):
            warn(line)


def _failure_summary(spec: Any, result: Any) -> str:
    """The failed cases in one line, with a hint when a normal draw left its range."""
    from ..sweep.failures import summarise_failures

    text = summarise_failures(result.failures, spec.size)
    normal = [s.name for s in spec.samples if s.distribution.kind == "normal"]
    if any(r.startswith(f"{n} must be") for r in result.failures.values() for n in normal):
        text += ("; a normal distribution can reach non-physical values: use "
                 "lognormal:MEAN:SD for a positive quantity")
    return text


def _run_planar(args: argparse.Namespace) -> int:
    from ..planar import LEVEL_SCHEMES
    from ..plot.sweep import plot_ratio_sweep
    from ..sweep import ratio_sweep, write_ratio_sweep

    if args.ratio_range is None:
        raise ParameterError("--model planar needs --ratio-range A B (force ratios R > 0)")
    if args.levels not in LEVEL_SCHEMES:
        raise ParameterError(f"unknown level scheme {args.levels!r}; choose one of "
                             f"{', '.join(LEVEL_SCHEMES)}")
    a, b = args.ratio_range
    for v in (a, b):
        if not (math.isfinite(v) and v > 0):
            raise ParameterError(f"--ratio-range ends must be finite and > 0, got {v!r}")
    n = increments_option(args.increments, loops=2 * _cases(args))
    _check_outputs(args)
    tip_p, centre_p = planar_zones(preset("table2-tip"), preset("table2-centre"),
                                   clamp_overrides(args))
    ratios = np.geomspace(a, b, _cases(args)) if a != b else np.array([a])
    opt = model_options(args)
    sweep = ratio_sweep(ratios, tip_params=tip_p, centre_params=centre_p, levels=args.levels,
                        increments=n, options=opt, strain_energy=args.strain_energy,
                        progress=not args.no_progress, contact=contact_from_args(args, tip_p))
    if args.out:
        write_ratio_sweep(sweep, args.out)
    if args.plot:
        plot_ratio_sweep(sweep, args.plot)
    failed = [c for c in sweep.cases if c.result is None]
    print(f"planar model, {len(sweep.cases)} force ratios R from {a:g} to {b:g} "
          f"(levels {args.levels}, {n} increments, U: {sweep.strain_energy_kind}; "
          "tip table2-tip, centre table2-centre"
          + "".join(f", {k} {v:g}" for k, v in clamp_overrides(args).items()) + ")")
    eta_p = sweep.loss_factor("paper")
    eta_w = sweep.loss_factor("work")
    ok = np.isfinite(eta_p)
    if ok.any():
        print(f"  paper coupling eta     {np.nanmin(eta_p):.6g} .. {np.nanmax(eta_p):.6g} "
              "(dimensionless)")
        print(f"  work-based eta         {np.nanmin(eta_w):.6g} .. {np.nanmax(eta_w):.6g} "
              "(dimensionless)")
    if failed:
        print(f"  not computed           {len(failed)} ratio(s), e.g. R = {failed[0].ratio:g}: "
              f"{failed[0].error}")
    if args.out:
        print(f"  wrote                  {args.out} ({len(sweep.cases)} rows)")
    if args.plot:
        print(f"  figure                 {args.plot}")
    return 0
