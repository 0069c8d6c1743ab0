"""Quadratic hexahedra in the built-in solver (issue 29, item 3): the element against exact
references (patch test, Timoshenko cantilever), the contact of 8-node faces, the promotion
of an 8-node mesh, CalculiX C3D20R's stuck frequencies, the command line."""

from __future__ import annotations

import json
import math
import shutil

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from microslip.cli.main import main
from microslip.errors import ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.hex20 import (
    CONTACT_WEIGHTS,
    HEX20_ELEMENTS,
    NODE_XI20,
    assemble_hex20,
    element_stiffness20,
    face_mass,
    mass_matrix20,
)
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import cantilever_mesh, grid_mesh
from microslip.fe.meshfile import read_mesh
from microslip.fe.promote import as_element, demote_mesh, promote_mesh
from microslip.fe.refine import refine_mesh
from microslip.meshdynamics.modes import linear_modes

E, NU, RHO = 70000.0, 0.33, 2700.0


def _box20(xs, ys, zs, **kw):
    return promote_mesh(grid_mesh(xs, ys, zs, **kw))


# --- the element ------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", list(HEX20_ELEMENTS))
def test_patch_test_distorted_mesh(kind: str) -> None:
    """A 2x2x2 mesh with its middle node moved off centre (distorted elements, straight
    edges): a linear displacement imposed on the boundary gives the same linear field inside
    (the interior nodes) to rounding, and a linear field is a zero-residual state at every
    interior dof."""
    mesh8 = grid_mesh([0, 1, 2], [0, 1, 2], [0, 1, 2])
    nodes = mesh8.nodes.copy()
    centre = int(np.flatnonzero(np.all(nodes == 1.0, axis=1))[0])
    nodes[centre] = (1.2, 0.85, 1.1)
    mesh = promote_mesh(type(mesh8)(nodes, mesh8.elements))
    x = mesh.nodes
    k = assemble_hex20(x, mesh.elements, E, NU, kind)
    grad = np.array([[1e-3, 2e-4, -3e-4], [5e-4, -1e-3, 1e-4], [-2e-4, 3e-4, 7e-4]])
    u_exact = (x @ grad.T + np.array([1e-3, -2e-3, 5e-4])).ravel()
    boundary = np.any((x <= 1e-12) | (x >= 2 - 1e-12), axis=1)
    inner = np.flatnonzero(~boundary)
    dof_in = (3 * inner[:, None] + np.arange(3)).ravel()
    dof_b = np.setdiff1d(np.arange(3 * len(x)), dof_in)
    k = k.tocsr()
    u_in = spla.spsolve(k[dof_in][:, dof_in].tocsc(), -k[dof_in][:, dof_b] @ u_exact[dof_b])
    np.testing.assert_allclose(u_in, u_exact[dof_in], rtol=0, atol=1e-14)
    assert np.max(np.abs((k @ u_exact)[dof_in])) < 1e-9


def test_rigid_motions_and_rank() -> None:
    """One C3D20 element: six zero-energy rigid motions, rank 60 - 6; C3D20R (2x2x2) has
    the known further spurious modes of a lone element (rank 60 - 12)."""
    cube = NODE_XI20[None] * np.array([2.0, 1.0, 0.5]) + 1.0
    full = np.linalg.eigvalsh(element_stiffness20(cube, E, NU, "C3D20")[0])
    reduced = np.linalg.eigvalsh(element_stiffness20(cube, E, NU, "C3D20R")[0])
    tol = 1e-9 * full.max()
    assert int(np.sum(np.abs(full) < tol)) == 6
    assert int(np.sum(np.abs(reduced) < tol)) == 12


def test_mass_of_a_distorted_element() -> None:
    """The consistent mass carries rho V in each direction (V of a distorted element with
    straight edges: the trilinear volume)."""
    mesh8 = grid_mesh([0, 2], [0, 1], [0, 1])
    nodes = mesh8.nodes.copy()
    nodes[-1] += (0.3, 0.2, 0.1)
    mesh = promote_mesh(type(mesh8)(nodes, mesh8.elements))
    m = mass_matrix20(mesh.nodes, mesh.elements, 3.0)
    from microslip.fe.builtin.mass import mass_matrix

    v8 = float(mass_matrix(nodes, mesh8.elements, 1.0).sum()) / 3
    assert float(m.sum()) / 3 == pytest.approx(3.0 * v8, rel=1e-13)
    # mass.mass_matrix dispatches 20-node meshes here
    assert abs(mass_matrix(mesh.nodes, mesh.elements, 3.0) - m).max() == 0.0


