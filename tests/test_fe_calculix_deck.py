"""Mesh, load case and deck cards of the CalculiX model: exact strings and invariants."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import preset
from microslip.errors import MacroslipError, ParameterError
from microslip.fe import LEVELS, FECase, MeshSpec, mesh_spec, run_case
from microslip.fe.calculix import deck as d
from microslip.fe.calculix.boxrun import box20_mesh, box_calculix_setup
from microslip.fe.calculix.meshdeck import build_mesh_deck, load_plan
from microslip.fe.meshload import MeshLoad

P = preset("table1")


# -- exact cards ------------------------------------------------------------------------------
def test_heading_and_nodes():
    assert d.heading_card("tip") == "*HEADING\ntip\n"
    assert d.nodes_card([[0.0, 0.0, 0.0], [254.0, 25.4, 3.18]], first=7) == (
        "*NODE\n7, 0, 0, 0\n8, 254, 25.4, 3.18\n")


def test_twenty_node_element_line_continues_after_fifteen_nodes():
    conn = np.arange(1, 21).reshape(1, 20)
    assert d.elements_card("C3D20R", "BAR", conn) == (
        "*ELEMENT, TYPE=C3D20R, ELSET=BAR\n"
        "1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,\n"
        "16, 17, 18, 19, 20\n")


def test_sets_wrap_at_sixteen_entries():
    assert d.nset_card("NBASE", np.arange(1, 18)) == (
        "*NSET, NSET=NBASE\n1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16\n17\n")
    assert d.elset_card("etop", [3]) == "*ELSET, ELSET=ETOP\n3\n"


def test_surface_material_section():
    assert d.surface_card("SBASE", [41, 42], "S2") == (
        "*SURFACE, NAME=SBASE, TYPE=ELEMENT\n41, S2\n42, S2\n")
    assert d.material_card("BAR", 68947.0, 0.3) == "*MATERIAL, NAME=BAR\n*ELASTIC\n68947, 0.3\n"
    assert d.solid_section_card("BASE", "BAR") == "*SOLID SECTION, ELSET=BASE, MATERIAL=BAR\n"


def test_contact_cards():
    assert d.surface_interaction_card("SI", 1e5, 0.8, 1e4) == (
        "*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
        "100000\n*FRICTION\n0.8, 10000\n")
    assert d.contact_pair_card("SI", "SBOTTOM", "SBASE") == (
        "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSBOTTOM, SBASE\n")


def test_boundary_amplitude_step_cards():
    assert d.boundary_card([("NBASE", 1, 3), ("NSYM", 2, 2)]) == (
        "*BOUNDARY\nNBASE, 1, 3, 0\nNSYM, 2, 2, 0\n")
    assert d.amplitude_card("FT", [0, 0.25, 0.5, 0.75, 1.0], [0, 1, 0, -1, 0]) == (
        "*AMPLITUDE, NAME=FT\n0, 0, 0.25, 1, 0.5, 0, 0.75, -1\n1, 0\n")
    assert d.step_card(60) == "*STEP, INC=60\n"
    assert d.step_card(60, nlgeom=True) == "*STEP, NLGEOM, INC=60\n"
    assert d.static_card(0.025, 1.25, direct=True) == "*STATIC, DIRECT\n0.025, 1.25\n"
    assert d.static_card(1.0, 1.0, direct=False) == "*STATIC\n1, 1\n"
    assert d.controls_card(26) == "*CONTROLS, PARAMETERS=TIME INCREMENTATION\n, , , 26\n"
    assert d.end_step_card() == "*END STEP\n"


def test_load_and_output_cards():
    assert d.dload_card("ETOP", "S2", 445 / (254 * 25.4)) == (
        "*DLOAD\nETOP, P2, 0.0689751379503\n")
    assert d.cload_card([3, 9], 1, [-22.25, 89.0], amplitude="FT") == (
        "*CLOAD, AMPLITUDE=FT\n3, 1, -22.25\n9, 1, 89\n")
    assert d.node_print_card("NLOAD", ["U"]) == "*NODE PRINT, NSET=NLOAD\nU\n"
    assert d.node_file_card(["U"]) == "*NODE FILE\nU\n"
    assert d.contact_file_card(["CDIS", "CSTR"]) == "*CONTACT FILE\nCDIS, CSTR\n"


@pytest.mark.parametrize("call", [
    lambda: d.heading_card("*STEP"),
    lambda: d.heading_card("two\nlines"),
    lambda: d.nodes_card([[0.0, math.nan, 0.0]]),
    lambda: d.nodes_card([[0.0, 0.0]]),
    lambda: d.elements_card("C3D20R", "BAR", np.ones((1, 8), dtype=int)),
    lambda: d.elements_card("S8R", "BAR", np.ones((1, 8), dtype=int)),
    lambda: d.elements_card("C3D8", "BAR", np.zeros((1, 8), dtype=int)),
    lambda: d.nset_card("1BAD", [1]),
    lambda: d.nset_card("OK", []),
    lambda: d.nset_card("OK", [0]),
    lambda: d.surface_card("S", [1], "S7"),
    lambda: d.material_card("M", -1.0, 0.3),
    lambda: d.material_card("M", 1.0, 0.5),
    lambda: d.surface_interaction_card("SI", 1e5, 0.8, 0.0),
    lambda: d.surface_interaction_card("SI", math.inf, 0.8, 1e4),
    lambda: d.surface_interaction_card("SI", 1e5, -0.8, 1e4),
    lambda: d.boundary_card([("N", 0, 3)]),
    lambda: d.boundary_card([]),
    lambda: d.amplitude_card("A", [0.0, 0.0], [0.0, 1.0]),
    lambda: d.amplitude_card("A", [0.0], [0.0]),
    lambda: d.step_card(0),
    lambda: d.static_card(2.0, 1.0, direct=True),
    lambda: d.static_card(0.0, 1.0, direct=True),
    lambda: d.controls_card(2),
    lambda: d.dload_card("E", "S2", -0.1),
    lambda: d.cload_card([1, 2], 1, [1.0]),
    lambda: d.cload_card([1], 4, [1.0]),
    lambda: d.node_print_card("N", ["S"]),
    lambda: d.contact_file_card([]),
])
def test_invalid_card_inputs_raise_parameter_error(call):
    with pytest.raises(ParameterError):
        call()


# -- mesh -------------------------------------------------------------------------------------
@given(nx=st.integers(1, 8).map(lambda k: 2 * k), ny=st.integers(1, 3).map(lambda k: 2 * k),
       nz=st.integers(1, 3))
@settings(max_examples=25, deadline=None)
def test_mesh_counts_volumes_and_load_shares(nx, ny, nz):
    spec = MeshSpec(nx, ny, nz)
    m = box20_mesh(P, spec)
    assert len(m.nodes) == spec.nodes
    assert m.elements.shape == (nx * ny * nz, 20)
    # every node is used, no element repeats a node
    assert set(np.unique(m.elements)) == set(range(spec.nodes))
    assert all(len(set(row)) == 20 for row in m.elements)
    # corners span a box of the element size, in the C3D20 orientation (positive volume)
    xyz = m.nodes[m.elements[:, :8]]
    size = np.array([P.length / nx, P.width / ny, P.thickness / nz])
    np.testing.assert_allclose(xyz[:, 6] - xyz[:, 0], np.broadcast_to(size, (xyz.shape[0], 3)))
    np.testing.assert_allclose(xyz[:, 1, 0] - xyz[:, 0, 0], size[0])
    np.testing.assert_allclose(xyz[:, 3, 1] - xyz[:, 0, 1], size[1])
    # mid-side nodes halfway between their corners (edges 1-2, ..., 4-8)
    pairs = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7)]
    mids = m.nodes[m.elements[:, 8:]]
    for e, (a, b) in enumerate(pairs):
        np.testing.assert_allclose(mids[:, e], 0.5 * (xyz[:, a] + xyz[:, b]), atol=1e-12)
    # the dof count subtracts u_y on the symmetry plane
    sym = m.node_sets["sym"]
    assert spec.dof == 3 * spec.nodes - sym.size
    np.testing.assert_allclose(m.nodes[sym, 1], P.width / 2)
    for model, x in (("tip", P.length), ("centre", P.length / 2)):
        plan = load_plan(m, [MeshLoad(model, (1.0, 0.0, 0.0), 1.0)])
        np.testing.assert_allclose(m.nodes[plan.loaded, 0], x)
        # consistent loads of a uniform traction: total 1, resultant through the centroid
        u = np.zeros((3, plan.loaded.size, 3))
        u[0, :, 0] = 1.0
        u[1, :, 0] = m.nodes[plan.loaded, 1]
        u[2, :, 0] = m.nodes[plan.loaded, 2]
        share = plan.conjugate(u)[:, 0]
        assert share[0] == pytest.approx(1.0, abs=1e-12)
        assert share[1] == pytest.approx(P.width / 2, rel=1e-12)
        assert share[2] == pytest.approx(P.thickness / 2, rel=1e-12)


def test_named_meshes_and_their_sizes():
    """The levels on the Table 1 bar (the built-in solver's counts) and their C3D20R DOF:
    3 per node (corners and edge mid-points) less u_y on the symmetry plane."""
    specs = {k: mesh_spec(k, P) for k in LEVELS}
    assert {k: v.label() for k, v in specs.items()} == {
        "tiny": "8x2x1", "coarse": "24x4x1", "medium": "48x4x1", "fine": "96x8x2",
        "paper": "96x4x1"}
    assert {k: v.dof for k, v in specs.items()} == {
        "tiny": 452, "coarse": 2322, "medium": 4578, "fine": 27082, "paper": 9090}
    assert not any(v.graded for v in specs.values())


@pytest.mark.parametrize("bad", [(3, 2, 1), (2, 3, 1), (2, 2, 0), (0, 2, 1), (2.0, 2, 1),
                                 (True, 2, 1)])
def test_mesh_spec_rejects(bad):
    with pytest.raises(ParameterError):
        MeshSpec(*bad)


# -- load case and deck -----------------------------------------------------------------------
def test_case_validation():
    with pytest.raises(MacroslipError):
        FECase("tip", amplitude=356.0)
    for kwargs in ({"model": "side"}, {"model": "tip", "substeps": 52},
                   {"model": "tip", "stick_slope": 0.0}, {"model": "tip", "mesh": "huge"},
                   {"model": "tip", "element": "C3D8"}, {"model": "tip", "element": "C3D20"},
                   {"model": "tip", "max_iterations": 2}):
        with pytest.raises(ParameterError):
            FECase(**kwargs)


def test_case_times_and_force():
    c = FECase("centre")
    assert c.times.shape == (51,) and c.times[-1] == pytest.approx(1.25)
    assert c.quarter == 10 and c.times[c.quarter] == pytest.approx(0.25)
    assert c.force(0.25) == pytest.approx(267.0) and c.force(0.75) == pytest.approx(-267.0)
    assert c.pressure == pytest.approx(445.0 / (254.0 * 25.4))


def test_deck_of_the_tip_case():
    """The box's deck is the mesh deck: the symmetry plane a support (u_y), the clamping
    pressure F_N / (L w) on the top face, the paper's sine in 50 increments over 1.25 s."""
    case = FECase("tip", mesh=MeshSpec(2, 2, 1))
    mesh, assembly, loads, opts = box_calculix_setup(case)
    deck = build_mesh_deck(mesh, assembly, loads=loads, **opts)
    assert "*ELEMENT, TYPE=C3D20R, ELSET=BODY" in deck and "\nNFIX1, 2, 2, 0\n" in deck
    assert "SCLAMP, P, 0.0689751379503\n" in deck and "\n0.8, 10000\n" in deck
    assert "*STATIC, DIRECT\n0.025, 1.25\n" in deck
    # the nodal forces of the CLOAD card add up to the amplitude, on the loaded end face
    lines = deck.split("*CLOAD, AMPLITUDE=L1\n")[1].split("*")[0].splitlines()
    nodes = [int(ln.split(",")[0]) for ln in lines]
    forces = [float(ln.split(",")[2]) for ln in lines]
    assert sum(forces) == pytest.approx(267.0, rel=1e-12)
    np.testing.assert_allclose(mesh.nodes[np.array(nodes) - 1, 0], P.length)


def test_nlgeom_is_refused_in_one_line(tmp_path):
    case = FECase("centre", mesh=MeshSpec(4, 2, 1), nlgeom=True)
    with pytest.raises(ParameterError, match="nlgeom is not available") as err:
        run_case(case, tmp_path / "never")
    assert "\n" not in str(err.value) and not (tmp_path / "never").exists()
