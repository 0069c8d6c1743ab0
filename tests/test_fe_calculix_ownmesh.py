"""CalculiX on the user's own mesh (issue 22, item 4): the deck's cards as exact strings, the
box run through the mesh deck (issue 32, item 4), the 8-node box against the built-in
solver's, and the cantilever with its overhang (runs, converges, dissipates a plausible W)."""

from __future__ import annotations

import re
import shutil
from dataclasses import replace

import numpy as np
import pytest

from microslip import preset
from microslip.errors import ParameterError
from microslip.fe import ResultsError, SolverNotFoundError, run_case, run_loop
from microslip.fe.assembly import Support
from microslip.fe.calculix.boxrun import box20_mesh
from microslip.fe.calculix.case import FECase
from microslip.fe.calculix.mesh import MeshSpec
from microslip.fe.calculix.meshdeck import (
    base_slab,
    build_mesh_deck,
    dsload_card,
    element_surface_card,
    load_plan,
)
from microslip.fe.calculix.meshhistory import load_factors, load_history, load_times
from microslip.fe.calculix.meshrun import run_mesh_calculix
from microslip.fe.clamp import MeshClamp
from microslip.fe.examples import box_hexmesh, grid_mesh
from microslip.fe.hexmesh import HexMesh
from microslip.fe.meshload import MeshLoad

P = preset("table1")
NO_CCX = "CalculiX (ccx) is not on PATH; run `bash scripts/setup.sh`"


def _grid(length: float, width: float, thickness: float, nx: int, ny: int, nz: int,
          x: np.ndarray | None = None) -> HexMesh:
    """A box of hexahedra numbered slice by slice along x (corners in CalculiX order), with
    the node sets bottom, top and end (x = length)."""
    b = grid_mesh(np.linspace(0.0, length, nx + 1) if x is None else x,
                  np.linspace(0.0, width, ny + 1), np.linspace(0.0, thickness, nz + 1))
    xyz = b.nodes
    return HexMesh(xyz, b.elements, {"bottom": np.flatnonzero(xyz[:, 2] == 0.0),
                                     "top": np.flatnonzero(xyz[:, 2] == thickness),
                                     "end": np.flatnonzero(xyz[:, 0] == length)},
                   source="grid")


def one_element() -> HexMesh:
    b = _grid(2.0, 1.0, 1.0, 1, 1, 1)
    return HexMesh(b.nodes, b.elements, dict(b.node_sets), source="one")


def box8(nx: int, ny: int, nz: int) -> HexMesh:
    """The built-in solver's 8-node box (box_hexmesh numbers its corners in CalculiX order)."""
    b = box_hexmesh(P, (nx, ny, nz))
    return HexMesh(b.nodes, b.elements, {k: b.node_sets[k] for k in ("contact", "clamp", "tip")},
                   source="box8")


TABLE1_CLAMP = MeshClamp("contact", "clamp", normal_force=P.normal_force, friction=P.friction,
                         stick_slope=1e4, normal_contact="penalty", normal_slope=1e5,
                         modulus=P.modulus, poisson_ratio=P.poisson_ratio)
TABLE1 = dict(increments_per_cycle=40, cycles=1)
ONE = MeshClamp("bottom", "top", normal_force=10.0, friction=0.5, stick_slope=1e4,
                normal_contact="penalty", normal_slope=1e5, modulus=1000.0, poisson_ratio=0.25)
TIP = [MeshLoad("tip", (1.0, 0.0, 0.0), 267.0)]


def block(deck: str, header: str) -> str:
    """A keyword card of a deck: its header line and data lines, up to the next card."""
    i = deck.index(header + "\n")
    m = re.compile(r"^\*", re.M).search(deck, i + len(header) + 1)
    return deck[i:m.start() if m else len(deck)]


# --- cards ------------------------------------------------------------------------------------

def test_element_surface_card_names_each_face_one_based():
    assert element_surface_card("SC", [[0, 0], [4, 5]]) == (
        "*SURFACE, NAME=SC, TYPE=ELEMENT\n1, S1\n5, S6\n")
    with pytest.raises(ParameterError, match=re.escape("face 0..5")):
        element_surface_card("SC", [[0, 6]])


