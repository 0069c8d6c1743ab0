"""Mesh files: the .inp parser, the meshio formats, and write_inp -> read_mesh round trips."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.examples import bolt_pad_mesh, cantilever_mesh
from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshfile import read_mesh, write_inp

CUBE_INP = """** a unit-height brick 2 x 1 x 1 mm, node and element numbers with gaps
*Heading
  not a keyword line
*node, nset=every
10, 0, 0, 0
11, 2, 0, 0
12, 2., 1, 0
13, 0, 1, 0
20, 0, 0, 1
21, 2, 0, 1
22, 2, 1, 1
23, 0, 1,
 1.0
99, 5, 5, 5
*Element, type=C3D8R, elset=Body
7, 10, 11, 12, 13, 20, 21, 22, 23
*ELEMENT, TYPE=CPS4, ELSET=base
100, 10, 11, 12, 13
*NSET, NSET=bot
10, 11, 12,
13
*Nset, nset=top, generate
20, 23, 1
*NSET, NSET=both
bot, top
*Surface, name=lid, type=element
Body, S2
*SURFACE, NAME=side
7, s3
*MATERIAL, NAME=al
*ELASTIC
70000, 0.33
"""


def _write(tmp_path: Path, text: str, name: str = "m.inp") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def _same(a: HexMesh, b: HexMesh) -> None:
    assert np.array_equal(a.nodes, b.nodes) and np.array_equal(a.elements, b.elements)
    assert a.node_sets.keys() == b.node_sets.keys() and a.surfaces.keys() == b.surfaces.keys()
    for k in a.node_sets:
        assert np.array_equal(a.node_sets[k], b.node_sets[k]), k
    for k in a.surfaces:
        assert np.array_equal(a.surfaces[k], b.surfaces[k]), k


def test_inp_parser_reads_sets_surfaces_gaps_and_continuations(tmp_path: Path) -> None:
    m = read_mesh(_write(tmp_path, CUBE_INP))
    assert m.nodes.shape == (8, 3) and m.nodes[7].tolist() == [0.0, 1.0, 1.0]
    assert m.elements.tolist() == [list(range(8))]  # node 99 is used by no element: dropped
    assert m.node_ids.tolist() == [10, 11, 12, 13, 20, 21, 22, 23]
    assert m.element_label(0) == 7
    assert m.node_sets["bot"].tolist() == [0, 1, 2, 3]
    assert m.node_sets["top"].tolist() == [4, 5, 6, 7]
    assert m.node_sets["both"].tolist() == list(range(8))
    assert m.node_sets["every"].tolist() == list(range(8))
    # S2 is the face 5-8-7-6, S3 the face 1-5-6-2 (0-based faces 1 and 2)
    assert m.surfaces["lid"].tolist() == [[0, 1]] and m.surfaces["side"].tolist() == [[0, 2]]
    # a 2-D element set (as gmsh exports a physical surface): node set and matching surface
    assert m.node_sets["base"].tolist() == [0, 1, 2, 3]
    assert m.surfaces["base"].tolist() == [[0, 0]]


def test_inp_hex20_continuation_lines(tmp_path: Path) -> None:
    m = cantilever_mesh(3, 1, 1, quadratic=True)
    p = write_inp(m, tmp_path / "c20.inp")
    text = p.read_text()
    assert "TYPE=C3D20R" in text and text.count("*ELEMENT") == 1
    first = text.split("*ELEMENT")[1].splitlines()[1]
    assert first.endswith(",") and len(first.split(",")) == 17  # 16 numbers and a comma
    _same(read_mesh(p), m)


@pytest.mark.parametrize("make", [lambda: cantilever_mesh(6, 2, 1),
                                  lambda: cantilever_mesh(3, 1, 1, quadratic=True),
                                  lambda: bolt_pad_mesh(20.0)])
def test_write_then_read_is_exact(tmp_path: Path, make) -> None:  # type: ignore[no-untyped-def]
    m = make()
    again = read_mesh(write_inp(m, tmp_path / "m.inp"))
    _same(again, m)
    # a second pass writes the same text (the file's numbers are kept)
    assert write_inp(again, tmp_path / "n.inp").read_text().splitlines()[1:] == \
        (tmp_path / "m.inp").read_text().splitlines()[1:]


def test_round_trip_keeps_irrational_coordinates(tmp_path: Path) -> None:
    rng = np.random.default_rng(1)
    m = cantilever_mesh(3, 1, 1)
    moved = HexMesh(m.nodes + rng.uniform(-1e-3, 1e-3, m.nodes.shape) / 7.0, m.elements,
                    m.node_sets, m.surfaces, node_ids=3 * np.arange(len(m.nodes)) + 5,
                    element_ids=np.arange(len(m.elements))[::-1] + 100)
    again = read_mesh(write_inp(moved, tmp_path / "m.inp"))
    _same(again, moved)
    assert np.array_equal(again.node_ids, moved.node_ids)
    assert np.array_equal(again.element_ids, moved.element_ids)


@pytest.mark.parametrize("text, message", [
    ("*INCLUDE, INPUT=nodes.inp\n", r"m.inp, line 1: \*INCLUDE is not read"),
    ("*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n*ELEMENT, TYPE=C3D4\n1,1,2,3,4\n",
     r"m.inp, line 6: TYPE=C3D4 elements are tetrahedra; .*Recombine3DAll"),
    ("*NODE\n1,0,0,0\n*ELEMENT, TYPE=C3D10\n", "tetrahedra"),
    ("*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT, TYPE=S4, ELSET=a\n1,1,2,3,4\n",
     r"m.inp: no hexahedra .*Recombine3DAll"),
    ("*NODE\n1,0,0,0\n*ELEMENT, TYPE=C3D8\n1,1,2,3\n", "needs its number and 8 nodes"),
    ("*NODE\n1,0,0,0\n1,1,0,0\n", "node 1 is defined twice"),
    ("*NODE\n1,0,0,0\n*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n",
     "refers to node 2, which is not defined"),
    ("*NSET, NSET=a\nb\n", "'b' is neither a node number nor a node set"),
    ("*NSET, NSET=a, GENERATE\n5, 1\n", "GENERATE needs first, last"),
    ("*SURFACE, NAME=s\n1, S7\n", r"'ELSET or element, Sk'"),
    ("1, 2, 3\n", "data before the first keyword"),
])
def test_bad_inp_files_are_refused_in_one_line(tmp_path: Path, text: str, message: str) -> None:
    with pytest.raises(ParameterError, match=message) as err:
        read_mesh(_write(tmp_path, text))
    assert "\n" not in str(err.value)


def test_missing_file_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ParameterError, match=r"nope\.inp: no such mesh file"):
        read_mesh(tmp_path / "nope.inp")


def test_vtu_hex20_reads_through_meshio(tmp_path: Path) -> None:
    meshio = pytest.importorskip("meshio")
    m = cantilever_mesh(3, 1, 1, quadratic=True)
    p = tmp_path / "c.vtu"
    meshio.write(p, meshio.Mesh(m.nodes, [("hexahedron20", m.elements)],
                                point_sets={"tip": m.node_sets["tip"]}))
    r = read_mesh(p)
    assert np.array_equal(r.nodes, m.nodes) and np.array_equal(r.elements, m.elements)
    assert r.element_label(2) == 3 and r.source == str(p)


def test_gmsh22_physical_groups_become_sets_and_surfaces(tmp_path: Path) -> None:
    meshio = pytest.importorskip("meshio")
    m = cantilever_mesh(6, 2, 1)
    bottom = m.face_corners(m.surfaces["contact"])
    tip = m.face_corners(m.surfaces["tip"])
    one = np.ones(len(m.elements), dtype=int)
    mesh = meshio.Mesh(
        m.nodes, [("hexahedron", m.elements), ("quad", bottom), ("quad", tip)],
        cell_data={"gmsh:physical": [one, np.full(len(bottom), 2), np.full(len(tip), 3)],
                   "gmsh:geometrical": [one, np.ones(len(bottom), int), np.full(len(tip), 2)]},
        field_data={"body": np.array([1, 3]), "contact": np.array([2, 2])})
    p = tmp_path / "c.msh"
    meshio.write(p, mesh, file_format="gmsh22", binary=False)
    r = read_mesh(p)
    assert np.array_equal(r.elements, m.elements)
    assert np.array_equal(r.node_sets["contact"], m.node_sets["contact"])
    assert sorted(map(tuple, r.faces("contact").tolist())) == \
        sorted(map(tuple, m.surfaces["contact"].tolist()))
    # an unnamed physical surface is named by its dimension and number
    assert sorted(map(tuple, r.faces("surface3").tolist())) == \
        sorted(map(tuple, m.surfaces["tip"].tolist()))
    assert len(r.node_sets["body"]) == len(m.nodes)  # a volume group: all its nodes


GMSH41 = """$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "Base"
3 2 "body"
$EndPhysicalNames
$Entities
0 0 1 1
1 0 0 0 1 1 0 1 1 0
1 0 0 0 1 1 1 1 2 0
$EndEntities
$Nodes
1 9 1 9
3 1 0 9
1
2
3
4
5
6
7
8
9
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
7 7 7
$EndNodes
$Elements
2 2 1 2
2 1 3 1
1 1 2 3 4
3 1 5 1
2 1 2 3 4 5 6 7 8
$EndElements
"""


def test_gmsh41_cell_sets_name_the_groups(tmp_path: Path) -> None:
    pytest.importorskip("meshio")
    r = read_mesh(_write(tmp_path, GMSH41, "cube.msh"))
    assert r.nodes.shape == (8, 3)  # the stray node 9 is dropped
    assert r.node_sets["Base"].tolist() == [0, 1, 2, 3]
    assert r.faces("Base").tolist() == [[0, 0]]


def test_meshio_tetrahedra_are_refused_with_the_gmsh_hint(tmp_path: Path) -> None:
    meshio = pytest.importorskip("meshio")
    p = tmp_path / "t.vtu"
    meshio.write(p, meshio.Mesh(np.eye(4, 3), [("tetra", np.array([[0, 1, 2, 3]]))]))
    with pytest.raises(ParameterError, match=r"t.vtu: the mesh has tetrahedra; .*Recombine"):
        read_mesh(p)
    meshio.write(p, meshio.Mesh(np.eye(4, 3), [("quad", np.array([[0, 1, 2, 3]]))]))
    with pytest.raises(ParameterError, match=r"t.vtu: no hexahedra in the mesh; .*Layers"):
        read_mesh(p)


def test_write_refuses_a_set_name_inp_cannot_hold(tmp_path: Path) -> None:
    m = cantilever_mesh(3, 1, 1)
    bad = HexMesh(m.nodes, m.elements, {"two words": [0]})
    with pytest.raises(ParameterError, match="'two words' cannot be written"):
        write_inp(bad, tmp_path / "b.inp")
    assert not (tmp_path / "b.inp").exists()


GMSH_STYLE_INP = """*Heading
 cube.inp
