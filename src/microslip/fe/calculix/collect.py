"""Reading a CalculiX run into the one FE result, :class:`~microslip.fe.result.FELoopResult`.

The FE loop arrives as a :class:`~microslip.results.HysteresisLoop` (``source="calculix"``)
and its damping as a :class:`~microslip.results.DampingResult` from
:func:`microslip.energy.damping_from_loop`, exactly as the analytical models and the built-in
solver deliver theirs, so comparison code never cares where a loop came from.

Conventions (docs/validation.md):

- The loop displacement is the work-conjugate displacement of the loaded section, the
  force-weighted mean sum_i w_i u_x,i of its nodes with the consistent-load shares w_i (sum 1),
  measured from the clamped state (end of step 1). The clamping pressure itself moves the
  section by a Poisson expansion of order 1e-6 mm; it is reported as ``clamp_displacement``.
- The closed loop is t = 0.25 .. 1.25 s (force peak to force peak). Its amplitude is half the
  peak-to-peak displacement (``HysteresisLoop.peak_displacement``): residual tractions of the
  clamping step can shift the loop by a small ``offset`` (mid-point of the extremes), which
  half peak-to-peak does not see.
- Contact status of a contact point (a slave node of the lower face) at a substep: ``open``
  if its pressure is zero; ``slip`` if its shear traction is at the friction limit
  (|tau| >= (1 - ratio_tol) mu p, ratio_tol = 0.5 by default: nodal tractions are smeared
  over an element next to the stick-slip boundary) *and* it slipped irreversibly during the
  substep (|delta s - delta tau / lambda| > slip_tol); ``stick`` otherwise. The second condition
  separates a point that slips from one that is locked at the limit traction after a load
  reversal (which ANSYS, and the paper's Fig. 8, count as sticking).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...named import result
from ..result import (
    OPEN,
    SLIP,
    STATUS,
    STICK,
)
from .case import FECase

__all__ = [
    "STATUS",
    "CalculixDetails",
    "contact_status",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def contact_status(pressure: FloatArray, shear: FloatArray, slip: FloatArray, friction: float,
                   stick_slope: float, *, ratio_tol: float = 0.5,
                   slip_tol: float | None = None) -> NDArray[np.int8]:
    """Stick/slip/open status of every contact point at every state.

    Parameters
    ----------
    pressure : ndarray, shape (k, m)
        Contact pressure p, MPa, at k states (the first is the reference for increments).
    shear : ndarray, shape (k, m, 2)
        Shear traction tau, MPa.
    slip : ndarray, shape (k, m, 2)
        Total tangential relative displacement s, mm.
    friction, stick_slope : float
        mu and lambda (N/mm^3) of the friction law.
    ratio_tol : float
        A point may slip only when |tau| >= (1 - ratio_tol) mu p. The irreversible slip is the
        discriminating test (a stuck point has delta s = delta tau / lambda exactly, also in
        the nodal values, which are linear extrapolations of integration-point values); this
        one only guards against rounding noise far from the limit. Nodal tractions next to
        the stick-slip boundary are smeared over an element, hence the generous default.
    slip_tol : float, optional
        Irreversible slip per substep above which a point at the limit counts as slipping, mm.
        Default: 1 % of the elastic slip at the limit, mu p_mean / lambda, plus twice the
        resolution of the ``.frd`` file's five-digit slips (2e-5 max |s|).

    Returns
    -------
    ndarray of int8, shape (k, m)
        Codes into :data:`STATUS` (0 open, 1 stick, 2 slip). The first state's increment is
        taken from the unloaded, unclamped state (s = 0, tau = 0).

    Examples
    --------
    >>> p = np.full((2, 3), 0.07); tau = np.zeros((2, 3, 2)); s = np.zeros((2, 3, 2))
    >>> tau[1, :2, 0] = 0.056; s[1, 0, 0] = 1e-4; s[1, 1, 0] = 0.056 / 1e4
    >>> contact_status(p, tau, s, 0.8, 1e4).tolist()   # slipping, locked at the limit, stuck
    [[1, 1, 1], [2, 1, 1]]
    """
    p = np.asarray(pressure, dtype=float)
    tau = np.asarray(shear, dtype=float)
    s = np.asarray(slip, dtype=float)
    if tau.shape != (*p.shape, 2) or s.shape != tau.shape:
        raise ValueError("pressure (k, m), shear and slip (k, m, 2) shapes do not match")
    if slip_tol is None:
        closed = p > 0.0
        p_mean = float(np.mean(p[closed])) if np.any(closed) else 0.0
        s_max = float(np.max(np.abs(s))) if s.size else 0.0
        slip_tol = 0.01 * friction * p_mean / stick_slope + 2e-5 * s_max
    ds = np.diff(s, axis=0, prepend=0.0)
    dtau = np.diff(tau, axis=0, prepend=0.0)
    plastic = np.linalg.norm(ds - dtau / stick_slope, axis=-1)
    at_limit = np.linalg.norm(tau, axis=-1) >= (1.0 - ratio_tol) * friction * p
    status = np.full(p.shape, STICK, dtype=np.int8)
    status[at_limit & (plastic > slip_tol)] = SLIP
    status[p <= 0.0] = OPEN
    return status


@result
class CalculixDetails:
    """What a CalculiX run adds to its :class:`~microslip.fe.result.FELoopResult`.

    Attributes
    ----------
    case : FECase
        The load case as run (mesh, element, contact slopes, iteration limit).
    clamp_displacement : float
        Work-conjugate displacement caused by the clamping step alone, mm.
    pressure : ndarray, shape (k, m)
        Contact pressure at every state, MPa.
    shear : ndarray, shape (k, m, 2)
        Shear traction in x and y at every state, MPa.
    """

    case: FECase
    clamp_displacement: float
    pressure: FloatArray
    shear: FloatArray

    def options(self) -> dict[str, Any]:
        c = self.case
        return {"mesh": c.spec.label(), "graded": c.spec.graded, "element": c.element,
                "stick_slope": c.stick_slope,
                "normal_slope": c.normal_slope, "max_iterations": c.max_iterations,
                "nlgeom": c.nlgeom}

    def summary(self) -> dict[str, Any]:
        return {"clamp_displacement_mm": self.clamp_displacement}