def _clamped_beam(nx: int, ny: int, nz: int, length: float, b: float, h: float, kind: str,
                  nu: float = 0.0):
    """A cantilever x in [0, L] (width b along y, height h along z), every dof of x = 0 held:
    the stiffness and mass of the free dofs and its nodes."""
    mesh = _box20(np.linspace(0, length, nx + 1), np.linspace(0, b, ny + 1),
                  np.linspace(0, h, nz + 1))
    k = assemble_hex20(mesh.nodes, mesh.elements, E, nu, kind).tocsr()
    m = mass_matrix20(mesh.nodes, mesh.elements, RHO * 1e-12).tocsr()
    free = np.flatnonzero(np.repeat(mesh.nodes[:, 0] > 1e-12, 3))
    return mesh, k[free][:, free], m[free][:, free], free


@pytest.mark.parametrize("kind", list(HEX20_ELEMENTS))
def test_cantilever_tip_deflection_timoshenko(kind: str) -> None:
    """A 100 x 10 x 10 mm beam, nu = 0, 10 x 1 x 1 hex20 (10 elements): the tip deflection
    under an end shear P (consistent traction on the end face) against Timoshenko's
    P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6: within 0.5 % (the fully held root
    face is stiffer than the beam theory's clamp; 10 hex8 C3D8I elements are 2 % off)."""
    length, b, h, p = 100.0, 10.0, 10.0, 100.0
    mesh, k, _, free = _clamped_beam(10, 1, 1, length, b, h, kind)
    end = mesh.nodes[:, 0] > length - 1e-9
    from microslip.fe.hexmesh import face_load

    faces = np.array([[e, 3] for e in range(len(mesh.elements))
                      if np.all(end[mesh.elements[e, [1, 5, 6, 2]]])])
    nodes, share, _ = face_load(mesh, faces)
    f = np.zeros(3 * len(mesh.nodes))
    f[3 * nodes + 2] = p * share
    u = spla.spsolve(k.tocsc(), f[free])
    full = np.zeros(3 * len(mesh.nodes))
    full[free] = u
    tip = float(np.mean(full[3 * np.flatnonzero(end) + 2]))
    inertia, g = b * h**3 / 12.0, E / 2.0
    exact = p * length**3 / (3 * E * inertia) + p * length / (5.0 / 6.0 * g * b * h)
    assert tip == pytest.approx(exact, rel=5e-3)


@pytest.mark.parametrize(("kind", "n"), [("C3D20R", 2), ("C3D20", 1)])
def test_cantilever_first_frequency_euler_bernoulli(kind: str, n: int) -> None:
    """The same beam 200 x 10 x 10 mm (L/h = 20), 10 x n x n elements (C3D20R needs two
    through each direction: a lone element's spurious modes communicate along a beam one
    element thick): the first bending frequency against Euler-Bernoulli
    (1.8751^2 / (2 pi L^2)) sqrt(E I / (rho A)): within 0.6 % and below it (shear and rotary
    inertia lower it by about 0.3 % at L/h = 20, Timoshenko); the two bending planes agree."""
    length, b, h = 200.0, 10.0, 10.0
    _, k, m, _ = _clamped_beam(10, n, n, length, b, h, kind)
    vals = spla.eigsh(k.tocsc(), k=2, M=m.tocsc(), sigma=0.0, which="LM")[0]
    f = np.sqrt(np.sort(vals)) / (2 * math.pi)
    eb = 1.8751040687**2 / (2 * math.pi * (length * 1e-3) ** 2) * math.sqrt(
        E * 1e6 * (b * h**3 / 12 * 1e-12) / (RHO * b * h * 1e-6))
    assert f[0] == pytest.approx(f[1], rel=1e-9)
    assert 0.994 * eb < f[0] < eb


# --- contact on 8-node faces -------------------------------------------------------------------

