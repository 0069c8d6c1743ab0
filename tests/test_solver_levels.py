"""Mesh levels from the geometry and the mesh convergence of a thick block (issue 11, item 4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip import preset
from microslip.params import ClampParams
from microslip.solver import solve_uniaxial
from microslip.solver.mesh import MESH_LEVELS, MESHES, level_counts, mesh_from_spec

TITANIUM = ClampParams(length=30.0, width=12.0, thickness=8.0, modulus=113_800.0,
                       poisson_ratio=0.342, friction=0.5, normal_force=12_000.0)


@pytest.mark.parametrize("level", list(MESH_LEVELS))
def test_levels_give_the_table1_counts(level):
    """The Table 1 runs keep their meshes (and so every number)."""
    assert level_counts(preset("table1"), level) == MESHES[level]


def test_a_thick_block_gets_layers_and_square_elements():
    for level, layers in (("coarse", 3), ("medium", 3), ("fine", 6)):
        nx, ny, nz = level_counts(TITANIUM, level)
        assert nz == layers == math.ceil(TITANIUM.thickness / (TITANIUM.width / ny))
        assert nx % 2 == 0 and nx >= MESHES[level][0]
    box = mesh_from_spec(TITANIUM, "coarse")
    assert (box.nx, box.ny, box.nz) == (24, 4, 3)
    # fixed counts stay fixed; the layers are capped
    assert level_counts(TITANIUM, "paper") == MESHES["paper"]
    tall = TITANIUM.replace(thickness=300.0)
    assert level_counts(tall, "coarse")[2] == MESH_LEVELS["coarse"].max_layers


def test_thick_block_converges_at_the_measured_rate():
    """Uniform refinement of the titanium block (fixed normal, stick slope 1e5 N/mm^3): W_d
    decreases monotonically and the differences fall by 2.45 per halving (order 1.3: the
    stress singularity at the loaded edge; docs/solver.md, mesh convergence)."""
    w = np.array([solve_uniaxial(TITANIUM, "tip", 3600.0, mesh=m, stick_slope=1e5)
                  .dissipated_energy for m in ((4, 2, 1), (8, 4, 2), (16, 8, 4))])
    diff = -np.diff(w)
    assert np.all(diff > 0)
    order = math.log2(diff[0] / diff[1])
    assert 1.0 < order < 1.6