def test_dsload_card_is_a_pressure_on_a_surface():
    assert dsload_card("SCLAMP", 0.0689751379503) == "*DSLOAD\nSCLAMP, P, 0.0689751379503\n"
    with pytest.raises(ParameterError, match="pressure"):
        dsload_card("SCLAMP", 0.0)


def test_one_element_deck_exactly():
    deck = build_mesh_deck(one_element(), ONE, loads=[MeshLoad("end", (-1, 0, 0), 2.0, 90.0)],
                           increments_per_cycle=4, cycles=1)
    assert deck.startswith("*HEADING\nmicroslip own mesh one: 1 C3D8I, 2 x 1 x 1 mm, on a "
                           "rigid base\n*NODE\n1, 0, 0, 0\n2, 0, 0, 1\n")
    base_nodes = "".join(f"{9 + i}, {x:g}, {y:g}, {z:g}\n" for i, (z, y, x) in enumerate(
        (z, y, x) for z in (-1, 0) for y in (-1, 0, 1, 2) for x in (-2, 0, 2, 4)))
    tail = (
        "*ELEMENT, TYPE=C3D8I, ELSET=BODY\n1, 1, 5, 7, 3, 2, 6, 8, 4\n"
        "*ELEMENT, TYPE=C3D8, ELSET=BASE\n2, 9, 10, 14, 13, 25, 26, 30, 29\n")
    assert base_nodes + tail in deck
    assert deck.endswith(
        "*NSET, NSET=NBASE\n"
        "9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24\n"
        "25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40\n"
        "*NSET, NSET=NLOADED\n5, 6, 7, 8\n"
        "*SURFACE, NAME=SCONTACT, TYPE=ELEMENT\n1, S1\n"
        "*SURFACE, NAME=SCLAMP, TYPE=ELEMENT\n1, S2\n"
        "*SURFACE, NAME=SBASE, TYPE=ELEMENT\n"
        + "".join(f"{e}, S2\n" for e in range(2, 11)) +
        "*MATERIAL, NAME=BODY\n*ELASTIC\n1000, 0.25\n"
        "*SOLID SECTION, ELSET=BODY, MATERIAL=BODY\n*SOLID SECTION, ELSET=BASE, MATERIAL=BODY\n"
        "*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n100000\n"
        "*FRICTION\n0.5, 10000\n"
        "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSCONTACT, SBASE\n"
        "*BOUNDARY\nNBASE, 1, 3, 0\n"
        "*AMPLITUDE, NAME=L1\n"
        "0, 0, 0.25, 1.22464679915e-16, 0.5, -1, 0.75, -2.44929359829e-16\n"
        "1, 1, 1.25, 1.22464679915e-16\n"
        "** step 1: clamping pressure F_N / A = 10 N / 2 mm^2 on top\n"
        "*STEP, INC=100\n*STATIC\n1, 1\n*DSLOAD\nSCLAMP, P, 5\n"
        "*NODE PRINT, NSET=NLOADED\nU\n*NODE FILE\nU\n*CONTACT FILE\nCDIS, CSTR\n*END STEP\n"
        "** step 2: end 2 N along (-1, 0, 0) at 90 deg; 1 cycle(s) after a quarter-cycle "
        "start, 4 increments per cycle\n"
        "*STEP, INC=15\n*STATIC, DIRECT\n0.25, 1.25\n"
        "*CONTROLS, PARAMETERS=TIME INCREMENTATION\n, , , 26\n"
        "*CLOAD, AMPLITUDE=L1\n5, 1, -0.5\n6, 1, -0.5\n7, 1, -0.5\n8, 1, -0.5\n"
        "*NODE PRINT, NSET=NLOADED\nU\n*NODE FILE\nU\n*CONTACT FILE\nCDIS, CSTR\n*END STEP\n")


def test_load_step_is_the_paper_sine_for_one_load_at_phase_zero():
    case = FECase("tip", P, 267.0, mesh=MeshSpec(2, 2, 1))
    t = load_times(40, 1)
    np.testing.assert_array_equal(t * 1.0, case.times)
    np.testing.assert_allclose(267.0 * load_factors(TIP[0], t), case.force(case.times),
                               rtol=0.0, atol=1e-12)


