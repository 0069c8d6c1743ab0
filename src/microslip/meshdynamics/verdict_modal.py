"""A model's modal curve against the full FE's, judged from the numbers (issue 23, item 5).

The full FE's quasi-static modal analysis (:mod:`microslip.meshdynamics.qsma`) is the truth;
a model (the contact-node ROM's EPMC, the whole-joint model's EPMC) is compared with it at
equal amplitude over the *microslip range*: the FE's amplitudes whose damping ratio lies
between :data:`DAMPING_FLOOR` and :data:`DAMPING_CEILING` (5 %), and that lie inside the
model's own amplitude range. At each such amplitude a_i, the model's frequency and damping
ratio are interpolated log-log on its own amplitudes (:func:`loglog_interp`) and

    e_f = max_i |f_model(a_i) / f_FE(a_i) - 1|,  e_zeta = max_i |zeta_model(a_i) /
    zeta_FE(a_i) - 1|;

the model meets its targets (:data:`TARGETS`: issue 23's "Checks that must hold") when both
are within them. Units: amplitudes in mm, frequencies in Hz, damping ratios and errors
dimensionless (printed in %).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["DAMPING_CEILING", "DAMPING_FLOOR", "TARGETS", "ModalVerdict", "Targets",
           "loglog_interp", "modal_verdict"]

FloatArray = NDArray[np.float64]

#: Lowest FE damping ratio of the microslip range: below it the loop's work is a few
#: slipping nodes and rounding, and a relative error means nothing (the FE has no linear
#: damping, so issue 23's "twice the linear damping" is this floor).
DAMPING_FLOOR = 1e-4
#: Highest FE damping ratio of the microslip range (issue 23: up to 5 %).
DAMPING_CEILING = 0.05


@dataclass(frozen=True)
class Targets:
    """Largest relative errors against the full FE a model must keep (dimensionless)."""

    frequency: float
    damping_ratio: float


#: Issue 23's targets per model: the contact-node ROM (frequency 0.5 %, damping ratio 5 %) and
#: the whole-joint model (10 % on both). A model not named here is compared without a target.
TARGETS: dict[str, Targets] = {
    "rom": Targets(frequency=0.005, damping_ratio=0.05),
    "joint": Targets(frequency=0.10, damping_ratio=0.10),
    # issue 28 item 4: within 0.2 % / 2 % of the ROM, so against the full FE the ROM's own
    "interface": Targets(frequency=0.005, damping_ratio=0.05),
}


@dataclass(frozen=True)
class ModalVerdict:
    """One model against the full FE (see the module docstring).

    Attributes
    ----------
    model : str
    amplitude_mm : tuple of float
        The FE's amplitudes compared at, mm (empty: nothing to compare).
    frequency_error, damping_error : float
        Largest relative errors e_f and e_zeta (NaN without amplitudes).
    targets : Targets or None
    meets : bool or None
        Both errors within the targets; None when there is no target or nothing to compare.
    line : str
        The verdict in one line.
    """

    model: str
    amplitude_mm: tuple[float, ...]
    frequency_error: float
    damping_error: float
    targets: Targets | None
    meets: bool | None
    line: str

    def summary(self) -> dict[str, Any]:
        """Plain figures for JSON (errors and targets in %)."""
        t = self.targets
        a = self.amplitude_mm

        def pct(x: float) -> float | None:
            return None if not math.isfinite(x) else 100.0 * x

        return {"amplitude_range_mm": [min(a), max(a)] if a else None, "points": len(a),
                "frequency_error_percent": pct(self.frequency_error),
                "damping_ratio_error_percent": pct(self.damping_error),
                "frequency_target_percent": None if t is None else 100.0 * t.frequency,
                "damping_ratio_target_percent": None if t is None else 100.0 * t.damping_ratio,
                "meets_targets": self.meets, "verdict": self.line}


def _column(values: Sequence[float | None]) -> FloatArray:
    return np.array([math.nan if v is None else v for v in values], dtype=float)


def loglog_interp(x: FloatArray, xp: FloatArray, fp: FloatArray) -> FloatArray:
    """fp(xp) interpolated at x, linear in log x and log fp (xp increasing, > 0); a column
    with a value <= 0 is interpolated linearly in fp against log x.

    >>> loglog_interp(np.array([2.0]), np.array([1.0, 4.0]), np.array([1.0, 16.0]))
    array([4.])
    """
    lx, lxp = np.log(x), np.log(xp)
    if np.all(fp > 0):
        return np.exp(np.interp(lx, lxp, np.log(fp)))
    return np.interp(lx, lxp, fp)


def _pct(x: float) -> str:
    """A relative error in % to two digits (``0.21 %``, ``4.3 %``, ``12 %``, ``140 %``)."""
    v = 100.0 * x
    return f"{v:.2g} %" if v < 100 else f"{v:.0f} %"


def modal_verdict(model: str, fe: dict[str, Sequence[float | None]],
                  curve: dict[str, Sequence[float | None]],
                  targets: Targets | None = None, *, floor: float = DAMPING_FLOOR,
                  ceiling: float = DAMPING_CEILING) -> ModalVerdict:
    """Judge ``curve`` (the model's) against ``fe`` (the full FE's) over the microslip range.

    ``fe`` and ``curve`` hold the columns ``amplitude_mm``, ``frequency_Hz`` and
    ``damping_ratio`` (None or NaN: a failed amplitude, left out). ``targets`` default to
    :data:`TARGETS` of ``model``.

    >>> fe = {"amplitude_mm": [0.01, 0.02], "frequency_Hz": [100.0, 99.0],
    ...       "damping_ratio": [0.01, 0.02]}
    >>> rom = {"amplitude_mm": [0.01, 0.02], "frequency_Hz": [100.1, 99.0],
    ...        "damping_ratio": [0.0102, 0.02]}
    >>> v = modal_verdict("rom", fe, rom)
    >>> v.meets, round(100 * v.frequency_error, 9), round(100 * v.damping_error, 9)
    (True, 0.1, 2.0)
    >>> v.line.split(": ")[-1]
    'meets the targets (0.5 %, 5 %)'
    """
    targets = TARGETS.get(model) if targets is None else targets
    a, f, z = (_column(fe[k]) for k in ("amplitude_mm", "frequency_Hz", "damping_ratio"))
    ma, mf, mz = (_column(curve[k]) for k in ("amplitude_mm", "frequency_Hz", "damping_ratio"))
    ok = np.isfinite(ma) & np.isfinite(mf) & np.isfinite(mz) & (ma > 0)
    order = np.argsort(ma[ok])
    ma, mf, mz = ma[ok][order], mf[ok][order], mz[ok][order]
    use = np.isfinite(a) & np.isfinite(f) & np.isfinite(z) & (z >= floor) & (z <= ceiling)
    if ma.size:
        use &= (a >= ma[0]) & (a <= ma[-1])
    else:
        use[:] = False
    if not np.any(use):
        span = (f"a = {ma[0]:.3g}-{ma[-1]:.3g} mm" if ma.size else "no amplitude")
        line = (f"{model}: cannot be compared with the full FE: no FE amplitude with damping "
                f"ratio between {_pct(floor)} and {_pct(ceiling)} inside the model's "
                f"amplitudes ({span})")
        return ModalVerdict(model, (), math.nan, math.nan, targets, None, line)
    at, ft, zt = a[use], f[use], z[use]
    e_f = float(np.max(np.abs(loglog_interp(at, ma, mf) / ft - 1.0)))
    e_z = float(np.max(np.abs(loglog_interp(at, ma, mz) / zt - 1.0)))
    span = (f"at a = {at[0]:.3g} mm" if at.size == 1 else
            f"over a = {at.min():.3g}-{at.max():.3g} mm")
    line = (f"{model}: frequency within {_pct(e_f)} and damping ratio within {_pct(e_z)} of "
            f"the full FE {span}")
    meets: bool | None = None
    if targets is None:
        line += ": no target set"
    else:
        missed = [name for name, e, t in (("frequency", e_f, targets.frequency),
                                          ("damping ratio", e_z, targets.damping_ratio))
                  if not e <= t]
        meets = not missed
        goal = f"({_pct(targets.frequency)}, {_pct(targets.damping_ratio)})"
        line += (f": meets the targets {goal}" if meets else
                 f": misses the target on {' and '.join(missed)} {goal}")
    return ModalVerdict(model, tuple(float(x) for x in at), e_f, e_z, targets, meets, line)
