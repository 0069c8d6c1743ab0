"""The built-in frictional FE on the engineer's own mesh (issue 22): the box's load shares,
closed forms, a rotating load, and the bad inputs."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from microslip import preset
from microslip.errors import MacroslipError, ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.condense import condense
from microslip.fe.builtin.meshmodel import MeshModel, build_mesh_model, set_faces
from microslip.fe.builtin.meshrun import LoadFactors, SineCycles, solve_mesh
from microslip.fe.examples import box_hexmesh, grid_mesh
from microslip.fe.hexmesh import HexMesh, face_load
from microslip.fe.meshload import MeshLoad

TABLE1 = preset("table1")


def _box_model(normal_contact: str = "fixed", **kw: object) -> MeshModel:
    p = TABLE1
    return build_mesh_model(box_hexmesh(p, "24x4x1"), rigid_base(contact_set="contact",
                                                                 clamp_set="clamp",
                                                                 normal_force=p.normal_force,
                                                                 modulus=p.modulus,
                                                                 poisson_ratio=p.poisson_ratio,
                                                                 friction=p.friction,
                                                                 normal_contact=normal_contact,
                                                                 normal_slope=1e6), **kw)


def test_the_centre_section_counts_once() -> None:
    """The centre set is a section inside the body: each of its faces is found from the
    elements on both sides but counts once (the section's area, not twice it), and its load
    shares are the box's tributary areas."""
    m = _box_model()
    once = set_faces(m.mesh, "centre", "set of a load")
    assert len(m.mesh.faces("centre")) == 8 and len(once) == 4
    _, _, area = face_load(m.mesh, set_faces(m.mesh, "centre", "set of a load"))
    assert area == pytest.approx(TABLE1.width * TABLE1.thickness, rel=1e-14)
    p = m.unit_load(MeshLoad("centre", (1.0, 0.0, 0.0), 1.0))
    assert float(p.sum()) == pytest.approx(1.0, rel=1e-14)
    ys = np.linspace(0.0, TABLE1.width, 5)
    zs = np.array([0.0, TABLE1.thickness])
    trib = [np.r_[0.5 * np.diff(a), 0.0] + np.r_[0.0, 0.5 * np.diff(a)] for a in (ys, zs)]
    w = np.outer(trib[0], trib[1]).ravel()  # the section's tributary areas, y slowest
    x_dofs = m.index[3 * m.model_nodes(m.mesh.node_sets["centre"])]
    assert p[x_dofs] == pytest.approx(w / w.sum(), rel=1e-13)
    assert float(m.contact_area.sum()) == pytest.approx(TABLE1.length * TABLE1.width, 1e-14)
    assert float(m.normal_force.sum()) == pytest.approx(TABLE1.normal_force, rel=1e-12)


def _block(nx: int, ny: int, nz: int, size: tuple[float, float, float] = (10.0, 10.0, 2.0)
           ) -> HexMesh:
    b = grid_mesh(*(np.linspace(0.0, a, n + 1) for a, n in zip(size, (nx, ny, nz),
                                                                strict=True)))
    x, z = b.nodes[:, 0], b.nodes[:, 2]
    tol = 1e-9
    sets = {"bottom": np.flatnonzero(z <= tol), "top": np.flatnonzero(z >= size[2] - tol),
            "left": np.flatnonzero(x <= tol), "right": np.flatnonzero(x >= size[0] - tol)}
    return HexMesh(b.nodes, b.elements, sets, source="block")


def test_stuck_block_is_linear_elastic() -> None:
    """Far below the slip limit (mu huge) the response is that of the linear system
    (K + C^T lambda A C) u = f: checked against a direct solve; W = 0 with its reason."""
    mesh = _block(3, 3, 2)
    m = build_mesh_model(mesh, rigid_base(contact_set="bottom", clamp_set="top",
                                          normal_force=1000.0, modulus=70000.0, poisson_ratio=0.3,
                                          friction=1e6))
    load = MeshLoad("right", (0.0, 1.0, 0.0), 50.0)
    r = solve_mesh(m, [load], SineCycles(increments=8))
    assert r.dissipated_energy == 0.0 and "stick throughout" in (r.reason or "")
    k = m.stiffness.toarray()
    for c in range(2):
        k[m.contact_dofs[:, c], m.contact_dofs[:, c]] += m.contact_stiffness
    p = m.unit_load(load)
    d = float(p @ np.linalg.solve(k, p))  # compliance, mm/N
    assert r.peak_displacement == pytest.approx(50.0 * d, rel=1e-9)


def _torsion_closed_form(m: MeshModel, torque: float) -> tuple[float, float]:
    """Rigid block turning by theta on its nodal Jenkins elements (k_i = lambda A_i r_i^2,
    slip torque t_i = mu N_i r_i): backbone T(theta) = sum min(k_i theta, t_i); under a torque
    amplitude T0 the Masing loop has the peak theta0 = T^-1(T0) and dissipates
    W = sum_i 4 t_i max(0, theta0 - t_i / k_i)."""
    xy = m.mesh.nodes[m.contact_nodes][:, :2] - 5.0
    r = np.hypot(*xy.T)
    k = m.contact_stiffness * r**2
    t = m.friction_limit * r
    theta0 = brentq(lambda th: float(np.sum(np.minimum(k * th, t))) - torque, 0.0,
                    float(np.max(t / np.where(k > 0, k, 1.0))) * 2)
    return float(np.sum(4 * t * np.maximum(0.0, theta0 - t / np.where(k > 0, k, 1.0)))), theta0


def test_rigid_block_in_torsion_matches_the_closed_form() -> None:
    """A very stiff block (E 1e9 MPa, nu 0: N_i are exactly the area shares of F_N) turned by a
    couple of two loads on its end faces: its nodes are Jenkins elements in parallel on a rigid
    body. W and the peak rotation from the closed form (to the stiffness ratio and the
    trapezoidal loop of 80 increments)."""
    mesh = _block(4, 4, 1)
    m = build_mesh_model(mesh, rigid_base(contact_set="bottom", clamp_set="top",
                                          normal_force=1000.0, modulus=1e9, poisson_ratio=0.0,
                                          friction=0.5, stick_slope=1e3))
    assert m.normal_force == pytest.approx(1000.0 * m.contact_area / 100.0, rel=1e-9)
    f0 = 150.0  # torque 10 F0 = 1500 N mm: first slip at 1.2e3, full slip at 1.9e3 N mm
    loads = [MeshLoad("right", (0.0, 1.0, 0.0), f0), MeshLoad("left", (0.0, -1.0, 0.0), f0)]
    r = solve_mesh(m, loads, SineCycles(increments=80, tol=1e-6))
    w, theta0 = _torsion_closed_form(m, 10.0 * f0)
    assert w > 0
    assert r.loads[0].peak_displacement == pytest.approx(5.0 * theta0, rel=1e-4)
    assert r.dissipated_energy == pytest.approx(w, rel=2e-3)
    assert r.settled and not r.gross_sliding


def test_rotating_load_ratchets_then_settles() -> None:
    """Two loads at 90 degrees (the box's planar path: along the bar at the tip, across it at
    the centre): the work per cycle changes from the first to the second cycle and then
    settles to the tolerance."""
    m = _box_model()
    loads = [MeshLoad("tip", (1.0, 0.0, 0.0), 150.0),
             MeshLoad("centre", (0.0, 1.0, 0.0), 150.0, 90.0)]
    r = solve_mesh(m, loads, SineCycles(increments=24, tol=1e-3, max_cycles=12))
    w = r.work_per_cycle
    assert r.settled and r.cycles >= 3
    assert abs(w[1] - w[0]) > 1e-3 * w[1]
    assert abs(w[-1] - w[-2]) <= 1e-3 * w[-1]
    assert r.dissipated_energy == pytest.approx(w[-1], rel=1e-12)
    assert r.dissipated_energy == pytest.approx(sum(ld.work for ld in r.loads), rel=1e-12)


def test_a_rotated_mesh_gives_the_same_answer() -> None:
    """The block stood on its side (contact normal along -x): the solver works in the contact
    plane's frame, so W and the displacement are those of the upright block."""
    mesh = _block(3, 2, 1)
    rot = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])  # z -> -x
    turned = HexMesh(mesh.nodes @ rot.T, mesh.elements, mesh.node_sets, source="turned")
    kw = {"contact_set": "bottom", "clamp_set": "top", "normal_force": 1000.0,
          "modulus": 70000.0, "poisson_ratio": 0.3, "friction": 0.3}
    a = solve_mesh(build_mesh_model(mesh, rigid_base(**kw)),
                   [MeshLoad("right", (1.0, 0.0, 0.0), 200.0)],
                   SineCycles(increments=16), record=True)
    b = solve_mesh(build_mesh_model(turned, rigid_base(**kw)),
                   [MeshLoad("right", tuple(rot @ (1.0, 0.0, 0.0)), 200.0)],  # type: ignore
                   SineCycles(increments=16), record=True)
    assert a.dissipated_energy > 0
    assert b.dissipated_energy == pytest.approx(a.dissipated_energy, rel=1e-8)
    assert b.peak_displacement == pytest.approx(a.peak_displacement, rel=1e-8)
    assert a.displacement is not None and b.displacement is not None
    scale = float(np.max(np.abs(a.displacement)))
    assert np.max(np.abs(b.displacement - a.displacement @ rot.T)) <= 1e-8 * scale