def test_several_loads_ramp_straight_then_cycle():
    a, b = MeshLoad("s", (1, 0, 0), 2.0, 0.0), MeshLoad("s", (0, 1, 0), 1.0, 60.0)
    t = load_times(8, 2)
    assert t[-1] == 2.25 and t.size == 19
    fa, fb = load_factors(a, t), load_factors(b, t)
    ramp = t <= 0.25
    np.testing.assert_allclose(fb[ramp] * np.cos(0.0), fa[ramp] * np.cos(np.pi / 3), atol=1e-15)
    np.testing.assert_allclose(fb[~ramp], np.sin(2 * np.pi * t[~ramp] + np.pi / 3), atol=1e-15)
    with pytest.raises(ParameterError, match="multiple of 4"):
        load_times(10, 1)
    with pytest.raises(ParameterError, match="cycles"):
        load_times(8, 0)


def test_ramp_start_is_the_builtin_solvers_sine_cycles():
    """``ramp``: cycles from t = 0; a quarter cycle of straight ramp before it only when a
    phase makes the loads non-zero at t = 0 (the built-in own-mesh solver's SineCycles)."""
    a, b = MeshLoad("s", (1, 0, 0), 2.0, 0.0), MeshLoad("s", (0, 1, 0), 1.0, 60.0)
    h = load_history([a], 8, 2, "ramp")
    np.testing.assert_array_equal(h.time, np.arange(17) / 8)
    np.testing.assert_array_equal(h.factors[:, 0], np.r_[0.0, a.force(h.time[1:]) / 2.0])
    assert (h.first_cycle, h.cycles) == (0, 2)
    h = load_history([a, b], 8, 2, "ramp")
    assert h.time[0] == -0.25 and h.time.size == 19 and (h.first_cycle, h.cycles) == (2, 2)
    np.testing.assert_array_equal(h.factors[:2, 1], [0.0, 0.5 * np.sin(np.pi / 3)])
    np.testing.assert_array_equal(h.factors[2:, 1], b.force(h.time[2:]))
    np.testing.assert_array_equal(h.step_time, np.arange(19) / 8)
    q = load_history([a, b], 8, 2)  # quarter: the paper's start
    assert q.time[0] == 0.0 and q.first_cycle == 2 and q.cycles == 2
    with pytest.raises(ParameterError, match="startup must be one of quarter, ramp"):
        load_history([a], 8, 2, "jump")


def _applied_forces(deck: str, n_nodes: int, times: np.ndarray) -> np.ndarray:
    """Nodal forces (time, node, dof) of the deck's *CLOAD cards and amplitudes."""
    amps = {}
    for m in re.finditer(r"^\*AMPLITUDE, NAME=(\w+)\n((?:[^*].*\n)+)", deck, re.M):
        v = np.array([float(x) for x in m.group(2).replace("\n", ",").split(",") if x.strip()])
        amps[m.group(1)] = np.interp(times, v[0::2], v[1::2])
    f = np.zeros((times.size, n_nodes, 3))
    seen = set()
    for m in re.finditer(r"^\*CLOAD, AMPLITUDE=(\w+)\n((?:[^*].*\n)+)", deck, re.M):
        for line in m.group(2).splitlines():
            node, dof, val = line.split(",")
            key = (int(node), int(dof))
            assert key not in seen, "a node and dof loaded twice: CalculiX keeps only the last"
            seen.add(key)
            f[:, int(node) - 1, int(dof) - 1] += float(val) * amps[m.group(1)]
    return f


def test_loads_sharing_nodes_and_dofs_add_up():
    mesh = one_element()
    loads = [MeshLoad("end", (1, 1, 0), 3.0, 0.0), MeshLoad("end", (1, -1, 0), 2.0, 90.0),
             MeshLoad("end", (0, 0, 1), 1.0, 30.0)]
    deck = build_mesh_deck(mesh, ONE, loads=loads, increments_per_cycle=8, cycles=2)
    t = load_times(8, 2)
    got = _applied_forces(deck, 8, t)
    plan = load_plan(mesh, loads)
    want = np.zeros_like(got)
    for ld, nodes, w in zip(plan.loads, plan.nodes, plan.shares, strict=True):
        want[:, nodes, :] += (ld.amplitude * load_factors(ld, t))[:, None, None] * (
            w[None, :, None] * np.asarray(ld.direction)[None, None, :])
    np.testing.assert_allclose(got, want, atol=1e-11)
    assert "AMPLITUDE=M1" in deck and "AMPLITUDE=L3" in deck
    ramped = build_mesh_deck(mesh, ONE, loads=loads, increments_per_cycle=8, cycles=2,
                             startup="ramp")
    h = load_history(loads, 8, 2, "ramp")
    got = _applied_forces(ramped, 8, h.step_time)
    want = np.zeros_like(got)
    for j, (ld, nodes, w) in enumerate(zip(plan.loads, plan.nodes, plan.shares, strict=True)):
        want[:, nodes, :] += (ld.amplitude * h.factors[:, j])[:, None, None] * (
            w[None, :, None] * np.asarray(ld.direction)[None, None, :])
    np.testing.assert_allclose(got, want, atol=1e-11)
    assert "*STATIC, DIRECT\n0.125, 2.25\n" in ramped
    assert "after a straight ramp if needed" in ramped


