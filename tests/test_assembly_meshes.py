"""The committed assembly meshes: two (or one) deformable bodies meeting on conforming faces.

For every mesh: ``read_mesh`` gives the expected element sets, node sets and element-face
surfaces; every element has a positive Jacobian; the element connectivity has as many
connected bodies as element sets, each element set one body; each contact face's nodes pair
one to one with nodes of its counter face (another body's) at the same place (cKDTree, 1e-9
of the part's size) and no other nodes coincide (the bodies touch nowhere else); each
body's volume (its elements' volumes summed) and bounding box, and each face's area, are the
drawn ones. The generators: tests/data/meshes/make_assemblies.py and make_hertz.py (numpy;
checked here to write the committed files), examples/bolted_lap/make_bolted_lap.py and
examples/brb/make_brb.py (gmsh; not run here: the tests read the committed files).
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from microslip.fe.assembly import Assembly, Contact, Material, Preload, Support
from microslip.fe.hexmesh import HexMesh, face_load
from microslip.fe.meshcheck import boundary_faces, check_elements, jacobian_dets
from microslip.fe.meshfile import read_mesh

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "meshes"
EXAMPLES = ROOT / "examples"
COINCIDENT = 1e-9
Bounds = tuple[tuple[float, float, float], tuple[float, float, float]]


@dataclass(frozen=True)
class Spec:
    """What a mesh file must hold: element sets (volume mm^3, bounding box), surfaces (area
    mm^2), the other node-set names, contacts (face, counter, whether the counter face is the
    same size), the node and element counts; ``same``: pairs of sets with the same nodes;
    ``rel``: the relative tolerance of a volume or an area that the faceted mesh only
    approximates (default 1e-12 for volumes, 1e-9 for areas)."""

    path: Path
    nodes: int
    elements: int
    bodies: dict[str, tuple[float, Bounds]]
    surfaces: dict[str, float]
    contacts: tuple[tuple[str, str, bool], ...] = ()
    node_sets: tuple[str, ...] = ()
    same: tuple[tuple[str, str], ...] = ()
    rel: dict[str, float] = field(default_factory=dict)


BAR: Bounds = ((0.0, 0.0, 0.0), (152.4, 25.4, 6.35))
BAR_VOLUME = 152.4 * 25.4 * 6.35
CLAMPED = 50.8 * 25.4
_BAR_SURFACES = {"contact": CLAMPED, "clamp": CLAMPED, "tip": 25.4 * 6.35, "bar_int": CLAMPED}
#: The wide block reaches 2 elements (2 x 25.4 / 6 mm) beyond the bar in y: planes to 1e-10 mm.
_WIDE_LO, _WIDE_HI = -8.4666666666, 33.8666666666
_WIDE = 57.15 * (_WIDE_HI - _WIDE_LO)

SPECS = {
    "cantilever_on_block": Spec(
        DATA / "cantilever_on_block.inp", 525 + 9 * 7 * 3, 288 + 96,
        {"BAR": (BAR_VOLUME, BAR),
         "BASE": (CLAMPED * 6.35, ((0.0, 0.0, -6.35), (50.8, 25.4, 0.0)))},
        {**_BAR_SURFACES, "base_int": CLAMPED, "base_fix": CLAMPED},
        (("bar_int", "base_int", True),), ("response",),
        same=(("bar_int", "contact"),)),
    "cantilever_on_block_wide": Spec(
        DATA / "cantilever_on_block_wide.inp", 525 + 10 * 11 * 3, 288 + 180,
        {"BAR": (BAR_VOLUME, BAR),
         "BASE": (_WIDE * 6.35, ((-6.35, _WIDE_LO, -6.35), (50.8, _WIDE_HI, 0.0)))},
        {**_BAR_SURFACES, "base_int": _WIDE, "base_fix": _WIDE},
        (("bar_int", "base_int", False),), ("response",),
        same=(("bar_int", "contact"),)),
}

_LAP = {"PLATE_A": (10000.0, ((0.0, 0.0, 0.0), (100.0, 25.0, 4.0))),
        "PLATE_B": (10000.0, ((75.0, 0.0, 4.0), (175.0, 25.0, 8.0)))}
_LAP_SURFACES = {"a_int": 625.0, "b_int": 625.0, "head": 144.0, "nut": 144.0, "fix": 100.0,
                 "tip": 100.0, "response": 100.0}
SPECS["bolted_lap"] = Spec(EXAMPLES / "bolted_lap" / "bolted_lap.msh", 2 * 42 * 12 * 3,
                           2 * 41 * 11 * 2, _LAP, _LAP_SURFACES, (("a_int", "b_int", True),),
                           same=(("tip", "response"),))
SPECS["bolted_lap_small"] = Spec(DATA / "bolted_lap_small.msh", 2 * 23 * 8 * 3,
                                 2 * 22 * 7 * 2, _LAP, _LAP_SURFACES,
                                 (("a_int", "b_int", True),), same=(("tip", "response"),))


_HALF = 293.5 * 25.4**2 + 122.0 * 25.4 * 12.7  # full section to the shoulder, tongue beyond
_PATCHES = {f"{k}{i}": 256.0 for i in (1, 2, 3) for k in ("head", "nut")}
SPECS["brb"] = Spec(EXAMPLES / "brb" / "brb.msh", 10890, 8256,
                    {"HALF_A": (_HALF, ((0.0, 0.0, 0.0), (415.5, 25.4, 25.4))),
                     "HALF_B": (_HALF, ((295.5, 0.0, 0.0), (711.0, 25.4, 25.4)))},
                    {"lap_a": 3048.0, "lap_b": 3048.0, **_PATCHES, "tip": 645.16,
                     "response": 645.16},
                    (("lap_a", "lap_b", True),), same=(("tip", "response"),))


#: The paraboloid z = r^2 / 200 under the 20 x 20 plan: the block's volume 4000 - 400 / 3
#: and the curved face's area 400 + 4 / 3 - 0.0031 (sqrt(1 + r^2 / R^2) to second order);
#: the bilinear faces lie 2.2e-4 of the volume and 1.5e-6 of the area off.
SPECS["hertz_block"] = Spec(DATA / "hertz_block.inp", 13452, 11968,
                            {"BLOCK": (4000.0 - 400.0 / 3.0,
                                       ((-10.0, -10.0, 0.0), (10.0, 10.0, 10.0)))},
                            {"bottom": 400.0 + 4.0 / 3.0 - 0.0031, "top": 400.0,
                             "top_left": 200.0, "top_right": 200.0},
                            rel={"BLOCK": 3e-4, "bottom": 1e-5})


@pytest.fixture(scope="module", params=sorted(SPECS))
def case(request: pytest.FixtureRequest) -> tuple[Spec, HexMesh]:
    spec = SPECS[request.param]
    return spec, read_mesh(spec.path)


def _size(mesh: HexMesh) -> float:
    return float(np.max(np.ptp(mesh.nodes, axis=0)))


def _face_nodes(mesh: HexMesh, name: str) -> np.ndarray:
    return np.unique(mesh.face_corners(mesh.surfaces[name]))


def _body_of_elements(mesh: HexMesh) -> np.ndarray:
    """The connected body (0, 1, ...) of each element, by shared nodes."""
    e = mesh.elements
    rows = np.repeat(e[:, 0], e.shape[1])
    graph = coo_matrix((np.ones(e.size), (rows, e.ravel())), shape=(len(mesh.nodes),) * 2)
    _, label = connected_components(graph, directed=False)
    _, body = np.unique(label[e[:, 0]], return_inverse=True)
    return body


def _partners(mesh: HexMesh, face: str, counter: str) -> tuple[np.ndarray, np.ndarray]:
    """The face's nodes and the counter face's node at the same place as each."""
    a, b = _face_nodes(mesh, face), _face_nodes(mesh, counter)
    dist, idx = cKDTree(mesh.nodes[b]).query(mesh.nodes[a])
    assert dist.max() <= COINCIDENT * _size(mesh), (face, counter, dist.max())
    return a, b[idx]


def test_sets_and_counts(case: tuple[Spec, HexMesh]) -> None:
    spec, mesh = case
    assert (len(mesh.nodes), len(mesh.elements)) == (spec.nodes, spec.elements)
    assert set(spec.bodies) <= set(mesh.element_sets)
    assert set(mesh.surfaces) == set(spec.surfaces)
    assert set(mesh.node_sets) >= set(spec.surfaces) | set(spec.node_sets)
    for name in spec.surfaces:  # a surface's nodes are its node set (8-node faces)
        assert np.array_equal(_face_nodes(mesh, name), mesh.node_sets[name]), name
        assert boundary_faces(mesh, mesh.surfaces[name]).all(), name
    for a, b in spec.same:
        assert np.array_equal(mesh.node_sets[a], mesh.node_sets[b])


def test_elements_are_positive_and_each_element_set_is_one_body(
        case: tuple[Spec, HexMesh]) -> None:
    spec, mesh = case
    check_elements(mesh)
    body = _body_of_elements(mesh)
    assert body.max() + 1 == len(spec.bodies)
    covered = np.concatenate([mesh.element_sets[k] for k in spec.bodies])
    assert np.array_equal(np.sort(covered), np.arange(len(mesh.elements)))
    assert len({int(body[mesh.element_sets[k][0]]) for k in spec.bodies}) == len(spec.bodies)
    for k in spec.bodies:
        assert len(np.unique(body[mesh.element_sets[k]])) == 1, k


def test_volumes_bounds_and_areas(case: tuple[Spec, HexMesh]) -> None:
    spec, mesh = case
    volume = jacobian_dets(mesh)[:, 8:].sum(axis=1)  # 2 x 2 x 2 Gauss points, weights 1
    for name, (v, (lo, hi)) in spec.bodies.items():
        rows = mesh.element_sets[name]
        assert volume[rows].sum() == pytest.approx(v, rel=spec.rel.get(name, 1e-12)), name
        x = mesh.nodes[np.unique(mesh.elements[rows])]
        assert x.min(axis=0) == pytest.approx(lo, abs=1e-9) and x.max(axis=0) == pytest.approx(
            hi, abs=1e-9), name
    for name, area in spec.surfaces.items():
        assert face_load(mesh, mesh.surfaces[name])[2] == pytest.approx(
            area, rel=spec.rel.get(name, 1e-9)), name


def test_contact_faces_pair_one_to_one_and_nothing_else_coincides(
        case: tuple[Spec, HexMesh]) -> None:
    spec, mesh = case
    body = _body_of_elements(mesh)
    node_body = np.zeros(len(mesh.nodes), dtype=np.int64)
    node_body[mesh.elements.ravel()] = np.repeat(body, mesh.elements.shape[1])
    expected = set()
    for face, counter, same_size in spec.contacts:
        a, b = _partners(mesh, face, counter)
        assert len(np.unique(b)) == len(a), "two face nodes share a counter node"
        assert not np.intersect1d(a, _face_nodes(mesh, counter)).size
        assert len(np.unique(node_body[a])) == 1 and len(np.unique(node_body[b])) == 1
        assert node_body[a[0]] != node_body[b[0]]
        n_counter = len(_face_nodes(mesh, counter))
        assert (n_counter == len(a)) if same_size else (n_counter > len(a))
        expected |= {tuple(sorted(p)) for p in zip(a.tolist(), b.tolist(), strict=True)}
    found = cKDTree(mesh.nodes).query_pairs(COINCIDENT * _size(mesh), output_type="ndarray")
    assert {tuple(sorted(p)) for p in found.tolist()} == expected


def _generator(name: str):  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location(name, DATA / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_numpy_generators_write_the_committed_files(tmp_path: Path) -> None:
    written = [*_generator("make_assemblies").write_all(tmp_path),
               _generator("make_hertz").write(tmp_path)]
    for p in written:
        assert p.read_text() == (DATA / p.name).read_text(), p.name


def test_hertz_block_is_fine_at_the_axis_and_its_top_halves_meet_at_x_0() -> None:
    mesh = read_mesh(SPECS["hertz_block"].path)
    x = mesh.nodes[mesh.node_sets["bottom"]]
    assert np.abs(x[:, 2] - (x[:, 0] ** 2 + x[:, 1] ** 2) / 200.0).max() < 1e-12
    corners = mesh.nodes[mesh.face_corners(mesh.surfaces["bottom"])]  # (k, 4, 3)
    centre = corners.mean(axis=1)
    near = np.hypot(centre[:, 0], centre[:, 1]) < 1.5
    edges = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2)
    assert near.sum() >= 200 and edges[near].max() < 0.2
    left, right = (mesh.nodes[mesh.face_corners(mesh.surfaces[k])][:, :, 0]
                   for k in ("top_left", "top_right"))
    assert left.max() == 0.0 and right.min() == 0.0
    assert len(left) + len(right) == len(mesh.surfaces["top"])


def _steel(*elsets: str) -> tuple[Material, ...]:
    return tuple(Material(210000.0, 0.3, 7850.0, e) for e in elsets)


#: The assembly each mesh is made for: every set and element set it names is in the mesh.
ASSEMBLIES = {
    "cantilever_on_block": Assembly((Contact("bar_int", "base_int"),),
                                    (Preload("clamp", 2000.0),), _steel("BAR", "BASE"), 0.5,
                                    (Support("base_fix"),)),
    "bolted_lap": Assembly((Contact("a_int", "b_int"),),
                           (Preload("head", 10000.0), Preload("nut", 10000.0)),
                           _steel("PLATE_A", "PLATE_B"), 0.5, (Support("fix"),)),
    "brb": Assembly((Contact("lap_a", "lap_b"),),
                    tuple(Preload(f"{k}{i}", 10000.0) for i in (1, 2, 3) for k in ("head", "nut")),
                    _steel("HALF_A", "HALF_B"), 0.5),
    "hertz_block": Assembly((Contact("bottom"),), (Preload("top", 1000.0),), _steel("BLOCK"),
                            0.5),
}
ASSEMBLIES["cantilever_on_block_wide"] = ASSEMBLIES["cantilever_on_block"]
ASSEMBLIES["bolted_lap_small"] = ASSEMBLIES["bolted_lap"]


def test_each_mesh_has_the_sets_of_its_assembly(case: tuple[Spec, HexMesh]) -> None:
    spec, mesh = case
    a = ASSEMBLIES[spec.path.stem]
    assert set(a.set_names()) <= set(mesh.surfaces)
    assert {m.elset for m in a.materials} == set(spec.bodies) <= set(mesh.element_sets)
    assert {(c.face, c.counter) for c in a.contacts if c.counter} == {
        (f, c) for f, c, _ in spec.contacts}