def _cantilever(nx: int, ny: int, nz: int) -> HexMesh:
    """The issue's cantilever (clamped 50.8, overhang 101.6, 25.4 x 6.35 mm) as a block with
    the sets contact and clamp under and over the clamped length, and the end face tip."""
    b = grid_mesh(np.linspace(0.0, 152.4, nx + 1), np.linspace(0.0, 25.4, ny + 1),
                  np.linspace(0.0, 6.35, nz + 1))
    x, z = b.nodes[:, 0], b.nodes[:, 2]
    under = x <= 50.8 + 1e-9
    sets = {"contact": np.flatnonzero(under & (z <= 1e-9)),
            "clamp": np.flatnonzero(under & (z >= 6.35 - 1e-9)),
            "tip": np.flatnonzero(x >= 152.4 - 1e-9)}
    return HexMesh(b.nodes, b.elements, sets, source="cantilever")


@pytest.mark.parametrize("normal", ["fixed", "penalty"])
def test_the_condensed_body_gives_the_full_answer(normal: str) -> None:
    """The loading on the body condensed onto its contact dofs equals the loading on every
    dof (to the Newton tolerance: measured 1e-11 to 6e-10), W, the loops and the recorded
    displacement field; an axial and a lateral end load at 90 degrees."""
    kw = {"contact_set": "contact", "clamp_set": "clamp", "normal_force": 2000.0,
          "modulus": 70000.0, "poisson_ratio": 0.33, "friction": 0.5,
          "normal_contact": normal, "normal_slope": 1e6}
    mesh = _cantilever(12, 3, 1)
    loads = [MeshLoad("tip", (1.0, 0.0, 0.0), 500.0), MeshLoad("tip", (0.0, 1.0, 0.0), 60.0,
                                                                90.0)]
    runs = []
    for condensed in (False, True):
        m = build_mesh_model(mesh, rigid_base(**kw), condensed=condensed)  # type: ignore[arg-type]
        assert (m.reduced is not None) == condensed
        runs.append(solve_mesh(m, loads, SineCycles(increments=16), record=True))
    full, cond = runs
    assert full.dissipated_energy > 0
    assert cond.dissipated_energy == pytest.approx(full.dissipated_energy, rel=1e-8)
    for a, b in zip(full.loads, cond.loads, strict=True):
        assert b.displacement == pytest.approx(a.displacement, rel=1e-7, abs=1e-9 * np.max(
            np.abs(a.displacement)))
    assert full.displacement is not None and cond.displacement is not None
    scale = float(np.max(np.abs(full.displacement)))
    assert np.max(np.abs(cond.displacement - full.displacement)) <= 1e-8 * scale


