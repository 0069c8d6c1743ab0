"""Linear modes of a clamped mesh (meshdynamics.modes, issue 23): closed forms, orthogonality,
the frames, the labels, ParaView output, bad input, and CalculiX on the same mesh."""

from __future__ import annotations

import dataclasses
import math
import shutil

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import MeshModel, build_mesh_model
from microslip.fe.examples import CANTILEVER, cantilever_mesh
from microslip.fe.hexmesh import HexMesh
from microslip.meshdynamics.modes import (
    describe_motion,
    linear_modes,
    modal_mass,
    modal_stiffness,
    write_modes_vtu,
)

E, NU, RHO = 70000.0, 0.33, 2700.0


def _model(mesh: HexMesh, normal: str = "penalty", slope: float = 1e4,
           element: str = "C3D8I") -> MeshModel:
    return build_mesh_model(mesh, rigid_base(contact_set="contact", clamp_set="clamp",
                                             normal_force=2000.0, modulus=E, poisson_ratio=NU,
                                             friction=0.5, stick_slope=slope, normal_contact=normal,
                                             normal_slope=1e6), element=element)


@pytest.fixture(scope="module")
def cantilever() -> MeshModel:
    return _model(cantilever_mesh(24, 6, 2))


def test_euler_bernoulli_bound() -> None:
    """A slender bar (overhang 200 mm, 12.7 x 6.35 mm) stuck on a very stiff contact: the
    clamped-free Euler-Bernoulli beam (beta_1 L = 1.8751, rigid clamp at the clamp edge) is an
    upper bound the FE reaches within 3 % out of plane and 5 % in plane (the clamped part's
    own flexibility and shear lower the FE)."""
    length, w, h = 200.0, 12.7, 6.35
    mesh = cantilever_mesh(50, 2, 2, clamped_length=50.0, overhang=length, width=w,
                           thickness=h)
    modes = linear_modes(_model(mesh, "fixed", 1e9), RHO, 4, response_set="response")

    def eb(i: float) -> float:
        return 1.8751040687**2 / (2 * math.pi) * math.sqrt(
            E * i / (RHO * 1e-12 * w * h)) / length**2

    out_of_plane, in_plane = modes.frequencies_Hz[:2] / [eb(w * h**3 / 12), eb(h * w**3 / 12)]
    assert 0.97 < out_of_plane < 1.0
    assert 0.95 < in_plane < 1.0
    assert modes.labels[:2] == ("bending out of plane", "bending in the contact plane")


@pytest.mark.slow
def test_convergence_from_above() -> None:
    """Refining the cantilever (12x3x1, 24x6x2, 48x12x4) lowers every one of the first four
    stuck frequencies; 24x6x2 is within 2.5 % of 48x12x4."""
    f = np.array([linear_modes(_model(cantilever_mesh(*s)), RHO, 4).frequencies_Hz
                  for s in ((12, 3, 1), (24, 6, 2), (48, 12, 4))])
    assert np.all(np.diff(f, axis=0) < 0)
    assert np.all(np.abs(f[1] / f[2] - 1) < 0.025)


def test_orthogonal_and_mass_normalised(cantilever: MeshModel) -> None:
    modes = linear_modes(cantilever, RHO, 6)
    k = modal_stiffness(cantilever)
    m = modal_mass(cantilever, RHO)
    phi = modes.vectors.T
    np.testing.assert_allclose(phi.T @ (m @ phi), np.eye(6), atol=1e-9)
    w2 = (2 * math.pi * modes.frequencies_Hz) ** 2
    np.testing.assert_allclose(phi.T @ (k @ phi), np.diag(w2), atol=1e-6 * w2.max())
    # the mass of the whole body along each axis (rho V, t)
    volume = (CANTILEVER["clamped_length"] + CANTILEVER["overhang"]) * CANTILEVER["width"] * \
        CANTILEVER["thickness"]
    full = np.zeros(cantilever.index.size)
    full[0::3] = 1.0
    ex = full[cantilever.free]
    assert float(ex @ (m @ ex)) == pytest.approx(RHO * 1e-12 * volume, rel=1e-12)


