"""The main job's structure study (``microslip reproduce``, issue 23): every model on the
cantilever's two bending modes, written as JSON and figures with the verdicts in report
lines (on the 12x3x1 mesh here; the main job runs 24x6x2)."""

from __future__ import annotations

import json

import pytest

from microslip.reproduce.structurejob import STRUCTURE_MODES, structure_study


@pytest.mark.slow
def test_structure_study_writes_every_mode(tmp_path) -> None:  # type: ignore[no-untyped-def]
    files, lines = structure_study(tmp_path, counts=(12, 3, 1), amplitudes=3)
    names = sorted(f.name for f in files)
    assert names == sorted(["cantilever_12x3x1.inp",
                            *(f"mode{n}.{e}" for n in STRUCTURE_MODES for e in ("json", "png"))])
    for n in STRUCTURE_MODES:
        out = json.loads((tmp_path / "structure" / f"mode{n}.json").read_text())
        assert out["mode"] == n and out["mesh"] == "cantilever_12x3x1.inp"
        assert set(out["solvers"]) == {"fe", "rom", "interface", "joint"}
        assert set(out["verdicts"]) == {"rom", "interface", "joint"}
        assert (tmp_path / "structure" / f"mode{n}.png").stat().st_size > 10_000
    verdicts = [line for line in lines if line.startswith("- ")]
    assert len(verdicts) == 3 * len(STRUCTURE_MODES)
    assert all(v.split()[1] in ("rom:", "interface:", "joint:") for v in verdicts)
