"""``microslip fit --plot``: the figure shows the measured loops and the fitted model."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

import microslip.plot.fit as fit_plot
from microslip.cli.main import main
from microslip.fit import read_loop_csv


def _fe_loop_csv(tmp_path: Path, capsys) -> Path:  # type: ignore[no-untyped-def]
    assert main(["fe", "--model", "tip", "--mesh", "tiny", "--substeps", "40", "--json"]) == 0
    fe = json.loads(capsys.readouterr().out)
    path = tmp_path / "loop.csv"
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["force_N", "displacement_mm"])
        w.writerows(zip(fe["loop"]["force_N"], fe["loop"]["displacement_mm"], strict=True))
    return path


def test_plot_draws_the_data_and_the_model(tmp_path, capsys, monkeypatch):
    path = _fe_loop_csv(tmp_path, capsys)
    saved = {}
    monkeypatch.setattr(fit_plot, "save_figure", lambda fig, p: saved.update(fig=fig, path=p))
    out = tmp_path / "fit.png"
    assert main(["fit", str(path), "--model", "tip", "--fit", "friction", "--plot",
                 str(out), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["figure"] == str(out) and saved["path"] == str(out)
    lines = saved["fig"].axes[0].get_lines()
    measured = [ln for ln in lines if ln.get_marker() == "o"]
    model = [ln for ln in lines if ln.get_linestyle() == "-" and ln.get_marker() != "o"
             and len(ln.get_xdata()) > 2]
    assert len(measured) == 1 and len(model) == 1
    f, d = read_loop_csv(str(path)).centred()
    np.testing.assert_array_equal(measured[0].get_xdata(), d)
    np.testing.assert_array_equal(measured[0].get_ydata(), f)
    np.testing.assert_array_equal(model[0].get_ydata(), f)
    # the model's loop is the fit: within the reported rms residual of the data, point by point
    gap = np.asarray(model[0].get_xdata()) - d
    assert np.sqrt(np.mean(gap**2)) == pytest.approx(result["rms_residual_mm"], rel=1e-9)
    assert f"friction = {result['friction']:.4g}" in saved["fig"].axes[0].get_title()


def test_plot_file_is_written(tmp_path, capsys):
    path = _fe_loop_csv(tmp_path, capsys)
    out = tmp_path / "fit.svg"
    assert main(["fit", str(path), "--model", "tip", "--fit", "friction", "--plot",
                 str(out)]) == 0
    assert f"figure         {out}" in capsys.readouterr().out
    assert out.read_text().count("<svg") == 1


def test_plot_extension_is_checked_before_fitting(tmp_path, capsys):
    code = main(["fit", "missing.csv", "--model", "tip", "--plot", str(tmp_path / "f.txt")])
    err = capsys.readouterr().err
    assert code == 1 and "--plot file must end in .png, .pdf or .svg" in err
    assert err.count("\n") == 1
