"""A preload's pressure law (issue 32, item 4): the paper's box's clamping pressure as the
distribution of the assembly's preload, integrated along an axis of the face."""

from __future__ import annotations

import numpy as np
import pytest

from microslip import preset
from microslip.errors import ParameterError
from microslip.fe.assembly import Assembly, Contact, Material, Preload, rigid_base
from microslip.fe.builtin.meshgeometry import set_faces
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.examples import box_hexmesh, grid_mesh, to_hex20
from microslip.fe.hexmesh import face_load
from microslip.models.interface import power_law, pressure_law, table_law

P = preset("table1")
PARABOLIC = pressure_law("parabolic")


def _strip(nx: int, quadratic: bool = False):
    """A bar L x w x t with nx elements along x, one across and through; ``clamp`` its top."""
    mesh = grid_mesh(np.linspace(0.0, P.length, nx + 1), np.array([0.0, P.width]),
                     np.array([0.0, P.thickness]),
                     node_sets={"contact": lambda x, y, z: np.isclose(z, 0.0),
                                "clamp": lambda x, y, z: np.isclose(z, P.thickness)},
                     surfaces=("contact", "clamp"), source="strip")
    return to_hex20(mesh) if quadratic else mesh


def _line_shares(mesh, law) -> tuple[np.ndarray, np.ndarray]:
    """The law's shares of the strip's top, summed over each section: (x, share)."""
    nodes, share = Preload("clamp", 1.0, law).shares(mesh, set_faces(mesh, "clamp", "x"))
    x = mesh.nodes[nodes, 0]
    cols, which = np.unique(np.round(x, 9), return_inverse=True)
    return cols, np.bincount(which, weights=share)


def test_a_linear_law_gets_the_exact_consistent_shares():
    """n = 1: p is linear on each half, kinked on the mid node; the consistent force of a
    linear traction on hat functions is h/6 (p_(i-1) + 4 p_i + p_(i+1)) inside and
    h/6 (2 p_0 + p_1) at the ends."""
    law, nx = power_law(1.0, 3.0), 8
    x, share = _line_shares(_strip(nx), law)
    p = law.shape(x / P.length)
    h = P.length / nx
    line = np.empty(nx + 1)
    line[1:-1] = h / 6 * (p[:-2] + 4 * p[1:-1] + p[2:])
    line[0] = h / 6 * (2 * p[0] + p[1])
    line[-1] = h / 6 * (2 * p[-1] + p[-2])
    assert np.allclose(share, line / line.sum(), rtol=1e-13)


def test_a_parabolic_law_gets_its_closed_form_integral():
    """p = c (1 + b (2 xi - 1)^2) times a hat function is a cubic on each element: Simpson's
    rule is its exact integral, h/6 (p_i + 2 p_(i+1/2)) from each side of node i."""
    nx = 6
    x, share = _line_shares(_strip(nx), PARABOLIC)
    xe = np.linspace(0.0, P.length, nx + 1)
    p = PARABOLIC.shape(xe / P.length)
    pm = PARABOLIC.shape(0.5 * (xe[1:] + xe[:-1]) / P.length)
    h = P.length / nx
    line = np.zeros(nx + 1)
    line[:-1] += h / 6 * (p[:-1] + 2 * pm)
    line[1:] += h / 6 * (p[1:] + 2 * pm)
    assert np.allclose(x, xe, rtol=0, atol=1e-9)
    assert line.sum() == pytest.approx(P.length, rel=1e-14)  # mean of the law is 1
    assert np.allclose(share, line / P.length, rtol=1e-13)


def test_quadratic_faces_carry_the_whole_force():
    nodes, share = Preload("clamp", 1.0, PARABOLIC).shares(
        m := _strip(4, quadratic=True), set_faces(m, "clamp", "x"))
    assert share.sum() == pytest.approx(1.0, rel=1e-14)
    assert nodes.size == 5 * 2 + 4 * 2 + 5  # the top's corners and edge nodes, no centres


def test_no_distribution_is_the_uniform_traction_bit_for_bit():
    mesh = box_hexmesh(P, "coarse")
    faces = set_faces(mesh, "clamp", "x")
    n0, s0, _ = face_load(mesh, faces)
    n1, s1 = Preload("clamp", P.normal_force).shares(mesh, faces)
    assert np.array_equal(n0, n1) and np.array_equal(s0, s1)
    assert "distribution" not in rigid_base(
        contact_set="contact", clamp_set="clamp", normal_force=1.0, modulus=1.0,
        poisson_ratio=0.3, friction=0.5).describe()["preloads"][0]


@pytest.mark.parametrize("law", [PARABOLIC, power_law(4.0, 3.0),
                                 table_law([0.0, 100.0, 254.0], [2.0, 0.5, 1.0], 254.0)])
def test_the_nodal_forces_of_the_pressed_box_add_up_to_the_clamping_force(law):
    a = Assembly(contacts=(Contact("contact"),),
                 preloads=(Preload("clamp", P.normal_force, law),),
                 materials=(Material(P.modulus, P.poisson_ratio),), friction=P.friction)
    m = build_mesh_model(box_hexmesh(P, (8, 2, 1)), a, condensed=False)
    assert float(m.clamp_load.sum()) == pytest.approx(-P.normal_force, rel=1e-13)
    assert float(m.normal_force.sum()) == pytest.approx(P.normal_force, rel=1e-12)
    assert a.describe()["preloads"][0]["distribution"] == law.name


def test_bad_distributions_are_refused_in_one_line():
    with pytest.raises(ParameterError, match="must be a PressureLaw"):
        Preload("clamp", 1.0, "parabolic")
    with pytest.raises(ParameterError, match="one of x, y, z"):
        Preload("clamp", 1.0, PARABOLIC, axis="r")
    mesh = _strip(2)
    with pytest.raises(ParameterError, match="lie across it"):
        Preload("clamp", 1.0, PARABOLIC, axis="z").shares(mesh, set_faces(mesh, "clamp", "x"))


def test_calculix_refuses_a_pressure_law_rather_than_press_uniformly():
    from microslip.fe.calculix.assemblydeck import resolve_assembly

    a = Assembly(contacts=(Contact("contact"),), preloads=(Preload("clamp", 1.0, PARABOLIC),),
                 materials=(Material(P.modulus, P.poisson_ratio),), friction=P.friction)
    with pytest.raises(ParameterError, match="'clamp' has a pressure law"):
        resolve_assembly(box_hexmesh(P, (8, 2, 1)), a)
