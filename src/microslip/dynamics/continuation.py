"""Newton's method and pseudo-arclength continuation of a solution curve R(y) = 0.

``y`` has one more entry than ``R`` (the continuation parameter is the last one, e.g. the
frequency); ``fun(y)`` returns ``R`` and its Jacobian ``dR/dy`` of shape (n, n + 1). Lengths
along the curve are measured in a weighted norm, ``|dy|_W^2 = sum (dy_i / scale_i)^2``, so
that coefficients in mm and a frequency in rad/s count alike; ``scale`` may be updated after
every accepted point (e.g. with the amplitude reached so far).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.linalg.lapack import dgetrf, dgetrs

from ..named import result

__all__ = ["Corrector", "Curve", "arclength", "newton"]

Array = NDArray[np.float64]
Fun = Callable[[Array], tuple[Array, Array]]
#: ``(y_pred, row, scale, tol) -> (y, converged, [dR/dy; row])``: Newton on the
#: pseudo-arclength system ``[R(y); row . (y - y_pred)] = 0`` from ``y_pred``.
Corrector = Callable[[Array, Array, Array, float], tuple[Array, bool, Array]]

#: Newton iterations at most per corrector.
MAX_ITERATIONS = 12

#: Contraction below which Newton's error estimate is trusted, and halvings of a step that
#: increases the residual (shared with the compiled corrector, :mod:`.hbkernel`).
CONTRACTION, MAX_HALVINGS = 0.5, 10

#: Relative step below which a sharp turn of the tangent is accepted as a kink of the curve.
KINK_STEP = 1.0 / 64.0


@result
class Curve:
    """Points of a continued solution curve.

    Attributes
    ----------
    points : ndarray, shape (m, n + 1)
        Converged points y along the curve, in order.
    success : bool
        True if the curve reached its end condition.
    message : str
        Why the continuation stopped.
    """

    points: np.ndarray
    success: bool
    message: str


def newton(fun: Callable[[Array], tuple[Array, Array]], y0: Array, scale: Array,
           tol: float, max_iter: int = MAX_ITERATIONS,
           factors: list[tuple[Array, Array]] | None = None) -> tuple[Array, bool, Array]:
    """Solve the square system ``fun(y) = (r, dr/dy) = 0`` from ``y0``.

    Converged when the error left after a Newton step, estimated from the contraction
    ``theta = |dy_k| / |dy_k-1|`` as ``|dy_k| theta / (1 - theta)`` (``theta <
    CONTRACTION``), or the step itself, is below ``tol`` in the norm ``max |dy / scale|``;
    that last step is taken without evaluating ``fun`` again (Deuflhard's a-posteriori
    estimate for a contracting Newton iteration). A step that increases the residual norm
    is halved (up to ``MAX_HALVINGS`` times). Returns the solution, whether it converged,
    and the Jacobian at the last iterate evaluated (one step from the solution); on
    convergence ``factors``, if given, receives that Jacobian's LU factors (LAPACK's
    ``dgetrf``), for more solves with it at O(n^2) each (the continuation's tangent).
    """
    y = np.array(y0, dtype=np.float64)
    r, jac = fun(y)
    previous = 0.0  # the size of the last full step, 0 before the first
    for _ in range(max_iter):
        step, info, lu = _factor_solve(jac, -r)
        if info != 0:  # singular
            return y, False, jac
        size = float(np.max(np.abs(step / scale)))
        theta = size / previous if previous > 0.0 else 1.0
        if size < tol or (theta < CONTRACTION and size * theta / (1.0 - theta) < tol):
            if factors is not None:
                factors[:] = [lu]
            y = y + step
            return y, bool(np.all(np.isfinite(y))), jac
        previous = size
        norm0 = float(r @ r)
        lam = 1.0
        for _ in range(MAX_HALVINGS):
            trial = y + lam * step
            r_new, jac_new = fun(trial)
            if float(r_new @ r_new) <= norm0 or lam * size < tol:
                break
            lam *= 0.5
        y, r, jac = trial, r_new, jac_new
        if not np.all(np.isfinite(r)):
            return y, False, jac
    return y, False, jac


def _solve(a: Array, b: Array) -> tuple[Array, int]:
    """``a^-1 b`` by LAPACK (a third of np.linalg.solve's overhead on the small systems
    here) and its ``info`` (> 0: ``a`` is singular)."""
    x, info, _ = _factor_solve(a, b)
    return x, info


def _factor_solve(a: Array, b: Array) -> tuple[Array, int, tuple[Array, Array]]:
    """``a^-1 b``, its ``info`` (> 0: ``a`` is singular) and the LU factors of ``a``: LAPACK's
    dgetrf and dgetrs, the two halves of dgesv (the same numbers)."""
    lu, piv, info = dgetrf(a)
    if info != 0:
        return b, int(info), (lu, piv)
    x, info = dgetrs(lu, piv, b)
    return x, int(info), (lu, piv)


def _tangent(jac: Array, previous: Array, scale: Array) -> Array:
    """Unit tangent (weighted norm) of the curve, oriented like ``previous``."""
    n = jac.shape[0]
    aug = np.empty((n + 1, n + 1))
    aug[:n] = jac
    aug[n] = previous / scale**2
    return _oriented(aug, scale)


def _oriented(aug: Array, scale: Array, lu: tuple[Array, Array] | None = None) -> Array:
    """The unit tangent (weighted norm) t with ``aug t = [0, ..., 0, 1]``, ``aug`` the
    Jacobian with the previous tangent's row ``previous / scale^2`` appended (``lu``: its
    LU factors if known, which skips the factorization)."""
    rhs = np.zeros(aug.shape[0])
    rhs[-1] = 1.0
    if lu is None:
        t, info = _solve(aug, rhs)
    else:
        t, info = dgetrs(*lu, rhs)
    if info != 0:
        raise np.linalg.LinAlgError("Singular matrix")
    return np.asarray(t / np.sqrt(np.sum((t / scale) ** 2)))


def arclength(fun: Fun, y0: Array, direction: Array, step: float,
              stop: Callable[[Array], bool], scale: Array,
              rescale: Callable[[Array, Array], Array] | None = None, *,
              tol: float = 1e-10, min_step: float | None = None,
              max_points: int = 10_000, corrector: Corrector | None = None) -> Curve:
    """Pseudo-arclength continuation from the solution ``y0`` of ``fun(y)[0] = 0``.

    Parameters
    ----------
    fun : callable
        ``y -> (R (n,), dR/dy (n, n + 1))``.
    y0 : ndarray, shape (n + 1,)
        A converged starting point.
    direction : ndarray, shape (n + 1,)
        Initial orientation (only its sign against the first tangent matters).
    step : float
        Largest step along the curve (weighted norm).
    stop : callable
        ``y -> True`` when the curve has reached its end (the point is kept).
    scale : ndarray, shape (n + 1,)
        Weights of the norm; ``rescale(y, scale)`` may return new ones after each point.
    tol : float
        Newton tolerance in the weighted max norm.
    min_step : float
        Smallest step before giving up (default step / 1024).
    max_points : int
        Largest number of points.
    corrector : callable, optional
        A compiled equivalent of the default corrector, :func:`newton` (``MAX_ITERATIONS``)
        on ``fun`` augmented by the arclength row (e.g.
        :meth:`~.hb.HarmonicBalance.corrector`); same algorithm, same results.

    Notes
    -----
    Predictor ``y_p = y + h t`` with t the unit tangent (null vector of dR/dy), corrector
    Newton on ``[R(y); t . W (y - y_p)] = 0`` (Keller's pseudo-arclength). The step h is
    halved when the corrector fails or the tangent turns by more than 30 degrees (unless the
    step is already below ``KINK_STEP * step``: a corner of a piecewise-smooth curve), and
    grows by 1.5 (up to ``step``) after every accepted point.
    """
    min_step = step / 1024.0 if min_step is None else min_step
    y = np.array(y0, dtype=np.float64)
    scale = np.array(scale, dtype=np.float64)
    _, jac = fun(y)
    t = _tangent(jac, direction, scale)
    points = [y.copy()]
    h = step
    n = y.size - 1
    factors: list[tuple[Array, Array]] = []  # the default corrector's last LU factors

    def augmented(y_pred: Array, row: Array, scale: Array, tol: float
                  ) -> tuple[Array, bool, Array]:
        def aug(z: Array) -> tuple[Array, Array]:
            r, j = fun(z)
            # column-major: LAPACK factors it without a transposing copy
            r_aug, j_aug = np.empty(n + 1), np.empty((n + 1, n + 1), order="F")
            r_aug[:n] = r
            r_aug[n] = row @ (z - y_pred)
            j_aug[:n] = j
            j_aug[n] = row
            return r_aug, j_aug
        return newton(aug, y_pred, scale, tol, factors=factors)

    correct = augmented if corrector is None else corrector
    while len(points) < max_points:
        y_pred = y + h * t
        factors.clear()
        y_new, ok, jac = correct(y_pred, t / scale**2, scale, tol)
        t_new = t
        if ok:  # its last row is t / scale^2; factored by the corrector's last step
            t_new = _oriented(jac, scale, factors[0] if factors else None)
            # a kink of the curve (an element starting to slip) turns the tangent at any h
            ok = (float((t_new / scale) @ (t / scale)) > np.cos(np.pi / 6.0)
                  or h <= KINK_STEP * step)
        if not ok:
            h *= 0.5
            if h < min_step:
                return Curve(np.array(points), False,
                             f"step fell below {min_step:.3g} at parameter {y[-1]:.6g}")
            continue
        y, t = y_new, t_new
        points.append(y.copy())
        if stop(y):
            return Curve(np.array(points), True, "reached the end of the range")
        h = min(1.5 * h, step)
        if rescale is not None:
            scale = rescale(y, scale)
            t = t / np.linalg.norm(t / scale)
    return Curve(np.array(points), False, f"stopped after {max_points} points")
