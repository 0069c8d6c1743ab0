"""Mesh levels shared by both solvers, graded meshes and the mesh convergence of a thick block
(issue 10 item 3, issue 11 item 4; docs/solver.md 8.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip import preset
from microslip.fe import mesh_spec
from microslip.fe.builtin import box_model, solve_uniaxial
from microslip.fe.builtin.box import box_counts, box_describe
from microslip.fe.builtin.meshgeometry import set_faces
from microslip.fe.examples import box_hexmesh, grid_mesh
from microslip.fe.hexmesh import face_load
from microslip.meshlevels import FIXED_COUNTS, LEVELS, MESH_LEVELS, level_axes, level_counts
from microslip.params import ClampParams

TITANIUM = ClampParams(length=30.0, width=12.0, thickness=8.0, modulus=113_800.0,
                       poisson_ratio=0.342, friction=0.5, normal_force=12_000.0)
def _graded(mesh) -> tuple[bool, bool, bool]:
    """Whether the node planes along x, y, z are not equally spaced."""
    out = []
    for c in range(3):
        a = np.unique(mesh.nodes[:, c])
        out.append(not np.allclose(a, np.linspace(a[0], a[-1], a.size), rtol=0.0,
                                   atol=1e-12 * (a[-1] - a[0])))
    return out[0], out[1], out[2]


TABLE1_COUNTS = {"tiny": (8, 2, 1), "coarse": (24, 4, 1), "medium": (48, 4, 1),
                 "fine": (96, 8, 2), "paper": (96, 4, 1)}


@pytest.mark.parametrize("level", LEVELS)
def test_a_level_is_the_same_mesh_for_both_solvers(level):
    """Same counts and the same corner planes in the built-in (C3D8I) and CalculiX (C3D20R)
    meshes, on the slender Table 1 bar (uniform, the built-in solver's old counts) and on the
    squat titanium block (graded)."""
    assert level_counts(preset("table1"), level) == TABLE1_COUNTS[level]
    for params in (preset("table1"), TITANIUM):
        box = box_hexmesh(params, level)
        spec = mesh_spec(level, params)
        assert box_counts(box) == (spec.nx, spec.ny, spec.nz)
        squat = params is TITANIUM and level not in FIXED_COUNTS
        assert spec.graded == box_describe(box)["graded"] == any(_graded(box)) == squat


def test_explicit_counts_and_unknown_levels():
    assert level_counts(TITANIUM, "12x2x3") == (12, 2, 3)
    with pytest.raises(Exception, match="unknown mesh 'huge'"):
        level_counts(TITANIUM, "huge")
    # a tuple stays a uniform mesh; a level string on a squat body is graded
    assert not any(_graded(box_hexmesh(TITANIUM, (12, 2, 3))))
    assert _graded(box_hexmesh(TITANIUM, "12x2x3")) == (True, False, True)


def test_a_thick_block_gets_graded_layers():
    for level, layers in (("coarse", 4), ("medium", 6), ("fine", 8)):
        nx, ny, nz = level_counts(TITANIUM, level)
        lv = MESH_LEVELS[level]
        assert nz == layers == min(lv.max_layers, math.ceil(2 * TITANIUM.thickness * ny
                                                             / TITANIUM.width))
        assert nx % 2 == 0
    assert level_counts(TITANIUM, "paper") == FIXED_COUNTS["paper"]
    tall = TITANIUM.replace(thickness=300.0)
    assert level_counts(tall, "coarse")[2] == MESH_LEVELS["coarse"].max_layers


def test_graded_planes_crowd_towards_the_loaded_sections():
    """Power law p = 2: node planes at L/2 and L stay, elements shrink towards x = L/2 (from
    the far side), x = L and z = 0 by 1/n^2 of the half (of the thickness)."""
    x, y, z = level_axes(30.0, 12.0, 8.0, (8, 4, 4), True)
    dx, dz = np.diff(x), np.diff(z)
    assert x[4] == 15.0 and x[-1] == 30.0 and z[-1] == 8.0
    assert np.all(np.diff(dx[:4]) < 0) and np.all(np.diff(dx[4:]) < 0)
    assert np.all(np.diff(dz) > 0)
    assert dx[-1] == pytest.approx(15.0 / 16) and dz[0] == pytest.approx(8.0 / 16)
    np.testing.assert_array_equal(y, np.linspace(0.0, 12.0, 5))


def test_graded_mesh_areas_and_clamping_use_the_actual_spacing():
    """Contact areas add up to the faces, every node's area is its share of the elements
    around it, and the clamping reactions add up to F_N on a graded mesh."""
    box = box_hexmesh(TITANIUM, "12x2x3")
    nx, ny, _ = box_counts(box)
    m = box_model(TITANIUM, box)
    w = m.contact_area.reshape(nx + 1, ny + 1)
    dx = np.diff(np.unique(box.nodes[:, 0]))
    trib_x = np.concatenate([[0.5 * dx[0]], 0.5 * (dx[1:] + dx[:-1]), [0.5 * dx[-1]]])
    np.testing.assert_allclose(w[:, 1], trib_x * TITANIUM.width / ny, rtol=1e-13)
    assert face_load(box, set_faces(box, "tip", "set"))[2] == pytest.approx(12.0 * 8.0,
                                                                              rel=1e-13)
    assert m.normal_force.sum() == pytest.approx(TITANIUM.normal_force, rel=1e-10)
    assert np.all(m.normal_force > 0)


def test_graded_stiffness_matches_per_element_assembly():
    """The stiffness of a graded mesh (one element matrix per class of translated copies)
    equals the sum of every element's own matrix."""
    from microslip.fe.builtin.element import assemble_hex8, element_stiffness

    box = grid_mesh(np.array([0, 1, 3, 5.5, 6.0]), np.linspace(0.0, 2.0, 3),
                    np.array([0, 0.5, 1.5, 3.0]))
    k = assemble_hex8(box.nodes, box.elements, 1000.0, 0.3, "C3D8I").toarray()
    ke = element_stiffness(box.nodes[box.elements], 1000.0, 0.3, "C3D8I")
    ref = np.zeros_like(k)
    for e, conn in enumerate(box.elements):
        dofs = (3 * conn[:, None] + np.arange(3)).ravel()
        ref[np.ix_(dofs, dofs)] += ke[e]
    np.testing.assert_allclose(k, ref, atol=1e-9 * np.abs(ref).max())


def _wd(mesh):
    return solve_uniaxial(TITANIUM, "tip", 3600.0, mesh=mesh,
                          stick_slope=1e5).dissipated_energy


def test_uniform_refinement_converges_at_the_singular_rate():
    """Uniform refinement of the titanium block (fixed normal, stick slope 1e5 N/mm^3): W_d
    decreases monotonically and the differences fall by 2.45 per halving (order 1.3: the
    stress singularity at the loaded edge; docs/solver.md 8.4)."""
    w = np.array([_wd(m) for m in ((4, 2, 1), (8, 4, 2), (16, 8, 4))])
    diff = -np.diff(w)
    assert np.all(diff > 0)
    order = math.log2(diff[0] / diff[1])
    assert 1.0 < order < 1.6


@pytest.mark.slow
def test_grading_restores_the_convergence_rate_and_wins_at_equal_dof():
    """Same counts (nx, 2, nz), graded versus uniform, errors against the graded 64x2x16 mesh
    of the same family (measured: graded 16x2x4 / 32x2x8 errors 1.8 % / 0.05 %, uniform
    5.3 % / 2.3 %). Grading makes the error fall at least as fast as the order 2 of
    trilinear elements on a smooth field (measured ratio 33); uniform meshes fall at the
    singular rate (ratio 2.3, order 1.2). At equal DOF the graded error is 40 times smaller."""
    ref = _wd("64x2x16")
    graded = np.array([abs(_wd(f"{n}x2x{n // 4}") / ref - 1) for n in (16, 32)])
    uniform = np.array([abs(_wd((n, 2, n // 4)) / ref - 1) for n in (16, 32)])
    graded_order = math.log2(graded[0] / graded[1])
    uniform_order = math.log2(uniform[0] / uniform[1])
    assert graded_order >= 2.0
    assert 0.9 < uniform_order < 1.6
    assert graded[1] < uniform[1] / 10
