"""The ROM's forced response in the two-mode study (:mod:`.twomode`, step 2).

The ROM's frequency response (harmonic balance, continuation,
:func:`microslip.dynamics.response.frequency_response`) to ``F cos(w t)`` on the top set along
the forcing angle, with light linear modal damping zeta_0 in the ROM's stuck modes (without
it an undamped microslip peak is unbounded and the continuation stalls). From every point:
the top's first-harmonic amplitude along x and y, the interface orbit (the area-weighted mean
tangential displacement of the contact nodes, first harmonic: an ellipse whose axes ratio is
0 for a line and 1 for a circle) and the energy per cycle: W = pi F s . S_1 (the force's work,
s the forcing shape and S_1 the sine coefficients), of which the joints dissipate
W_J = W - W_visc, W_visc = pi w sum_h h^2 (C_h^T C C_h + S_h^T C S_h).

Units: N, mm, s, Hz, t (ROM masses; SI in the :class:`~microslip.dynamics.structure.
Structure`), N·mm for energies.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from ..errors import ParameterError
from ..fe.builtin.meshmodel import MeshModel
from .reduce import SI_FACTOR, Rom
from .twomodecase import COUPLINGS, TwoModeCase

if TYPE_CHECKING:
    from ..dynamics.structure import Structure

__all__ = ["Orbit", "Peak", "ResponseCurve", "energy_table", "first_harmonic",
           "forced_response", "forcing_shape", "interface_rows", "orbit", "rom_system"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


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
    from ..dynamics.assemble import PlacedJoint, from_joints, with_output
    from ..dynamics.files import MatrixFile
    from ..dynamics.operators import jenkins

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


def first_harmonic(q: FloatArray) -> ComplexArray:
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
    from ..dynamics.response import frequency_response

    shape = forcing_shape(rom, case.angle_deg)
    s = rom_system(rom, coupling, case.damping_ratio, shape)
    r = frequency_response(s, force, shape, frequency_range, case.harmonics, step=step)
    h = 2 * case.harmonics + 1
    q = r.coefficients.reshape(r.coefficients.shape[0], rom.dofs, h)
    assert rom.output is not None
    top = np.abs(first_harmonic(np.einsum("cn,mnh->mch", rom.output[:2], q)))
    inter = first_harmonic(np.einsum("cn,mnh->mch", interface_rows(model, rom), q))
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


def energy_table(curves: Sequence[ResponseCurve]) -> list[dict[str, float | str]]:
    """One row per curve and peak: coupling, F, axis, frequency, amplitude, W_J, orbit."""
    return [{"coupling": c.coupling, "force_N": c.force, "axis": p.axis,
             "frequency_Hz": p.frequency_Hz, "amplitude_mm": p.amplitude_mm,
             "joint_energy_Nmm": p.joint_energy_Nmm, "orbit_ratio": p.orbit.ratio}
            for c in curves for p in c.peaks]
