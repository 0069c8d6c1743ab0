"""Bad mesh input stays one line (issue 29 item 5): several gmsh volumes (read, joined or
refused when meshed apart), mixed element types, physical groups of the wrong dimension, and
a mesh in metres (a warning). The gmsh files are tests/data/meshes (make_meshes.py)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from microslip.cli.main import main
from microslip.errors import ParameterError
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshcheck import check_roles, scale_warnings
from microslip.fe.meshfile import read_mesh

MESHES = Path(__file__).resolve().parent / "data" / "meshes"
RUN = ["--contact-set", "contact", "--clamp-set", "clamp", "--normal-force", "200",
       "--friction", "0.5", "--modulus", "70000", "--poisson-ratio", "0.33",
       "--load", "tip:1,0,0:60"]


def _fe(capsys: pytest.CaptureFixture[str], name: str) -> tuple[int, str, str]:
    code = main(["fe", "--mesh", str(MESHES / name), *RUN, "--json"])
    out, err = capsys.readouterr()
    return code, out, err


def test_two_gmsh_volumes_read_as_one_body() -> None:
    pytest.importorskip("meshio")
    m = read_mesh(MESHES / "two_volumes.msh")
    assert len(m.elements) == 16 and len(m.nodes) == 5 * 3 * 3  # joined on x = 2
    assert len(m.faces("contact")) == 8 and len(m.faces("tip")) == 4
    assert m.set_dims == {"body": 3, "contact": 2, "clamp": 2, "tip": 2}
    check_roles(m, "contact", "clamp", ["tip"])


def test_two_gmsh_volumes_run(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("meshio")
    code, out, err = _fe(capsys, "two_volumes.msh")
    assert code == 0 and "error" not in err
    assert json.loads(out)["elements"] == 16


@pytest.mark.parametrize("name, message", [
    ("separate_volumes.msh", r"touch at 9 coincident nodes with no contact named"),
    ("contact_curve.msh", r"set 'contact' \(the contact set\) is a curve \(1-D\) group"),
    ("contact_volume.msh", r"set 'contact' \(the contact set\) is a volume \(3-D\) group"),
])
def test_bad_gmsh_files_are_one_line(capsys: pytest.CaptureFixture[str], name: str,
                                     message: str) -> None:
    pytest.importorskip("meshio")
    code, out, err = _fe(capsys, name)
    lines = err.strip().splitlines()
    assert code == 1 and out.strip() == "" and len(lines) == 1, err
    assert lines[0].startswith(f"error: {MESHES / name}: ")
    assert __import__("re").search(message, lines[0]), lines[0]


def test_a_mesh_in_metres_is_refused_in_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    """A part 0.004 mm across with forces in N cannot be meant (issue 34): an error, not a
    result with a warning."""
    pytest.importorskip("meshio")
    code, out, err = _fe(capsys, "metres.msh")
    lines = [ln for ln in err.splitlines() if ln.startswith("error: ")]
    assert code == 1 and out.strip() == "" and len(lines) == 1
    assert "the part is 0.004 mm across" in lines[0] and "a mesh in metres" in lines[0]


def test_scale_warnings_bounds() -> None:
    m = cantilever_mesh(3, 1, 1)  # 152.4 mm long, clamp 50.8 x 25.4 mm
    area = 50.8 * 25.4
    assert scale_warnings(m, "clamp", 2000.0, 70000.0) == []
    low = scale_warnings(m, "clamp", 2000.0, 70000e6)  # the modulus in Pa
    assert len(low) == 1 and "modulus in Pa" in low[0]
    # just inside the upper bound: no warning; just outside: one
    assert scale_warnings(m, "clamp", 0.99e-2 * 70000 * area, 70000.0) == []
    assert len(scale_warnings(m, "clamp", 1.01e-2 * 70000 * area, 70000.0)) == 1


def _meshio_file(tmp_path: Path, cells: list[tuple[str, np.ndarray]], points: np.ndarray,
                 name: str = "m.vtu") -> Path:
    meshio = pytest.importorskip("meshio")
    p = tmp_path / name
    meshio.write(p, meshio.Mesh(points, cells))
    return p


def test_mixed_hexahedra_and_tetrahedra_are_refused(tmp_path: Path) -> None:
    m = cantilever_mesh(3, 1, 1)
    tet = np.array([[0, 1, 2, 3]])
    p = _meshio_file(tmp_path, [("hexahedron", m.elements), ("tetra", tet)], m.nodes)
    with pytest.raises(ParameterError, match=r"m.vtu: the mesh has tetrahedra; "):
        read_mesh(p)


def test_mixed_hexahedra_and_wedges_are_refused(tmp_path: Path) -> None:
    m = cantilever_mesh(3, 1, 1)
    wedge = np.array([[0, 1, 2, 3, 4, 5]])
    p = _meshio_file(tmp_path, [("hexahedron", m.elements), ("wedge", wedge)], m.nodes)
    with pytest.raises(ParameterError, match=r"m.vtu: the mesh has wedges; "):
        read_mesh(p)


def test_mixed_8_and_20_node_hexahedra_are_refused(tmp_path: Path) -> None:
    m = cantilever_mesh(3, 1, 1, quadratic=True)
    cells = [("hexahedron", m.elements[:1, :8]), ("hexahedron20", m.elements[1:])]
    p = _meshio_file(tmp_path, cells, m.nodes)
    with pytest.raises(ParameterError, match="mixes 8- and 20-node hexahedra; use one kind"):
        read_mesh(p)


def test_several_hexahedron_blocks_are_one_mesh(tmp_path: Path) -> None:
    """The several-volume case without gmsh: two blocks of one cell type."""
    m = cantilever_mesh(3, 1, 1)
    cells = [("hexahedron", m.elements[:1]), ("hexahedron", m.elements[1:])]
    r = read_mesh(_meshio_file(tmp_path, cells, m.nodes))
    assert np.array_equal(r.elements, m.elements)