def test_conjugate_displacement_is_the_share_weighted_mean_along_the_load():
    mesh = one_element()
    plan = load_plan(mesh, [MeshLoad("end", (0, 3, 4), 1.0)])
    u = np.zeros((1, plan.loaded.size, 3))
    u[0, :, 1], u[0, :, 2] = 1.0, 2.0
    assert plan.conjugate(u)[0, 0] == pytest.approx(0.6 * 1.0 + 0.8 * 2.0)


# --- bad input ----------------------------------------------------------------------------------

@pytest.mark.parametrize(("change", "message"), [
    ({"normal_contact": "fixed"}, "normal_contact must be 'penalty' for CalculiX, got 'fixed'"),
    ({"contact_set": "contakt"}, "no set named 'contakt'"),
    ({"clamp_set": "tip"}, ""),
    ({"increments_per_cycle": 42}, "multiple of 4"),
    ({"supports": (Support("nope", "x"),)}, "no set named 'nope' (support)"),
    ({"loads": []}, "at least one load"),
])
def test_bad_input_is_one_line(change, message):
    hm = box8(4, 1, 1)
    clamp = {k: v for k, v in change.items() if k in ("normal_contact", "contact_set",
                                                          "clamp_set")}
    assembly = replace(TABLE1_CLAMP, **clamp).assembly
    if "supports" in change:
        assembly = replace(assembly, supports=change["supports"])
    args = {**TABLE1, "loads": TIP, **{k: v for k, v in change.items()
                                       if k in ("increments_per_cycle", "loads")}}
    if change == {"clamp_set": "tip"}:  # a legal set: the deck is written
        assert build_mesh_deck(hm, assembly, **args).endswith("*END STEP\n")
        return
    with pytest.raises(ParameterError, match=re.escape(message)):
        build_mesh_deck(hm, assembly, **args)


def test_a_contact_set_that_is_not_flat_is_refused():
    b = _grid(4.0, 1.0, 1.0, 2, 1, 1)
    nodes = b.nodes.copy()
    nodes[b.node_sets["bottom"][0], 2] = -0.1
    hm = HexMesh(nodes, b.elements, {"bottom": b.node_sets["bottom"]}, source="bent.inp")
    with pytest.raises(ParameterError, match=re.escape("bent.inp: set 'bottom' is not flat")):
        base_slab(hm, hm.faces("bottom"), "bottom")


def test_a_contact_set_inside_the_body_is_refused():
    b = _grid(4.0, 1.0, 2.0, 2, 1, 2)
    hm = HexMesh(b.nodes, b.elements, {"mid": np.flatnonzero(b.nodes[:, 2] == 1.0)},
                 source="m.inp")
    both = hm.faces("mid")  # each inner face twice, once per element: opposite normals
    with pytest.raises(ParameterError, match="set 'mid': the contact faces have no area"):
        base_slab(hm, both, "mid")
    lower = both[both[:, 1] == 1]  # the S2 faces: upper faces of the lower layer
    assert lower.shape == (2, 2)
    with pytest.raises(ParameterError, match="body reaches below the contact plane"):
        base_slab(hm, lower, "mid")


def test_a_load_on_a_set_without_faces_is_refused():
    hm = box8(2, 1, 1)
    lone = HexMesh(hm.nodes, hm.elements, {**hm.node_sets, "edge": [0, 1]}, source="m.inp")
    with pytest.raises(ParameterError, match="set 'edge' holds no element face"):
        load_plan(lone, [MeshLoad("edge", (1, 0, 0), 1.0)])