def test_descriptions(cantilever: MeshModel) -> None:
    modes = linear_modes(cantilever, RHO, 4, response_set="response")
    assert modes.labels == ("bending out of plane", "bending in the contact plane",
                            "bending out of plane", "torsion")
    np.testing.assert_allclose(np.abs(modes.directions[0]), [0, 0, 1], atol=5e-3)
    np.testing.assert_allclose(np.abs(modes.directions[1]), [0, 1, 0], atol=5e-3)
    assert modes.direction(2) @ modes.directions[1] == pytest.approx(1.0)
    assert abs(modes.directions[3][1]) > 0.99  # torsion about the bottom: a side sway too
    still = dataclasses.replace(modes, response_motion=1e-7 * modes.response_motion)
    with pytest.raises(ParameterError, match="does not move in mode 4"):
        still.direction(4)
    with pytest.raises(ParameterError, match=r"mode must be a whole number in \[1, 4\]"):
        modes.mode(5)
    assert modes.summary()[0]["label"] == "bending out of plane"


def test_describe_motion_rules() -> None:
    pts = np.array([[0, y, z] for y in (-1.0, 1.0) for z in (-0.5, 0.5)])
    axis, normal = np.array([1.0, 0, 0]), np.array([0, 0, 1.0])
    twist = np.cross(np.array([1.0, 0, 0]), pts)
    assert describe_motion(pts, twist, axis, normal)[0] == "torsion"
    assert describe_motion(pts, np.tile([2.0, 0, 0], (4, 1)), axis, normal)[0] == "axial"
    assert describe_motion(pts, np.tile([0, 0, 1.0], (4, 1)), axis, normal)[0] == \
        "bending out of plane"
    assert describe_motion(pts, np.tile([0, 1.0, 0], (4, 1)), axis, normal)[0] == \
        "bending in the contact plane"
    assert describe_motion(pts, np.tile([0, 1.0, 1.0], (4, 1)), axis, normal)[0] == "mixed"
    # a post on a plate: the axis along the normal, all bending in the contact plane
    assert describe_motion(pts, np.tile([1.0, 0, 0], (4, 1)), normal, normal)[0] == \
        "bending in the contact plane"


def test_free_contact_has_three_rigid_motions(cantilever: MeshModel) -> None:
    stuck = linear_modes(cantilever, RHO, 6)
    free = linear_modes(cantilever, RHO, 6, contact="free")
    assert np.all(free.frequencies_Hz[:3] < 1e-3 * stuck.frequencies_Hz[0])
    assert free.frequencies_Hz[3] > 100.0
    # in-plane rigid motions: no normal motion of the contact nodes
    for i in range(3):
        s = free.shapes[i][cantilever.contact_nodes]
        assert np.max(np.abs(s[:, 2])) < 1e-6 * np.max(np.abs(s))
    # the stick springs only add stiffness: every free frequency is lower (Rayleigh)
    assert np.all(free.frequencies_Hz < stuck.frequencies_Hz)


def test_rotated_mesh_same_modes() -> None:
    """The same cantilever turned so that its contact faces +y (the model rotates it back):
    the same frequencies, the shapes turned with it."""
    mesh = cantilever_mesh(12, 3, 1)
    q = np.array([[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]])  # z -> y
    turned = HexMesh(mesh.nodes @ q.T, mesh.elements, dict(mesh.node_sets),
                     dict(mesh.surfaces), source="turned")
    a = linear_modes(_model(mesh), RHO, 4, response_set="response")
    b = linear_modes(_model(turned), RHO, 4, response_set="response")
    np.testing.assert_allclose(b.frequencies_Hz, a.frequencies_Hz, rtol=1e-8)
    np.testing.assert_allclose(np.abs(b.directions), np.abs(a.directions @ q.T), atol=1e-6)
    assert b.labels == a.labels


