"""The two-mode study's ROM loaded quasi-statically (:mod:`.twomodecheck`): each contact node
a 2-D Jenkins element of the full FE's law, ``circular`` (one circular Coulomb limit,
:func:`~.contact.return_map`) or ``decoupled`` (two independent 1-D elements along e1, e2),
cycled under two loads in quadrature on :class:`~.meshrun.SineCycles`' increments.

Units: N, mm, N·mm.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..fe.builtin.contact import return_map
from ..fe.builtin.meshrun import SineCycles, VectorLoad
from .reduce import Rom

__all__ = ["RETURN_MAPS", "QuasiStatic", "rom_quasistatic"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def _time_samples(history: SineCycles, cycles: int) -> tuple[FloatArray, FloatArray, int]:
    """(t cycles, [cos, -sin] factors (k, 2), index of t = 0): the quadrature loads'
    time functions on :class:`SineCycles`' increments and start-up ramp."""
    loads = (VectorLoad(np.ones(1), 1.0, 90.0), VectorLoad(np.ones(1), 1.0, 180.0))
    t, f, k0 = history.samples(loads, cycles)
    return t, f, k0


def _work(g: FloatArray, u: FloatArray) -> float:
    """sum_j of the trapezoidal integral of g_j du_j over the samples (k, n), N·mm
    (:func:`microslip.energy.loop_work` per load)."""
    return float(np.sum(0.5 * (g[1:] + g[:-1]) * np.diff(u, axis=0)))


def _decoupled_map(g: FloatArray, slip: FloatArray, k: FloatArray, s: FloatArray
                   ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Two independent 1-D Jenkins elements per node: force (n, 2), tangent (n, 3) as
    (D_xx, D_xy, D_yy), new slip."""
    trial = k[:, None] * (g - slip)
    slipping = np.abs(trial) > s[:, None]
    force = np.where(slipping, np.sign(trial) * s[:, None], trial)
    tangent = np.stack([np.where(slipping[:, 0], 0.0, k), np.zeros_like(k),
                        np.where(slipping[:, 1], 0.0, k)], axis=1)
    new = np.where(slipping, g - force / k[:, None], slip)
    return force, tangent, new


def _circular_map(g: FloatArray, slip: FloatArray, k: FloatArray, s: FloatArray
                  ) -> tuple[FloatArray, FloatArray, FloatArray]:
    r = return_map(g, slip, k, s)
    return r.force, r.tangent, r.slip


#: Coupling -> the node law's return map (force, tangent, slip).
RETURN_MAPS = {"circular": _circular_map, "decoupled": _decoupled_map}


#: Newton iterations per (sub-)increment, and halvings of a failed increment.
MAX_ITERATIONS = 50
MAX_CUTS = 6

Law = Callable[[FloatArray, FloatArray, FloatArray, FloatArray],
               tuple[FloatArray, FloatArray, FloatArray]]


def _newton(kbb: FloatArray, law: Law, k: FloatArray, s: FloatArray, u: FloatArray,
            slip: FloatArray, g: FloatArray, tol: float
            ) -> tuple[FloatArray, FloatArray] | None:
    """K_bb u + f(u; slip) = g by Newton with the law's consistent tangent: (u, new slip)
    or None."""
    rows = np.arange(k.size) * 2
    for _ in range(MAX_ITERATIONS):
        force, tan, new = law(u.reshape(-1, 2), slip, k, s)
        r = g - kbb @ u - force.reshape(-1)
        if float(np.max(np.abs(r))) <= tol:
            return u, new
        jac = kbb.copy()
        jac[rows, rows] += tan[:, 0]
        jac[rows, rows + 1] += tan[:, 1]
        jac[rows + 1, rows] += tan[:, 1]
        jac[rows + 1, rows + 1] += tan[:, 2]
        try:
            u = u + np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            return None
    return None


def _increment(kbb: FloatArray, law: Law, k: FloatArray, s: FloatArray, u: FloatArray,
               slip: FloatArray, g0: FloatArray, g1: FloatArray, tol: float, cuts: int
               ) -> tuple[FloatArray, FloatArray] | None:
    """The load step g0 -> g1, halved (up to ``cuts`` times) where Newton fails."""
    done = _newton(kbb, law, k, s, u, slip, g1, tol)
    if done is not None or cuts == 0:
        return done
    mid = 0.5 * (g0 + g1)
    half = _increment(kbb, law, k, s, u, slip, g0, mid, tol, cuts - 1)
    if half is None:
        return None
    return _increment(kbb, law, k, s, half[0], half[1], mid, g1, tol, cuts - 1)


@dataclass(frozen=True)
class QuasiStatic:
    """W per cycle of a structure loaded quasi-statically (N·mm), per cycle run, and whether
    it settled."""

    energy_Nmm: float
    work_per_cycle: tuple[float, ...]
    settled: bool


def rom_quasistatic(rom: Rom, load: ComplexArray, coupling: str,
                    history: SineCycles | None = None) -> QuasiStatic:
    """The ROM loaded quasi-statically by ``Re(load e^{2 pi i t})`` (N), cycles until W per
    cycle settles as :class:`SineCycles` says.

    Notes
    -----
    Craig-Bampton's K_r is block-diagonal (boundary, modes): the boundary solves
    K_bb u + f_J(u) = g_b by Newton with the node laws' consistent tangents
    (:data:`RETURN_MAPS`), the modes are elastic and do no work over a cycle. W is the
    loads' work, trapezoidal over the increments, as the full FE's.
    """
    history = SineCycles() if history is None else history
    law = RETURN_MAPS[coupling]
    nb = rom.boundary.size
    kbb = rom.stiffness[:nb, :nb]
    gb = np.stack([load[:nb].real, load[:nb].imag], axis=1)  # cos and -sin columns
    k, s = rom.contact_stiffness, rom.slip_force
    _, f, k0 = _time_samples(history, history.max_cycles)
    g_all = f @ gb.T  # (k, nb), N
    n = history.increments
    tol = 1e-10 * float(np.sum(s))  # N: the residual, against mu F_N
    u = np.zeros(nb)
    slip = np.zeros((k.size, 2))
    states = np.zeros_like(g_all)
    works: list[float] = []
    previous = np.zeros(nb)
    for i, g in enumerate(g_all):
        step = _increment(kbb, law, k, s, u, slip, previous, g, tol, MAX_CUTS)
        if step is None:
            raise ParameterError(f"the ROM's quasi-static increment {i} did not converge "
                                 f"({coupling} joints), even cut into {2**MAX_CUTS}: is "
                                 "the load more than the friction holds?")
        u, slip = step
        previous = g
        states[i] = u
        c = (i - k0) // n
        if i > k0 and (i - k0) % n == 0:
            a = k0 + (c - 1) * n
            works.append(_work(g_all[a:i + 1], states[a:i + 1]))
            if len(works) >= history.min_cycles and abs(works[-1] - works[-2]) <= (
                    history.tol * abs(works[-1])):
                return QuasiStatic(works[-1], tuple(works), True)
    return QuasiStatic(works[-1], tuple(works), False)