def test_a_run_without_results_is_a_results_error(tmp_path):
    fake = tmp_path / "fakeccx"
    fake.write_text("#!/bin/sh\nexit 0\n")
    fake.chmod(0o755)
    with pytest.raises(ResultsError, match=r"job\.dat is missing") as err:
        run_mesh_calculix(one_element(), ONE, loads=[MeshLoad("end", (1, 0, 0), 2.0)],
                          increments_per_cycle=4, job_dir=tmp_path / "job",
                          executable=str(fake))
    assert err.value.job_dir == tmp_path / "job"
    assert (tmp_path / "job" / "job.inp").is_file()


def test_no_solver_is_one_line_before_anything_is_written(tmp_path):
    with pytest.raises(SolverNotFoundError, match="not on PATH"):
        run_mesh_calculix(one_element(), ONE, loads=[MeshLoad("end", (1, 0, 0), 2.0)],
                          increments_per_cycle=4, job_dir=tmp_path / "job",
                          executable="no-such-ccx")
    assert not (tmp_path / "job").exists()


# --- runs (ccx) ---------------------------------------------------------------------------------

TINY = MeshSpec(8, 2, 1)


@pytest.fixture(scope="module")
def box_run(tmp_path_factory):
    """The box's tip run on 8 x 2 x 1 C3D20R (about 10 s)."""
    return run_case(FECase("tip", P, 267.0, mesh=TINY), tmp_path_factory.mktemp("box"))


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_the_box_runs_on_the_mesh_deck(box_run):
    """run_case writes the box with the mesh deck (the symmetry plane as a support) and
    converts its result: the box's DOF count, pressure and shear at every state, the loop from
    the first force peak."""
    assert box_run.converged and box_run.message == "converged"
    assert box_run.dof == TINY.dof == 452
    assert "*DSLOAD\nSCLAMP, P, 0.0689751379503\n" in (box_run.job_dir / "job.inp").read_text()
    d = box_run.details
    m = box_run.contact.nodes.size
    assert d.pressure.shape == (51, m) and d.shear.shape == (51, m, 2)
    assert d.pressure[0].mean() == pytest.approx(445.0 / (254.0 * 25.4), rel=0.05)
    assert box_run.loop.force[0] == pytest.approx(267.0)
    assert box_run.loop.peak_displacement > 0 and box_run.damping.dissipated_energy > 0


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_without_the_symmetry_plane_the_box_loop_barely_moves(box_run, tmp_path):
    """Friction alone holds the lateral motion (the built-in solver's set-up): on 8 x 2 x 1
    W rises by 0.5 % (0.16 % on 20 x 2 x 1), the peak moves by 2e-5 (docs/validation.md)."""
    hm = box20_mesh(P, TINY)
    r = run_mesh_calculix(hm, TABLE1_CLAMP, loads=TIP, job_dir=tmp_path, **TABLE1)
    assert r.converged
    w0, d0 = box_run.damping.dissipated_energy, box_run.loop.peak_displacement
    assert 0.0 < r.dissipated_energy / w0 - 1.0 < 0.01
    assert r.peak_displacement[0] == pytest.approx(d0, rel=1e-4)


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_8_node_box_agrees_with_the_builtin_solver(tmp_path):
    """C3D8I on the built-in solver's box 8 x 2 x 1 against the built-in solver with the
    same penalty normal contact: W +0.8 %, peak -0.06 % (nodal against face-to-face friction;
    on 24 x 4 x 1 -0.02 % and -0.006 %, docs/validation.md)."""
    r = run_mesh_calculix(box8(8, 2, 1), TABLE1_CLAMP, loads=TIP, job_dir=tmp_path, **TABLE1)
    b, _ = run_loop("tip", solver="builtin", mesh="8x2x1", normal_contact="penalty",
                    normal_slope=1e5)
    assert r.converged and r.element == "C3D8I" and r.dof == 3 * 9 * 3 * 2
    assert r.dissipated_energy == pytest.approx(b.damping.dissipated_energy, rel=0.02)
    assert r.peak_displacement[0] == pytest.approx(b.loop.peak_displacement, rel=2e-3)


