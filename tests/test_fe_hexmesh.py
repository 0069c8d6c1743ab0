"""HexMesh faces from sets, consistent face loads, and the load spec, against hand values."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.hexmesh import HexMesh, face_load
from microslip.fe.meshload import MeshLoad

CUBE = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0],
                 [0, 0, 1], [2, 0, 1], [2, 1, 1], [0, 1, 1]], dtype=float)
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]


def test_faces_from_a_node_set_point_into_the_element() -> None:
    m = HexMesh(CUBE, [list(range(8))], {"bottom": [0, 1, 2, 3], "top": [4, 5, 6, 7]})
    for name, inward in (("bottom", [0, 0, 1]), ("top", [0, 0, -1])):
        p = CUBE[m.face_corners(m.faces(name))[0]]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        assert np.allclose(n / np.linalg.norm(n), inward)


def test_linear_face_load_is_area_shares() -> None:
    m = HexMesh(CUBE, [list(range(8))], {"bottom": [0, 1, 2, 3]})
    nodes, w, area = face_load(m, m.faces("bottom"))
    assert nodes.tolist() == [0, 1, 2, 3] and area == pytest.approx(2.0, rel=1e-15)
    assert np.allclose(w, 0.25, rtol=0, atol=1e-15)


def test_serendipity_face_load_is_minus_one_twelfth_and_one_third() -> None:
    # The consistent load of a uniform traction on an 8-node rectangle: -1/12 of the
    # total at each corner, 1/3 at each mid-side (exact, Zienkiewicz & Taylor).
    nodes20 = np.vstack([CUBE] + [0.5 * (CUBE[a] + CUBE[b]) for a, b in EDGES])
    m = HexMesh(nodes20, [list(range(20))], {"side": [1, 5, 6, 2, 17, 13, 18, 9]})
    nodes, w, area = face_load(m, m.faces("side"))
    assert area == pytest.approx(1.0, rel=1e-14)
    corner = np.isin(nodes, [1, 2, 5, 6])
    assert np.allclose(w[corner], -1 / 12, atol=1e-15)
    assert np.allclose(w[~corner], 1 / 3, atol=1e-15)


def test_a_misspelt_set_lists_the_names() -> None:
    m = HexMesh(CUBE, [list(range(8))], {"bottom": [0, 1, 2, 3]}, source="cube.inp")
    with pytest.raises(ParameterError, match=r"cube.inp: no set named 'botom'; .*bottom"):
        m.faces("botom")


def test_load_spec_parses_and_normalises() -> None:
    load = MeshLoad.parse("tip:0,3,4:150")
    assert load.direction == pytest.approx((0.0, 0.6, 0.8), abs=1e-16)
    assert load.phase_deg == 0.0 and load.amplitude == 150.0
    assert float(MeshLoad.parse("a:1,0,0:2:90").force(0.0)) == pytest.approx(2.0, rel=1e-15)


@pytest.mark.parametrize("spec, message", [
    ("tip:0,0,0:10", "zero length"),
    ("tip:1,0:10", "three numbers"),
    ("tip:1,0,0:-5", "amplitude must be > 0 N"),
    ("tip:1,0,0", "SET:DX,DY,DZ:AMPLITUDE"),
    ("tip:x,0,0:5", "with numbers"),
])
def test_bad_load_specs_are_refused(spec: str, message: str) -> None:
    with pytest.raises(ParameterError, match=message):
        MeshLoad.parse(spec)


def test_consistent_mass_of_a_brick_against_the_closed_form() -> None:
    """The consistent mass of a rectangular brick a x b x c: M_ab = rho V / 216 * prod over
    the axes of (2 if nodes a, b share the coordinate else 1), per direction (exact)."""
    from microslip.fe.builtin.mass import density_t_per_mm3, mass_matrix

    rho = density_t_per_mm3(2700.0)
    m = mass_matrix(CUBE, np.arange(8)[None, :], rho).toarray()
    volume = 2.0
    xi = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                   [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]])
    same = (xi[:, None, :] == xi[None, :, :]).astype(float) + 1.0
    exact = rho * volume / 216.0 * same.prod(axis=2)
    for d in range(3):
        assert np.allclose(m[d::3, d::3], exact, rtol=1e-13, atol=0)
    assert np.count_nonzero(m[0::3, 1::3]) == 0
    with pytest.raises(ParameterError, match="density must be > 0 kg/m"):
        density_t_per_mm3(-1.0)