def test_a_renumbered_mesh_gives_the_same_answer() -> None:
    """The cantilever with its nodes shuffled (a mesher's numbering): reverse Cuthill-McKee
    restores a narrow band, and W, the displacements and every contact node's pressure
    (reported under the file's node numbers) are those of the ordered mesh."""
    kw = {"contact_set": "contact", "clamp_set": "clamp", "normal_force": 2000.0,
          "modulus": 70000.0, "poisson_ratio": 0.33, "friction": 0.5,
          "normal_contact": "penalty", "normal_slope": 1e6}
    mesh = _cantilever(12, 3, 1)
    perm = np.random.default_rng(1).permutation(len(mesh.nodes))  # new node k = old perm[k]
    inv = np.argsort(perm)
    shuffled = HexMesh(mesh.nodes[perm], inv[mesh.elements],
                       {k: inv[v] for k, v in mesh.node_sets.items()}, source="shuffled")
    loads = [MeshLoad("tip", (1.0, 0.0, 0.0), 500.0)]
    a_model = build_mesh_model(mesh, rigid_base(**kw), condensed=False)  # type: ignore[arg-type]
    b_model = build_mesh_model(shuffled, rigid_base(**kw),  # type: ignore[arg-type]
                               condensed=False)
    assert not np.array_equal(b_model.order, np.sort(b_model.order))  # renumbered
    a = solve_mesh(a_model, loads, SineCycles(increments=16))
    b = solve_mesh(b_model, loads, SineCycles(increments=16))
    assert a.dissipated_energy > 0
    assert b.dissipated_energy == pytest.approx(a.dissipated_energy, rel=1e-8)
    assert b.peak_displacement == pytest.approx(a.peak_displacement, rel=1e-8)
    where = {int(n): i for i, n in enumerate(b.contact.nodes)}
    back = [where[int(inv[n])] for n in a.contact.nodes]
    assert b.pressure[:, back] == pytest.approx(a.pressure, rel=1e-6, abs=1e-9)


