"""Quasi-static modal analysis of the full FE (meshdynamics.qsma, issue 23): the first-harmonic
and secant stiffness of a Jenkins loop, the linear limit, a two-Jenkins closed form on a tiny
mesh, the amplitude grid, local processes and progress."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import MeshModel, build_mesh_model
from microslip.fe.builtin.meshrun import SineCycles
from microslip.fe.examples import cantilever_mesh, grid_mesh
from microslip.meshdynamics.modes import Mode, linear_modes, modal_mass
from microslip.meshdynamics.qsma import (
    first_harmonic,
    first_slip_force,
    loop_stiffness,
    qsma,
    qsma_amplitudes,
    qsma_point,
)

RHO = 2700.0


def _jenkins_loop(k: float, xs: float, amp: float, n: int = 4000) -> tuple[np.ndarray, ...]:
    """A Jenkins element (k, slip displacement xs) driven by x = amp sin(2 pi t), settled
    (second) cycle."""
    t = np.linspace(0.0, 2.0, 2 * n + 1)
    x = amp * np.sin(2 * np.pi * t)
    f = np.empty_like(x)
    slip = 0.0
    for i, xi in enumerate(x):
        trial = k * (xi - slip)
        if abs(trial) > k * xs:
            trial = math.copysign(k * xs, trial)
            slip = xi - trial / k
        f[i] = trial
    return t[n:] - 1.0, f[n:], x[n:]


def test_jenkins_first_harmonic_and_secant() -> None:
    """The issue's figures: at four times its slip displacement a Jenkins element has the
    secant stiffness 0.25 k and the first-harmonic one 0.196 k (k/pi (beta - sin 2beta / 2),
    cos beta = 1 - 2 x_s / A, beta = pi/3)."""
    t, f, x = _jenkins_loop(2.0, 0.5, 2.0)
    k1, ks = loop_stiffness(t, f, x)
    beta = math.acos(1 - 2 * 0.5 / 2.0)
    assert ks / 2.0 == pytest.approx(0.25, rel=1e-12)
    assert k1 / 2.0 == pytest.approx((beta - math.sin(2 * beta) / 2) / math.pi, rel=1e-5)
    assert round(k1 / 2.0, 3) == 0.196
    # below slip: both are k
    t, f, x = _jenkins_loop(2.0, 0.5, 0.4)
    assert loop_stiffness(t, f, x) == pytest.approx((2.0, 2.0), rel=1e-12)


def test_first_harmonic_phase() -> None:
    t = np.linspace(0.0, 1.0, 81)
    c = first_harmonic(t, 2 * np.cos(2 * np.pi * t) + 0.3)
    assert c == pytest.approx(2.0 + 0j, abs=1e-12)


# ---------------------------------------------------------------- two Jenkins on a tiny mesh
@pytest.fixture(scope="module")
def block() -> MeshModel:
    """Three elements 30 x 10 x 5 mm, nearly rigid (E = 1e8 MPa, nu = 0: no Poisson stick
    forces), on its whole bottom face, the clamping pressure on the middle element's top: the
    four middle contact nodes carry 24.84 N each, the four end ones 0.163 N; the stick springs
    lambda A_i (lambda 1e3 N/mm^3): 5e4 and 2.5e4 N/mm."""
    mesh = grid_mesh([0, 10, 20, 30], [0, 10], [0, 5], node_sets={
        "contact": lambda x, y, z: z < 1e-9,
        "clamp": lambda x, y, z: (z > 5 - 1e-9) & (x > 10 - 1e-9) & (x < 20 + 1e-9),
        "response": lambda x, y, z: z > 5 - 1e-9}, surfaces=("contact", "clamp"))
    return build_mesh_model(mesh, rigid_base(contact_set="contact", clamp_set="clamp",
                                             normal_force=100.0, modulus=1e8, poisson_ratio=0.0,
                                             friction=0.5, stick_slope=1e3, normal_contact="fixed"))


def _translation(model: MeshModel) -> tuple[Mode, float]:
    """The rigid translation along x as a mass-normalised pattern, and the body's mass (t)."""
    m = modal_mass(model, RHO)
    full = np.zeros(model.index.size)
    full[0::3] = 1.0
    ones = full[model.free]
    mass = float(ones @ (m @ ones))
    phi = ones / math.sqrt(mass)
    k = float(model.contact_stiffness.sum())
    mode = Mode(number=1, frequency_Hz=math.sqrt(k / mass) / (2 * math.pi), vector=phi,
                inertia=np.asarray(m @ phi), direction=np.array([1.0, 0, 0]),
                label="axial", response_set="response")
    return mode, mass


