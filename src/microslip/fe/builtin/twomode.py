"""Two close modes that share the interface: coupled against decoupled joints (issue 23, item 6).

A post on a foot flange (:func:`microslip.fe.examples.post_on_plate_mesh`) bends in x and in
y at two close frequencies; a force on its top at 45 degrees excites both, and the contact
under the flange moves on an ellipse, whose shape the structure decides (the paper's
circular and elliptical loading, section 2 of Lord and Rongong 2016). Each contact node is
the 2-D Jenkins element of the full FE's law (stick slope x area, slip force mu N_i) with

* ``circular`` coupling: one circular Coulomb limit on the resultant (the full FE's own
  law, :mod:`.contact`), or
* ``decoupled``: two independent 1-D elements along x and y, the paper's decoupled sum
  (:data:`microslip.dynamics.operators2d.COUPLINGS`).

The study, all on the Craig-Bampton ROM of :mod:`.reduce` (fixed normal contact, every
contact node kept) and checked on the full FE:

1. :func:`bending_pair`: the full FE's two lowest stuck modes, their directions (x, y) and
   their closeness;
2. :func:`forced_response`: the ROM's frequency response (harmonic balance, continuation,
   :func:`microslip.dynamics.response.frequency_response`) to ``F cos(w t)`` on the top set
   along the forcing angle, with light linear modal damping zeta_0 in the ROM's stuck modes
   (without it an undamped microslip peak is unbounded and the continuation stalls). From
   every point: the top's first-harmonic amplitude along x and y, the interface orbit (the
   area-weighted mean tangential displacement of the contact nodes, first harmonic: an
   ellipse whose axes ratio is 0 for a line and 1 for a circle) and the energy per cycle:
   W = pi F s . S_1 (the force's work, s the forcing shape and S_1 the sine coefficients),
   of which the joints dissipate W_J = W - W_visc,
   W_visc = pi w sum_h h^2 (C_h^T C C_h + S_h^T C S_h);
3. :func:`fe_check`: the full FE at a point of the ROM's curve. The ROM's harmonic solution
   q(t) satisfies K q + f_J(q) = g(t) with ``g = p - M q'' - C q'``: loaded quasi-statically
   by g, the same joints follow the same path and dissipate W_J (the inertial and viscous
   terms do no work over a period). g is carried to the full FE by the two bending modes:
   ``G = F s + sum_k (w^2 - 2 i zeta_0 w w_k) eta_k M phi_k`` with eta_k = psi_k^T M_r Q_1
   the ROM's modal coordinates of its first harmonic (psi_k its stuck modes, which the
   Craig-Bampton basis maps onto the full FE's phi_k: the same frequencies to 1e-9 here),
   F s the forcing (equal nodal shares on the top set: the ROM's output rows are exactly
   its reduction). Two loads in quadrature, ``Re G cos(w t) - Im G sin(w t)``
   (:class:`~.meshrun.VectorLoad` with phases 90 and 180 degrees), are applied cyclically
   to the full frictional FE (:func:`~.meshrun.solve_mesh`) and, with the same increments,
   to the ROM quasi-statically with circular and with decoupled joints
   (:func:`rom_quasistatic`). The ROM's boundary is the exact static condensation of the
   body (Craig-Bampton's constraint modes), so under the same load the coupled ROM must give
   the full FE's W to the load's reduction error: the check tests the whole chain (load
   mapping, node laws, the equivalence of the harmonic solution and its quasi-static load;
   the first harmonic and two modes only: ``inertia_share`` says how much of M Q_1 the two
   modes carry) and shows the decoupled joints' error on the full FE's own terms. It does
   not test the ROM's dynamics (its fixed-interface modes; :func:`.reduce.convergence`
   does).

Units: N, mm, s, Hz, t (ROM masses; SI in the :class:`~microslip.dynamics.structure.
Structure`), N·mm for energies.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from ...errors import ParameterError
from ..hexmesh import HexMesh
from .contact import return_map
from .meshmodel import MeshModel, build_mesh_model
from .meshrun import SineCycles, VectorLoad, solve_mesh
from .modes import Modes, linear_modes
from .reduce import SI_FACTOR, Rom, build_rom

if TYPE_CHECKING:
    from ...dynamics.structure import Structure

__all__ = [
    "COUPLINGS",
    "BendingPair",
    "CheckPoint",
    "Orbit",
    "Peak",
    "ResponseCurve",
    "TwoModeCase",
    "TwoModeStudy",
    "bending_pair",
    "check_points",
    "fe_check",
    "forced_response",
    "forcing_shape",
    "interface_rows",
    "node_orbits",
    "orbit",
    "quadrature_load",
    "rom_quasistatic",
    "rom_system",
    "two_mode_model",
    "two_mode_study",
]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

#: The two couplings compared.
COUPLINGS = ("circular", "decoupled")


@dataclass(frozen=True)
class TwoModeCase:
    """The post-on-plate case (N, mm, MPa, kg/m^3): aluminium, mu 0.5, F_N 2000 N, stick
    slope 1e4 N/mm^3, fixed normal contact; the ROM's fixed-interface modes, its linear
    modal damping ratio zeta_0, the forcing angle from x (degrees) and the harmonics."""

    contact_set: str = "contact"
    clamp_set: str = "clamp"
    top_set: str = "top"
    modulus: float = 70000.0
    poisson_ratio: float = 0.33
    density: float = 2700.0
    friction: float = 0.5
    normal_force: float = 2000.0
    stick_slope: float = 1e4
    rom_modes: int = 10
    damping_ratio: float = 0.005
    angle_deg: float = 45.0
    harmonics: int = 3

    def __post_init__(self) -> None:
        if not (math.isfinite(self.damping_ratio) and 0.0 < self.damping_ratio < 1.0):
            raise ParameterError(f"damping ratio zeta_0 must be in (0, 1), got "
                                 f"{self.damping_ratio!r}")
        if not math.isfinite(self.angle_deg):
            raise ParameterError(f"forcing angle must be finite (degrees), got "
                                 f"{self.angle_deg!r}")


def two_mode_model(mesh: HexMesh, case: TwoModeCase) -> MeshModel:
    """The clamped body of ``mesh`` (fixed normal contact, the case's law)."""
    return build_mesh_model(mesh, contact_set=case.contact_set, clamp_set=case.clamp_set,
                            normal_force=case.normal_force, modulus=case.modulus,
                            poisson_ratio=case.poisson_ratio, friction=case.friction,
                            stick_slope=case.stick_slope)


@dataclass(frozen=True, eq=False)
class BendingPair:
    """The full FE's two lowest stuck modes (:func:`bending_pair`).

    Attributes
    ----------
    frequencies_Hz : ndarray, shape (2,)
    directions : ndarray, shape (2, 3)
        Unit direction of the top set's motion in each (global axes).
    labels : tuple of str
    separation : float
        (f2 - f1) / f1.
    modes : Modes
        The stuck modes computed (at least 6), for the loads of :func:`fe_check`.
    """

    frequencies_Hz: FloatArray
    directions: FloatArray
    labels: tuple[str, str]
    separation: float
    modes: Modes = field(repr=False)


def bending_pair(model: MeshModel, case: TwoModeCase, count: int = 6) -> BendingPair:
    """The two lowest stuck modes of the full FE, described by the top set's motion."""
    modes = linear_modes(model, case.density, count, response_set=case.top_set)
    f = np.asarray(modes.frequencies_Hz[:2])
    return BendingPair(frequencies_Hz=f, directions=np.asarray(modes.directions[:2]),
                       labels=(modes.labels[0], modes.labels[1]),
                       separation=float((f[1] - f[0]) / f[0]), modes=modes)


def forcing_shape(rom: Rom, angle_deg: float) -> FloatArray:
    """ROM load of 1 N on the top (response) set along ``angle_deg`` from x in the x-y plane,
    in equal nodal shares (the ROM's output rows are exactly its reduction), N per N."""
    if rom.output is None:
        raise ParameterError("the ROM has no response set: build it with response_set")
    a = math.radians(angle_deg)
    return np.asarray(math.cos(a) * rom.output[0] + math.sin(a) * rom.output[1])


def interface_rows(model: MeshModel, rom: Rom) -> FloatArray:
    """(2, n_rom): the contact's area-weighted mean tangential displacement along global x
    and y per unit ROM coordinate (the boundary dofs are the nodes' e1, e2, node-major)."""
    w = model.contact_area / model.contact_area.sum()
    rows = np.zeros((2, rom.dofs))
    nb = rom.boundary.size
    tangent = model.rotation[:2]  # e1, e2 in global components
    for d in range(2):
        rows[:, d:nb:rom.per_node] = np.outer(tangent[d, :2], w)
    return rows


def _damping(rom: Rom, zeta: float) -> FloatArray:
    """Modal damping zeta_0 in every stuck mode of the ROM, SI (N s/m)."""
    m = rom.mass * SI_FACTOR
    k = (rom.stiffness + np.diag(rom.contact_springs())) * SI_FACTOR
    lam, v = eigh(k, m)
    mv = m @ v
    c = mv @ np.diag(2.0 * zeta * np.sqrt(np.maximum(lam, 0.0))) @ mv.T
    return np.asarray(0.5 * (c + c.T))


def rom_system(rom: Rom, coupling: str, damping_ratio: float, output: FloatArray
               ) -> Structure:
    """The ROM as a :class:`~microslip.dynamics.structure.Structure`: each contact node a
    Jenkins element (lambda A_i, mu N_i) to the ground, ``circular`` (one 2-D element) or
    ``decoupled`` (two 1-D elements), modal damping zeta_0, reporting ``output``."""
    from ...dynamics.assemble import PlacedJoint, from_joints, with_output
    from ...dynamics.files import MatrixFile
    from ...dynamics.operators import jenkins

    if coupling not in COUPLINGS:
        raise ParameterError(f"unknown coupling {coupling!r}; valid: {', '.join(COUPLINGS)}")
    if rom.per_node != 2:
        raise ParameterError("the two-mode study takes the ROM of 'fixed' normal contact")
    first = np.arange(rom.contact_stiffness.size) * 2
    rows = np.stack([np.stack([first, first + 1], axis=1),
                     np.full((first.size, 2), -1)], axis=2).astype(np.int64)
    mats = MatrixFile(mass=rom.mass * SI_FACTOR, stiffness=rom.stiffness * SI_FACTOR,
                      damping=_damping(rom, damping_ratio), joints=rows, path="rom")
    joints = [PlacedJoint(r, jenkins(float(k), float(s)), coupling)
              for r, k, s in zip(rows, rom.contact_stiffness, rom.slip_force, strict=True)]
    return with_output(from_joints(mats, joints), np.asarray(output, dtype=float))


@dataclass(frozen=True)
class Orbit:
    """A first-harmonic orbit in the x-y plane: ``Re(X e^{i w t}), Re(Y e^{i w t})``, mm.

    ``major``, ``minor`` are the ellipse's semi-axes (mm), ``ratio`` = minor / major (0: a
    line, 1: a circle), ``angle_deg`` the major axis's direction from x."""

    x: complex
    y: complex
    major: float
    minor: float
    ratio: float
    angle_deg: float


def orbit(x: complex, y: complex) -> Orbit:
    """The ellipse traced by ``(Re(x e^{it}), Re(y e^{it}))``: singular values of
    [[Re x, Im x], [Re y, Im y]].

    >>> o = orbit(1.0, -1j)
    >>> round(o.ratio, 12), round(o.major, 12)
    (1.0, 1.0)
    """
    a = np.array([[x.real, x.imag], [y.real, y.imag]])
    u, s, _ = np.linalg.svd(a)
    ratio = float(s[1] / s[0]) if s[0] > 0 else 0.0
    ang = math.degrees(math.atan2(u[1, 0], u[0, 0])) % 180.0
    return Orbit(complex(x), complex(y), float(s[0]), float(s[1]), ratio, ang)


@dataclass(frozen=True)
class Peak:
    """The largest first-harmonic amplitude of the top's motion along one axis.

    Attributes
    ----------
    axis : str
        ``x`` or ``y``.
    index : int
        Its continuation point.
    frequency_Hz, amplitude_mm : float
    joint_energy_Nmm, total_energy_Nmm : float
        W_J (the joints) and W (the force's work, joints plus viscous) per cycle there.
    orbit : Orbit
        The interface's orbit there.
    complete : bool
        The curve went on past it (False: the continuation stopped at this point, which is
        then no peak).
    """

    axis: str
    index: int
    frequency_Hz: float
    amplitude_mm: float
    joint_energy_Nmm: float
    total_energy_Nmm: float
    orbit: Orbit
    complete: bool = True


@dataclass(frozen=True, eq=False)
class ResponseCurve:
    """One frequency-response curve of the ROM (:func:`forced_response`).

    Attributes
    ----------
    coupling : str
    force : float
        F, N.
    frequency_Hz : ndarray, shape (m,)
    top_x_mm, top_y_mm : ndarray, shape (m,)
        First-harmonic amplitude of the top set's mean displacement along x and y.
    interface_mm : ndarray of complex, shape (m, 2)
        The interface's first harmonic (X, Y) at every point, mm: its orbit is
        ``(Re(X e^{i w t}), Re(Y e^{i w t}))``.
    orbit_ratio : ndarray, shape (m,)
        The interface orbit's axes ratio at every point.
    joint_energy_Nmm : ndarray, shape (m,)
        W_J per cycle at every point.
    coefficients : ndarray, shape (m, n_rom (2H + 1))
        The harmonic coefficients (mm, :mod:`microslip.dynamics.hb` layout).
    peaks : tuple of Peak
        The x and y peaks.
    success : bool
    message : str
    """

    coupling: str
    force: float
    frequency_Hz: FloatArray = field(repr=False)
    top_x_mm: FloatArray = field(repr=False)
    top_y_mm: FloatArray = field(repr=False)
    interface_mm: ComplexArray = field(repr=False)
    orbit_ratio: FloatArray = field(repr=False)
    joint_energy_Nmm: FloatArray = field(repr=False)
    coefficients: FloatArray = field(repr=False)
    peaks: tuple[Peak, Peak]
    harmonics: int
    success: bool
    message: str


def _first(q: FloatArray) -> ComplexArray:
    """Q_1 = C_1 - i S_1 of coefficient rows (..., n, 2H + 1): q = Re(Q_1 e^{i w t})."""
    return np.asarray(q[..., 1] - 1j * q[..., 2])


def _energies(q: FloatArray, omega: float, force: float, shape: FloatArray,
              c_si: FloatArray) -> tuple[float, float]:
    """(W, W_J) per cycle of one point, N·mm (q (n, 2H + 1) in mm, omega rad/s)."""
    total = math.pi * force * float(shape @ q[:, 2])
    visc = 0.0
    for h in range(1, (q.shape[1] - 1) // 2 + 1):
        c, s = q[:, 2 * h - 1], q[:, 2 * h]
        visc += h * h * float(c @ c_si @ c + s @ c_si @ s)
    visc *= math.pi * omega * 1e-3  # N s/m * mm/s * mm -> N mm
    return total, total - visc


def forced_response(model: MeshModel, rom: Rom, case: TwoModeCase, force: float,
                    coupling: str, frequency_range: tuple[float, float],
                    step: float = 0.02) -> ResponseCurve:
    """The ROM's response to ``force cos(w t)`` (N) on the top set along the case's angle
    over ``frequency_range`` (Hz), by harmonic balance with ``case.harmonics`` harmonics."""
    from ...dynamics.response import frequency_response

    shape = forcing_shape(rom, case.angle_deg)
    s = rom_system(rom, coupling, case.damping_ratio, shape)
    r = frequency_response(s, force, shape, frequency_range, case.harmonics, step=step)
    h = 2 * case.harmonics + 1
    q = r.coefficients.reshape(r.coefficients.shape[0], rom.dofs, h)
    assert rom.output is not None
    top = np.abs(_first(np.einsum("cn,mnh->mch", rom.output[:2], q)))
    inter = _first(np.einsum("cn,mnh->mch", interface_rows(model, rom), q))
    ratios = np.array([orbit(complex(a), complex(b)).ratio for a, b in inter])
    omega = 2.0 * math.pi * r.frequency
    w = np.array([_energies(q[i], float(omega[i]), force, shape, s.damping)
                  for i in range(q.shape[0])])
    peaks = []
    for axis, amp in (("x", top[:, 0]), ("y", top[:, 1])):
        i = int(np.argmax(amp))
        peaks.append(Peak(axis=axis, index=i, frequency_Hz=float(r.frequency[i]),
                          amplitude_mm=float(amp[i]), joint_energy_Nmm=float(w[i, 1]),
                          total_energy_Nmm=float(w[i, 0]),
                          orbit=orbit(complex(inter[i, 0]), complex(inter[i, 1])),
                          complete=bool(r.success or i < r.frequency.size - 1)))
    return ResponseCurve(coupling=coupling, force=float(force),
                         frequency_Hz=np.asarray(r.frequency), top_x_mm=top[:, 0],
                         top_y_mm=top[:, 1], interface_mm=np.asarray(inter),
                         orbit_ratio=ratios, joint_energy_Nmm=w[:, 1],
                         coefficients=np.asarray(r.coefficients),
                         peaks=(peaks[0], peaks[1]), harmonics=case.harmonics,
                         success=bool(r.success), message=r.message)


def _rom_modes(rom: Rom, count: int) -> tuple[FloatArray, FloatArray]:
    """The ROM's lowest stuck modes, mass-normalised in t: (omega rad/s, psi (n, count))."""
    k = rom.stiffness + np.diag(rom.contact_springs())
    lam, v = eigh(k, rom.mass, subset_by_index=[0, count - 1])
    return np.sqrt(np.maximum(lam, 0.0)), np.asarray(v)


@dataclass(frozen=True, eq=False)
class QuadratureLoad:
    """The quasi-static equivalent of a harmonic solution (:func:`quadrature_load`):
    g(t) = Re(G e^{i w t}) on the ROM (``rom``, N) and on the full FE's free dofs
    (``full``, N), with the modal coordinates eta_k (sqrt(t)·mm) of the two modes and the
    share of M Q_1 they carry (``inertia_share``, 1 if the response is the two modes)."""

    rom: ComplexArray
    full: ComplexArray
    eta: ComplexArray
    inertia_share: float


def quadrature_load(model: MeshModel, rom: Rom, pair: BendingPair, case: TwoModeCase,
                    curve: ResponseCurve, index: int) -> QuadratureLoad:
    """G = F s + sum_k (w^2 - 2 i zeta_0 w w_k) eta_k M phi_k at point ``index`` of ``curve``
    (the module docstring), on the ROM and on the full FE; the ROM's stuck modes signed to
    move the top set as the full FE's do."""
    h = 2 * curve.harmonics + 1
    q1 = _first(curve.coefficients[index].reshape(rom.dofs, h))
    omega = 2.0 * math.pi * float(curve.frequency_Hz[index])
    wk, psi = _rom_modes(rom, 2)
    assert rom.output is not None
    for k in range(2):
        if float((rom.output @ psi[:, k]) @ pair.modes.response_motion[k]) < 0.0:
            psi[:, k] = -psi[:, k]
    m_psi = rom.mass @ psi
    eta = m_psi.T @ q1
    factor = omega**2 - 2j * case.damping_ratio * omega * wk
    shape = forcing_shape(rom, case.angle_deg)
    g_rom = curve.force * shape + m_psi @ (factor * eta)
    full_inertia = np.asarray(pair.modes.inertia[:2]).T  # (dof, 2): M phi_k
    g_full = curve.force * _top_vector(model, case) + full_inertia @ (factor * eta)
    mq = rom.mass @ q1
    rest = mq - m_psi @ eta
    share = 1.0 - float(np.linalg.norm(rest) / np.linalg.norm(mq))
    return QuadratureLoad(rom=np.asarray(g_rom), full=np.asarray(g_full), eta=eta,
                          inertia_share=share)


def _top_vector(model: MeshModel, case: TwoModeCase) -> FloatArray:
    """The full FE's 1 N on the top set along the angle, equal nodal shares (free dofs)."""
    nodes = model.model_nodes(np.asarray(model.mesh.node_sets[case.top_set]))
    a = math.radians(case.angle_deg)
    d = model.rotation @ np.array([math.cos(a), math.sin(a), 0.0])
    out = np.zeros(model.dof)
    for c in range(3):
        pos = model.index[3 * nodes + c]
        out[pos[pos >= 0]] += d[c] / nodes.size
    return out


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


@dataclass(frozen=True)
class CheckPoint:
    """The full FE at one point of the ROM's coupled curve (:func:`fe_check`).

    Attributes
    ----------
    force : float
        F, N.
    point : str
        Which point (``x peak``, ``y peak``, ``roundest``: :func:`check_points`).
    frequency_Hz : float
    orbit_ratio : float
        The interface orbit's axes ratio there (ROM).
    inertia_share : float
        Share of M Q_1 the two bending modes carry.
    rom_harmonic_Nmm : float
        W_J of the ROM's harmonic solution.
    rom_circular_Nmm, rom_decoupled_Nmm : float
        W of the ROM loaded quasi-statically by g, circular and decoupled joints.
    fe_Nmm : float
        W of the full frictional FE under the same g.
    fe_settled : bool
    node_ratio, node_angle_deg : float
        The contact nodes' own orbits there (ROM, first harmonic): the median axes ratio and
        the median angle of their major axes from the nearer contact-plane axis (0 to 45
        degrees; the decoupled elements act along these axes, so they are the circular
        element only for nodes at 0 degrees on a line).
    """

    force: float
    point: str
    frequency_Hz: float
    orbit_ratio: float
    inertia_share: float
    rom_harmonic_Nmm: float
    rom_circular_Nmm: float
    rom_decoupled_Nmm: float
    fe_Nmm: float
    fe_settled: bool
    node_ratio: float = math.nan
    node_angle_deg: float = math.nan


def check_points(curve: ResponseCurve, floor: float = 0.5) -> dict[str, int]:
    """The points of ``curve`` that :func:`fe_check` checks: the x and y peaks and the
    roundest interface orbit among the points whose top amplitude (the larger of x and y)
    is at least ``floor`` times the curve's largest (between the resonances, where the two
    modes answer about equally and out of phase)."""
    amp = np.maximum(curve.top_x_mm, curve.top_y_mm)
    strong = np.flatnonzero(amp >= floor * float(amp.max()))
    round_i = int(strong[np.argmax(curve.orbit_ratio[strong])])
    return {"x peak": curve.peaks[0].index, "y peak": curve.peaks[1].index,
            "roundest": round_i}


def fe_check(model: MeshModel, rom: Rom, pair: BendingPair, case: TwoModeCase,
             curve: ResponseCurve, index: int, label: str = "",
             history: SineCycles | None = None) -> CheckPoint:
    """W per cycle of the full FE, and of the ROM with circular and decoupled joints, under
    the quasi-static equivalent of ``curve``'s harmonic solution at point ``index`` (the
    module docstring)."""
    history = SineCycles() if history is None else history
    load = quadrature_load(model, rom, pair, case, curve, index)
    qs = {c: rom_quasistatic(rom, load.rom, c, history) for c in COUPLINGS}
    loads = [VectorLoad(v / np.linalg.norm(v), float(np.linalg.norm(v)), phase,
                        set=f"g {part}")
             for v, phase, part in ((load.full.real, 90.0, "cos"),
                                    (load.full.imag, 180.0, "-sin"))]
    fe = solve_mesh(model, loads, history)
    inter = curve.interface_mm[index]
    ratio, angle = node_orbits(rom, curve, index)
    return CheckPoint(force=curve.force, point=label or f"point {index}",
                      frequency_Hz=float(curve.frequency_Hz[index]),
                      orbit_ratio=orbit(complex(inter[0]), complex(inter[1])).ratio,
                      inertia_share=load.inertia_share,
                      rom_harmonic_Nmm=float(curve.joint_energy_Nmm[index]),
                      rom_circular_Nmm=qs["circular"].energy_Nmm,
                      rom_decoupled_Nmm=qs["decoupled"].energy_Nmm,
                      fe_Nmm=float(fe.dissipated_energy), fe_settled=bool(fe.settled),
                      node_ratio=float(np.median(ratio)), node_angle_deg=float(np.median(angle)))


def node_orbits(rom: Rom, curve: ResponseCurve, index: int) -> tuple[FloatArray, FloatArray]:
    """Each contact node's first-harmonic orbit at point ``index``: its axes ratio and the
    angle of its major axis from the nearer of the contact plane's axes e1, e2 (degrees,
    0 to 45)."""
    h = 2 * curve.harmonics + 1
    q = _first(curve.coefficients[index].reshape(rom.dofs, h)[:rom.boundary.size])
    nodes = [orbit(complex(a), complex(b)) for a, b in q.reshape(-1, rom.per_node)[:, :2]]
    ratio = np.array([o.ratio for o in nodes])
    angle = np.array([min(o.angle_deg % 90.0, 90.0 - o.angle_deg % 90.0) for o in nodes])
    return ratio, angle


def study_rom(model: MeshModel, case: TwoModeCase) -> Rom:
    """The Craig-Bampton ROM of the case (``case.rom_modes`` fixed-interface modes, the top
    set as its output)."""
    return build_rom(model, case.density, modes=case.rom_modes, response_set=case.top_set)


def frequency_window(pair: BendingPair, margin: float = 0.05) -> tuple[float, float]:
    """The range through both resonances: ``(1 - margin) f1`` to ``(1 + margin) f2``, Hz."""
    f1, f2 = (float(v) for v in pair.frequencies_Hz)
    return (1.0 - margin) * f1, (1.0 + margin) * f2


def energy_table(curves: Sequence[ResponseCurve]) -> list[dict[str, float | str]]:
    """One row per curve and peak: coupling, F, axis, frequency, amplitude, W_J, orbit."""
    return [{"coupling": c.coupling, "force_N": c.force, "axis": p.axis,
             "frequency_Hz": p.frequency_Hz, "amplitude_mm": p.amplitude_mm,
             "joint_energy_Nmm": p.joint_energy_Nmm, "orbit_ratio": p.orbit.ratio}
            for c in curves for p in c.peaks]


@dataclass(frozen=True, eq=False)
class TwoModeStudy:
    """The whole study (:func:`two_mode_study`).

    Attributes
    ----------
    case : TwoModeCase
    dof : int
        The full FE's unknowns.
    contact_nodes : int
    pair : BendingPair
    rom_dofs : int
    rom_frequencies_Hz : ndarray, shape (2,)
        The ROM's two lowest stuck frequencies (the full FE's to ~1e-9).
    frequency_range : tuple of float
        Hz.
    curves : tuple of ResponseCurve
        For each force, the circular then the decoupled curve.
    checks : tuple of CheckPoint
        At :func:`check_points` of each circular curve of the check forces that crossed
        the whole range.
    """

    case: TwoModeCase
    dof: int
    contact_nodes: int
    pair: BendingPair = field(repr=False)
    rom_dofs: int
    rom_frequencies_Hz: FloatArray = field(repr=False)
    frequency_range: tuple[float, float]
    curves: tuple[ResponseCurve, ...] = field(repr=False)
    checks: tuple[CheckPoint, ...] = field(repr=False)

    def curve(self, force: float, coupling: str) -> ResponseCurve:
        """The curve of ``force`` (N) and ``coupling``."""
        for c in self.curves:
            if c.force == force and c.coupling == coupling:
                return c
        raise ParameterError(f"no {coupling} curve at {force:g} N")

    def differences(self) -> list[dict[str, float | str]]:
        """Decoupled against circular at each force and peak that both curves passed:
        relative differences of the peak amplitude, the peak frequency and W_J at the peak
        ((decoupled - circular) / circular)."""
        out: list[dict[str, float | str]] = []
        for force in sorted({c.force for c in self.curves}):
            a, b = self.curve(force, "circular"), self.curve(force, "decoupled")
            for pa, pb in zip(a.peaks, b.peaks, strict=True):
                if not (pa.complete and pb.complete):
                    continue
                out.append({"force_N": force, "axis": pa.axis,
                            "amplitude": pb.amplitude_mm / pa.amplitude_mm - 1.0,
                            "frequency": pb.frequency_Hz / pa.frequency_Hz - 1.0,
                            "joint_energy": pb.joint_energy_Nmm / pa.joint_energy_Nmm - 1.0})
        return out


def two_mode_study(mesh: HexMesh, case: TwoModeCase, forces: Sequence[float],
                   check_forces: Sequence[float] = (),
                   frequency_range: tuple[float, float] | None = None,
                   history: SineCycles | None = None) -> TwoModeStudy:
    """Coupled against decoupled joints on the ROM at each of ``forces`` (N), and the full
    FE at :func:`check_points` of the circular curves of ``check_forces`` (a subset of
    ``forces``); ``frequency_range`` default :func:`frequency_window`."""
    bad = [f for f in check_forces if f not in forces]
    if bad:
        raise ParameterError(f"check forces must be among the forces {list(forces)} N, got "
                             f"{bad}")
    model = two_mode_model(mesh, case)
    pair = bending_pair(model, case)
    rom = study_rom(model, case)
    window = frequency_window(pair) if frequency_range is None else frequency_range
    curves = [forced_response(model, rom, case, float(f), c, window)
              for f in forces for c in COUPLINGS]
    checks = []
    for f in check_forces:
        curve = next(c for c in curves if c.force == f and c.coupling == "circular")
        if not curve.success:  # its peaks may be where the continuation stopped
            continue
        for label, i in check_points(curve).items():
            checks.append(fe_check(model, rom, pair, case, curve, i, label, history))
    return TwoModeStudy(case=case, dof=model.dof, contact_nodes=int(model.contact_nodes.size),
                        pair=pair, rom_dofs=rom.dofs,
                        rom_frequencies_Hz=rom.stuck_frequencies(2),
                        frequency_range=(float(window[0]), float(window[1])),
                        curves=tuple(curves), checks=tuple(checks))