@pytest.mark.parametrize("name", list(CONTACT_WEIGHTS))
def test_contact_weights_positive_and_exact_area(name: str) -> None:
    """On a parallelogram face every weighting is positive and adds up to the area; the
    consistent shares are -1/12 and 1/3 (what the weights replace)."""
    x = np.array([[0, 0, 0], [2, 0, 0], [2.5, 1, 0], [0.5, 1, 0], [1, 0, 0], [2.25, 0.5, 0],
                  [1.5, 1, 0], [0.25, 0.5, 0]], float)[None]
    w = CONTACT_WEIGHTS[name][0](x)[0]
    assert np.all(w > 0) and w.sum() == pytest.approx(2.0, rel=1e-14)
    cons = face_mass(x)[0][0].sum(axis=1) / 2.0
    np.testing.assert_allclose(cons, [-1 / 12] * 4 + [1 / 3] * 4, rtol=1e-13)
    if name == "calculix":
        np.testing.assert_allclose(w / 2.0, [0.01] * 4 + [0.24] * 4, rtol=1e-14)


def _block(normal_contact: str = "fixed", weights: str = "calculix"):
    mesh = _box20([0, 5, 10], [0, 4, 8], [0, 3], node_sets={
        "contact": lambda x, y, z: z == 0, "clamp": lambda x, y, z: z == 3})
    return build_mesh_model(mesh, rigid_base(contact_set="contact", clamp_set="clamp",
                                             normal_force=800.0, modulus=E, poisson_ratio=0.0,
                                             friction=0.5, normal_contact=normal_contact,
                                             normal_slope=1e6), contact_weights=weights)


@pytest.mark.parametrize("weights", list(CONTACT_WEIGHTS))
def test_uniform_pressure_gives_the_weights(weights: str) -> None:
    """A block (nu = 0) pressed uniformly on the base: the pressure is uniform, so
    N_i = A_i F_N / A exactly, positive at the corners (the consistent reactions are
    negative there), and they add up to F_N."""
    m = _block(weights=weights)
    assert m.element == "C3D20R"
    np.testing.assert_allclose(m.normal_force, m.contact_area * 800.0 / 80.0, rtol=1e-9)
    assert m.normal_force.sum() == pytest.approx(800.0, rel=1e-12)
    assert np.all(m.normal_force > 0)


@pytest.mark.parametrize("weights", list(CONTACT_WEIGHTS))
def test_penalty_opens_the_corners(weights: str) -> None:
    """Penalty normal contact (N_i = k_n A_i (-u_n), k_n 1e6 N/mm^3) on the same block: the
    N_i still add up to F_N, but a uniform sinking is not an equilibrium (the body's
    consistent reactions want -1/12 and 1/3, the springs give positive areas), so the face
    warps and the corner nodes lift off, whatever the positive weighting: the known defect of
    node-to-surface contact on quadratic faces (CalculiX's manual advises against it). Hence
    hex20 runs take the fixed normal contact (docs/interpretation.md §18)."""
    m = _block("penalty", weights)
    corner = np.isin(m.contact_nodes, np.unique(m.mesh.elements[:, :8]))
    assert m.normal_force.sum() == pytest.approx(800.0, rel=1e-12)
    assert not np.any(m.closed[corner]) and np.all(m.closed[~corner])


# --- the mesh: promotion, refinement --------------------------------------------------------

def test_promoted_cantilever_is_the_example_hex20_file() -> None:
    """examples/cantilever.inp promoted is the geometry of examples/cantilever_hex20.inp:
    the same stuck frequencies (to rounding) and the same sets' sizes."""
    a = promote_mesh(read_mesh("examples/cantilever.inp"))
    b = read_mesh("examples/cantilever_hex20.inp")
    assert a.nodes.shape == b.nodes.shape and a.elements.shape == b.elements.shape
    for name in b.node_sets:
        assert len(a.node_sets[name]) == len(b.node_sets[name]), name
    kw = dict(contact_set="contact", clamp_set="clamp", normal_force=2000.0, modulus=E,
              poisson_ratio=NU, friction=0.5, stick_slope=1e4)
    fa = linear_modes(build_mesh_model(a, rigid_base(**kw)), RHO, 3).frequencies_Hz
    fb = linear_modes(build_mesh_model(b, rigid_base(**kw)), RHO, 3).frequencies_Hz
    np.testing.assert_allclose(fa, fb, rtol=1e-9)


