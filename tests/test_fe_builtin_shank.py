"""A bolt's shank (issue 32): the beam between the head's and the nut's mean motions.

Exact checks: the rigid fit recovers any rigid motion of a face; the shank stores no energy
in a rigid motion of both faces; its axial and torsional stiffness are EA/L and GJ/L, its
tip stiffness against a lateral offset of the nut (rotations held) is 12 EI / (L^3 (1 + Phi));
on the bolted lap it carries a lateral load the friction torque alone cannot.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip.fe.builtin.shank import beam_stiffness, rigid_fit, shank_stiffness

E, NU, D = 210000.0, 0.3, 10.0


def _face(z: float, n: int = 4, size: float = 12.0) -> np.ndarray:
    g = np.linspace(-size / 2, size / 2, n)
    x, y = np.meshgrid(g, g)
    return np.column_stack([x.ravel(), y.ravel(), np.full(x.size, z)])


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-1.0, 1.0), min_size=6, max_size=6))
def test_the_rigid_fit_recovers_a_rigid_motion(motion: list[float]) -> None:
    x = _face(3.0) + np.array([0.3, -0.2, 0.0])
    w = np.random.default_rng(0).uniform(0.5, 1.5, len(x))
    w /= w.sum()
    c, a = rigid_fit(x, w)
    t, th = np.array(motion[:3]), np.array(motion[3:]) * 0.01
    u = t + np.cross(th, x - c)
    assert np.allclose(a @ u.ravel(), np.concatenate([t, th]), atol=1e-12)


def _shank(length: float = 8.0) -> tuple[np.ndarray, object, int]:
    head, nut = _face(length), _face(0.0)
    nodes = np.vstack([head, nut])
    n = len(head)
    w = np.full(n, 1.0 / n)
    s = shank_stiffness(nodes, (np.arange(n), w), (n + np.arange(n), w), D, E, NU)
    return nodes, s, n


def test_a_rigid_motion_of_both_faces_stores_nothing() -> None:
    nodes, s, _ = _shank()
    c = nodes.mean(axis=0)
    for k in range(6):
        t, th = np.eye(6)[k, :3], np.eye(6)[k, 3:]
        u = (t + np.cross(th, nodes - c)).ravel()
        assert np.abs(s @ u).max() < 1e-6 * abs(s).max()


def test_axial_torsional_and_lateral_stiffness_are_the_beams() -> None:
    length = 8.0
    nodes, s, n = _shank(length)
    area, inertia = math.pi * D ** 2 / 4, math.pi * D ** 4 / 64
    g = E / (2 * (1 + NU))
    # the head moves up by delta: the force on the head is EA/L delta along -z in total
    u = np.zeros(nodes.shape)
    u[:n, 2] = 1e-3
    f = (s @ u.ravel()).reshape(-1, 3)
    assert f[:n, 2].sum() == pytest.approx(E * area / length * 1e-3, rel=1e-12)
    assert f[n:, 2].sum() == pytest.approx(-E * area / length * 1e-3, rel=1e-12)
    # the head twists by theta about the axis: moment GJ/L theta
    th = 1e-4
    u = np.zeros(nodes.shape)
    u[:n] = np.cross([0.0, 0.0, th], nodes[:n] - nodes[:n].mean(axis=0))
    f = (s @ u.ravel()).reshape(-1, 3)
    r = nodes[:n] - nodes[:n].mean(axis=0)
    assert np.cross(r, f[:n])[:, 2].sum() == pytest.approx(g * 2 * inertia / length * th,
                                                           rel=1e-12)
    # the head offset sideways without rotating: 12 EI / (L^3 (1 + Phi))
    kappa = 6 * (1 + NU) / (7 + 6 * NU)
    phi = 12 * E * inertia / (kappa * g * area * length ** 2)
    u = np.zeros(nodes.shape)
    u[:n, 0] = 1e-3
    f = (s @ u.ravel()).reshape(-1, 3)
    assert f[:n, 0].sum() == pytest.approx(12 * E * inertia / (length ** 3 * (1 + phi)) * 1e-3,
                                           rel=1e-12)


def test_the_beam_matrix_is_symmetric_with_six_rigid_modes() -> None:
    k = beam_stiffness(8.0, D, E, NU, np.array([0.3, -0.4, 1.0]))
    assert np.allclose(k, k.T, rtol=0, atol=1e-9 * np.abs(k).max())
    ev = np.linalg.eigvalsh(k)
    assert np.sum(ev < 1e-9 * ev.max()) == 6 and ev.min() > -1e-9 * ev.max()


LAP = Path(__file__).parent / "data" / "meshes" / "bolted_lap_small.msh"


@pytest.mark.slow
def test_the_shank_carries_the_lap_past_its_friction_torque() -> None:
    """Without a shank a lateral tip load turns the lap about the bolt once the friction
    torque is spent: no equilibrium past about 95 N (an independent CalculiX model of a
    two-plate lap fails at 96.7 N, issue 32); with a 10 mm shank 150 N is carried, and below
    the limit the shank's torsion takes part of the torque off the friction (less W)."""
    from microslip.fe.assembly import Assembly, Contact, Material, Support, bolt
    from microslip.fe.builtin.meshmodel import build_mesh_model
    from microslip.fe.builtin.meshrun import SineCycles, solve_mesh
    from microslip.fe.errors import NonConvergenceError
    from microslip.fe.meshfile import read_mesh
    from microslip.fe.meshload import MeshLoad

    mesh = read_mesh(LAP)

    def run(diameter: float | None, force: float) -> tuple[float, float]:
        pre, shanks = bolt("head", "nut", 5000.0, diameter)
        a = Assembly(contacts=(Contact("a_int", "b_int"),), preloads=pre,
                     supports=(Support("fix"),), materials=(Material(E, NU),), friction=0.3,
                     shanks=shanks)
        r = solve_mesh(build_mesh_model(mesh, a), [MeshLoad("tip", (0.0, 1.0, 0.0), force)],
                       SineCycles(increments=20))
        assert r.settled
        return r.dissipated_energy, float(np.ptp(r.loads[0].loop.displacement))

    with pytest.raises(NonConvergenceError):
        run(None, 150.0)
    w, d = run(D, 150.0)
    assert w > 0 and d > 0
    w_free, d_free = run(None, 50.0)
    w_held, d_held = run(D, 50.0)
    assert w_held < 0.8 * w_free and d_held < d_free


def test_calculix_refuses_a_shank_in_one_line() -> None:
    """The CalculiX deck has no shank yet: an assembly with one is refused, never run
    without it silently."""
    from microslip.errors import ParameterError
    from microslip.fe.assembly import Assembly, Contact, Material, Support, bolt
    from microslip.fe.calculix.meshdeck import build_mesh_deck
    from microslip.fe.meshfile import read_mesh
    from microslip.fe.meshload import MeshLoad

    pre, shanks = bolt("head", "nut", 5000.0, D)
    a = Assembly(contacts=(Contact("a_int", "b_int"),), preloads=pre, shanks=shanks,
                 supports=(Support("fix"),), materials=(Material(E, NU),), friction=0.3,
                 normal_contact="penalty")
    with pytest.raises(ParameterError, match="shanks are not written") as err:
        build_mesh_deck(read_mesh(LAP), a, loads=[MeshLoad("tip", (1.0, 0.0, 0.0), 10.0)])
    assert "\n" not in str(err.value)
