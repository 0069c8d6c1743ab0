"""Nonlinear modal analysis: natural frequency and damping ratio versus vibration amplitude.

Two methods: the single-nonlinear-mode energy method (:func:`energy_method`, from each
joint's describing function along the stuck linear mode) and the extended periodic motion
concept with harmonic balance (:func:`epmc`, Krack 2015: several harmonics, the mode
shape free to change with amplitude). The amplitude is the first-harmonic amplitude of the
structure's output coordinate, mm.

Units: amplitude mm, frequency Hz, damping ratio (-).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eigh

from ..blas import single_threaded_blas
from ..errors import ParameterError
from ..named import result
from .continuation import newton
from .describing import DEFAULT_SAMPLES, describing_function
from .hb import DEFAULT_HB_SAMPLES, HarmonicBalance
from .operators import HystereticOperator
from .operators2d import CircularIwan
from .operators3d import Contact3D
from .structure import SI_PER_MM, Structure

__all__ = [
    "AMPLITUDE_COORDINATES",
    "METHODS",
    "MODAL_COORDINATE",
    "RESPONSE_SET_COORDINATE",
    "ModalCurve",
    "energy_method",
    "epmc",
    "quasi_static",
]

Array = NDArray[np.float64]

#: ``amplitude_coordinate`` of a modal curve's JSON: what its ``amplitude_mm`` measures.
#: A structure's output coordinate is the stuck mode's modal coordinate q (x = q phi;
#: :func:`~microslip.dynamics.assemble.modal_output`) for a one-mode structure or a
#: structure file; on a mesh it is the response set's mean displacement along the mode
#: (:mod:`microslip.meshdynamics`).
MODAL_COORDINATE = "modal"
RESPONSE_SET_COORDINATE = "response_set"
AMPLITUDE_COORDINATES = {
    MODAL_COORDINATE: "first harmonic of the stuck mode's modal coordinate q (x = q phi), mm",
    RESPONSE_SET_COORDINATE: "first harmonic of the response set's mean displacement along "
                             "the mode's direction, mm",
}

#: Newton tolerance of the extended periodic motion concept (relative).
TOLERANCE = 1e-11

#: Newton iterations at most at an amplitude of the grid, and at one in between (a Newton
#: run that has not converged in 20 wanders: a shorter step from a nearer start is cheaper
#: than more iterations; each is a dense LU of the whole balance).
MAX_NEWTON, MAX_SUBSTEP_NEWTON = 20, 15
#: Newton iterations at most at a point of the adaptive harmonics' ladder
#: (:mod:`.harmonics`: one try per level from the level below; no steps in between).
MAX_POINT_NEWTON = 50
#: Halvings (in log amplitude) at most of the step to an amplitude Newton does not reach
#: directly, and the first amplitude's first intermediate step from the stuck mode (ai / it).
SUBSTEPS, SUBSTEP_RATIO = 4, 16.0

#: Relative component across an axis below which the energy method takes an anisotropic
#: joint's motion as along that axis.
AXIS_TOLERANCE = 1e-9


@result
class ModalCurve:
    """Amplitude-dependent natural frequency and damping ratio of one mode.

    Attributes
    ----------
    method : str
        ``energy``, ``epmc`` or ``qsma`` (:func:`quasi_static`).
    amplitude : ndarray, shape (n,)
        First-harmonic amplitude of the output coordinate, mm.
    frequency : ndarray, shape (n,)
        Natural frequency, Hz.
    damping_ratio : ndarray, shape (n,)
        Modal damping ratio, linear damping included (-).
    harmonics : int
        Harmonics of the balance (1 for the energy method; with harmonics chosen per point,
        :mod:`.harmonics`, the most any point took).
    samples : int
        Time samples per period (of the describing function or the AFT scheme; with
        harmonics chosen per point, those of the point with the most harmonics).
    point_harmonics : ndarray of int, shape (n,), or None
        With harmonics chosen per point (:mod:`.harmonics`): each point's harmonics; None
        when fixed.
    harmonic_error_estimate : ndarray, shape (n,), or None
        With harmonics chosen per point: each point's estimated relative error from the
        truncation (:func:`~.harmonics.change`, the change from the next smaller harmonics
        of the ladder); None when fixed.
    """

    method: str
    amplitude: np.ndarray
    frequency: np.ndarray
    damping_ratio: np.ndarray
    harmonics: int
    samples: int
    point_harmonics: np.ndarray | None = None
    harmonic_error_estimate: np.ndarray | None = None


def stuck_mode(structure: Structure, mode: int = 0) -> tuple[Array, float, float, float]:
    """Linear mode ``mode`` (0-based, by frequency) with every joint stuck: shape
    (output . shape = 1), modal mass (kg), stiffness (N/m, joints removed) and damping
    (N·s/m)."""
    if not (isinstance(mode, int) and 0 <= mode < structure.dofs):
        raise ParameterError(f"mode must be in [1, {structure.dofs}] (1-based), got "
                             f"{mode + 1 if isinstance(mode, int) else mode!r}")
    _, vecs = eigh(structure.stuck_stiffness(), structure.mass)
    phi = vecs[:, mode]
    norm = float(structure.output @ phi)
    if abs(norm) <= 1e-12 * float(np.max(np.abs(phi))):
        raise ParameterError(f"the output coordinate does not move in stuck mode {mode + 1}")
    phi = phi / norm
    return (phi, float(phi @ structure.mass @ phi), float(phi @ structure.stiffness @ phi),
            float(phi @ structure.damping @ phi))


def energy_method(structure: Structure, amplitude: ArrayLike,
                  samples: int = DEFAULT_SAMPLES, mode: int = 0) -> ModalCurve:
    """Frequency and damping ratio from the joints' describing functions.

    Notes
    -----
    Along the stuck mode shape phi (output . phi = 1) of modal mass m, stiffness k and
    damping c, a joint with participation p = W^T phi (one entry per direction) moves on
    a line with amplitude |p| a and adds |p|^2 K_eq and |p|^2 D_eq (N/mm, x 1e3 to N/m):
    w^2 = (k + sum |p|^2 K_eq) / m and zeta = (c w + sum |p|^2 D_eq) / (2 m w^2)
    = zeta_lin + W_d / (2 pi m w^2 a^2) (REFERENCES.md, 1-DOF single-harmonic balance).
    A circular two-directional joint on a line is its 1-D operator (isotropic: on any line;
    anisotropic: only along x or y, :meth:`~.CircularIwan.along`; on another line its force
    turns away from the line, and the energy method refuses: use :func:`epmc`). Exact
    single-harmonic balance for one degree of freedom.
    """
    a = _amplitudes(amplitude)
    phi, m, k, c = stuck_mode(structure, mode)
    k_eq = np.full(a.size, k)
    d_eq = np.zeros(a.size)
    for link in structure.joints:
        p = float(np.linalg.norm(link.weights.T @ phi))
        if p == 0.0:
            continue
        op = link.operator
        if isinstance(op, Contact3D):
            raise ParameterError("the energy method takes 1-D and 2-D joints; a 3-D contact "
                                 "element needs epmc")
        line = (_on_line(op, link.weights.T @ phi / p) if isinstance(op, CircularIwan)
                else op)
        df = describing_function(line, p * a, samples)
        k_eq += p * p * df.stiffness / SI_PER_MM
        d_eq += p * p * df.damping / SI_PER_MM
    omega = np.sqrt(k_eq / m)
    return ModalCurve(method="energy", amplitude=a, frequency=omega / (2.0 * np.pi),
                      damping_ratio=(c * omega + d_eq) / (2.0 * m * omega**2), harmonics=1,
                      samples=samples)


def _on_line(op: CircularIwan, direction: Array) -> HystereticOperator:
    """The 1-D operator of a 2-D joint moving along the unit vector ``direction``."""
    if op.isotropic:
        return op.axial
    for axis in (0, 1):
        if abs(direction[1 - axis]) <= AXIS_TOLERANCE:
            return op.along(axis)
    raise ParameterError(f"the energy method needs the anisotropic joint {op.name!r} to move "
                         f"along x or y, the mode moves it along ({direction[0]:.3g}, "
                         f"{direction[1]:.3g}): use epmc")


def epmc(structure: Structure, amplitude: ArrayLike, harmonics: int,
         samples: int = DEFAULT_HB_SAMPLES, mode: int = 0, *,
         failures: list[str] | None = None) -> ModalCurve:
    """Frequency and damping ratio by the extended periodic motion concept.

    Notes
    -----
    The autonomous system ``M q'' + (C - xi M) q' + K q + joints = 0`` has periodic
    solutions once the artificial negative damping xi balances the dissipation; harmonic
    balance with the amplitude constraint ``output . c_1 = a`` and the phase constraint
    ``output . s_1 = 0`` gives X, w and xi, and the modal damping ratio is
    ``zeta = xi / (2 w)`` (Krack 2015). Each amplitude starts Newton's method from the
    previous one (the first from the stuck linear mode); where Newton does not reach it, from
    amplitudes in between (halving the step in log amplitude, up to ``SUBSTEPS`` times).
    An amplitude that is still not reached raises, or, with ``failures`` given, is NaN, its
    reason appended to ``failures``, and the next amplitude starts from the last point
    reached.
    """
    with single_threaded_blas():  # small dense solves: threads cost 10x on a shared machine
        return _epmc(structure, _amplitudes(amplitude), harmonics, samples, mode,
                     failures=failures)


def _epmc(structure: Structure, a: Array, harmonics: int, samples: int, mode: int,
          odd: bool = False, failures: list[str] | None = None) -> ModalCurve:
    """EPMC on every harmonic, or (``odd``) on the odd ones only, the even ones held at zero
    (:func:`.modal_odd.epmc_odd`; the balance itself is then built on the odd harmonics,
    :class:`~.hb.HarmonicBalance`)."""
    hb = HarmonicBalance(structure, harmonics, samples, odd=odd)
    m_k = hb.size
    guess, omega0 = epmc_start(structure, hb, mode)
    freq = np.empty(a.size)
    zeta = np.empty(a.size)
    balances = {harmonics: hb}

    def lower(h: int) -> HarmonicBalance:
        """The balance one level down the ladder 1, 3, 7, 15, ... ((h - 1) / 2 harmonics)."""
        low = (h - 1) // 2
        if low not in balances:
            balances[low] = HarmonicBalance(structure, low, samples, odd=odd)
        return balances[low]

    def solve(b: HarmonicBalance, start: Array, previous: float, ai: float, max_iter: int
              ) -> tuple[Array, bool]:
        """Newton at amplitude ``ai`` from the point ``start`` at amplitude ``previous``
        (its harmonics scaled by ai / previous)."""
        g = start.copy()
        g[:b.size] *= ai / previous
        return epmc_newton(b, ai, g, omega0, max_iter)

    def reach(b: HarmonicBalance, start: Array, previous: float | None, ai: float,
              depth: int = 0) -> tuple[Array, bool]:
        """Newton at ``ai`` from the last point (``previous`` None: the stuck mode, exact as
        the amplitude goes to 0); if it fails, from the same point reached with fewer
        harmonics (:func:`_from_fewer`), then through amplitudes in between (the geometric
        mean, or ai / SUBSTEP_RATIO from the stuck mode), halving the step in log amplitude
        up to SUBSTEPS times: contact nodes that open, close or start slipping make the
        balance piecewise smooth, and Newton from too far a start wanders."""
        y, ok = solve(b, start, 1.0 if previous is None else previous, ai,
                      MAX_NEWTON if depth == 0 else MAX_SUBSTEP_NEWTON)
        if ok:
            return y, ok
        if depth == 0 and b.harmonics >= 3:
            y_low, ok = _from_fewer(b, lower(b.harmonics), start, previous, ai, reach)
            if ok:
                y, ok = epmc_newton(b, ai, y_low, omega0, MAX_NEWTON)
                if ok:
                    return y, ok
        if depth >= SUBSTEPS:
            return y, False
        mid = ai / SUBSTEP_RATIO if previous is None else float(np.sqrt(previous * ai))
        y_mid, ok = reach(b, start, previous, mid, depth + 1)
        if not ok:
            return y_mid, False
        return reach(b, y_mid, mid, ai, depth + 1)

    previous: float | None = None
    for i, ai in enumerate(a):
        y, ok = reach(hb, guess, previous, float(ai))
        if not ok:
            why = (f"the extended periodic motion concept did not converge at amplitude "
                   f"{ai:.6g} mm")
            if failures is None:
                raise ParameterError(why)
            failures.append(why)
            freq[i] = zeta[i] = np.nan
            continue
        freq[i] = y[m_k] / (2.0 * np.pi)
        zeta[i] = y[m_k + 1] / (2.0 * y[m_k])
        guess, previous = y, float(ai)
    return ModalCurve(method="epmc", amplitude=a, frequency=freq, damping_ratio=zeta,
                      harmonics=harmonics, samples=samples)


def _from_fewer(b: HarmonicBalance, low: HarmonicBalance, start: Array,
                previous: float | None, ai: float,
                reach: Callable[..., tuple[Array, bool]]) -> tuple[Array, bool]:
    """The point at amplitude ``ai`` reached on the balance ``low`` (fewer harmonics, from
    ``start`` truncated to them), as a start on ``b``: its harmonics, the ones ``low`` lacks
    zero, and its frequency and negative damping.

    Where open contact nodes close (a penalty normal law's kink) Newton on 7 harmonics
    wanders from the previous point (frequency iterates of -2900 and 8500 Hz on the bracket
    at 0.016 mm, a residual stuck at 1e2) where 3 harmonics, whose balance is smoother,
    reach the point, and 7 converge from it (1861.45 Hz)."""
    dofs = b.structure.dofs
    full = b.expand(start[:b.size]).reshape(dofs, 2 * b.harmonics + 1)
    x = low.restrict(np.ascontiguousarray(full[:, :2 * low.harmonics + 1]).ravel())
    y_low, ok = reach(low, np.concatenate([x, start[b.size:]]), previous, ai)
    if not ok:
        return y_low, False
    out = np.zeros((dofs, 2 * b.harmonics + 1))
    out[:, :2 * low.harmonics + 1] = low.expand(y_low[:low.size]).reshape(dofs, -1)
    return np.concatenate([b.restrict(out.ravel()), y_low[low.size:]]), True


def epmc_start(structure: Structure, hb: HarmonicBalance, mode: int) -> tuple[Array, float]:
    """The EPMC's unknowns ``[x, w, xi]`` on the stuck linear mode ``mode`` at unit output
    amplitude (mm, rad/s, 1/s), in ``hb``'s layout, and the stuck frequency (rad/s)."""
    m_k, j = hb.size, hb.first
    phi, m, _, c = stuck_mode(structure, mode)
    omega0 = float(np.sqrt(phi @ structure.stuck_stiffness() @ phi / m))
    first = np.zeros((structure.dofs, hb.width))
    first[:, j] = phi
    guess = np.zeros(m_k + 2)
    guess[:m_k] = first.ravel()
    guess[m_k], guess[m_k + 1] = omega0, c / m
    return guess, omega0


def epmc_newton(hb: HarmonicBalance, amplitude: float, guess: Array, omega0: float,
                max_iter: int = MAX_NEWTON) -> tuple[Array, bool]:
    """Newton's method on the EPMC's unknowns ``y = [x, w, xi]`` (mm, rad/s, 1/s) at the
    output's first-harmonic amplitude ``amplitude`` (mm) from ``guess``; ``omega0`` (rad/s)
    scales the frequency and negative damping. Returns y and whether it converged."""
    structure = hb.structure
    m_k, j = hb.size, hb.first
    out = np.zeros((2, structure.dofs, hb.width))
    out[0, :, j] = structure.output
    out[1, :, j + 1] = structure.output
    rows = np.zeros((2, m_k + 2))
    rows[:, :m_k] = out.reshape(2, -1)
    load = np.zeros(m_k)

    def fun(y: Array) -> tuple[Array, Array]:
        # the balance writes its rows in place, column-major: LAPACK factors it as it is
        jac = np.zeros((m_k + 2, m_k + 2), order="F")
        res = hb.residual(y[:m_k], float(y[m_k]), load, float(y[m_k + 1]),
                          out=jac[:m_k, :m_k + 1])
        jac[:m_k, m_k + 1] = res.dxi
        jac[m_k:] = rows
        return np.concatenate([res.r, rows @ y - (amplitude, 0.0)]), jac

    scale = np.concatenate([np.full(m_k, amplitude), [omega0, omega0]])
    y, ok, _ = newton(fun, guess, scale, TOLERANCE, max_iter=max_iter)
    return np.asarray(y), bool(ok)


def epmc_point(hb: HarmonicBalance, amplitude: float, guess: Array, omega0: float) -> Array:
    """:func:`epmc_newton` that raises :class:`ParameterError` where Newton does not
    converge (the adaptive harmonics' step, :mod:`.harmonics`)."""
    y, ok = epmc_newton(hb, amplitude, guess, omega0, MAX_POINT_NEWTON)
    if not ok:
        raise ParameterError(f"the extended periodic motion concept did not converge at "
                             f"amplitude {amplitude:.6g} mm")
    return y


def quasi_static(structure: Structure, force: ArrayLike, harmonics: int,
                 samples: int = DEFAULT_HB_SAMPLES, mode: int = 0) -> ModalCurve:
    """Frequency and damping ratio by quasi-static modal analysis (Lacayo and Allen 2019) on
    the structure, the method :mod:`microslip.meshdynamics.qsma` applies to the full FE.

    Notes
    -----
    The stuck mode phi (mass-normalised in t: phi^T M phi = 1, output . phi > 0) gives the
    load ``q sin(theta) M phi`` (modal force q, sqrt(t)·mm/s^2, as the full FE's); the
    periodic response without inertia, ``K x + joints(x) = q sin(theta) M phi``, is solved
    by harmonic balance at w = 0 (H harmonics, the AFT's ``samples``; the odd harmonics only
    when every joint force is odd: no 3-D contact element). With eta = phi^T M x, eta_1 its
    first harmonic: a = |eta_1|, w^2 = Re(q_1 conj(eta_1)) / a^2 (the first-harmonic modal
    stiffness, as the EPMC defines the frequency), W = -pi q (phi^T M c_1) the load's work
    per cycle and zeta = W / (2 pi a^2 w^2); ``amplitude`` is the output's first harmonic.
    Against :func:`epmc` on the same structure it separates the quasi-static method from
    the dynamics (the EPMC's mode shape and harmonics free to change with amplitude).
    """
    q = np.asarray(force, dtype=np.float64).reshape(-1)
    if not (q.size and np.all(np.isfinite(q)) and np.all(q > 0.0)):
        raise ParameterError("modal forces must be finite and > 0")
    with single_threaded_blas():
        return _quasi_static(structure, q, harmonics, samples, mode)


def _quasi_static(structure: Structure, q: Array, harmonics: int, samples: int,
                  mode: int) -> ModalCurve:
    hb = HarmonicBalance(structure, harmonics, samples, odd=qsma_odd(structure))
    shape, y = qsma_start(structure, hb, mode)
    amp = np.empty(q.size)
    freq = np.empty(q.size)
    zeta = np.empty(q.size)
    previous = 1.0
    for i, qi in enumerate(q):
        y = qsma_point(hb, float(qi), y * (qi / previous), shape)
        amp[i], freq[i], zeta[i] = qsma_values(hb, float(qi), y, shape)
        previous = qi
    return ModalCurve(method="qsma", amplitude=amp, frequency=freq, damping_ratio=zeta,
                      harmonics=harmonics, samples=samples)


def qsma_odd(structure: Structure) -> bool:
    """Whether the quasi-static balance runs on the odd harmonics: odd joint forces (no 3-D
    contact element), a half-wave symmetric response (:mod:`.modal_odd`)."""
    return not any(isinstance(link.operator, Contact3D) for link in structure.joints)


def qsma_start(structure: Structure, hb: HarmonicBalance, mode: int) -> tuple[Array, Array]:
    """The stuck mode ``mode`` mass-normalised in t (phi^T M phi = 1, output . phi > 0), and
    the stuck response (mm, ``hb``'s layout) to the unit modal load ``sin(theta) M phi``."""
    h, j = hb.width, hb.first
    phi = stuck_mode(structure, mode)[0]
    mass = SI_PER_MM * np.asarray(structure.mass)  # t
    phi = phi / np.sqrt(phi @ mass @ phi)
    lin = hb.stuck_guess(0.0, hb.excitation(mass @ phi, 1.0))  # cos load; sin: shift below
    unit = np.zeros((structure.dofs, h))
    unit[:, j + 1] = lin.reshape(structure.dofs, h)[:, j]
    return phi, unit.ravel()


def qsma_point(hb: HarmonicBalance, force: float, guess: Array, phi: Array) -> Array:
    """The quasi-static response's coefficients (mm) under the modal load
    ``force sin(theta) M phi`` by Newton's method from ``guess``; raises
    :class:`ParameterError` if it does not converge."""
    structure = hb.structure
    load = np.zeros((structure.dofs, hb.width))
    load[:, hb.first + 1] = force * (SI_PER_MM * np.asarray(structure.mass) @ phi)
    flat = load.ravel()

    def fun(y: Array) -> tuple[Array, Array]:
        res = hb.residual(y, 0.0, flat)
        return res.r, res.dx

    y, ok, _ = newton(fun, guess, np.full(guess.size, float(np.max(np.abs(guess)))),
                      TOLERANCE, max_iter=50)
    if not ok:
        raise ParameterError(f"the quasi-static modal analysis did not converge at "
                             f"modal force {force:.6g}")
    return np.asarray(y)


def qsma_values(hb: HarmonicBalance, force: float, y: Array, phi: Array
                ) -> tuple[float, float, float]:
    """(output amplitude mm, frequency Hz, damping ratio) of the quasi-static response
    ``y`` to the modal force ``force`` (:func:`quasi_static`'s notes)."""
    structure = hb.structure
    j = hb.first
    mass = SI_PER_MM * np.asarray(structure.mass)
    pattern = mass @ phi
    x = y.reshape(structure.dofs, hb.width)
    eta1 = complex(phi @ mass @ x[:, j], -(phi @ mass @ x[:, j + 1]))
    k1 = (complex(0.0, -force) * eta1.conjugate()).real / abs(eta1) ** 2
    work = -np.pi * force * float(pattern @ x[:, j])
    amp = abs(complex(structure.output @ x[:, j], -(structure.output @ x[:, j + 1])))
    return (float(amp), float(np.sqrt(max(k1, 0.0)) / (2.0 * np.pi)),
            float(work / (2.0 * np.pi * abs(eta1) ** 2 * k1)))


def _energy(structure: Structure, amplitude: ArrayLike, harmonics: int, samples: int,
            mode: int = 0) -> ModalCurve:
    return energy_method(structure, amplitude, samples, mode)


#: Modal method name -> ``(structure, amplitudes mm, harmonics, samples, mode) ->
#: ModalCurve`` (mode 0-based by stuck frequency).
METHODS: dict[str, Callable[[Structure, ArrayLike, int, int, int], ModalCurve]] = {
    "epmc": epmc, "energy": _energy}


def _amplitudes(amplitude: ArrayLike) -> Array:
    a = np.asarray(amplitude, dtype=np.float64).reshape(-1)
    if not (a.size and np.all(np.isfinite(a)) and np.all(a > 0.0)):
        raise ParameterError("modal amplitudes must be finite and > 0 mm")
    return a
