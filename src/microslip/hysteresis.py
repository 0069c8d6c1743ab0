"""Masing's rule: hysteresis loops and arbitrary load histories from a virgin curve.

For a Jenkins/Iwan-type system starting from the virgin state, with virgin curve
d = g(F) (odd in F), a branch that starts at a reversal point (F_r, d_r) follows
d = d_r + 2 g((F - F_r) / 2) (Masing's rule, paper ref. [8]). A branch that reaches
the start of the branch before it closes that inner loop and the earlier branch
continues (the "wiping-out" memory of the extended Masing rules).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import MacroslipError, ParameterError
from .results import Backbone, HysteresisLoop

__all__ = ["VirginCurve", "masing_loop", "masing_response"]


def masing_loop(backbone: Backbone) -> HysteresisLoop:
    """Complete the hysteresis loop of a symmetric cycle of amplitude F0 from its backbone.

    The loop is built at the backbone's own samples, so it is exact wherever the
    backbone is: descending branch F = F0 - 2 F_j, d = d0 - 2 d_j; ascending branch
    F = -F0 + 2 F_j, d = -d0 + 2 d_j (j = 0..n).

    Parameters
    ----------
    backbone : Backbone
        First-loading curve sampled from F = 0 to the peak F0.

    Returns
    -------
    HysteresisLoop
        ``2 n + 1`` points, starting and ending at (F0, d0), descending first.

    Examples
    --------
    >>> import numpy as np
    >>> from microslip.results import Backbone
    >>> f = np.linspace(0.0, 2.0, 3); d = f**2
    >>> z = np.zeros((3, 1))
    >>> loop = masing_loop(Backbone("tip", f, d, ("tip",), z, z, z, d))
    >>> loop.force.tolist(), loop.displacement.tolist()
    ([2.0, 0.0, -2.0, 0.0, 2.0], [4.0, 2.0, -4.0, -2.0, 4.0])
    """
    f = np.asarray(backbone.force, dtype=float)
    d = np.asarray(backbone.displacement, dtype=float)
    f0, d0 = f[-1], d[-1]
    down_f, down_d = f0 - 2.0 * f, d0 - 2.0 * d
    up_f, up_d = -f0 + 2.0 * f[1:], -d0 + 2.0 * d[1:]
    return HysteresisLoop(
        force=np.concatenate([down_f, up_f]),
        displacement=np.concatenate([down_d, up_d]),
        source="masing",
        meta={"model": backbone.model, "amplitude_N": float(f0)},
    )


@dataclass(frozen=True)
class VirginCurve:
    """The virgin curve d = g(F) of a backbone, extended as an odd function.

    Monotone cubic (PCHIP) interpolation of the backbone samples; forces beyond the
    backbone's peak raise :class:`MacroslipError` (the model was not run that far).
    """

    force_max: float
    _interp: Any  # scipy.interpolate.PchipInterpolator, imported when first needed

    @classmethod
    def from_backbone(cls, backbone: Backbone) -> VirginCurve:
        f = np.asarray(backbone.force, dtype=float)
        d = np.asarray(backbone.displacement, dtype=float)
        if f.ndim != 1 or f.size < 2 or f[0] != 0.0 or np.any(np.diff(f) <= 0):
            raise ParameterError("a virgin curve needs forces rising from 0 in at least 1 step")
        from scipy.interpolate import PchipInterpolator

        return cls(float(f[-1]), PchipInterpolator(f, d, extrapolate=False))

    def __call__(self, force: ArrayLike) -> NDArray[np.float64]:
        f = np.asarray(force, dtype=float)
        a = np.abs(f)
        tol = 1e-9 * self.force_max
        if np.any(a > self.force_max + tol):
            raise MacroslipError(
                f"force {float(np.max(a)):g} N exceeds the backbone's peak "
                f"{self.force_max:g} N; run the model to a larger amplitude"
            )
        return np.asarray(np.sign(f) * self._interp(np.minimum(a, self.force_max)), dtype=float)


def masing_response(virgin: VirginCurve | Backbone, force: ArrayLike) -> NDArray[np.float64]:
    """Displacement history for an arbitrary force history by the extended Masing rules.

    Parameters
    ----------
    virgin : VirginCurve or Backbone
        The virgin curve g; a Backbone is converted with :meth:`VirginCurve.from_backbone`.
    force : array_like, shape (K,)
        Force samples, N, starting from the virgin state (``force[0]`` is reached along the
        virgin curve).

    Returns
    -------
    ndarray, shape (K,)
        Displacement, mm.

    Notes
    -----
    A stack of branches is kept. The virgin branch is d = g(F). At a reversal at
    (F_r, d_r) a branch d = d_r + 2 g((F - F_r) / 2) is pushed. A branch closes when the
    force passes the start of the branch beneath it (for the first branch off the virgin
    curve: the mirror point -F_r, where it meets the virgin curve); both are popped and the
    branch beneath continues. This is exact for any Iwan (parallel Jenkins) system, and
    hence for the rigid-foundation bars.

    Examples
    --------
    >>> import numpy as np
    >>> from microslip.results import Backbone
    >>> f = np.linspace(0.0, 2.0, 201); z = np.zeros((201, 1))
    >>> g = VirginCurve.from_backbone(Backbone("tip", f, f**2, ("tip",), z, z, z, f))
    >>> masing_response(g, [0.0, 2.0, 0.0, -2.0, 0.0, 2.0]).round(6).tolist()
    [0.0, 4.0, 2.0, -4.0, -2.0, 4.0]
    """
    g = virgin if isinstance(virgin, VirginCurve) else VirginCurve.from_backbone(virgin)
    f = np.asarray(force, dtype=float)
    if f.ndim != 1:
        raise ParameterError("force history must be one-dimensional")
    g(f)  # range check once, before the walk
    out = np.empty_like(f)
    if f.size == 0:
        return out
    # The walk visits reversals and closures only; the samples between two such events lie on
    # one branch and are evaluated together. fh[0] = 0 is the virgin state before f[0].
    fh = np.concatenate([[0.0], f])
    step = np.sign(np.diff(fh))
    idx = np.where(step != 0, np.arange(step.size), 0)
    np.maximum.accumulate(idx, out=idx)
    direction = np.where(step[idx] != 0, step[idx], 0.0)  # zero steps keep the last direction
    run_starts = np.flatnonzero(np.r_[True, direction[1:] != direction[:-1]])
    run_ends = np.r_[run_starts[1:], direction.size]
    # Each branch: (origin force, origin displacement, direction +1/-1); the virgin has 0.
    stack: list[tuple[float, float, int]] = [(0.0, 0.0, 0)]
    last_dir = 0
    d_prev = 0.0
    for a, b in zip(run_starts, run_ends, strict=True):
        dr = int(direction[a])
        if dr != 0 and last_dir != 0 and dr != last_dir:
            stack.append((float(fh[a]), d_prev, dr))
        if dr != 0:
            last_dir = dr
        seg = fh[a + 1 : b + 1]  # samples a+1..b of fh are out[a..b-1]; monotone in dr
        key = seg * dr if dr != 0 else seg
        pos = 0
        while pos < seg.size:
            end = seg.size
            if len(stack) > 1 and dr != 0:
                fo, _, bdr = stack[-1]
                target = -fo if len(stack) == 2 else stack[-2][0]
                j = pos + int(np.searchsorted(key[pos:], target * bdr, side="left"))
                if j < seg.size and bdr == dr:
                    end = j
            fo, do, bdr = stack[-1]
            part = seg[pos:end]
            out[a + pos : a + end] = g(part) if bdr == 0 else do + 2.0 * g((part - fo) / 2.0)
            if end < seg.size:  # the branch closed: return to the one it started from
                stack.pop()
                if len(stack) > 1:
                    stack.pop()
            pos = end
        d_prev = float(out[b - 1])
    return out
