"""The whole-joint model (meshdynamics.wholejoint): the reduction to the interface's rigid
motion, the joint from the FE's first loading, EPMC on it, and its measured error against the
full FE on the 12x3x1 cantilever."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import CANTILEVER, cantilever_mesh
from microslip.meshdynamics.modes import linear_modes
from microslip.meshdynamics.reduce import build_rom
from microslip.meshdynamics.wholejoint import (
    build_whole_joint,
    first_loading,
    interface,
    joint_backbone,
    reduce_to_interface,
    whole_joint_epmc,
)

RHO = 2700.0


@pytest.fixture(scope="module")
def model():  # type: ignore[no-untyped-def]
    return build_mesh_model(cantilever_mesh(12, 3, 1), rigid_base(contact_set="contact",
                                                                  clamp_set="clamp",
                                                                  normal_force=2000.0,
                                                                  modulus=70000.0,
                                                                  poisson_ratio=0.33, friction=0.5,
                                                                  stick_slope=1e4))


@pytest.fixture(scope="module")
def modes(model):  # type: ignore[no-untyped-def]
    return linear_modes(model, RHO, 6, "stuck", "response")


@pytest.fixture(scope="module")
def rom(model):  # type: ignore[no-untyped-def]
    return build_rom(model, RHO, modes=20, response_set="response")


def test_rigid_motion_of_the_interface_stores_no_energy(model,
                                                        rom) -> None:  # type: ignore[no-untyped-def]
    """r1, r2 and the in-plane rotation c move the whole body rigidly (the constraint modes
    carry the interface's rigid motion inside): K_j p = 0 to rounding."""
    face = interface(model)
    _, _, k = reduce_to_interface(rom, face)
    scale = float(np.max(np.abs(k)))
    for j in range(3):
        p = np.zeros(k.shape[0])
        p[j] = 1.0
        assert float(np.max(np.abs(k @ p))) < 1e-9 * scale


def test_rigid_translation_carries_the_body_mass(model,
                                                 rom) -> None:  # type: ignore[no-untyped-def]
    """T^T M T of a unit translation r1 (or r2) is the body's mass, rho x volume (t)."""
    _, m, _ = reduce_to_interface(rom, interface(model))
    c = CANTILEVER
    volume = (c["clamped_length"] + c["overhang"]) * c["width"] * c["thickness"]
    mass = RHO * 1e-12 * volume
    assert m[0, 0] == pytest.approx(mass, rel=1e-9)
    assert m[1, 1] == pytest.approx(mass, rel=1e-9)


def test_stuck_contact_is_the_summed_stiffness_on_every_coordinate(model) -> None:  # type: ignore[no-untyped-def]
    """Through the area-weighted averaging the stuck springs lambda A_i are G^T diag(k) G =
    (sum lambda A_i) I on (r1, r2, c): the centroid decouples them, R scales c."""
    face = interface(model)
    k = np.repeat(model.contact_stiffness, 2)
    g = face.rigid
    np.testing.assert_allclose(g.T @ (k[:, None] * g), model.contact_stiffness.sum()
                               * np.eye(3), rtol=0, atol=1e-9 * model.contact_stiffness.sum())


def test_backbone_starts_at_the_stuck_interface_stiffness(model,
                                                          modes) -> None:  # type: ignore[no-untyped-def]
    """The first loading's first (stuck) increment has the slope sum lambda A_i, in the
    translation and in the rotation, and both curves soften (concave) towards gross
    sliding."""
    bb = joint_backbone(model, modes.select(2))
    k = float(model.contact_stiffness.sum())
    assert bb.source == "mode"
    assert bb.force[1] / bb.displacement[1] == pytest.approx(k, rel=1e-9)
    assert bb.moment[1] / bb.rotation[1] == pytest.approx(k, rel=1e-9)
    for d, f in ((bb.displacement, bb.force), (bb.rotation, bb.moment)):
        slopes = np.diff(f) / np.diff(d)
        assert np.all(np.diff(slopes) <= 1e-9 * slopes[0])
        assert slopes[-1] < 0.2 * slopes[0]
    assert bb.translation().initial_stiffness == pytest.approx(k, rel=1e-9)


def test_out_of_plane_bending_gives_no_interface_law(model,
                                                     modes) -> None:  # type: ignore[no-untyped-def]
    """Out-of-plane bending: the contact's resultant opposes its mean motion (the bending
    strain stretches the interface), so the joint is the pull test's and the mode does
    not turn the interface."""
    mode = modes.select(1)
    own = first_loading(model, mode, interface(model))
    assert float(own.displacement[-1, 0] * own.force[-1, 0]) < 0
    bb = joint_backbone(model, mode)
    assert bb.source == "pull" and bb.rotation.size == 0
    assert bb.force[1] / bb.displacement[1] == pytest.approx(
        float(model.contact_stiffness.sum()), rel=1e-9)


@pytest.mark.slow
def test_epmc_starts_at_the_whole_joint_stuck_frequency(model, modes,
                                                        rom) -> None:  # type: ignore[no-untyped-def]
    """Below first slip the EPMC's frequency is the whole-joint model's stuck frequency and
    its damping ratio is nil."""
    mode = modes.select(2)
    wj = build_whole_joint(rom, model, mode, mode.direction @ rom.output)
    curve, failed = whole_joint_epmc(wj, np.array([1e-6]), 3, 32, mode.frequency_Hz)
    assert failed == ()
    stuck = wj.stuck_frequencies()[wj.mode_index(mode.frequency_Hz)]
    assert curve.frequency[0] == pytest.approx(stuck, rel=1e-9)
    assert abs(curve.damping_ratio[0]) < 1e-9


@pytest.mark.slow
def test_whole_joint_against_the_full_fe(model, modes) -> None:  # type: ignore[no-untyped-def]
    """The error the whole-joint model has on the in-plane bending of the 12x3x1 cantilever
    (benchmarks/joint_vs_fe.py, measured): its stuck frequency is 3.6 % high (the rigid
    interface stiffens the clamped length) and at the first slipping amplitude its damping
    ratio is about a twentieth of the full FE's (6 %): along the mode's first loading the
    interface's rigid motion does only 14 % of the friction forces' work there, the rest
    is the distortion of the contact (the bar bending inside the clamp) that the reduction
    removes. Bounds a little wider than the measurement."""
    from microslip.meshdynamics.qsma import qsma, qsma_amplitudes

    mode = modes.select(2)
    rom = build_rom(model, RHO, modes=60, response_set="response")
    wj = build_whole_joint(rom, model, mode, mode.direction @ rom.output)
    stuck = wj.stuck_frequencies()[wj.mode_index(mode.frequency_Hz)]
    assert 0.03 < stuck / mode.frequency_Hz - 1 < 0.042
    fe = qsma(model, mode, qsma_amplitudes(model, mode, 1))
    a = fe.amplitude_mm
    curve, _ = whole_joint_epmc(wj, a, 7, 64, mode.frequency_Hz)
    assert 0.03 < curve.frequency[0] / fe.frequency_Hz[0] - 1 < 0.045
    assert 0.03 < curve.damping_ratio[0] / fe.damping_ratio[0] < 0.12
    loading = wj.backbone.loading
    share = loading.rigid_work[1:] / loading.work[1:]
    assert 0.1 < share[1] < 0.2 and share[-1] > 0.6
    assert math.isfinite(curve.damping_ratio[0])


def test_penalty_interface_holds_its_normal_motion_on_the_summed_springs() -> None:
    """With penalty normal contact the interface also translates along the normal (w) and
    tilts: a unit w stretches no element and compresses every penalty spring, K_j[w, w] =
    sum k_n A_i, and the tilts are held by sum k_n A_i times the squared arm (over R^2),
    uncoupled from w about the area-weighted centroid."""
    m = build_mesh_model(cantilever_mesh(6, 1, 1), rigid_base(contact_set="contact",
                                                              clamp_set="clamp",
                                                              normal_force=2000.0, modulus=70000.0,
                                                              poisson_ratio=0.33, friction=0.5,
                                                              stick_slope=1e4,
                                                              normal_contact="penalty"))
    rom = build_rom(m, RHO, modes=5)
    face = interface(m)
    assert face.coordinates == ("r1", "r2", "c", "w", "t1", "t2")
    _, _, k = reduce_to_interface(rom, face)
    kn = np.asarray(m.normal.stiffness)
    assert k[3, 3] == pytest.approx(kn.sum(), rel=1e-9)
    x = face.points  # a tilt of the whole body is rigid too: only the springs resist it
    assert k[4, 4] == pytest.approx(float(kn @ x[:, 1] ** 2) / face.radius**2, rel=1e-9)
    assert k[5, 5] == pytest.approx(float(kn @ x[:, 0] ** 2) / face.radius**2, rel=1e-9)
    assert abs(k[3, 4]) < 1e-9 * kn.sum() and abs(k[3, 5]) < 1e-9 * kn.sum()
    for j in range(3):
        assert abs(k[j, j]) < 1e-9 * kn.sum()


def test_clamp_model_backbone_on_the_contact_patch(model,
                                                   modes) -> None:  # type: ignore[no-untyped-def]
    """--backbone tip: the paper's tip model on the contact patch seen along the mode's
    motion (in-plane bending: along y, the patch 25.4 mm long, 50.8 mm wide, the bar 6.35 mm
    thick) behind the contact layer sum lambda A_i: its initial slope is near the FE's
    stuck interface stiffness and it slides as a whole at mu F_N."""
    from microslip.meshdynamics.wholejoint import clamp_backbone, patch

    mode = modes.select(2)
    face = interface(model)
    p = patch(model, face, np.array([0.0, 1.0]))
    c = CANTILEVER
    assert (p.length, p.width, p.thickness) == pytest.approx(
        (c["width"], c["clamped_length"], c["thickness"]), rel=1e-12)
    bb = clamp_backbone(model, mode, "tip", face)
    k = float(model.contact_stiffness.sum())
    assert bb.source == "tip" and bb.loading is None and bb.rotation.size == 0
    # the first segment is the secant to the model's first force step (mu F_N / 201): the
    # bar's own microslip (F ~ sqrt(d)) in series with the layer takes 3.5 % off k there
    slope = bb.force[1] / bb.displacement[1]
    assert 0.95 * k < slope < k
    assert bb.force[-1] == pytest.approx(0.5 * 2000.0, rel=1e-9)
    assert bb.translation().initial_stiffness == pytest.approx(slope, rel=1e-9)


def test_work_backbone_does_the_interface_s_whole_work(model,
                                                       modes) -> None:  # type: ignore[no-untyped-def]
    """--backbone work: the same forces as the kinematic backbone, the displacements
    stretched by the interface's work over its rigid motion's, so that the joint's work
    along the loading is the friction forces' whole work (to the concave majorant's
    discreteness); its initial slope is the stuck interface stiffness times the rigid share
    of the stuck contact's energy (14 % on the 12x3x1 cantilever's in-plane bending)."""
    from microslip.meshdynamics.wholejoint import work_backbone

    mode = modes.select(2)
    bb = work_backbone(model, mode)
    assert bb.source == "work" and bb.loading is not None
    loading = bb.loading
    share = loading.rigid_work[1] / loading.work[1]
    k = float(model.contact_stiffness.sum())
    assert bb.force[1] / bb.displacement[1] == pytest.approx(k * share, rel=1e-6)
    assert 0.1 < share < 0.2

    def work(d: np.ndarray, f: np.ndarray) -> float:
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(d)))

    total = work(bb.displacement, bb.force) + work(bb.rotation, bb.moment)
    assert total == pytest.approx(loading.work[-1], rel=0.02)
    # out-of-plane bending: nothing to stretch, the pull test's joint
    assert work_backbone(model, modes.select(1)).source == "pull"


def test_command_line_names_every_backbone() -> None:
    """The parser's --backbone choices are the library's backbones (named twice so that the
    command line starts without importing the FE)."""
    from microslip.meshdynamics.case import BACKBONE_NAMES
    from microslip.meshdynamics.wholejoint import BACKBONES

    assert tuple(BACKBONES) == BACKBONE_NAMES
