"""Hanging nodes and local refinement (issue 33): the constraint rows u_h = sum w_k u_k with
the assembly's transformation u = T v, the 2 x 2 x 2 and directional splits, their sets and
the 2:1 rule; a mesh without hanging nodes is solved bit for bit as before."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.bodies import relative_transform
from microslip.fe.builtin.element import assemble_hex8
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.builtin.meshrun import SineCycles, solve_mesh
from microslip.fe.examples import cantilever_mesh, grid_mesh
from microslip.fe.hanging import ConstrainedMesh, HangingNodes
from microslip.fe.hexmesh import face_load
from microslip.fe.localrefine import check_conforming, refine_local, start
from microslip.fe.meshload import MeshLoad
from microslip.fe.refine import refine_mesh

E, NU, TRACTION = 1000.0, 0.3, 10.0


def _block():
    return grid_mesh([0, 1, 2, 3], [0, 1, 2], [0, 1, 2],
                     node_sets={"end": lambda x, y, z: np.abs(x - 3) < 1e-9,
                                "low": lambda x, y, z: np.abs(z) < 1e-9},
                     surfaces=("end", "low"))


def _mixed():
    """A block refined at one corner twice, once along x only and once along y, z only."""
    r = start(_block())
    r = refine_local(r, [0])
    r = refine_local(r, np.flatnonzero(r.level == 1)[:1])
    r = refine_local(r, [len(r.mesh.elements) - 1], [[True, False, False]])
    r = refine_local(r, [len(r.mesh.elements) - 1], [[False, True, True]])
    return r


def _volumes(mesh):
    from microslip.fe.builtin.element import hex8_b_matrices

    _, det, _ = hex8_b_matrices(mesh.nodes[mesh.elements])
    return np.asarray(det).sum(axis=1)  # the 2 x 2 x 2 Gauss weights are 1


def test_constraint_rows_resolve_chains():
    h = HangingNodes([5, 6], [[0, 1, -1, -1], [5, 2, -1, -1]],
                     [[0.5, 0.5, 0, 0], [0.5, 0.5, 0, 0]])
    r = h.resolved()
    assert r.parents[1].tolist()[:3] == [0, 1, 2]
    assert r.weights[1][:3].tolist() == [0.25, 0.25, 0.5]
    m = h.matrix(7).toarray()
    assert np.allclose(m.sum(axis=1), 1.0) and not m[:, [5, 6]].any()
    nodes, values = h.lump(np.array([0, 1, 5]), np.array([1.0, 1.0, 2.0]))
    assert nodes.tolist() == [0, 1] and values.tolist() == [2.0, 2.0]


@pytest.mark.parametrize("kind", ["C3D8", "C3D8I"])
def test_patch_test_refined_and_unrefined_block_under_uniform_traction(kind):
    """u = T v, K -> T^T K T, f -> T^T f: a block split here and there (2:1 and directional
    splits, hanging nodes on edges and faces) under a uniform traction gives the exact
    uniform strain at every node, the hanging ones included."""
    r = _mixed()
    mesh = r.mesh
    assert len(mesh.hanging) > 20
    n = len(mesh.nodes)
    k = assemble_hex8(mesh.nodes, mesh.elements, E, NU, kind)
    t = relative_transform(np.zeros(0, np.int64), np.zeros(0, np.int64), n, mesh.hanging)
    kt = (t.T @ k @ t).tocsr()
    x = mesh.nodes
    held = list(3 * np.flatnonzero(x[:, 0] < 1e-9))
    held += list(3 * np.flatnonzero((x[:, 0] < 1e-9) & (x[:, 1] < 1e-9)) + 1)
    held += list(3 * np.flatnonzero((x[:, 0] < 1e-9) & (x[:, 2] < 1e-9)) + 2)
    held += list(mesh.hanging.dofs(np.arange(n)))
    free = np.setdiff1d(np.arange(3 * n), held)
    nodes, share, area = face_load(mesh, mesh.faces("end"))
    f = np.zeros(3 * n)
    f[3 * nodes] = share * area * TRACTION
    v = np.zeros(3 * n)
    v[free] = spla.spsolve(kt[free][:, free].tocsc(), (t.T @ f)[free])
    u = (t @ v).reshape(-1, 3)
    strain = TRACTION / E
    exact = np.stack([strain * x[:, 0], -NU * strain * x[:, 1], -NU * strain * x[:, 2]], 1)
    assert np.max(np.abs(u - exact)) < 1e-12


def test_refinement_keeps_volume_sets_and_conformity():
    base = _block()
    r = _mixed()
    mesh = r.mesh
    check_conforming(r)
    assert _volumes(mesh).sum() == pytest.approx(_volumes(base).sum(), rel=1e-13)
    for name in ("end", "low"):
        assert face_load(mesh, mesh.faces(name))[2] == pytest.approx(
            face_load(base, base.faces(name))[2], rel=1e-13)
        # every node of the set's faces is in the node set, and nothing else
        on = np.unique(mesh.face_corners(mesh.surfaces[name]))
        assert set(on.tolist()) == set(mesh.node_sets[name].tolist())
    # the children of the refined corner element lie in it
    assert (r.parent == 0).sum() == 8 + 7
    assert mesh.levels.max() == 2


def test_the_two_to_one_rule_splits_the_coarse_neighbour():
    r = start(_block())
    r = refine_local(r, [0])
    child = int(np.flatnonzero((r.level == 1)
                               & (r.mesh.nodes[r.mesh.elements].mean(axis=1)[:, 0] > 0.5))[0])
    before = len(r.mesh.elements)
    r = refine_local(r, [child])
    check_conforming(r)
    assert len(r.mesh.elements) > before + 7  # a neighbour of element 0 split too
    assert r.level.max() == 2


def test_local_refinement_of_every_element_is_the_uniform_refinement():
    base = cantilever_mesh(6, 2, 1)
    r = refine_local(start(base), np.arange(len(base.elements)))
    uni = refine_mesh(base, 2)
    assert len(r.hanging) == 0
    assert len(r.mesh.nodes) == len(uni.nodes)
    a = np.unique(np.round(r.mesh.nodes, 9), axis=0)
    b = np.unique(np.round(uni.nodes, 9), axis=0)
    assert np.array_equal(a, b)
    for name in ("contact", "clamp", "tip"):
        assert len(r.mesh.surfaces[name]) == len(uni.surfaces[name])
        assert len(r.mesh.node_sets[name]) == len(uni.node_sets[name])


def _clamp(normal="penalty"):
    return rigid_base(contact_set="contact", clamp_set="clamp", normal_force=2000.0,
                      modulus=70000.0, poisson_ratio=0.33, friction=0.5, stick_slope=1e4,
                      normal_contact=normal, normal_slope=1e6)


@pytest.mark.parametrize("normal", ["fixed", "penalty"])
def test_a_mesh_without_hanging_nodes_is_solved_bit_for_bit(normal):
    base = cantilever_mesh(12, 2, 1)
    same = ConstrainedMesh(base.nodes, base.elements, dict(base.node_sets),
                           dict(base.surfaces), source=base.source,
                           hanging=HangingNodes(np.zeros(0, np.int64), np.zeros((0, 4), np.int64),
                                                np.zeros((0, 4))))
    a, b = (build_mesh_model(m, _clamp(normal)) for m in (base, same))
    assert b.transform is None and a.transform is None
    for name in ("u0", "normal_force", "contact_area", "clamp_load"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert (a.stiffness != b.stiffness).nnz == 0
    load = [MeshLoad.parse("tip:1,0,0:300")]
    wa, wb = (solve_mesh(m, load, SineCycles(increments=16, max_cycles=3)).dissipated_energy
              for m in (a, b))
    assert wa == wb


@pytest.mark.parametrize("normal", ["fixed", "penalty"])
def test_the_clamp_on_a_locally_refined_contact_carries_its_force(normal):
    """Hanging nodes on the contact face give their areas to their parents: the contact area
    and the normal forces still sum to the face's area and the clamping force."""
    base = cantilever_mesh(12, 2, 2)
    r = start(base)
    c = base.nodes[base.elements].mean(axis=1)
    r = refine_local(r, np.flatnonzero(c[:, 0] > 38.0), None)
    r = refine_local(r, np.flatnonzero(r.mesh.nodes[r.mesh.elements].mean(axis=1)[:, 0] > 46.0),
                     [[True, False, True]] * int(np.sum(
                         r.mesh.nodes[r.mesh.elements].mean(axis=1)[:, 0] > 46.0)))
    assert np.isin(r.hanging.nodes, r.mesh.node_sets["contact"]).any()
    m = build_mesh_model(r.mesh, _clamp(normal))
    assert not np.isin(m.contact_nodes, r.hanging.nodes).any()
    assert m.contact_area.sum() == pytest.approx(50.8 * 25.4, rel=1e-12)
    assert m.normal_force.sum() == pytest.approx(2000.0, rel=1e-9)
    run = solve_mesh(m, [MeshLoad.parse("tip:1,0,0:300")], SineCycles(increments=16,
                                                                       max_cycles=4))
    assert run.dissipated_energy > 0 and np.all(np.isfinite(run.displacement is None or 0.0))
