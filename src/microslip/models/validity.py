"""When a 1-D clamp model can be trusted: indicators and one-line warnings.

The 1-D models treat the clamped zone as a bar: all compliance axial (plus, with a stick slope,
a shear layer), pressure fixed by the clamping step. Against mesh-converged finite elements
(docs/interpretation.md, "validity"), the shear-layer model stays within 5 % down to a length /
thickness ratio of about 10 and is 8 % high at 5; the rigid-foundation model is already 7 % high
at 10. Three things make the answer untrustworthy, each measured here:

- ``slenderness`` L / t: below :data:`MIN_SLENDERNESS` the through-thickness stress field is
  two-dimensional and the normal pressure moves under the tangential load's moment;
- ``stiffness_sensitivity`` d ln W_d / d ln k_c, by central difference over a factor 2 of the
  contact stiffness: above :data:`MAX_SENSITIVITY` the result depends on a poorly known
  parameter, and the answer is only as good as that parameter;
- ``slip_fraction`` a / L at the peak: above :data:`MAX_SLIP_FRACTION` the joint is close to
  gross sliding, where W_d is steep in every parameter;
- ``shear_lag_effect``: for the rigid foundation, the relative change of W_d once the body's own
  shear lag is included; above :data:`MAX_SHEAR_LAG_EFFECT` the rigid model is off by that much.
"""

from __future__ import annotations

import dataclasses
import math

from ..params import ClampParams
from .interface import PressureLaw, masing_dissipation, virgin_curve

__all__ = [
    "MAX_SENSITIVITY",
    "MAX_SHEAR_LAG_EFFECT",
    "MAX_SLIP_FRACTION",
    "MIN_SLENDERNESS",
    "Validity",
    "validity",
]

#: L / t below which a bar model misses the 2-D stress field (8 % at 5 against CalculiX).
MIN_SLENDERNESS = 8.0
#: |d ln W_d / d ln k_c| above which the contact stiffness dominates the answer.
MAX_SENSITIVITY = 0.1
#: Peak slip length / clamped length above which the joint is close to gross sliding.
MAX_SLIP_FRACTION = 0.9
#: Relative W_d change from the body's shear lag above which the rigid bar is off.
MAX_SHEAR_LAG_EFFECT = 0.03


@dataclasses.dataclass(frozen=True)
class Validity:
    """Indicators of one 1-D result and the warnings they raise (sentences, may be empty)."""

    slenderness: float
    slip_fraction: float
    stiffness_sensitivity: float
    shear_lag_effect: float
    warnings: tuple[str, ...]

    def summary(self) -> dict[str, object]:
        return {"slenderness": self.slenderness, "slip_fraction": self.slip_fraction,
                "stiffness_sensitivity": self.stiffness_sensitivity,
                "shear_lag_effect": self.shear_lag_effect, "warnings": list(self.warnings)}


def _fe_hint(loading: str, p: ClampParams, amplitude: float, stick_slope: float) -> str:
    slope = f" --stick-slope {stick_slope:g}" if math.isfinite(stick_slope) else ""
    return (f"check with `microslip fe --model {loading} --length {p.length:g} --width "
            f"{p.width:g} --thickness {p.thickness:g} --modulus {p.modulus:g} --poisson-ratio "
            f"{p.poisson_ratio:g} --friction {p.friction:g} --normal-force {p.normal_force:g} "
            f"--amplitude {amplitude:g}{slope}`")


def validity(loading: str, params: ClampParams, amplitude: float, *,
             stick_slope: float = math.inf, law: PressureLaw | None = None) -> Validity:
    """Indicators and warnings for the 1-D model of ``loading`` at ``amplitude`` (N).

    ``stick_slope`` (N/mm^3) infinite means the paper's rigid foundation; finite, the
    shear-layer model with the body's shear lag.
    """
    slender = params.length / params.thickness
    if amplitude >= params.macroslip_force:
        return Validity(slender, 1.0, math.nan, math.nan, (
            f"the load {amplitude:g} N reaches the slip limit mu F_N = "
            f"{params.macroslip_force:g} N of a bar pressed on one face: that is gross "
            "sliding, not microslip (only the paper's reading of Eq. 11 puts it at 2 mu F_N)",))
    slip = virgin_curve(loading, params, [amplitude], stick_slope=stick_slope,
                        shear_lag=math.isfinite(stick_slope), law=law)[0]
    span = params.length if slip.shape[0] == 1 else 0.5 * params.length
    fraction = float(slip.max()) / span
    rigid = masing_dissipation(loading, params, amplitude, shear_lag=False, law=law)[0]
    lagged = masing_dissipation(loading, params, amplitude, shear_lag=True, law=law)[0]
    lag_effect = abs(rigid / lagged - 1.0) if lagged > 0.0 else math.inf
    sensitivity = 0.0
    if math.isfinite(stick_slope):
        hi = masing_dissipation(loading, params, amplitude, stick_slope=2 * stick_slope, law=law)[0]
        lo = masing_dissipation(loading, params, amplitude, stick_slope=0.5 * stick_slope,
                                law=law)[0]
        sensitivity = math.inf if lo <= 0.0 else math.log(hi / lo) / math.log(4.0)
    warnings = []
    hint = _fe_hint(loading, params, amplitude, stick_slope)
    if slender < MIN_SLENDERNESS:
        warnings.append(f"the clamped zone is squat (length/thickness {slender:.3g} < "
                        f"{MIN_SLENDERNESS:g}): a bar model misses its 2-D stress field and the "
                        f"pressure shift under load; {hint}")
    if sensitivity > MAX_SENSITIVITY:
        how = (f"d ln W_d / d ln k = {sensitivity:.2g} > {MAX_SENSITIVITY:g}"
               if math.isfinite(sensitivity) else "no slip at all with half the stiffness")
        warnings.append(f"W_d depends strongly on the contact stiffness ({how}): the result is "
                        f"only as good as --stick-slope {stick_slope:g} N/mm^3")
    if fraction > MAX_SLIP_FRACTION:
        warnings.append(f"the slip zone covers {100 * fraction:.0f} % of the clamped length "
                        f"(> {100 * MAX_SLIP_FRACTION:.0f} %): close to gross sliding")
    if not math.isfinite(stick_slope) and lag_effect > MAX_SHEAR_LAG_EFFECT:
        by = (f"{100 * lag_effect:.0f} %" if lag_effect < 9.0
              else "more than a factor of 10")
        warnings.append(f"the rigid-foundation model ignores the body's shear lag, which "
                        f"changes W_d by {by} here; give --stick-slope")
    return Validity(slender, fraction, sensitivity, lag_effect, tuple(warnings))