def test_refine_and_demote_round_trip() -> None:
    """A promoted mesh demotes to the original; refining a 20-node mesh refines its corner
    mesh and promotes it (the same as promoting the refined 8-node mesh); curved edges are
    refused; --element hex8 refuses a 20-node mesh."""
    m8 = cantilever_mesh(6, 2, 1)
    m20 = promote_mesh(m8)
    back = demote_mesh(m20)
    np.testing.assert_array_equal(back.nodes, m8.nodes)
    np.testing.assert_array_equal(back.elements, m8.elements)
    r = refine_mesh(m20, 2)
    ref = promote_mesh(refine_mesh(m8, 2))
    np.testing.assert_array_equal(r.nodes, ref.nodes)
    assert {k: len(v) for k, v in r.node_sets.items()} == {
        k: len(v) for k, v in ref.node_sets.items()}
    bent = m20.nodes.copy()
    bent[m20.elements[0, 8]] += (0.0, 0.0, 0.1)
    with pytest.raises(ParameterError, match="curved edges"):
        refine_mesh(type(m20)(bent, m20.elements, m20.node_sets), 2)
    with pytest.raises(ParameterError, match="--element hex8"):
        as_element(m20, "hex8")
    assert as_element(m8, None) is m8 and as_element(m8, "hex8") is m8


# --- against CalculiX ---------------------------------------------------------------------------

@pytest.mark.ccx
@pytest.mark.skipif(shutil.which("ccx") is None, reason="ccx not on PATH")
def test_stuck_frequencies_against_calculix_c3d20r() -> None:
    """The cantilever 12x3x1 promoted to C3D20R (2700 kg/m^3, E 70000 MPa, nu 0.33, F_N
    2000 N) on a rigid contact (stick and normal slopes 1e9 N/mm^3; ours fixed normal): the
    first six stuck frequencies equal CalculiX C3D20R's on the same mesh within 0.1 % (modes
    1, 2, 4 to 1e-5; 5e-4 on mode 5). The contact is rigid so that the two contact
    formulations (CalculiX's face-to-face, our nodal springs) drop out: the element and its
    mass are compared."""
    from microslip.fe.calculix.meshrun import run_frequency_calculix

    mesh = promote_mesh(cantilever_mesh(12, 3, 1))
    model = build_mesh_model(mesh, rigid_base(contact_set="contact", clamp_set="clamp",
                                              normal_force=2000.0, modulus=E, poisson_ratio=NU,
                                              friction=0.5, stick_slope=1e9))
    ours = linear_modes(model, RHO, 6).frequencies_Hz
    ccx = run_frequency_calculix(
        mesh, rigid_base(contact_set="contact", clamp_set="clamp", normal_force=2000.0,
                         friction=0.5, stick_slope=1e9, normal_contact="penalty",
                         normal_slope=1e9, modulus=E, poisson_ratio=NU),
        density_kg_m3=RHO, modes=6)
    np.testing.assert_allclose(ours, ccx[:6], rtol=1e-3)
    np.testing.assert_allclose(ours[[0, 1, 3]], ccx[[0, 1, 3]], rtol=1e-5)


# --- the command line -----------------------------------------------------------------------

CANTILEVER = ["fe", "--mesh", "examples/cantilever.inp", "--contact-set", "contact",
              "--clamp-set", "clamp", "--normal-force", "2000", "--friction", "0.5",
              "--stick-slope", "1e4", "--modulus", "70000", "--poisson-ratio", "0.33",
              "--load", "tip:1,0,0:300"]


@pytest.mark.parametrize(("argv", "message"), [
    (["fe", "--model", "tip", "--element", "hex20"], "--element hex20 applies to --mesh FILE"),
    ([*CANTILEVER, "--element", "C3D8I"], "--element C3D8I applies to the box"),
    (["fe", "--mesh", "examples/cantilever_hex20.inp", *CANTILEVER[3:], "--element", "hex8"],
     "would drop its mid-edge nodes"),
])
def test_cli_refusals(argv, message, capsys) -> None:
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: ") and message in err and "Traceback" not in err


@pytest.mark.slow
def test_cli_hex20_run(capsys) -> None:
    """fe --mesh cantilever.inp --element hex20: the promoted mesh, C3D20R, the W of the
    regression value (0.018072 N·mm, 5314 DOF; hex8 on the same mesh 0.024276)."""
    assert main([*CANTILEVER, "--element", "hex20", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["element"] == "C3D20R" and out["dof"] == 5314
    assert out["dissipated_energy_Nmm"] == pytest.approx(0.0180723, rel=1e-4)
