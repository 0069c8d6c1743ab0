"""Two close modes that share the interface (issue 23, item 6): the post-on-plate mesh, its
two bending modes, the quasi-static ROM's node laws, and coupled against decoupled joints."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.builtin.meshrun import SineCycles
from microslip.fe.examples import POST_ON_PLATE, post_on_plate_mesh
from microslip.fe.hexmesh import face_load
from microslip.fe.meshcheck import check_roles
from microslip.meshdynamics import twomode as tm
from microslip.meshdynamics.reduce import Rom

CASE = tm.TwoModeCase()
#: One harmonic for the slow tests (the continuation's speed; the physics' tests need not
#: the converged microslip W_J).
CASE1 = tm.TwoModeCase(harmonics=1)


@pytest.fixture(scope="module")
def small():  # type: ignore[no-untyped-def]
    """The coarse post (5 mm elements, 10 mm in the flange): 25 contact nodes."""
    mesh = post_on_plate_mesh(5.0, 5.0, 10.0)
    model = tm.two_mode_model(mesh, CASE)
    return model, tm.bending_pair(model, CASE), tm.study_rom(model, CASE)


def _area(mesh, name: str) -> float:  # type: ignore[no-untyped-def]
    return face_load(mesh, mesh.faces(name))[2]


def test_post_on_plate_sets() -> None:
    g = POST_ON_PLATE
    m = post_on_plate_mesh(2.5, 5.0, 5.0)
    check_roles(m, "contact", "clamp", loads=["top", "response"])
    assert _area(m, "contact") == pytest.approx(g.flange**2, rel=1e-12)
    assert _area(m, "clamp") == pytest.approx(g.flange**2 - g.post_x * g.post_y, rel=1e-12)
    assert _area(m, "top") == pytest.approx(g.post_x * g.post_y, rel=1e-12)
    top = g.flange_thickness + g.post_height
    assert np.all(m.nodes[m.node_sets["contact"], 2] == 0.0)
    assert np.all(m.nodes[m.node_sets["clamp"], 2] == g.flange_thickness)
    assert np.all(m.nodes[m.node_sets["top"], 2] == top)
    assert np.array_equal(m.node_sets["response"], m.node_sets["top"])
    # the clamp leaves the post's footprint out: no clamp node strictly inside it
    xy = m.nodes[m.node_sets["clamp"], :2]
    assert not np.any((np.abs(xy[:, 0]) < g.post_x / 2 - 1e-9)
                      & (np.abs(xy[:, 1]) < g.post_y / 2 - 1e-9))


def test_post_must_fit_and_sizes_positive() -> None:
    with pytest.raises(ParameterError, match="element size must be > 0 mm"):
        post_on_plate_mesh(0.0)
    with pytest.raises(ParameterError, match="must fit on the flange"):
        post_on_plate_mesh(5.0, geometry=tm_geometry(post_y=40.0))


def tm_geometry(**kw: float):  # type: ignore[no-untyped-def]
    from dataclasses import replace

    return replace(POST_ON_PLATE, **kw)


def test_two_lowest_modes_are_the_close_bending_pair(small) -> None:  # type: ignore[no-untyped-def]
    _, pair, rom = small
    assert 0.01 < pair.separation < 0.05  # 10 x 10.5 mm: bending in x about 4 % below y
    assert np.allclose(np.abs(pair.directions), [[1, 0, 0], [0, 1, 0]], atol=1e-6)
    assert all("bending" in lab for lab in pair.labels)
    # the ROM's two lowest stuck frequencies are the full FE's
    assert np.allclose(rom.stuck_frequencies(2), pair.frequencies_Hz, rtol=1e-7)


def test_orbit_axes() -> None:
    line = tm.orbit(1.0 + 0j, 0.5 + 0j)
    assert line.ratio == pytest.approx(0.0, abs=1e-15)
    assert line.major == pytest.approx(math.hypot(1.0, 0.5))
    assert line.angle_deg == pytest.approx(math.degrees(math.atan2(0.5, 1.0)))
    ellipse = tm.orbit(2.0 + 0j, -0.5j)
    assert (ellipse.major, ellipse.minor, ellipse.ratio) == pytest.approx((2.0, 0.5, 0.25))


def _one_node(k_body: float, k: float, s: float) -> Rom:
    """A one-node ROM: the body a spring k_body in x and y, the node (k, s) to the ground."""
    z = np.zeros(1)
    return Rom(mass=np.eye(2), stiffness=k_body * np.eye(2), boundary=np.arange(2),
               per_node=2, interface_frequencies=np.zeros(0), contact_stiffness=np.array([k]),
               slip_force=np.array([s]), normal_stiffness=z, friction=0.5, output=None,
               build_s=0.0)


def _jenkins_w(k_body: float, k: float, s: float, load: float) -> float:
    """W per cycle of a 1-D Jenkins (k, s) in parallel with k_body under a force +-load:
    4 s (u - s / k) at the displacement u of load = k_body u + s (slipping at the peak)."""
    u = (load - s) / k_body
    return 4.0 * s * (u - s / k)


@pytest.mark.parametrize("coupling", tm.COUPLINGS)
def test_straight_path_along_an_axis_is_the_1d_jenkins(coupling: str) -> None:
    """Along x both couplings are the 1-D element exactly (the path's y stays 0)."""
    rom = _one_node(100.0, 1000.0, 5.0)
    history = SineCycles(increments=400)
    w = tm.rom_quasistatic(rom, np.array([20.0, 0.0]), coupling, history)
    assert w.settled
    assert w.energy_Nmm == pytest.approx(_jenkins_w(100.0, 1000.0, 5.0, 20.0), rel=1e-4)


def test_diagonal_path_circular_against_decoupled() -> None:
    """At 45 degrees the circular element slips at s, the decoupled pair at s sqrt 2."""
    rom = _one_node(100.0, 1000.0, 5.0)
    history = SineCycles(increments=400)
    load = 20.0 * np.array([1.0, 1.0]) / math.sqrt(2.0)
    circ = tm.rom_quasistatic(rom, load.astype(complex), "circular", history).energy_Nmm
    dec = tm.rom_quasistatic(rom, load.astype(complex), "decoupled", history).energy_Nmm
    assert circ == pytest.approx(_jenkins_w(100.0, 1000.0, 5.0, 20.0), rel=1e-4)
    assert dec == pytest.approx(_jenkins_w(100.0, 1000.0, 5.0 * math.sqrt(2), 20.0), rel=1e-4)
    assert abs(dec / circ - 1.0) > 0.1  # under force control here: more W with the larger limit


def test_rotating_load_circular_closed_form_and_decoupled_differs() -> None:
    """A load of constant magnitude G turning on a circle: the circular element slides all
    round on a circle of radius A, its slider trailing at phi = s / k, so that
    G^2 = (K A + s phi / A)^2 + s^2 (A^2 - phi^2) / A^2 and W = 2 pi s sqrt(A^2 - phi^2)
    (REFERENCES.md, 2-D Jenkins); the decoupled pair gives another W."""
    from scipy.optimize import brentq

    kb, k, s, g = 100.0, 1000.0, 5.0, 20.0
    phi = s / k
    a = brentq(lambda r: (kb * r + s * phi / r) ** 2 + s**2 * (r**2 - phi**2) / r**2 - g**2,
               phi, g / kb)
    rom = _one_node(kb, k, s)
    load = np.array([g, -g * 1j])
    history = SineCycles(increments=400, tol=1e-5, max_cycles=20)
    circ = tm.rom_quasistatic(rom, load, "circular", history)
    dec = tm.rom_quasistatic(rom, load, "decoupled", history)
    assert circ.settled and dec.settled
    assert circ.energy_Nmm == pytest.approx(2 * math.pi * s * math.sqrt(a**2 - phi**2),
                                            rel=5e-3)  # backward Euler, 400 steps
    assert abs(circ.energy_Nmm / dec.energy_Nmm - 1.0) > 0.02


def test_unknown_coupling_refused(small) -> None:  # type: ignore[no-untyped-def]
    _, _, rom = small
    with pytest.raises(ParameterError, match="unknown coupling 'elliptic'"):
        tm.rom_system(rom, "elliptic", 0.005, tm.forcing_shape(rom, 45.0))


def test_forcing_and_interface_rows(small) -> None:  # type: ignore[no-untyped-def]
    model, _, rom = small
    rows = tm.interface_rows(model, rom)
    # a unit tangential displacement of every contact node along x moves the mean by 1 in x
    nb = rom.boundary.size
    ux = np.zeros(rom.dofs)
    ux[0:nb:2] = 1.0
    assert rows @ ux == pytest.approx([1.0, 0.0])
    s = tm.forcing_shape(rom, 45.0)
    assert s == pytest.approx((rom.output[0] + rom.output[1]) / math.sqrt(2.0))


@pytest.mark.slow
def test_forced_response_and_full_fe_check(small) -> None:  # type: ignore[no-untyped-def]
    """Both resonances; the interface on an ellipse; the full FE's W equals the circular
    ROM's under the same quasi-static load; the decoupled joints differ."""
    model, pair, rom = small
    window = tm.frequency_window(pair)
    curves = {c: tm.forced_response(model, rom, CASE1, 10.0, c, window)
              for c in tm.COUPLINGS}
    circ = curves["circular"]
    assert circ.success
    px, py = circ.peaks
    f1, f2 = pair.frequencies_Hz
    assert 0.98 * f1 < px.frequency_Hz < f1 < py.frequency_Hz < f2  # softened by the slip
    assert 0.0 < px.orbit.ratio < 1.0 and float(circ.orbit_ratio.max()) > 0.1
    assert 0.0 < px.joint_energy_Nmm < px.total_energy_Nmm
    assert curves["decoupled"].peaks[0].amplitude_mm != pytest.approx(px.amplitude_mm,
                                                                     rel=1e-3)
    check = tm.fe_check(model, rom, pair, CASE1, circ, px.index, "x peak")
    assert check.fe_settled and check.inertia_share > 0.99
    assert check.fe_Nmm == pytest.approx(check.rom_circular_Nmm, rel=2e-3)
    assert abs(check.rom_decoupled_Nmm / check.fe_Nmm - 1.0) > 0.05


@pytest.mark.slow
def test_forcing_along_x_puts_the_interface_on_a_line(small) -> None:  # type: ignore[no-untyped-def]
    """Forced along x, the interface's mean motion is a line along x (the y mode is not
    excited; by symmetry every node's y motion cancels in the mean)."""
    from dataclasses import replace

    model, pair, rom = small
    case = replace(CASE1, angle_deg=0.0)
    window = tm.frequency_window(pair)
    circ = tm.forced_response(model, rom, case, 10.0, "circular", window)
    assert float(np.max(circ.orbit_ratio)) < 1e-6
    assert float(np.max(np.abs(circ.interface_mm[:, 1]))) < 1e-6 * float(
        np.max(np.abs(circ.interface_mm[:, 0])))
    # ... but the nodes do not move along x: the flange carries the shear and the bending
    # out to its edges, each node on its own line or thin ellipse at up to tens of degrees
    # from x, so the decoupled joints are not the circular ones even here
    i = circ.peaks[0].index
    _, angle = tm.node_orbits(rom, circ, i)
    assert float(np.max(angle)) > 20.0
    load = tm.quadrature_load(model, rom, pair, case, circ, i)
    w = {c: tm.rom_quasistatic(rom, load.rom, c).energy_Nmm for c in tm.COUPLINGS}
    assert abs(w["decoupled"] / w["circular"] - 1.0) > 0.1


def test_figure_is_written(tmp_path) -> None:  # type: ignore[no-untyped-def]
    pytest.importorskip("matplotlib")
    from microslip.plot.twomode import plot_two_mode

    f = np.linspace(4600.0, 5000.0, 9)
    amp = 1.0 / (1.0 + np.abs(f - 4700.0))
    inter = np.stack([amp + 0j, -0.3j * amp], axis=1)
    o = tm.orbit(complex(inter[1, 0]), complex(inter[1, 1]))
    peak = tm.Peak("x", 1, 4650.0, 0.5, 1.0, 2.0, o)
    curves = [tm.ResponseCurve(coupling=c, force=10.0, frequency_Hz=f, top_x_mm=amp,
                               top_y_mm=0.5 * amp, interface_mm=inter,
                               orbit_ratio=np.full(9, 0.3), joint_energy_Nmm=amp,
                               coefficients=np.zeros((9, 3)), peaks=(peak, peak),
                               harmonics=1, success=True, message="")
              for c in tm.COUPLINGS]
    out = tmp_path / "two_mode.png"
    plot_two_mode(curves, out, [("x peak", 1)])
    assert out.stat().st_size > 1000
