"""``microslip fit``: identify friction and contact stiffness from measured loops."""

from __future__ import annotations

import argparse
from typing import Any

from ..case.table import add_option
from ..conventions import DEFAULT_STICK_SLOPE
from ..fit import FIT_PARAMETERS, FitResult, fit_loops, read_loop_csv
from ..models.interface import LOADINGS
from .common import add_params, params_from_args, print_json

__all__ = ["add_parser"]


def add_parser(sub: Any) -> None:
    p = sub.add_parser(
        "fit", help="identify friction and contact stiffness from measured loops",
        description="Fit the 1-D clamp model (bar on a shear layer with the body's shear lag, "
        "Masing loops) to measured force-displacement loops by bounded least squares, with "
        "confidence intervals from the Jacobian. Each CSV holds one loop with the columns "
        "force_N,displacement_mm in sampling order (as microslip writes loops); loops are "
        "centred first. The clamp options give the known values and the starting guesses.")
    p.add_argument("loops", nargs="+", metavar="LOOP.csv", help="measured loop(s)")
    add_option(p, "model", choices=list(LOADINGS), required=True)
    add_params(p)
    add_option(p, "fit", choices=list(FIT_PARAMETERS), default=["friction", "stick_slope"],
               metavar="NAME", note=f"from {', '.join(FIT_PARAMETERS)}")
    add_option(p, "stick_slope", default=DEFAULT_STICK_SLOPE,
               note="the known value or the starting guess of the fit")
    add_option(p, "confidence")
    add_option(p, "json")
    add_option(p, "plot", help="write a figure of the measured loops against the fitted model "
                               "(.png, .pdf or .svg)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if args.amplitude is not None:
        from ..errors import ParameterError

        raise ParameterError("--amplitude does nothing in fit: each loop's amplitude is "
                             "half its peak-to-peak force")
    params, _ = params_from_args(args, fallback_amplitude=1.0)
    _check_plot(args.plot)
    loops = [read_loop_csv(path) for path in args.loops]
    res = fit_loops(loops, args.model, params, fit=args.fit, stick_slope=args.stick_slope,
                    confidence=args.confidence)
    if args.plot:
        from ..plot.fit import plot_fit

        plot_fit(res, args.plot)
    if args.json:
        print_json(_json(res, args) | ({"figure": args.plot} if args.plot else {}))
        return 0
    _print(res, args)
    if args.plot:
        print(f"  figure         {args.plot}")
    return 0


def _check_plot(path: str | None) -> None:
    """A figure path must end in .png, .pdf or .svg, and matplotlib must be installed."""
    if path is None:
        return
    import os

    from ..errors import ParameterError
    from ..plot import pyplot

    if os.path.splitext(path)[1].lower() not in (".png", ".pdf", ".svg"):
        raise ParameterError(f"--plot file must end in .png, .pdf or .svg, got {path!r}")
    pyplot()


def _json(res: FitResult, args: argparse.Namespace) -> dict[str, Any]:
    return {"loops": list(args.loops), "units": {"force": "N", "length": "mm",
            "modulus": "MPa", "stick_slope": "N/mm^3"},
            "known": {k: v for k, v in res.params.as_dict().items() if k not in args.fit}
            | ({} if "stick_slope" in args.fit else {"stick_slope": res.stick_slope}),
            "amplitudes_N": [loop.amplitude for loop in res.loops]} | res.summary()


def _print(res: FitResult, args: argparse.Namespace) -> None:
    pct = round(100 * res.confidence)
    print(f"fit of the {res.model} model to {len(res.loops)} loop(s), {res.points} samples")
    for p in res.parameters:
        unit = f" {p.unit}" if p.unit else ""
        flag = "" if p.identified else "   NOT IDENTIFIED"
        print(f"  {p.name:<14} {p.value:12.6g}{unit}  ({pct} % interval {p.low:.6g} ... "
              f"{p.high:.6g}{unit}){flag}")
        if p.note:
            print(f"  {'':<14} {p.note}")
    print(f"  rms residual   {res.rms_residual_mm:12.4g} mm   R^2 = {res.r_squared:.6f}")
