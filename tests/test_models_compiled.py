"""One kernel per model, run two ways: the plain-Python functions of the model modules (a
short single loop, no numba) and their compiled copies (:mod:`microslip.models.compiled`,
the batch engine and long loops) give the same numbers bit for bit, so which one a process
takes (:func:`microslip.models.kernel`) changes the time only."""

from __future__ import annotations

import numpy as np
import pytest

from microslip import preset
from microslip.models import Contact, centre, layer, layered, masing, tip
from microslip.models.compiled import compiled
from microslip.models.interface import power_law, table_law
from microslip.options import CENTRE_READINGS, POISSON_MODES, ModelOptions

P = preset("table1")
CLAMP = (P.length, P.width, P.thickness, P.modulus, P.poisson_ratio, P.friction,
         P.normal_force)


def _same(a: tuple, b: tuple) -> None:
    assert len(a) == len(b)
    for x, y in zip(a, b, strict=True):
        assert np.array_equal(np.asarray(x), np.asarray(y), equal_nan=True)


def _options() -> list[tuple[int, ...]]:
    return [ModelOptions(poisson=p, centre=c, length_update=lu).codes
            for p in POISSON_MODES for c in CENTRE_READINGS for lu in (True, False)]


@pytest.mark.parametrize("backbone", [tip.tip_backbone, centre.centre_backbone],
                         ids=["tip", "centre"])
def test_rigid_backbones_are_the_compiled_ones_bit_for_bit(backbone) -> None:
    for codes in _options():
        args = (300.0, 200, *CLAMP, *codes)
        _same(backbone(*args), compiled(backbone)(*args))


@pytest.mark.parametrize("backbone", [layered.tip_layer_backbone,
                                      layered.centre_layer_backbone], ids=["tip", "centre"])
@pytest.mark.parametrize("law", ["uniform", "parabolic", "power", "table", "pow"])
def test_layer_backbones_are_the_compiled_ones_bit_for_bit(backbone, law) -> None:
    pressure = {"uniform": None, "parabolic": "parabolic",
                "power": power_law(3.0, 2.5), "pow": power_law(2.5, 2.0),
                "table": table_law([0.0, 0.3 * P.length, P.length], [1.5, 0.7, 1.0], P.length)}[law]
    contact = Contact.layer(1e4, pressure)
    args = (300.0, 150, *CLAMP, *ModelOptions().codes, *contact.kernel_args)
    _same(backbone(*args), compiled(backbone)(*args))


def test_masing_sums_and_layer_curves_are_the_compiled_ones_bit_for_bit() -> None:
    rng = np.random.default_rng(3)
    f = np.cumsum(rng.uniform(0.0, 1.0, 101))
    d = np.cumsum(rng.uniform(0.0, 1e-3, 101))
    _same(masing.backbone_sums(f, d), compiled(masing.backbone_sums)(f, d))
    law = power_law(3.0, 2.5)
    xi = np.linspace(0.0, 1.0, 57)
    for which in (0, 2, 3):
        _same((layer.law_values(which, law.code, law.data, xi),),
              (compiled(layer.law_values)(which, law.code, law.data, xi),))


def test_a_process_runs_plain_until_its_budget_then_compiled() -> None:
    """:func:`microslip.models.kernel`: plain while the steps fit in PLAIN_STEPS, compiled
    for a call beyond it and for every call once the compiled kernels are loaded (a fresh
    process: this one has loaded them)."""
    import subprocess
    import sys

    code = ("from microslip.models import LAYER_STEP, PLAIN_STEPS, kernel, tip\n"
            "f = tip.tip_backbone\n"
            "print(kernel(f, 1000) is f, kernel(f, PLAIN_STEPS - 1000) is f,\n"
            "      kernel(f, 1) is f, kernel(f, 1000) is f, LAYER_STEP > 1)")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout.split()
    assert out == ["True", "True", "False", "False", "True"]