@pytest.mark.parametrize("total_force", [10.0, 30.0])
def test_two_jenkins_closed_form(block: MeshModel, total_force: float) -> None:
    """The block translates as one body: a stuck spring k_s (the middle nodes) beside a
    Jenkins element (k_w, f_w: the end nodes, which slip). Force-driven at F_a (the inertial
    load q M phi sums to q sqrt(m)): the displacement amplitude X = (F_a - f_w) / k_s, W =
    4 f_w (X - f_w / k_w), and the loop x(F) of the Masing rule gives the first-harmonic and
    secant frequencies and zeta; the FE agrees to 1e-4."""
    mode, mass = _translation(block)
    heavy = block.normal_force > 1.0
    k_s = float(block.contact_stiffness[heavy].sum())
    k_w = float(block.contact_stiffness[~heavy].sum())
    f_w = float(block.friction_limit[~heavy].sum())
    s_w = f_w / k_w
    q = total_force / math.sqrt(mass)
    p = qsma_point(block, mode, q, SineCycles(increments=400))

    x_amp = (total_force - f_w) / k_s
    w = 4 * f_w * (x_amp - s_w)
    assert p.dissipated_energy_Nmm == pytest.approx(w, rel=5e-4)
    assert p.slip_fraction == pytest.approx(1 / 3)  # the four end nodes: 100 of 300 mm^2

    def backbone(load: np.ndarray) -> np.ndarray:
        x = load / (k_s + k_w)
        return np.where(x <= s_w, x, (load - f_w) / k_s)

    t = np.linspace(0.0, 1.0, 40001)
    force = total_force * np.sin(2 * np.pi * t)
    # the rising branch from (-F_a, -X) for t in [-1/4, 1/4], the falling one from (F_a, X)
    rising_from_min = (t <= 0.25) | (t >= 0.75)
    x = np.where(rising_from_min, -x_amp + 2 * backbone((force + total_force) / 2),
                 x_amp - 2 * backbone((total_force - force) / 2))
    k1, ks = loop_stiffness(t, force, x)
    a = abs(first_harmonic(t, x)) * math.sqrt(mass)
    assert p.modal_amplitude == pytest.approx(a, rel=1e-4)
    assert p.amplitude_mm == pytest.approx(a / math.sqrt(mass), rel=1e-4)
    assert p.frequency_Hz == pytest.approx(math.sqrt(k1 / mass) / (2 * math.pi), rel=1e-4)
    assert p.secant_frequency_Hz == pytest.approx(math.sqrt(ks / mass) / (2 * math.pi),
                                                  rel=1e-4)
    zeta = w / (2 * math.pi * a**2 * k1 / mass)
    assert p.damping_ratio == pytest.approx(zeta, rel=1e-3)
    assert max(p.secant_frequency_Hz, p.frequency_Hz) < mode.frequency_Hz


# ---------------------------------------------------------------- the cantilever
@pytest.fixture(scope="module")
def cantilever() -> tuple[MeshModel, Mode]:
    model = build_mesh_model(cantilever_mesh(12, 3, 1), rigid_base(contact_set="contact",
                                                                   clamp_set="clamp",
                                                                   normal_force=2000.0,
                                                                   modulus=70000.0,
                                                                   poisson_ratio=0.33, friction=0.5,
                                                                   stick_slope=1e4,
                                                                   normal_contact="penalty",
                                                                   normal_slope=1e6))
    return model, linear_modes(model, RHO, 4, response_set="response").select(1)


