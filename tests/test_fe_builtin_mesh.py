"""Mesh numbering, hexahedral elements and the banded factorisation of the built-in solver
(the paper's box as a HexMesh: :func:`microslip.fe.examples.box_hexmesh`)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from microslip import ParameterError, preset
from microslip.fe.builtin import box_model
from microslip.fe.builtin.element import NODE_XI, assemble_hex8, element_stiffness
from microslip.fe.builtin.linalg import BandedBackend, SpluBackend, make_backend
from microslip.fe.builtin.meshgeometry import set_faces
from microslip.fe.examples import box_hexmesh, grid_mesh
from microslip.fe.hexmesh import face_load


def _box(length: float, width: float, thickness: float, nx: int, ny: int, nz: int):
    """The box mesh of a clamped zone of that size, uniform (nx, ny, nz)."""
    p = preset("table1").replace(length=length, width=width, thickness=thickness)
    return box_hexmesh(p, (nx, ny, nz))


def _grid(length: float, width: float, thickness: float, nx: int, ny: int, nz: int):
    return grid_mesh(np.linspace(0.0, length, nx + 1), np.linspace(0.0, width, ny + 1),
                     np.linspace(0.0, thickness, nz + 1))


def test_slice_numbering_gives_a_band() -> None:
    m = _box(10.0, 2.0, 1.0, 6, 3, 2)
    s = (3 + 1) * (2 + 1)
    e = m.elements
    assert int(np.max(e.max(axis=1) - e.min(axis=1))) == s + (2 + 1) + 1
    # node numbers grow slice by slice along x
    assert np.all(np.diff(m.nodes[:, 0].reshape(7, s).mean(axis=1)) > 0)
    k = assemble_hex8(m.nodes, m.elements, 1.0, 0.3).tocoo()
    assert int(np.max(np.abs(k.row - k.col))) == 3 * (s + (2 + 1) + 1) + 2


@pytest.mark.parametrize("face, area", [("contact", 20.0), ("clamp", 20.0), ("tip", 2.0),
                                         ("centre", 2.0)])
def test_face_shares_add_up_to_the_face_area(face: str, area: float) -> None:
    m = _box(10.0, 2.0, 1.0, 6, 3, 2)
    nodes, share, total = face_load(m, set_faces(m, face, "set"))
    np.testing.assert_array_equal(nodes, m.node_sets[face])
    assert total == pytest.approx(area, rel=1e-12)
    assert share.sum() == pytest.approx(1.0, rel=1e-12)
    assert np.all(share > 0)


def test_mesh_spec_errors() -> None:
    p = preset("table1")
    with pytest.raises(ParameterError, match="unknown mesh 'huge'"):
        box_hexmesh(p, "huge")
    with pytest.raises(ParameterError, match="nx must be an integer >= 1"):
        box_hexmesh(p, (0, 2, 1))
    with pytest.raises(ParameterError, match="mesh must be"):
        box_hexmesh(p, (2, 1))
    with pytest.raises(ParameterError, match="built for other parameters"):
        box_model(p, box_model(p.replace(length=100.0), (2, 1, 1)))
    with pytest.raises(ParameterError, match="even nx"):
        box_model(p, (3, 1, 1))


@pytest.mark.parametrize("kind", ["C3D8", "C3D8I"])
def test_element_rigid_modes_and_patch_test(kind: str) -> None:
    box = NODE_XI[None] * np.array([1.5, 0.4, 0.2]) + np.array([3.0, 1.0, 0.5])
    k = element_stiffness(box, 200.0, 0.3, kind)[0]
    np.testing.assert_allclose(k, k.T, atol=1e-10)
    ev = np.linalg.eigvalsh(k)
    assert np.sum(np.abs(ev) < 1e-9 * ev.max()) == 6  # three translations, three rotations
    # Uniform strain eps_xx = 1e-3 with free lateral contraction: only the x = max face loads.
    x = box[0]
    e, nu, eps = 200.0, 0.3, 1e-3
    u = np.stack([eps * x[:, 0], -nu * eps * x[:, 1], -nu * eps * x[:, 2]], axis=1).ravel()
    f = (k @ u).reshape(8, 3)
    area = 0.8 * 0.4
    right = x[:, 0] == x[:, 0].max()
    assert f[right, 0].sum() == pytest.approx(e * eps * area, rel=1e-12)
    np.testing.assert_allclose(f[:, 1:], 0.0, atol=1e-12)


def test_incompatible_modes_remove_shear_locking() -> None:
    """Cantilever 10 x 1 x 1 under a tip shear: C3D8I is within 1 % of Timoshenko's beam;
    C3D8 locks (about 2/3 of it)."""
    m = _grid(10.0, 1.0, 1.0, 10, 1, 1)
    n = len(m.nodes)
    start = np.flatnonzero(m.nodes[:, 0] == 0.0)
    end = np.flatnonzero(m.nodes[:, 0] == 10.0)
    fixed = np.r_[3 * start, 3 * start + 1, 3 * start + 2]
    free = np.setdiff1d(np.arange(3 * n), fixed)
    e, nu = 1000.0, 0.0
    beam = 10.0**3 / (3 * e / 12.0) + 10.0 / (5.0 / 6.0 * e / 2.0)
    tip = {}
    for kind in ("C3D8", "C3D8I"):
        k = assemble_hex8(m.nodes, m.elements, e, nu, kind)[free][:, free].tocsc()
        f = np.zeros(3 * n)
        f[3 * end + 2] = 1.0 / end.size
        u = np.zeros(3 * n)
        u[free] = spla.spsolve(k, f[free])
        tip[kind] = float(u[3 * end + 2].mean())
    assert tip["C3D8I"] == pytest.approx(beam, rel=0.01)
    assert tip["C3D8"] < 0.7 * beam


def test_banded_and_sparse_backends_agree() -> None:
    m = _grid(20.0, 2.0, 1.0, 8, 2, 1)
    bottom = np.flatnonzero(m.nodes[:, 2] == 0.0)
    free = np.setdiff1d(np.arange(3 * len(m.nodes)), 3 * bottom + 2)  # u_z = 0 on the base
    k = assemble_hex8(m.nodes, m.elements, 100.0, 0.3, "C3D8")[free][:, free].tocsr()
    cx = np.searchsorted(free, 3 * bottom)
    cy = cx + 1
    rng = np.random.default_rng(0)
    d = np.stack([rng.uniform(1, 2, bottom.size), rng.uniform(-0.1, 0.1, bottom.size),
                  rng.uniform(1, 2, bottom.size)], axis=1)
    b = rng.normal(size=k.shape[0])
    x1 = BandedBackend(k, cx, cy).factor(d).solve(b)
    x2 = SpluBackend(k, cx, cy).factor(d).solve(b)
    np.testing.assert_allclose(x1, x2, rtol=1e-9, atol=1e-12 * np.abs(x2).max())
    with pytest.raises(ParameterError, match="unknown linear solver 'magic'"):
        make_backend("magic", k, cx, cy)