def test_sparse_and_banded_factorisations_agree() -> None:
    """SuperLU (the wide-band meshes) and the banded Cholesky give the same loading, and the
    condensation's Schur complement is the same through either."""
    kw = {"contact_set": "contact", "clamp_set": "clamp", "normal_force": 2000.0,
          "modulus": 70000.0, "poisson_ratio": 0.33, "friction": 0.5}
    mesh = _cantilever(12, 3, 1)
    loads = [MeshLoad("tip", (1.0, 0.0, 0.0), 500.0)]
    w = []
    for solver in ("banded", "splu"):
        m = build_mesh_model(mesh, rigid_base(**kw),  # type: ignore[arg-type]
                             linear_solver=solver, condensed=False)
        assert m.backend.name == solver
        w.append(solve_mesh(m, loads, SineCycles(increments=16)).dissipated_energy)
    assert w[0] > 0 and w[1] == pytest.approx(w[0], rel=1e-9)
    band, lu = (condense(m.stiffness, m.contact_dofs, m.normal, m.clamp_load, m.u0, limit)
                for limit in (10**6, 0))
    assert band.solver.band is not None and lu.solver.lu is not None
    scale = float(np.max(np.abs(band.stiffness)))
    assert np.max(np.abs(lu.stiffness - band.stiffness)) <= 1e-10 * scale
    assert lu.clamp_load == pytest.approx(band.clamp_load, rel=1e-9, abs=1e-12)


