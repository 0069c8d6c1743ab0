"""The reproduction's step "the clamp as one joint against finite elements"
(microslip.reproduce.joint_fe) on an 8 x 2 x 1 mesh; the figures themselves are checked in
test_dynamics_fe_check.py and docs/dynamics.md."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.meshdynamics.fe_check import cycle_work
from microslip.reproduce.joint_fe import (
    JOINTS,
    joint_fe_figure,
    joint_fe_section,
    joint_fe_study,
)

#: the module's fixture runs the joint-against-FE study (about 4 s of CPU)
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def study():
    return joint_fe_study(mesh=(8, 2, 1), ratios=(1.0, 4.0))


def test_the_columns_are_the_comparisons(study):
    cols, runs = study
    assert cols["R"] == [1.0, 4.0] and len(runs) == 2
    for i, run in enumerate(runs):
        # the FE's W is its applied force's closed work on the orbit (same samples), up to
        # the orbit's closure gap: the cycle has settled to 1e-3 in W, not to round-off
        assert cycle_work(run.fe_force, run.orbit) == pytest.approx(run.fe_coupled, rel=1e-3)
        shifted = cycle_work(np.roll(run.fe_force, 1, axis=0), run.orbit)
        assert shifted != pytest.approx(run.fe_coupled, rel=1e-2)  # one sample off: wrong
        assert cols["fe_dissipated_energy_Nmm"][i] == run.fe_coupled
        for key in JOINTS:
            name = key.replace(" ", "_")
            w = cycle_work(run.joint_force[key], run.orbit)
            assert cols[f"{name}_Nmm"][i] == w
            assert cols[f"{name}_over_fe"][i] == pytest.approx(w / run.fe_coupled, rel=1e-15)
        assert cols["circular_Nmm"][i] == pytest.approx(run.circular, rel=1e-12)
        assert cols["anisotropic_spatial_Nmm"][i] == pytest.approx(run.anisotropic["spatial"],
                                                                   rel=1e-12)
    assert np.allclose(np.array(cols["tip_amplitude_N"]) / cols["centre_amplitude_N"],
                       cols["R"])


def test_the_section_names_the_closest_joint_from_the_numbers(study):
    cols, _ = study
    text = joint_fe_section(cols)
    assert text.count("\n| ") == 1 + 1 + len(cols["R"]) - 1  # header, rule, rows
    assert "Closest: anisotropic, spatial pairing." in text  # 3.3 % and 4.5 % on this mesh
    assert f"{cols['circular_over_fe'][0]:.3f}" in text


def test_the_figure_is_written(study, tmp_path):
    cols, runs = study
    path = tmp_path / "fig13.png"
    joint_fe_figure(path, cols, runs)
    assert path.stat().st_size > 10_000