def test_vtu(cantilever: MeshModel, tmp_path) -> None:
    meshio = pytest.importorskip("meshio")
    modes = linear_modes(cantilever, RHO, 3)
    path = write_modes_vtu(cantilever, modes, tmp_path / "modes.vtu")
    back = meshio.read(path)
    assert len(back.point_data) == 3
    first = next(iter(back.point_data.values()))
    assert np.max(np.linalg.norm(first, axis=1)) == pytest.approx(1.0)
    assert back.points.shape == cantilever.mesh.nodes.shape


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"density_kg_m3": 0.0}, "density must be > 0"),
    ({"n_modes": 0}, "n_modes must be a whole number"),
    ({"contact": "glued"}, "unknown contact state 'glued'"),
    ({"response_set": "nowhere"}, "no set named 'nowhere'"),
])
def test_bad_input(cantilever: MeshModel, kwargs: dict, message: str) -> None:
    args = {"density_kg_m3": RHO} | kwargs
    with pytest.raises(ParameterError, match=message):
        linear_modes(cantilever, **args)


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason="ccx not on PATH")
@pytest.mark.parametrize(("element", "tol"), [("C3D8", 0.01), ("C3D8I", 0.02)])
def test_against_calculix(element: str, tol: float) -> None:
    """The cantilever 24x6x2 (2700 kg/m^3, E 70000 MPa, nu 0.33, mu 0.5, F_N 2000 N, stick slope
    1e4 N/mm^3, penalty normal 1e6 N/mm^3): the first six stuck frequencies against CalculiX's
    perturbation frequency step after its clamping step. C3D8 on both sides: within 1 % (the
    nodal stick springs against CalculiX's face-to-face contact: up to 0.94 %, and 0 with a
    rigid contact); C3D8I: within 2 % (the two incompatible-mode elements differ by up to
    1.4 % in the fifth mode even with a rigid contact), the first four within 1 %."""
    from microslip.fe.calculix.meshrun import run_frequency_calculix

    mesh = cantilever_mesh(24, 6, 2)
    ours = linear_modes(_model(mesh, element=element), RHO, 6).frequencies_Hz
    ccx = run_frequency_calculix(
        mesh, rigid_base(contact_set="contact", clamp_set="clamp", normal_force=2000.0,
                         friction=0.5, stick_slope=1e4, normal_contact="penalty",
                         normal_slope=1e6, modulus=E, poisson_ratio=NU),
        density_kg_m3=RHO, modes=6, element=element)
    np.testing.assert_allclose(ours, ccx[:6], rtol=tol)
    np.testing.assert_allclose(ours[:4], ccx[:4], rtol=0.01)


def test_rigid_block_on_its_stick_springs() -> None:
    """A nearly rigid block (30 x 10 x 5 mm, E = 1e8 MPa) on soft stick springs lambda A_i
    (lambda 1e3 N/mm^3, fixed normal): the first two modes are the in-plane translations,
    omega^2 = lambda A / m, the third the turn about the normal,
    omega^2 = sum lambda A_i r_i^2 / J_z, J_z = m (Lx^2 + Ly^2) / 12; to 1e-4 (3e-5: the
    body is not quite rigid)."""
    from microslip.fe.examples import grid_mesh

    mesh = grid_mesh([0, 10, 20, 30], [0, 10], [0, 5], node_sets={
        "contact": lambda x, y, z: z < 1e-9, "clamp": lambda x, y, z: z > 5 - 1e-9},
        surfaces=("contact", "clamp"))
    model = build_mesh_model(mesh, rigid_base(contact_set="contact", clamp_set="clamp",
                                              normal_force=100.0, modulus=1e8, poisson_ratio=0.0,
                                              friction=0.5, stick_slope=1e3,
                                              normal_contact="fixed"))
    modes = linear_modes(model, RHO, 3)
    mass = RHO * 1e-12 * 30 * 10 * 5
    k = float(model.contact_stiffness.sum())
    r = mesh.nodes[model.contact_nodes, :2] - [15.0, 5.0]
    k_turn = float(np.sum(model.contact_stiffness * np.sum(r**2, axis=1)))
    omega = np.sqrt([k / mass, k / mass, k_turn / (mass * (30**2 + 10**2) / 12)])
    np.testing.assert_allclose(modes.frequencies_Hz, omega / (2 * math.pi), rtol=1e-4)
