"""Fitting measured loops: recovery of known parameters, intervals, identifiability, CLI."""

from __future__ import annotations

import csv
import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from microslip import preset
from microslip.cli.main import main
from microslip.fit import MeasuredLoop, _predict, fit_loops

P = preset("table1")
#: A clamp whose loop depends strongly on the contact stiffness (issue 11's titanium block).
TI = dataclasses.replace(P, length=30.0, width=12.0, thickness=8.0, modulus=114000.0,
                         poisson_ratio=0.34, friction=0.5, normal_force=12000.0)


def _loop(params, slope: float, f0: float, n: int = 161) -> MeasuredLoop:  # type: ignore[no-untyped-def]
    t = np.linspace(0.25, 1.25, n)
    f = f0 * np.sin(2 * np.pi * t)
    return MeasuredLoop(f, _predict("tip", params, slope, None, f, f0))


def test_noise_free_model_loops_give_the_parameters_back() -> None:
    loops = [_loop(TI, 3e4, f0) for f0 in (2000.0, 3600.0)]
    start = dataclasses.replace(TI, friction=0.3)
    res = fit_loops(loops, "tip", start, stick_slope=1e5)
    got = {p.name: p for p in res.parameters}
    assert got["friction"].value == pytest.approx(0.5, rel=1e-7)
    assert got["stick_slope"].value == pytest.approx(3e4, rel=1e-6)
    assert all(p.identified for p in res.parameters)
    assert res.rms_residual_mm < 1e-12


def test_intervals_cover_the_truth_and_shrink_with_the_noise() -> None:
    clean = _loop(TI, 3e4, 3600.0)
    scale = float(np.ptp(clean.displacement))
    rng = np.random.default_rng(7)
    widths = []
    for noise in (0.02, 0.01):
        d = clean.displacement + rng.normal(0.0, noise * scale, clean.displacement.size)
        res = fit_loops([MeasuredLoop(clean.force, d)], "tip", TI, stick_slope=1e5)
        got = {p.name: p for p in res.parameters}
        assert got["friction"].low < 0.5 < got["friction"].high
        assert got["stick_slope"].low < 3e4 < got["stick_slope"].high
        assert res.rms_residual_mm == pytest.approx(noise * scale, rel=0.25)
        widths.append(math.log(got["friction"].high / got["friction"].low))
    assert widths[1] / widths[0] == pytest.approx(0.5, rel=0.3)  # interval ~ noise


def test_product_mu_fn_is_not_separable() -> None:
    res = fit_loops([_loop(TI, 3e4, 3600.0)], "tip", TI, fit=("friction", "normal_force"),
                    stick_slope=3e4)
    assert not any(p.identified for p in res.parameters)
    assert all("cannot separate" in p.note for p in res.parameters)
    mu_fn = res.params.friction * res.params.normal_force
    assert mu_fn == pytest.approx(0.5 * 12000.0, rel=1e-6)


def _write(path: Path, f: np.ndarray, d: np.ndarray) -> Path:
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["force_N", "displacement_mm"])
        w.writerows(zip(f.tolist(), d.tolist(), strict=True))
    return path


def test_fe_loop_with_noise_recovers_friction(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """A loop of the built-in FE solver (Table 1, mu 0.8), 1 % noise added."""
    assert main(["fe", "--model", "tip", "--json"]) == 0
    fe = json.loads(capsys.readouterr().out)
    f = np.array(fe["loop"]["force_N"])
    d = np.array(fe["loop"]["displacement_mm"])
    d = d + np.random.default_rng(3).normal(0.0, 0.01 * np.ptp(d), d.size)
    path = _write(tmp_path / "loop.csv", f, d)
    assert main(["fit", str(path), "--model", "tip", "--friction", "0.4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["friction_low"] < 0.8 < out["friction_high"]
    assert out["friction_high"] / out["friction_low"] < 1.05
    assert out["friction_identified"] is True
    # the slender bar's loop hardly depends on the contact stiffness: said, not invented
    assert out["stick_slope_identified"] is False
    assert "stick_slope_note" in out


@pytest.mark.parametrize(("content", "message"), [
    ("a,b\n1,2\n", "needs the columns force_N,displacement_mm"),
    ("force_N,displacement_mm\n1,x\n", "not a number"),
    ("force_N,displacement_mm\n1,2\n", ">= 8 finite samples"),
])
def test_bad_loop_files_are_one_line(tmp_path: Path, capsys, content: str,  # type: ignore[no-untyped-def]
                                     message: str) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(content)
    assert main(["fit", str(path), "--model", "tip"]) == 1
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_loop_beyond_gross_sliding_needs_friction(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    loop = _loop(TI, 3e4, 3600.0)
    path = _write(tmp_path / "loop.csv", loop.force, loop.displacement)
    code = main(["fit", str(path), "--model", "tip", "--length", "30", "--width", "12",
                 "--thickness", "8", "--modulus", "114000", "--poisson-ratio", "0.34",
                 "--friction", "0.2", "--normal-force", "12000", "--fit", "stick_slope"])
    assert code == 1
    assert "beyond the clamp's gross-sliding force 2400 N" in capsys.readouterr().err
    assert main(["fit", str(path), "--model", "tip", "--amplitude", "5"]) == 1
    assert "--amplitude does nothing in fit" in capsys.readouterr().err


def test_loops_microslip_writes_are_what_fit_reads(tmp_path, capsys):
    """``loop --csv`` and ``fe --out DIR`` (DIR/loop.csv) write the format fit reads, with the
    samples of the JSON loop bit for bit."""
    from microslip.cli.main import main
    from microslip.fit import read_loop_csv

    assert main(["loop", "--model", "tip", "--amplitude", "200", "--increments", "100",
                 "--json", "--csv", str(tmp_path / "a.csv")]) == 0
    loop = json.loads(capsys.readouterr().out)["loop"]
    back = read_loop_csv(str(tmp_path / "a.csv"))
    assert back.force.tolist() == loop["force_N"]
    assert back.displacement.tolist() == loop["displacement_mm"]
    assert main(["fe", "--model", "tip", "--amplitude", "200", "--mesh", "tiny", "--json",
                 "--no-vtu", "--out", str(tmp_path / "fe")]) == 0
    fe = json.loads(capsys.readouterr().out)
    back = read_loop_csv(str(tmp_path / "fe" / "loop.csv"))
    assert back.displacement.tolist() == fe["loop"]["displacement_mm"]
    assert str(tmp_path / "fe" / "loop.csv") in fe["files"]
    assert main(["loop", "--model", "tip", "--csv", str(tmp_path / "x.txt")]) == 1
