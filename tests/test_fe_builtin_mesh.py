"""Mesh numbering, hexahedral elements and the banded factorisation of the built-in solver."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from microslip import ParameterError, preset
from microslip.fe.builtin.element import NODE_XI, assemble_stiffness, element_stiffness
from microslip.fe.builtin.linalg import BandedBackend, SpluBackend, make_backend
from microslip.fe.builtin.mesh import box_mesh, mesh_from_spec


def test_slice_numbering_gives_a_band() -> None:
    m = box_mesh(10.0, 2.0, 1.0, 6, 3, 2)
    s = (3 + 1) * (2 + 1)
    assert m.slice_size == s
    assert m.half_bandwidth() == s + (2 + 1) + 1
    # node numbers grow slice by slice along x
    assert np.all(np.diff(m.nodes[:, 0].reshape(7, s).mean(axis=1)) > 0)
    k = assemble_stiffness(m, 1.0, 0.3).tocoo()
    assert int(np.max(np.abs(k.row - k.col))) == 3 * m.half_bandwidth() + 2


@pytest.mark.parametrize("face, area", [("bottom", 20.0), ("top", 20.0), ("end", 2.0),
                                         ("mid", 2.0), ("start", 2.0)])
def test_face_weights_add_up_to_the_face_area(face: str, area: float) -> None:
    m = box_mesh(10.0, 2.0, 1.0, 6, 3, 2)
    w = m.face_weights(face)
    assert w.shape == m.face_nodes(face).shape
    assert w.sum() == pytest.approx(area, rel=1e-12)
    assert np.all(w > 0)


def test_mesh_spec_errors() -> None:
    p = preset("table1")
    with pytest.raises(ParameterError, match="unknown mesh 'huge'"):
        mesh_from_spec(p, "huge")
    with pytest.raises(ParameterError, match="nx must be an integer >= 1"):
        mesh_from_spec(p, (0, 2, 1))
    with pytest.raises(ParameterError, match="mesh must be"):
        mesh_from_spec(p, (2, 1))
    with pytest.raises(ParameterError, match="does not match"):
        mesh_from_spec(p, box_mesh(1.0, 1.0, 1.0, 2, 1, 1))
    with pytest.raises(ParameterError, match="even nx"):
        box_mesh(1.0, 1.0, 1.0, 3, 1, 1).face_nodes("mid")


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
    m = box_mesh(10.0, 1.0, 1.0, 10, 1, 1)
    start = m.face_nodes("start")
    end = m.face_nodes("end")
    fixed = np.r_[3 * start, 3 * start + 1, 3 * start + 2]
    free = np.setdiff1d(np.arange(3 * m.n_nodes), fixed)
    e, nu = 1000.0, 0.0
    beam = 10.0**3 / (3 * e / 12.0) + 10.0 / (5.0 / 6.0 * e / 2.0)
    tip = {}
    for kind in ("C3D8", "C3D8I"):
        k = assemble_stiffness(m, e, nu, kind)[free][:, free].tocsc()
        f = np.zeros(3 * m.n_nodes)
        f[3 * end + 2] = 1.0 / end.size
        u = np.zeros(3 * m.n_nodes)
        u[free] = spla.spsolve(k, f[free])
        tip[kind] = float(u[3 * end + 2].mean())
    assert tip["C3D8I"] == pytest.approx(beam, rel=0.01)
    assert tip["C3D8"] < 0.7 * beam


def test_banded_and_sparse_backends_agree() -> None:
    m = box_mesh(20.0, 2.0, 1.0, 8, 2, 1)
    bottom = m.face_nodes("bottom")
    free = np.setdiff1d(np.arange(3 * m.n_nodes), 3 * bottom + 2)  # u_z = 0 on the base
    k = assemble_stiffness(m, 100.0, 0.3)[free][:, free].tocsr()
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