def test_linear_limit(cantilever: tuple[MeshModel, Mode]) -> None:
    """Below first slip the loop is the stuck mode itself: both frequencies equal the linear
    one to 1e-9 and nothing is dissipated."""
    model, mode = cantilever
    p = qsma_point(model, mode, 0.5 * first_slip_force(model, mode))
    assert p.frequency_Hz == pytest.approx(mode.frequency_Hz, rel=1e-9)
    assert p.secant_frequency_Hz == pytest.approx(mode.frequency_Hz, rel=1e-9)
    assert p.damping_ratio == 0.0
    assert p.dissipated_energy_Nmm == 0.0
    assert p.slip_fraction == 0.0
    # u = q phi / omega^2: the modal amplitude is q / omega^2
    assert p.modal_amplitude == pytest.approx(p.force / (2 * math.pi * mode.frequency_Hz)**2,
                                              rel=1e-9)


@pytest.mark.slow  # the grid's top is checked on cyclic runs (about 10 s)
def test_amplitude_grid(cantilever: tuple[MeshModel, Mode]) -> None:
    model, mode = cantilever
    q = qsma_amplitudes(model, mode, 5)
    assert q.size == 5
    assert q[0] == pytest.approx(1.05 * first_slip_force(model, mode))
    assert np.all(np.diff(np.log(q)) == pytest.approx(np.log(q[1] / q[0])))
    assert q[-1] > 5 * q[0]
    with pytest.raises(ParameterError, match="count must be a whole number"):
        qsma_amplitudes(model, mode, 0)


@pytest.mark.slow
def test_curve_processes_and_progress(cantilever: tuple[MeshModel, Mode]) -> None:
    """Two local processes give the in-process figures exactly; the frequency falls and the
    damping rises with amplitude over the grid; progress reaches done == total with ETA 0."""
    model, mode = cantilever
    calls: list[tuple[int, int, float]] = []
    grid = qsma_amplitudes(model, mode, 4)
    serial = qsma(model, mode, grid, progress=lambda d, n, eta: calls.append((d, n, eta)))
    assert [c[:2] for c in calls] == [(1, 4), (2, 4), (3, 4), (4, 4)]
    assert calls[-1][2] == 0.0
    parallel = qsma(model, mode, grid, workers=2)
    assert parallel.summary() == serial.summary()
    assert np.all(np.diff(serial.frequency_Hz) <= 1e-9 * mode.frequency_Hz)
    assert serial.frequency_Hz[-1] < 0.97 * mode.frequency_Hz
    assert serial.damping_ratio[-1] > serial.damping_ratio[0]
    assert np.all(serial.secant_frequency_Hz <= serial.frequency_Hz * (1 + 1e-9))
    assert serial.linear_frequency_Hz == mode.frequency_Hz


def test_gross_sliding_point_is_nan_with_reason(cantilever: tuple[MeshModel, Mode]) -> None:
    model, mode = cantilever
    top = 1e3 * first_slip_force(model, mode)  # the grid ends near 10 times first slip
    curve = qsma(model, mode, [100 * top], history=SineCycles(min_cycles=2, max_cycles=2))
    assert math.isnan(curve.frequency_Hz[0]) and math.isnan(curve.damping_ratio[0])
    assert len(curve.warnings) == 1 and "amplitude 1: failed:" in curve.warnings[0]


def test_bad_force(cantilever: tuple[MeshModel, Mode]) -> None:
    model, mode = cantilever
    with pytest.raises(ParameterError, match="modal force must be > 0"):
        qsma_point(model, mode, -1.0)
    with pytest.raises(ParameterError, match="forces must be"):
        qsma(model, mode, [])


@pytest.mark.slow
def test_dask_cluster_matches_local(cantilever: tuple[MeshModel, Mode]) -> None:
    """The amplitudes on a local Dask cluster (as ``sweep --scheduler``) give the in-process
    figures exactly."""
    distributed = pytest.importorskip("distributed")
    model, mode = cantilever
    grid = qsma_amplitudes(model, mode, 2)
    local = qsma(model, mode, grid)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        remote = qsma(model, mode, grid, scheduler=cluster.scheduler_address)
    assert remote.summary() == local.summary()
