"""One home for each name, default and check (microslip.conventions): the registries take
their names from it, and reading a case file imports no FE and no dynamics."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from microslip import conventions
from microslip.case import schema
from microslip.conventions import check_choice, check_positive, check_whole
from microslip.dynamics import operators2d
from microslip.errors import ParameterError
from microslip.fe import constants
from microslip.fe.builtin import DEFAULT_MESH, backbone
from microslip.loading import path
from microslip.meshdynamics import spec as dynamics_spec
from microslip.models import MODELS


def test_registries_are_keyed_by_the_one_name_list():
    assert tuple(MODELS) == conventions.CLAMP_MODELS
    assert tuple(operators2d.COUPLINGS) == conventions.COUPLINGS
    assert tuple(operators2d.PAIRINGS) == conventions.PAIRINGS
    assert tuple(dynamics_spec.TRANSVERSE) == conventions.TRANSVERSE
    # the case schema, the load path and the FE backbone hold the same objects, not copies
    assert schema.COUPLINGS is conventions.COUPLINGS
    assert schema.PAIRINGS is conventions.PAIRINGS
    assert schema.TRANSVERSE is conventions.TRANSVERSE
    assert schema.JOINT_MODELS is conventions.JOINT_MODELS
    assert path.COMPONENTS is backbone.BACKBONE_LOADS is conventions.CLAMP_MODELS


def test_one_default_mesh_and_stick_slope():
    assert DEFAULT_MESH == schema.DEFAULT_FE_MESH == conventions.DEFAULT_MESH == "coarse"
    assert constants.DEFAULT_STICK_SLOPE is conventions.DEFAULT_STICK_SLOPE
    assert conventions.DEFAULT_STICK_SLOPE == 1.0e4


def test_reading_a_case_file_imports_neither_fe_nor_dynamics():
    code = ("import sys, microslip.case, microslip.conventions\n"
            "print(sorted({m.split('.')[1] for m in sys.modules if m.startswith('microslip.')}"
            " & {'fe', 'dynamics', 'plot', 'cli'}))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


@pytest.mark.parametrize(("value", "message"), [
    (0, "must be a whole number in [1, 1000], got 0"),
    (1001, "must be a whole number in [1, 1000], got 1001"),
    (2.0, "must be a whole number in [1, 1000], got 2.0"),
    (True, "must be a whole number in [1, 1000], got True"),
])
def test_check_whole_names_the_value_and_the_range(value, message):
    with pytest.raises(ParameterError) as err:
        check_whole("n", value, 1, 1000)
    assert str(err.value) == f"n {message}"


def test_check_whole_takes_numpy_integers_and_open_ranges():
    assert check_whole("n", np.int64(7), 1) == 7
    with pytest.raises(ParameterError, match=r"tip_symmetry must be a whole number >= 1"):
        check_whole("tip_symmetry", -1, 1)


def test_check_choice_and_positive():
    assert check_choice("coupling", "decoupled", conventions.COUPLINGS) == "decoupled"
    with pytest.raises(ParameterError, match=r"unknown coupling 'round'; choose one of "
                                             r"circular, decoupled"):
        check_choice("coupling", "round", conventions.COUPLINGS)
    with pytest.raises(ParameterError, match=r"unknown coupling None"):
        check_choice("coupling", None, conventions.COUPLINGS)
    assert check_positive("f", "2.5", "Hz") == 2.5
    with pytest.raises(ParameterError, match=r"f must be < 1 \(Hz\), got 1"):
        check_positive("f", 1, "Hz", upper=1.0)


def test_the_strain_energy_check_is_the_same_everywhere():
    from microslip.energy import strain_energy
    from microslip.planar.damping import _check_kind

    with pytest.raises(ParameterError) as a:
        _check_kind("chord")
    with pytest.raises(ParameterError) as b:
        strain_energy(None, None, "chord")  # type: ignore[arg-type]
    assert str(a.value) == str(b.value) == (
        "unknown strain-energy definition 'chord'; choose one of secant, backbone, branch, "
        "stored")