*Node
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
******* E L E M E N T S *************
*Element, type=T3D2, ELSET=Line1
1, 1, 2
*Element, type=CPS4, ELSET=Surface1
2, 1, 4, 3, 2
*Element, type=C3D8, ELSET=Volume1
3, 1, 2, 3, 4,
5, 6, 7, 8
*ELSET,ELSET=Base
2,
*NSET,NSET=Base
1, 2, 3, 4,
"""


def test_gmsh_style_inp_with_trailing_commas_and_2d_element_sets(tmp_path: Path) -> None:
    m = read_mesh(_write(tmp_path, GMSH_STYLE_INP, "cube.inp"))
    assert m.elements.tolist() == [list(range(8))] and m.element_label(0) == 3
    assert m.surfaces["Base"].tolist() == [[0, 0]] and m.node_sets["Base"].tolist() == [0, 1, 2, 3]
    assert m.surfaces["Surface1"].tolist() == [[0, 0]]
    assert m.node_sets["Line1"].tolist() == [0, 1] and "Line1" not in m.surfaces


def test_meshio_27_node_hexahedra_drop_their_centres(tmp_path: Path) -> None:
    meshio = pytest.importorskip("meshio")
    m = cantilever_mesh(3, 1, 1, quadratic=True)
    e = m.elements
    centres = [m.nodes[e[:, list(f)]].mean(axis=1) for f in
               ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
                (3, 0, 4, 7))] + [m.nodes[e[:, :8]].mean(axis=1)]
    extra = np.concatenate(centres)  # 7 new nodes per element, element-major below
    n = len(m.nodes)
    ids = n + np.arange(7 * len(e)).reshape(7, -1).T
    p = tmp_path / "h27.vtu"
    meshio.write(p, meshio.Mesh(np.vstack([m.nodes, extra]),
                                [("hexahedron27", np.concatenate([e, ids], axis=1))]))
    r = read_mesh(p)
    assert np.array_equal(r.nodes, m.nodes) and np.array_equal(r.elements, m.elements)