def cantilever(clamped: int, overhang: int, ny: int, nz: int) -> HexMesh:
    """The issue's cantilever: clamped length 50.8, overhang 101.6, width 25.4, thickness
    6.35 mm; contact and clamp on the clamped length only, load on the free end."""
    x = np.concatenate([np.linspace(0.0, 50.8, clamped + 1),
                        np.linspace(50.8, 152.4, overhang + 1)[1:]])
    b = _grid(152.4, 25.4, 6.35, clamped + overhang, ny, nz, x)
    bottom, top = b.node_sets["bottom"], b.node_sets["top"]
    inside = b.nodes[:, 0] <= 50.8 + 1e-9
    return HexMesh(b.nodes, b.elements, {"contact": bottom[inside[bottom]],
                                         "clamp": top[inside[top]], "end": b.node_sets["end"]},
                   source="cantilever")


CANTILEVER_CLAMP = MeshClamp("contact", "clamp", normal_force=2000.0, friction=0.5,
                             stick_slope=1e4, normal_contact="penalty", normal_slope=1e6,
                             modulus=70000.0, poisson_ratio=0.33)
CANTILEVER = dict(increments_per_cycle=40)


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_cantilever_axial_end_load_dissipates_a_plausible_energy(tmp_path):
    """4 + 8 x 2 x 1 C3D8I (about 3 s): converges; 0 < W < 4 F0 d0 (the loop inside its
    bounding box); W within 25 % of the 1-D tip model on the clamped length (measured -13 % on
    this coarse mesh), d0 within 2 % of it plus the overhang's stretch (+0.7 %)."""
    f0 = 600.0
    r = run_mesh_calculix(cantilever(4, 8, 2, 1), CANTILEVER_CLAMP,
                          loads=[MeshLoad("end", (1, 0, 0), f0)],
                          job_dir=tmp_path, cycles=1, **CANTILEVER)
    ea, q = 70000.0 * 25.4 * 6.35, 0.5 * 2000.0 / 50.8
    d0 = r.peak_displacement[0]
    assert r.converged and r.message == "converged"
    assert 0.0 < r.dissipated_energy < 4.0 * f0 * d0
    assert r.dissipated_energy == pytest.approx(2 * f0**3 / (3 * ea * q), rel=0.25)
    assert d0 == pytest.approx(f0**2 / (2 * ea * q) + f0 * 101.6 / ea, rel=0.02)
    slipping = r.contact.status[r.last_cycle] == 2
    assert slipping.any() and not slipping.all(axis=1).any() and r.warnings() == []


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_cantilever_small_load_sticks_and_dissipates_nothing(tmp_path):
    """20 N: the tractions stay below mu p everywhere, so W = 0 exactly, with the reason."""
    r = run_mesh_calculix(cantilever(4, 8, 2, 1), CANTILEVER_CLAMP,
                          loads=[MeshLoad("end", (1, 0, 0), 20.0)],
                          job_dir=tmp_path, cycles=1, **CANTILEVER)
    assert r.converged and r.dissipated_energy == 0.0 and r.work.tolist() == [0.0]
    assert "stick throughout" in r.message and r.peak_displacement[0] > 0.0


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_cantilever_axial_and_lateral_at_90_degrees(tmp_path):
    """Two loads on the end face, 90 degrees apart, two cycles after the built-in solver's
    start-up ramp: both loops are read, each dissipates, and W is their sum."""
    loads = [MeshLoad("end", (1, 0, 0), 600.0), MeshLoad("end", (0, 1, 0), 50.0, 90.0)]
    r = run_mesh_calculix(cantilever(4, 8, 2, 1), CANTILEVER_CLAMP, loads=loads,
                          job_dir=tmp_path, cycles=2,
                          startup="ramp", **CANTILEVER)
    assert r.converged and r.cycles == 2 and (r.time[0], r.time[-1]) == (-0.25, 2.0)
    np.testing.assert_allclose(r.force[10:, 1], loads[1].force(r.time[10:]), atol=1e-12)
    assert r.force.shape == r.displacement.shape == (91, 2)
    assert np.all(r.work > 0.0)
    assert r.dissipated_energy == pytest.approx(float(r.work.sum()), rel=1e-12)
    assert r.cycle_work.shape == (2,) and r.cycle_work[-1] == pytest.approx(r.dissipated_energy)
    assert r.cycle_work[0] != r.cycle_work[1]  # the first cycle still ratchets a little
    summary = r.summary()
    assert summary["loads"][1]["work_Nmm"] == pytest.approx(r.work[1])
    assert summary["peak_displacement_mm"] == r.peak_displacement[0]


# --- contact formulations (issue 29) -------------------------------------------------------------

