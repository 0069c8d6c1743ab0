"""The full-FE check of the two-mode study (:mod:`.twomode`, step 3).

The full FE at a point of the ROM's curve. The ROM's harmonic solution q(t) satisfies
K q + f_J(q) = g(t) with ``g = p - M q'' - C q'``: loaded quasi-statically by g, the same
joints follow the same path and dissipate W_J (the inertial and viscous terms do no work over
a period). g is carried to the full FE by the two bending modes:
``G = F s + sum_k (w^2 - 2 i zeta_0 w w_k) eta_k M phi_k`` with eta_k = psi_k^T M_r Q_1 the
ROM's modal coordinates of its first harmonic (psi_k its stuck modes, which the
Craig-Bampton basis maps onto the full FE's phi_k: the same frequencies to 1e-9 here), F s
the forcing (equal nodal shares on the top set: the ROM's output rows are exactly its
reduction). Two loads in quadrature, ``Re G cos(w t) - Im G sin(w t)``
(:class:`~.meshrun.VectorLoad` with phases 90 and 180 degrees), are applied cyclically to the
full frictional FE (:func:`~.meshrun.solve_mesh`) and, with the same increments, to the ROM
quasi-statically with circular and with decoupled joints
(:func:`~.romquasistatic.rom_quasistatic`). The ROM's boundary is the exact static
condensation of the body (Craig-Bampton's constraint modes), so under the same load the
coupled ROM must give the full FE's W to the load's reduction error: the check tests the
whole chain (load mapping, node laws, the equivalence of the harmonic solution and its
quasi-static load; the first harmonic and two modes only: ``inertia_share`` says how much of
M Q_1 the two modes carry) and shows the decoupled joints' error on the full FE's own terms.
It does not test the ROM's dynamics (its fixed-interface modes; :func:`.reduce.convergence`
does).

Units: N, mm, s, Hz, t, N·mm for energies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from ..fe.builtin.meshmodel import MeshModel
from ..fe.builtin.meshrun import SineCycles, VectorLoad, solve_mesh
from .reduce import Rom
from .romquasistatic import rom_quasistatic
from .twomodecase import COUPLINGS, BendingPair, TwoModeCase
from .twomoderesponse import ResponseCurve, first_harmonic, forcing_shape, orbit

__all__ = ["CheckPoint", "QuadratureLoad", "check_points", "fe_check", "node_orbits",
           "quadrature_load"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


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
    q1 = first_harmonic(curve.coefficients[index].reshape(rom.dofs, h))
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
    q = first_harmonic(curve.coefficients[index].reshape(rom.dofs, h)[:rom.boundary.size])
    nodes = [orbit(complex(a), complex(b)) for a, b in q.reshape(-1, rom.per_node)[:, :2]]
    ratio = np.array([o.ratio for o in nodes])
    angle = np.array([min(o.angle_deg % 90.0, 90.0 - o.angle_deg % 90.0) for o in nodes])
    return ratio, angle
