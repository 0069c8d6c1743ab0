"""The example geometries of examples/: generators, their sets, and the committed files."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from microslip.errors import ParameterError
from microslip.fe.calculix.mesh import MeshSpec
from microslip.fe.examples import (
    EXAMPLES,
    bolt_pad_mesh,
    box_hexmesh,
    box_inp,
    cantilever_mesh,
    to_hex20,
    write_examples,
)
from microslip.fe.hexmesh import face_load
from microslip.fe.meshcheck import check_roles, jacobian_dets
from microslip.fe.meshfile import read_mesh
from microslip.params import preset

EXAMPLES_DIR = Path(__file__).resolve().parents[1] / "examples"


def _area(mesh, name: str) -> float:  # type: ignore[no-untyped-def]
    return face_load(mesh, mesh.faces(name))[2]


def test_committed_example_files_are_what_the_generators_write(tmp_path: Path) -> None:
    written = write_examples(tmp_path)
    assert sorted(p.name for p in written) == sorted(EXAMPLES)
    for p in written:
        assert p.read_text() == (EXAMPLES_DIR / p.name).read_text(), p.name


def test_cantilever_24x6x2_has_8_elements_under_the_clamp_and_its_sets() -> None:
    m = cantilever_mesh(24, 6, 2)
    assert m.elements.shape == (288, 8) and len(m.nodes) == 525  # 1575 DOF
    check_roles(m, "contact", "clamp", loads=["tip", "response"])
    x_el = m.nodes[m.elements].mean(axis=1)[:, 0]
    assert np.sum(x_el < 50.8) == 8 * 6 * 2
    assert _area(m, "contact") == pytest.approx(50.8 * 25.4, rel=1e-12)
    assert _area(m, "clamp") == pytest.approx(50.8 * 25.4, rel=1e-12)
    assert _area(m, "tip") == pytest.approx(25.4 * 6.35, rel=1e-12)
    contact = m.nodes[m.node_sets["contact"]]
    assert contact[:, 2].max() == 0.0 and contact[:, 0].max() == 50.8
    assert m.nodes[m.node_sets["clamp"], 2].min() == 6.35
    assert np.array_equal(m.node_sets["response"], m.node_sets["tip"])
    assert m.nodes[:, 0].max() == 152.4 and np.all(m.nodes[m.node_sets["tip"], 0] == 152.4)


@pytest.mark.parametrize("nx", [25, 1, 0])
def test_cantilever_needs_a_node_plane_at_the_clamp_edge(nx: int) -> None:
    with pytest.raises(ParameterError, match=r"nx must put a node plane at the clamp edge "
                                             r"x = 50\.8 mm"):
        cantilever_mesh(nx, 2, 1)


def test_cantilever_hex20_keeps_the_sets_and_the_volume() -> None:
    m = cantilever_mesh(6, 2, 1, quadratic=True)
    check_roles(m, "contact", "clamp", loads=["tip"])
    g, w = np.sqrt(0.6), np.array([5, 8, 5]) / 9.0
    weights = np.einsum("i,j,k->ijk", w, w, w).ravel()
    volume = float((jacobian_dets(m)[:, 8:] @ weights).sum())
    assert volume == pytest.approx(152.4 * 25.4 * 6.35, rel=1e-12) and g > 0
    # 8 mid-side nodes on each contact face: the node set holds the face's mid-edge nodes
    assert len(m.node_sets["contact"]) == 3 * 2 + 2 * 3 + 3 * 3
    assert _area(m, "tip") == pytest.approx(25.4 * 6.35, rel=1e-12)


def test_to_hex20_node_count_matches_the_calculix_bar() -> None:
    m = to_hex20(cantilever_mesh(6, 2, 2))
    assert len(m.nodes) == MeshSpec(6, 2, 2).nodes


def test_bolt_pad_sets_are_the_pad_the_partial_contact_and_the_arm_end() -> None:
    m = bolt_pad_mesh(4.0)
    check_roles(m, "contact", "clamp", loads=["end"])
    assert _area(m, "clamp") == pytest.approx(16.0 * 16.0, rel=1e-12)
    assert _area(m, "contact") == pytest.approx(40.0 * 40.0, rel=1e-12)
    assert _area(m, "end") == pytest.approx(40.0 * 6.0, rel=1e-12)
    centres = m.nodes[m.elements].mean(axis=1)
    assert not np.any((centres[:, 0] > 40) & (centres[:, 2] > 6))  # the step
    assert np.any((centres[:, 0] < 40) & (centres[:, 2] > 6))
    small = bolt_pad_mesh(20.0, quadratic=True)
    check_roles(small, "contact", "clamp", loads=["end"])


def test_box_is_the_built_in_box_node_for_node(tmp_path: Path) -> None:
    """The file of the box is the box: nodes slice by slice along x (node (i, j, k) is
    number (i (ny + 1) + j) (nz + 1) + k), its sets on their node planes, and the tip's
    consistent load the tributary areas of the end face."""
    params = preset("table1")
    box = box_hexmesh(params, "24x4x1")
    m = read_mesh(box_inp(params, "24x4x1", tmp_path / "box.inp"))
    assert np.array_equal(m.nodes, box.nodes) and np.array_equal(m.elements, box.elements)
    i, j, k = np.meshgrid(np.arange(25), np.arange(5), np.arange(2), indexing="ij")
    number = ((i * 5 + j) * 2 + k).ravel()
    xyz = np.stack([np.linspace(0.0, params.length, 25)[i.ravel()],
                    np.linspace(0.0, params.width, 5)[j.ravel()],
                    np.array([0.0, params.thickness])[k.ravel()]], axis=1)
    assert np.array_equal(m.nodes[number], xyz)
    for name, where in (("contact", k == 0), ("clamp", k == 1), ("tip", i == 24),
                        ("centre", i == 12)):
        assert np.array_equal(m.node_sets[name], np.sort(number[where.ravel()])), name
        assert np.array_equal(m.node_sets[name], box.node_sets[name]), name
    check_roles(m, "contact", "clamp", loads=["tip", "centre"])
    # the consistent load of the tip equals the box's tributary areas
    nodes, w, area = face_load(m, m.faces("tip"))
    trib_y = np.r_[0.5, np.ones(3), 0.5] * params.width / 4
    trib_z = np.array([0.5, 0.5]) * params.thickness
    assert np.array_equal(nodes, m.node_sets["tip"])
    assert np.allclose(w * area, np.outer(trib_y, trib_z).ravel(), rtol=1e-14, atol=0)


def test_box_with_odd_nx_has_no_centre() -> None:
    assert "centre" not in box_hexmesh(preset("table1"), "5x2x1").node_sets


def _ccx_tension(tmp_path: Path, name: str, load: str) -> float:
    """Mean u_x (mm) of the load face under 10 MPa tension, the contact face fixed, in ccx."""
    from microslip.fe.calculix.runner import run_ccx

    (tmp_path / "job.inp").write_text(
        f"*INCLUDE, INPUT={EXAMPLES_DIR / name}\n*MATERIAL, NAME=AL\n*ELASTIC\n70000, 0.33\n"
        "*SOLID SECTION, ELSET=EALL, MATERIAL=AL\n*BOUNDARY\ncontact, 1, 3\n*STEP\n*STATIC\n"
        f"*DSLOAD\n{load}, P, -10.\n*NODE PRINT, NSET={load}\nU\n*END STEP\n")
    run_ccx(tmp_path, "job", timeout=300)
    rows = [line.split() for line in (tmp_path / "job.dat").read_text().splitlines()]
    ux = [float(r[1]) for r in rows if len(r) == 4 and r[0].isdigit()]
    assert ux
    return float(np.mean(ux))


@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) not on PATH")
def test_calculix_reads_the_example_files_and_stretches_the_overhang(tmp_path: Path) -> None:
    # The free overhang alone stretches 10 * 101.6 / 70000 mm; the whole bar, were it free,
    # 10 * 152.4 / 70000: the clamped part, held at its bottom, adds a little.
    u8 = _ccx_tension(tmp_path, "cantilever.inp", "tip")
    u20 = _ccx_tension(tmp_path, "cantilever_hex20.inp", "tip")
    assert 10 * 101.6 / 70000 < u8 < 10 * 152.4 / 70000
    assert u20 == pytest.approx(u8, rel=0.02)
    assert 10 * 40 / 70000 < _ccx_tension(tmp_path, "bolt_pad.inp", "end") < 10 * 80 / 70000
    assert _ccx_tension(tmp_path, "box_table1_24x4x1.inp", "tip") > 0
