"""The flat public namespace: every name of ``microslip.__all__`` resolves, and ``import
microslip`` stays light (the heavy modules are imported on first use of a name)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import microslip

#: Modules that ``import microslip`` must not import (module name prefixes).
HEAVY = ("matplotlib", "scipy.sparse", "numba", "xarray", "dask", "microslip.models",
         "microslip.fe", "microslip.dynamics", "microslip.sweep", "microslip.energy")


def test_every_public_name_resolves():
    for name in microslip.__all__:
        assert getattr(microslip, name) is not None, name
    assert set(microslip.__all__) <= set(dir(microslip))
    assert len(set(microslip.__all__)) == len(microslip.__all__)


def test_public_names_are_the_defining_objects():
    from microslip.dynamics.modal import epmc
    from microslip.dynamics.structure import Structure
    from microslip.energy import damping
    from microslip.fe.run import run_loop

    assert microslip.epmc is epmc and microslip.Structure is Structure
    assert microslip.damping is damping and microslip.run_loop is run_loop
    assert microslip.planar.__name__ == "microslip.planar"


def test_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'dampign'"):
        _ = microslip.dampign  # type: ignore[attr-defined]


def test_internals_are_not_public():
    import microslip.blas
    import microslip.sweep

    for module in (microslip, microslip.sweep, microslip.blas):
        exported = set(getattr(module, "__all__", ()))
        assert not exported & {"single_threaded_blas", "map_on_cluster"}, module.__name__


@pytest.mark.parametrize("package", ["microslip", "microslip.fe"])
def test_import_is_light(package):
    code = (f"import sys, json; import {package}; "
            "print(json.dumps(sorted(sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout
    loaded = json.loads(out)
    heavy = [m for m in loaded if m.startswith(HEAVY) and not m.startswith(
        package + ".") and m != package]
    if package == "microslip.fe":  # the FE package loads its constants and errors only
        heavy = [m for m in heavy if m not in ("microslip.fe.constants", "microslip.fe.errors")]
    assert heavy == []
