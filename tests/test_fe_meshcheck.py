"""Bad input on the user's mesh: each refused in one line naming the file, the set and the fault."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.examples import box_hexmesh, cantilever_mesh, to_hex20
from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshcheck import check_elements, check_roles, jacobian_dets
from microslip.fe.meshfile import read_mesh, write_inp
from microslip.fe.meshload import MeshLoad
from microslip.params import preset

CUBE = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0],
                 [0, 0, 1], [2, 0, 1], [2, 1, 1], [0, 1, 1]], dtype=float)


@pytest.fixture(scope="module")
def bar(tmp_path_factory: pytest.TempPathFactory) -> HexMesh:
    """The cantilever 6 x 2 x 1, read back from a file so that messages name the file."""
    p = tmp_path_factory.mktemp("mesh") / "bar.inp"
    return read_mesh(write_inp(cantilever_mesh(6, 2, 1), p))


def _one_line(err: pytest.ExceptionInfo[ParameterError]) -> str:
    text = str(err.value)
    assert "\n" not in text
    return text


def test_the_example_roles_pass(bar: HexMesh) -> None:
    check_roles(bar, contact="contact", clamp="clamp", loads=[MeshLoad.parse("tip:1,0,0:300")])


def test_a_misspelt_set_names_the_file_and_the_closest_name(bar: HexMesh) -> None:
    with pytest.raises(ParameterError) as err:
        check_roles(bar, contact="contcat", clamp="clamp")
    text = _one_line(err)
    assert text.startswith(str(Path(bar.source))) and "bar.inp" in text
    assert "no set named 'contcat' (the contact set); did you mean 'contact'?" in text
    assert "The mesh has: clamp, contact, response, tip" in text


def test_a_set_in_the_wrong_case_is_suggested(bar: HexMesh) -> None:
    with pytest.raises(ParameterError, match=r"'CLAMP' \(the clamp set\); did you mean 'clamp'"):
        check_roles(bar, contact="contact", clamp="CLAMP")


def test_a_load_on_a_missing_set_without_a_close_name(bar: HexMesh) -> None:
    with pytest.raises(ParameterError) as err:
        check_roles(bar, "contact", "clamp", loads=[MeshLoad.parse("zzz:0,1,0:10")])
    text = _one_line(err)
    assert "no set named 'zzz' (the set of a load) The mesh has:" in text
    assert "did you mean" not in text


def test_an_empty_set_is_refused(tmp_path: Path, bar: HexMesh) -> None:
    text = write_inp(bar, tmp_path / "e.inp").read_text() + "*NSET, NSET=nothing\n"
    (tmp_path / "e.inp").write_text(text)
    mesh = read_mesh(tmp_path / "e.inp")
    with pytest.raises(ParameterError, match=r"e.inp: set 'nothing' \(the clamp set\) is empty"):
        check_roles(mesh, "contact", "nothing")


def test_a_set_without_a_whole_face_is_refused(bar: HexMesh) -> None:
    edge = np.flatnonzero((bar.nodes[:, 1] == 0) & (bar.nodes[:, 2] == 0))
    m = HexMesh(bar.nodes, bar.elements, {**bar.node_sets, "edge": edge}, source="bar.inp")
    with pytest.raises(ParameterError) as err:
        check_roles(m, "edge", "clamp")
    assert "bar.inp: set 'edge' (the contact set) holds no element face" in _one_line(err)
    assert f"among its {len(edge)} nodes" in str(err.value)


def test_an_interior_contact_is_refused_but_an_interior_load_is_not() -> None:
    box = box_hexmesh(preset("table1"), "4x2x1")
    check_roles(box, "contact", "clamp", loads=["tip", "centre"])
    with pytest.raises(ParameterError) as err:
        check_roles(box, "centre", "clamp")
    text = _one_line(err)
    assert "box 4x2x1: set 'centre' (the contact set) is not on the boundary" in text
    assert "4 of its 4 faces are shared by two elements" in text
    with pytest.raises(ParameterError, match=r"'centre' \(the clamp set\) is not on the bound"):
        check_roles(box, "contact", "centre")


def test_an_inverted_element_is_named_by_its_file_number(bar: HexMesh) -> None:
    elements = bar.elements.copy()
    elements[3] = elements[3][[4, 5, 6, 7, 0, 1, 2, 3]]  # mirrored: top face first
    m = HexMesh(bar.nodes, elements, bar.node_sets, source="bar.inp",
                element_ids=np.arange(len(elements)) + 501)
    with pytest.raises(ParameterError) as err:
        check_roles(m, "contact", "clamp")
    assert _one_line(err).startswith("bar.inp: element 504 is inverted")


def test_a_collapsed_element_is_degenerate() -> None:
    nodes = CUBE.copy()
    nodes[1] = nodes[0]  # an edge of zero length: det J = 0 at two corners
    m = HexMesh(nodes, [list(range(8))], source="c.inp")
    with pytest.raises(ParameterError, match=r"^c.inp: element 1 is degenerate"):
        check_elements(m)


def test_a_node_pushed_through_the_element_is_inside_out() -> None:
    nodes = CUBE.copy()
    nodes[6] = [0.5, 0.3, -0.5]  # corner 7 pushed below the bottom face
    m = HexMesh(nodes, [list(range(8))], source="c.inp")
    with pytest.raises(ParameterError, match=r"c.inp: element 1 is distorted inside out"):
        check_elements(m)


def test_hex20_jacobian_is_exact_and_a_bent_mid_edge_node_is_refused() -> None:
    m = to_hex20(HexMesh(CUBE, [list(range(8))]))
    g = np.sqrt(0.6)
    w = np.array([5, 8, 5]) / 9.0
    weights = np.einsum("i,j,k->ijk", w, w, w).ravel()
    volume = float(jacobian_dets(m)[0, 8:] @ weights)
    assert volume == pytest.approx(2.0, rel=1e-14) and g > 0
    check_elements(m)
    nodes = m.nodes.copy()
    nodes[8] += [0.0, 1.5, 0.0]  # the mid-node of edge 1-2 pushed past the opposite face
    with pytest.raises(ParameterError, match="element 1 is"):
        check_elements(HexMesh(nodes, m.elements, source="c20.inp"))


def test_zero_length_load_direction_is_refused() -> None:
    with pytest.raises(ParameterError, match="load on 'tip': direction 0,0,0 has zero length"):
        MeshLoad.parse("tip:0,0,0:300")


def test_a_mesh_without_elements_is_refused() -> None:
    with pytest.raises(ParameterError, match=r"x\.inp: no hexahedra"):
        HexMesh(CUBE, np.zeros((0, 8), dtype=int), source="x.inp")


def test_contact_and_clamp_on_the_same_faces_are_refused(bar: HexMesh) -> None:
    with pytest.raises(ParameterError) as err:
        check_roles(bar, "contact", "contact")
    assert "the contact set 'contact' and the clamp set 'contact' share 4 faces" in \
        _one_line(err)
