"""Time integration to steady state: the reference harmonic balance is checked against.

A one-degree-of-freedom structure with Iwan joints (parallel Jenkins elements) under
``F cos(w t)``, integrated by Newmark's average-acceleration rule (trapezoidal, second order,
unconditionally stable) with the elements' return mapping solved exactly in every step
(:func:`steady_state`); any structure, with 1-D and two-directional joints, by
explicit central differences (:func:`transient`).

Units: mass kg, displacement mm, force N, frequency Hz.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..errors import ParameterError
from ..named import result
from .kernels2d import return_map
from .operators import IwanOperator
from .operators2d import CircularIwan
from .structure import SI_PER_MM, Structure

__all__ = ["SteadyState", "steady_state", "transient"]


@result
class SteadyState:
    """The last period of a long time integration.

    Attributes
    ----------
    frequency : float
        Excitation frequency, Hz.
    displacement : ndarray, shape (steps,) or (keep steps, n_dof)
        Displacement over the last period, mm (at t = (j + 1) T / steps): of the one mode
        (:func:`steady_state`) or of every DOF over the last ``keep`` periods
        (:func:`transient`).
    amplitude : float
        First-harmonic amplitude over the last period, mm (for :func:`transient`, of the
        structure's output coordinate).
    change : float
        Relative change of that first harmonic over the last period (how settled it is).
    periods, steps : int
        Periods integrated and time steps per period.
    """

    frequency: float
    displacement: np.ndarray
    amplitude: float
    change: float
    periods: int
    steps: int


@njit(cache=True, nogil=True)
def _joint(u: float, k: np.ndarray, phi: np.ndarray, z: np.ndarray, z_new: np.ndarray
           ) -> tuple[float, float]:
    """Force (N) and tangent (N/mm) at joint displacement u from slider positions z."""
    f = 0.0
    kt = 0.0
    for e in range(k.size):
        ze = z[e]
        if u - ze > phi[e]:
            ze = u - phi[e]
        elif u - ze < -phi[e]:
            ze = u + phi[e]
        else:
            kt += k[e]
        z_new[e] = ze
        f += k[e] * (u - ze)
    return f, kt


@njit(cache=True, nogil=True)
def _newmark(m: float, c: float, kl: float, p: float, k: np.ndarray, phi: np.ndarray,
             force: float, omega: float, dt: float, steps: int, x_out: np.ndarray) -> None:
    """Integrate from rest (virgin joint) for ``x_out.size`` steps; mass N s^2/mm,
    damping N s/mm, stiffness N/mm."""
    x, v = 0.0, 0.0
    z = np.zeros(k.size)
    z_new = np.zeros(k.size)
    a = 0.0
    k_eff = 4.0 * m / dt**2 + 2.0 * c / dt + kl
    for n in range(steps):
        t = (n + 1) * dt
        rhs = (force * math.cos(omega * t) + m * (4.0 * x / dt**2 + 4.0 * v / dt + a)
               + c * (2.0 * x / dt + v))
        # g(y) = k_eff y + p f(p y) - rhs is increasing and piecewise linear: Newton,
        # safeguarded by bisection inside a bracket
        y = x + dt * v
        lo, hi = -np.inf, np.inf
        for _ in range(200):
            f, kt = _joint(p * y, k, phi, z, z_new)
            g = k_eff * y + p * f - rhs
            if g == 0.0:
                break
            if g > 0.0:
                hi = min(hi, y)
            else:
                lo = max(lo, y)
            y_next = y - g / (k_eff + p * p * kt)
            if not lo < y_next < hi and hi - lo < np.inf:
                y_next = 0.5 * (lo + hi)
            if abs(y_next - y) <= 1e-15 * (abs(y) + 1e-300):
                y = y_next
                break
            y = y_next
        _joint(p * y, k, phi, z, z_new)
        z[:] = z_new
        a_new = 4.0 * (y - x) / dt**2 - 4.0 * v / dt - a
        v = v + 0.5 * dt * (a + a_new)
        a = a_new
        x = y
        x_out[n] = x


def steady_state(structure: Structure, force: float, frequency: float, periods: int,
                 steps: int = 1000) -> SteadyState:
    """Integrate ``structure`` (one degree of freedom, Iwan joints) from rest under
    ``force cos(2 pi frequency t)`` for ``periods`` periods of ``steps`` steps each.

    Notes
    -----
    Newmark, gamma = 1/2, beta = 1/4: ``x_{n+1} = x_n + dt v_n + dt^2 (a_n + a_{n+1}) / 4``,
    ``v_{n+1} = v_n + dt (a_n + a_{n+1}) / 2``, equilibrium at t_{n+1} solved for x_{n+1}
    with the Jenkins return mapping from the sliders of step n (exact: a piecewise linear,
    increasing equation). Global error O(dt^2).
    """
    if structure.dofs != 1 or len(structure.joints) != 1:
        raise ParameterError("time integration is implemented for one degree of freedom and "
                             "one joint")
    op = structure.joints[0].operator
    if not isinstance(op, IwanOperator):
        raise ParameterError(f"time integration needs an Iwan joint, got {type(op).__name__}")
    if not (isinstance(periods, int) and periods >= 2 and isinstance(steps, int)
            and steps >= 16):
        raise ParameterError(f"need periods >= 2 and steps >= 16, got {periods}, {steps}")
    omega = 2.0 * np.pi * frequency
    x = np.empty(periods * steps)
    _newmark(SI_PER_MM * float(structure.mass[0, 0]), SI_PER_MM * float(structure.damping[0, 0]),
             SI_PER_MM * float(structure.stiffness[0, 0]),
             float(structure.joints[0].participation[0]), np.asarray(op.stiffness),
             np.asarray(op.slip), float(force), omega, 2.0 * np.pi / omega / steps,
             periods * steps, x)
    last, before = x[-steps:], x[-2 * steps:-steps]
    theta = 2.0 * np.pi * np.arange(1, steps + 1) / steps
    basis = np.exp(-1j * theta) * (2.0 / steps)
    h_last, h_before = last @ basis, before @ basis
    return SteadyState(frequency=float(frequency), displacement=last,
                       amplitude=float(abs(h_last)),
                       change=float(abs(h_last - h_before) / abs(h_last)),
                       periods=periods, steps=steps)


@njit(cache=True, nogil=True)
def _joint_forces(x: np.ndarray, rows: np.ndarray, first_row: np.ndarray,
                  first_el: np.ndarray, k: np.ndarray, ky: np.ndarray, phi: np.ndarray,
                  z: np.ndarray, g: np.ndarray) -> None:
    """Generalised joint forces ``g`` (N) at ``x`` (mm); sliders ``z`` (mm) stepped in
    place (1-D return mapping or the 2-D return map of :mod:`.kernels2d`, by the joint's
    number of rows)."""
    g[:] = 0.0
    for j in range(first_row.size - 1):
        r0 = first_row[j]
        d = first_row[j + 1] - r0
        ux = rows[r0] @ x
        uy = rows[r0 + 1] @ x if d == 2 else 0.0
        fx = 0.0
        fy = 0.0
        for e in range(first_el[j], first_el[j + 1]):
            if d == 1:
                if ux - z[e, 0] > phi[e]:
                    z[e, 0] = ux - phi[e]
                elif ux - z[e, 0] < -phi[e]:
                    z[e, 0] = ux + phi[e]
                fx += k[e] * (ux - z[e, 0])
            elif k[e] > 0.0:
                zx, zy = return_map(ux, uy, z[e, 0], z[e, 1], ky[e] / k[e], phi[e])
                z[e, 0], z[e, 1] = zx, zy
                fx += k[e] * (ux - zx)
                fy += ky[e] * (uy - zy)
        g += fx * rows[r0]
        if d == 2:
            g += fy * rows[r0 + 1]


@njit(cache=True, nogil=True)
def _central_difference(a_inv: np.ndarray, m2: np.ndarray, c2: np.ndarray, kl: np.ndarray,
                        load: np.ndarray, omega: float, dt: float, rows: np.ndarray,
                        first_row: np.ndarray, first_el: np.ndarray, k: np.ndarray,
                        ky: np.ndarray, phi: np.ndarray, x0: np.ndarray, x_before: np.ndarray,
                        out: np.ndarray) -> None:
    """Integrate from x_0 = ``x0`` and x_-1 = ``x_before`` (the sliders at zero) under
    the load ``load`` (n, 2H + 1: harmonic coefficients c_0, c_1, s_1, ..., N);
    ``out`` (steps, n) receives x_1 ... x_steps (mm)."""
    x_prev = x_before.copy()
    x = x0.copy()
    z = np.zeros((k.size, 2))
    g = np.zeros(x0.size)
    h = load.shape[1]
    basis = np.zeros(h)
    basis[0] = 1.0
    for s in range(out.shape[0]):
        _joint_forces(x, rows, first_row, first_el, k, ky, phi, z, g)
        for j in range(1, (h + 1) // 2):
            basis[2 * j - 1] = math.cos(j * omega * s * dt)
            basis[2 * j] = math.sin(j * omega * s * dt)
        rhs = (load @ basis - kl @ x - g + m2 @ (2.0 * x - x_prev) + c2 @ x_prev)
        x_prev = x
        x = a_inv @ rhs
        out[s] = x


def transient(structure: Structure, load: np.ndarray, frequency: float, periods: int,
              steps: int = 1000, initial: tuple[np.ndarray, np.ndarray] | None = None,
              keep: int = 1) -> SteadyState:
    """Integrate ``structure`` (any degrees of freedom, 1-D Iwan and 2-D joints) from
    rest under ``load cos(2 pi frequency t)`` (N per degree of freedom), or, ``load`` of
    shape (n_dof, 2H + 1), under the periodic load of those harmonic coefficients (the
    layout of :mod:`.hb`: c_0, c_1, s_1, ..., c_H, s_H; N).

    ``initial`` = (x_0, v_0) (mm, mm/s) starts it there instead (x_-1 = x_0 - dt v_0, the
    joints' sliders at zero: a state at rest relative to the sliders, e.g. a turning point
    of a periodic orbit, which a negative damping ``C = -xi M`` and no load then follow,
    :func:`~microslip.dynamics.modal.epmc`'s autonomous system); ``displacement`` holds the
    last ``keep`` periods.

    Notes
    -----
    Central differences, ``M (x_{n+1} - 2 x_n + x_{n-1}) / dt^2 + C (x_{n+1} - x_{n-1}) /
    (2 dt) + K x_n + g(x_n) = p(t_n)``, explicit (second order, stable for
    dt < 2 / w_max with w_max the highest stuck frequency: ``steps`` is raised to
    4 pi w_max / w if needed), the joints' sliders stepped by the exact return mapping (1-D)
    or the 2-D return map (:mod:`.kernels2d`, radial return if isotropic) at every step, as
    the harmonic balance's AFT does at its samples.
    """
    if not (isinstance(periods, int) and periods >= 2 and isinstance(steps, int)
            and steps >= 16):
        raise ParameterError(f"need periods >= 2 and steps >= 16, got {periods}, {steps}")
    if not (isinstance(keep, int) and 1 <= keep <= periods):
        raise ParameterError(f"keep must be a whole number in [1, {periods}], got {keep!r}")
    omega = 2.0 * np.pi * frequency
    w_max = 2.0 * np.pi * float(structure.linear_frequencies(stuck=True)[-1])
    steps = max(steps, int(np.ceil(4.0 * np.pi * w_max / omega)))
    dt = 2.0 * np.pi / omega / steps
    m2 = SI_PER_MM * np.asarray(structure.mass) / dt**2
    c2 = SI_PER_MM * np.asarray(structure.damping) / (2.0 * dt)
    rows, first_row, first_el, k, ky, phi = _flatten_joints(structure)
    x = np.empty((periods * steps, structure.dofs))
    p = np.asarray(load, dtype=np.float64)
    if p.ndim == 1:
        p = np.column_stack([np.zeros_like(p), p, np.zeros_like(p)])
    if p.ndim != 2 or p.shape[0] != structure.dofs or p.shape[1] % 2 != 1:
        raise ParameterError(f"load must have shape ({structure.dofs},) or "
                             f"({structure.dofs}, 2H + 1), got {np.shape(load)}")
    x0, v0 = ((np.zeros(structure.dofs), np.zeros(structure.dofs)) if initial is None
              else (np.asarray(initial[0], dtype=np.float64),
                    np.asarray(initial[1], dtype=np.float64)))
    _central_difference(np.linalg.inv(m2 + c2), m2, c2,
                        SI_PER_MM * np.asarray(structure.stiffness, dtype=np.float64),
                        np.ascontiguousarray(p), omega, dt, rows, first_row,
                        first_el, k, ky, phi, x0, x0 - dt * v0, x)
    out = x @ structure.output
    last, before = out[-steps:], out[-2 * steps:-steps]
    theta = 2.0 * np.pi * np.arange(1, steps + 1) / steps
    basis = np.exp(-1j * theta) * (2.0 / steps)
    h_last, h_before = last @ basis, before @ basis
    return SteadyState(frequency=float(frequency), displacement=x[-keep * steps:],
                     amplitude=float(abs(h_last)),
                     change=float(abs(h_last - h_before) / abs(h_last)), periods=periods,
                     steps=steps)


def _flatten_joints(structure: Structure) -> tuple[np.ndarray, ...]:
    """Participation rows, each joint's first row and first element, element stiffness
    along x and y (N/mm) and slip displacement along x (mm)."""
    rows, first_row, first_el = [], [0], [0]
    ks, kys, phis = [np.zeros(0)], [np.zeros(0)], [np.zeros(0)]
    for link in structure.joints:
        op = link.operator
        if not isinstance(op, IwanOperator | CircularIwan):
            raise ParameterError(f"time integration needs Iwan joints, got {type(op).__name__}")
        rows.extend(link.weights.T)
        first_row.append(len(rows))
        ks.append(op.stiffness)
        kys.append(op.along(1).stiffness if isinstance(op, CircularIwan) else op.stiffness)
        phis.append(op.slip)
        first_el.append(first_el[-1] + op.stiffness.size)
    if not rows:
        rows.append(np.zeros(structure.dofs))
    return (np.array(rows, dtype=np.float64), np.array(first_row, dtype=np.int64),
            np.array(first_el, dtype=np.int64), np.concatenate(ks), np.concatenate(kys),
            np.concatenate(phis))
