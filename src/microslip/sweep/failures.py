"""Cases of a sweep that cannot be computed: found vectorised, each with its reason.

A random draw can leave the range of a parameter (a normal friction below zero) or load a
clamp beyond its macroslip limit; :func:`case_failures` finds such cases of a chunk so that
:func:`microslip.sweep.run_sweep` records them (results NaN, the reason kept) and computes the
others, instead of stopping at the first. The checks are those of
:func:`microslip.batch.prepare_batch`, in the same order.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from ..batch import PARAM_FIELDS
from ..models import get_model
from .spec import SweepSpec

__all__ = ["case_failures", "summarise_failures"]


def _range_checks() -> list[tuple[str, str, float, bool, float]]:
    """(name, unit, lower, lower inclusive, upper) of every value, as prepare_batch checks."""
    checks = [("amplitude", "N", 0.0, False, np.inf)]
    for k, unit in PARAM_FIELDS.items():
        checks.append((k, unit, 0.0, k == "poisson_ratio", 0.5 if k == "poisson_ratio"
                       else np.inf))
    return checks


def case_failures(spec: SweepSpec, lo: int, hi: int) -> tuple[NDArray[np.bool_], dict[int, str]]:
    """(mask of the cases ``lo:hi`` that can be computed, case index -> reason of the others).

    >>> from microslip import preset
    >>> from microslip.sweep import make_sweep
    >>> s = make_sweep("tip", preset("table1"), grid=[("amplitude", [100.0, 400.0])])
    >>> ok, why = case_failures(s, 0, 2)
    >>> ok.tolist(), why[1]
    ([True, False], 'amplitude 400 N is at or beyond the macroslip limit 356 N (mu F_N)')
    """
    params, amp = spec.chunk_inputs(lo, hi)
    n = hi - lo
    values = {"amplitude": amp, **params}
    ok = np.ones(n, dtype=bool)
    reasons: dict[int, str] = {}
    for name, unit, lower, inclusive, upper in _range_checks():
        x = np.broadcast_to(np.asarray(values[name], dtype=np.float64), (n,))
        with np.errstate(invalid="ignore"):
            good = np.isfinite(x) & (x >= lower if inclusive else x > lower) & (x < upper)
        bad = np.flatnonzero(ok & ~good)
        if bad.size:
            rng = (f"{'[' if inclusive else '('}{lower:g}, "
                   f"{f'{upper:g})' if np.isfinite(upper) else 'inf)'}{f' {unit}' if unit else ''}")
            reasons.update({lo + int(i): f"{name} must be finite and in {rng}, got {float(x[i])!r}"
                            for i in bad})
            ok &= good
    factor = get_model(spec.model).macroslip_factor(spec.options)
    a = np.broadcast_to(np.asarray(amp, dtype=np.float64), (n,))
    limit = factor * np.broadcast_to(params["friction"], (n,)) * np.broadcast_to(
        params["normal_force"], (n,))
    with np.errstate(invalid="ignore"):
        beyond = ok & ~(a < limit)
    rule = "2 mu F_N" if factor == 2.0 else "mu F_N"
    reasons.update({lo + int(i): f"amplitude {a[i]:g} N is at or beyond the macroslip limit "
                    f"{limit[i]:g} N ({rule})" for i in np.flatnonzero(beyond)})
    return ok & ~beyond, reasons


def summarise_failures(failures: Mapping[int, str], size: int) -> str:
    """One line: how many cases failed, for which kinds of reason, and the first example."""
    if not failures:
        return ""
    kinds = Counter(_kind(r) for r in failures.values())
    first = min(failures)
    what = "; ".join(f"{k} x {v}" for k, v in kinds.most_common())
    return (f"{len(failures)} of {size} cases not computed (results nan): {what}; "
            f"e.g. case {first}: {failures[first]}")


def _kind(reason: str) -> str:
    if "macroslip" in reason:
        return "beyond the macroslip limit"
    return reason.split(" must be", 1)[0] + " out of range"
