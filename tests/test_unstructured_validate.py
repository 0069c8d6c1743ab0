"""The built-in solver and CalculiX node to surface solve the same equations on any mesh
(issue 33, item 8).

On the new user's unstructured plate (tests/data/meshes/plate_washer.msh: gmsh's
frontal-Delaunay quadrangles extruded, so the faces are not parallelograms) ``validate --mesh``
found W 2.5 % apart (the issue's own plate: 11.3 %) where the structured examples agree to
0.01-0.03 %. Two equations differed, both exact on parallelograms and parallelepipeds only:

* the contact nodes' areas A_i: the built-in solver took the consistent share integral N_i dA
  of each face, CalculiX's node-to-surface contact a quarter of each face's area (its
  ``xnoels`` 1/4): up to 18 % apart at a node of the plate, W +4.8 % (built-in alone);
* the incompatible-mode element: the built-in C3D8I scaled the modes' x-derivatives by
  det J0 / det J (Taylor's correction), CalculiX's does not: the plate's tip displacement
  3e-4 apart, W -2.1 %.

The built-in solver now takes CalculiX's areas and element: the static plate's displacements
agree to 1e-7 and ``validate --mesh`` passes (W 0.5 % apart, d 2e-5).
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from conftest import run_json

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.element import assemble_hex8
from microslip.fe.builtin.meshmodel import build_mesh_model
from microslip.fe.hexmesh import face_load
from microslip.fe.meshfile import read_mesh

PLATE = Path(__file__).resolve().parent / "data" / "meshes" / "plate_washer.msh"
STEEL = {"modulus": 210000.0, "poisson_ratio": 0.3}


def _quarters(mesh: object, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A quarter of each face's area (its diagonals' cross product, exact for a flat
    quadrilateral) at each corner."""
    corners = mesh.face_corners(faces)  # type: ignore[attr-defined]
    x = mesh.nodes[corners]  # type: ignore[attr-defined]
    area = 0.5 * np.linalg.norm(np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1]), axis=1)
    nodes = np.unique(corners)
    return nodes, np.bincount(np.searchsorted(nodes, corners.ravel()),
                              weights=np.repeat(area / 4.0, 4), minlength=nodes.size)


def test_the_contact_areas_are_calculix_quarters_on_the_unstructured_plate() -> None:
    mesh = read_mesh(PLATE)
    a = rigid_base(contact_set="contact", clamp_set="washer", normal_force=8000.0,
                   friction=0.5, normal_contact="penalty", normal_slope=1e5, **STEEL)
    model = build_mesh_model(mesh, a)
    nodes, quarter = _quarters(mesh, mesh.surfaces["contact"])
    assert np.array_equal(np.sort(model.contact_nodes), nodes)
    mine = model.contact_area[np.argsort(model.contact_nodes)]
    assert np.allclose(mine, quarter, rtol=1e-12)
    assert mine.sum() == pytest.approx(625.0, rel=1e-12)
    # the consistent shares, the other choice, differ here (not parallelograms)
    _, share, total = face_load(mesh, mesh.surfaces["contact"])
    assert np.max(np.abs(share * total - quarter) / quarter) > 0.1
    other = build_mesh_model(mesh, a, contact_weights="consistent")
    assert np.allclose(other.contact_area[np.argsort(other.contact_nodes)], share * total)


@pytest.mark.slow
@pytest.mark.ccx
def test_c3d8i_is_calculix_on_the_unstructured_plate(tmp_path: Path) -> None:
    """The plate held on its contact patch, 400 N along x and 100 N along z on its end face:
    the built-in C3D8I's displacements are CalculiX's to 1e-6 (measured 1e-7; with Taylor's
    det J0 / det J factor they were 2.3e-5 apart, the tip 3.4e-4)."""
    mesh = read_mesh(PLATE)
    n = len(mesh.nodes)
    fixed = np.unique(mesh.node_sets["contact"])
    nodes, share, _ = face_load(mesh, mesh.surfaces["end"])
    f = np.zeros(3 * n)
    f[3 * nodes] = 400.0 * share
    f[3 * nodes + 2] = 100.0 * share
    free = np.setdiff1d(np.arange(3 * n), (3 * fixed[:, None] + np.arange(3)).ravel())
    k = assemble_hex8(mesh.nodes, mesh.elements, STEEL["modulus"], STEEL["poisson_ratio"],
                      "C3D8I").tocsr()
    u = np.zeros(3 * n)
    u[free] = spla.spsolve(k[free][:, free].tocsc(), f[free])
    lines = ["*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {x!r}, {y!r}, {z!r}" for i, (x, y, z) in enumerate(mesh.nodes.tolist())]
    lines.append("*ELEMENT, TYPE=C3D8I, ELSET=PLATE")
    lines += [f"{i + 1}, " + ", ".join(str(v + 1) for v in e)
              for i, e in enumerate(mesh.elements.tolist())]
    lines.append("*NSET, NSET=FIX")
    lines += [f"{v + 1}," for v in fixed.tolist()]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000, 0.3",
              "*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL", "*BOUNDARY", "FIX, 1, 3",
              "*STEP", "*STATIC", "*CLOAD"]
    for v, s in zip(nodes.tolist(), share.tolist(), strict=True):
        lines += [f"{v + 1}, 1, {400.0 * s!r}", f"{v + 1}, 3, {100.0 * s!r}"]
    lines += ["*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    (tmp_path / "plate.inp").write_text("\n".join(lines) + "\n")
    subprocess.run(["ccx", "-i", "plate"], cwd=tmp_path, check=True, capture_output=True)
    ccx = np.zeros(3 * n)
    block = (tmp_path / "plate.dat").read_text().split("displacements")[1]
    for row in block.strip().splitlines()[1:]:
        p = row.split()
        if len(p) == 4:
            i = int(p[0]) - 1
            ccx[3 * i:3 * i + 3] = [float(v) for v in p[1:]]
    assert np.max(np.abs(u - ccx)) < 1e-6 * np.max(np.abs(ccx))


@pytest.mark.slow
@pytest.mark.ccx
def test_validate_mesh_passes_on_the_unstructured_plate(capsys: pytest.CaptureFixture[str],
                                                        tmp_path: Path) -> None:
    """The issue's check on the unstructured plate: node to surface, penalty 1e5, the paper's
    history (a quarter-cycle rise, one cycle): W and d within validate's tolerances
    (measured before the fix: W +2.5 %)."""
    out = run_json(capsys, "validate", "--mesh", PLATE, "--contact-set", "contact",
                   "--clamp-set", "washer", "--normal-force", 8000, "--load", "end:1,0,0:400",
                   "--modulus", 210000, "--poisson-ratio", 0.3, "--friction", 0.5,
                   "--normal-contact", "penalty", "--normal-slope", 1e5, "--history", "paper",
                   "--no-progress", "--out", tmp_path)
    rel = out["relative_difference"]
    assert abs(rel["dissipated_energy_Nmm"]) < 0.01, rel
    assert abs(rel["peak_displacement_mm"]) < 1e-3, rel
    assert out["passed"]