def _kw(**over: object) -> dict[str, object]:
    kw: dict[str, object] = {"contact_set": "bottom", "clamp_set": "top",
                             "normal_force": 1000.0, "modulus": 70000.0,
                             "poisson_ratio": 0.3, "friction": 0.3}
    kw.update(over)
    return kw


def test_bad_meshes_and_sets_are_refused_in_one_line() -> None:
    mesh = _block(2, 2, 2)
    cases = {
        "no set named 'botom'": (mesh, _kw(contact_set="botom")),
        "holds no element face": (HexMesh(mesh.nodes, mesh.elements,
                                          {**mesh.node_sets, "one": [0]}, source="block"),
                                  _kw(contact_set="one")),
        "is not on the boundary": (HexMesh(mesh.nodes, mesh.elements,
                                           {**mesh.node_sets, "mid": np.flatnonzero(
                                               np.isclose(mesh.nodes[:, 2], 1.0))},
                                           source="block"), _kw(contact_set="mid")),
        "is not flat": (HexMesh(mesh.nodes, mesh.elements, {
            **mesh.node_sets, "corner": np.flatnonzero(
                (mesh.nodes[:, 2] <= 1e-9) | (mesh.nodes[:, 0] <= 1e-9))}, source="block"),
            _kw(contact_set="corner")),
        "poisson_ratio must be in (-1, 0.5)": (mesh, _kw(poisson_ratio=0.5)),
        "unknown normal contact": (mesh, _kw(normal_contact="soft")),
    }
    for expected, (m, kw) in cases.items():
        with pytest.raises(ParameterError, match=expected.replace("(", r"\(").replace(
                ")", r"\)")) as err:
            build_mesh_model(m, rigid_base(**kw))  # type: ignore[arg-type]
        assert "\n" not in str(err.value)


def test_loose_parts_and_degenerate_meshes_are_refused() -> None:
    mesh = _block(2, 1, 1)
    far = mesh.nodes + np.array([0.0, 0.0, 50.0])
    two = HexMesh(np.vstack([mesh.nodes, far]),
                  np.vstack([mesh.elements, mesh.elements + len(mesh.nodes)]),
                  mesh.node_sets, source="two.inp")
    with pytest.raises(ParameterError, match="2 elements are not connected to the contact"):
        build_mesh_model(two, rigid_base(**_kw()))  # type: ignore[arg-type]
    flipped = mesh.elements.copy()
    flipped[1] = flipped[1][[4, 5, 6, 7, 0, 1, 2, 3]]  # top and bottom swapped: inside out
    bad = HexMesh(mesh.nodes, flipped, mesh.node_sets, source="bad.inp")
    with pytest.raises(ParameterError, match=r"bad\.inp: element 2 \(1-based\) has a "
                                             "non-positive Jacobian"):
        build_mesh_model(bad, rigid_base(**_kw()))  # type: ignore[arg-type]
    # 20-node meshes are built (fe.builtin.hex20), and a degenerate one refused the same way
    hex20 = HexMesh(np.zeros((20, 3)), np.arange(20)[None, :], {}, source="q.inp")
    with pytest.raises(ParameterError, match=r"q\.inp: element 1 \(1-based\) has a "
                                             "non-positive Jacobian"):
        build_mesh_model(hex20, rigid_base(**_kw()))  # type: ignore[arg-type]


def test_macroslip_and_bad_histories_are_refused() -> None:
    m = build_mesh_model(_block(2, 2, 1), rigid_base(**_kw()))  # type: ignore[arg-type]
    with pytest.raises(MacroslipError, match="reaches 300 N >= mu F_N = 300 N"):
        solve_mesh(m, [MeshLoad("right", (1.0, 0.0, 0.0), 300.0)])
    with pytest.raises(ParameterError, match="increments must be a multiple of 4"):
        SineCycles(increments=10)
    with pytest.raises(ParameterError, match="load factors have 1 columns for 2 loads"):
        solve_mesh(m, [MeshLoad("right", (1.0, 0.0, 0.0), 10.0)] * 2,
                   LoadFactors(np.zeros((4, 1))))