def test_node_to_surface_deck_differs_only_in_its_contact_cards():
    """node-to-surface: TYPE=NODE TO SURFACE and sigma_inf = 1e-5 of the mean contact pressure
    F_N / A (10 N on 2 mm^2: 5 MPa -> 5e-5 MPa); everything else is the face-to-face deck."""
    from microslip.fe.calculix.meshdeck import N2S_TENSION_RATIO

    args = dict(loads=[MeshLoad("end", (1, 0, 0), 2.0)], increments_per_cycle=4)
    f2f = build_mesh_deck(one_element(), ONE, **args)
    n2s = build_mesh_deck(one_element(), ONE, formulation="node-to-surface", **args)
    assert f2f == build_mesh_deck(one_element(), ONE, formulation="face-to-face", **args)
    assert N2S_TENSION_RATIO == 1e-5
    expected = f2f.replace("LINEAR\n100000\n", "LINEAR\n100000, 5e-05\n").replace(
        "TYPE=SURFACE TO SURFACE", "TYPE=NODE TO SURFACE")
    assert n2s == expected and n2s != f2f
    with pytest.raises(ParameterError, match="contact formulation must be one of"):
        build_mesh_deck(one_element(), ONE, formulation="mortar", **args)


def test_the_command_lines_formulations_are_the_decks():
    from microslip.fe.calculix.compare import DEFAULT_FORMULATION
    from microslip.fe.calculix.meshdeck import CONTACT_FORMULATIONS
    from microslip.fe.constants import CCX_CONTACT_FORMULATIONS

    assert set(CCX_CONTACT_FORMULATIONS) == set(CONTACT_FORMULATIONS)
    assert CCX_CONTACT_FORMULATIONS[0] == DEFAULT_FORMULATION == "node-to-surface"


def test_sta_increments_count_converged_increments_only(tmp_path):
    from microslip.fe.calculix.runner import _sta_increments

    sta = tmp_path / "job.sta"
    assert _sta_increments(sta) == 0
    sta.write_text(
        "SUMMARY OF JOB INFORMATION\n"
        " STEP      INC     ATT  ITRS     TOT TIME     STEP TIME         INC TIME\n"
        "     1          1     1     3  0.100000E+01  0.100000E+01  0.100000E+01\n"
        "     2          1     1     2  0.102500E+01  0.250000E-01  0.250000E-01\n"
        "     2          2     1U   11  0.102500E+01  0.250000E-01  0.250000E-01\n")
    assert _sta_increments(sta) == 2


@pytest.mark.ccx
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason=NO_CCX)
def test_node_to_surface_contact_is_the_builtin_solvers_law(tmp_path):
    """The 12x3x1 cantilever under an axial 300 N (validate's normal slope 1e5): CalculiX's
    node-to-surface contact gives the built-in solver's W of every cycle to 1e-4 and its
    displacement to 1e-5 (measured 7e-6 and 3e-6); face-to-face contact is 10 % below on the
    same mesh (docs/interpretation.md §21)."""
    from microslip.fe.calculix.compare import compare_on_mesh
    from microslip.fe.clamp import MeshClamp
    from microslip.fe.examples import cantilever_mesh
    from microslip.fe.meshfile import write_inp
    from microslip.fe.ownmesh import OwnMeshCase

    mesh = str(write_inp(cantilever_mesh(12, 3, 1), tmp_path / "c.inp"))
    clamp = MeshClamp("contact", "clamp", normal_force=2000.0, friction=0.5, modulus=70000.0,
                      poisson_ratio=0.33, stick_slope=1e4, normal_contact="penalty",
                      normal_slope=1e5)
    case = OwnMeshCase(mesh, clamp, (MeshLoad.parse("tip:1,0,0:300"),))
    r = compare_on_mesh(case, tmp_path, progress=False, sensitivity=False)
    b, c = r["cycle_work_Nmm"]["builtin"], r["cycle_work_Nmm"]["calculix"]
    assert len(b) == len(c) == r["cycles"] >= 2
    np.testing.assert_allclose(c, b, rtol=1e-4)
    assert abs(r["relative_difference"]["peak_displacement_mm"]) < 1e-5
    assert r["passed"] and all(r["settled"].values())
    assert r["calculix"]["contact"].startswith("node-to-surface")
    assert (tmp_path / "validation_mesh.json").is_file()
