"""``microslip sweep`` and microslip.sweep: grids, samples, files, plots, errors."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import listing, one_line_error, run

from microslip import ModelOptions, ParameterError, damping, preset
from microslip.cli.main import main
from microslip.sweep import (
    COLUMNS,
    Distribution,
    make_sweep,
    parse_grid,
    parse_sample,
    run_sweep,
    write_sweep,
)


def read_csv(path: Path) -> dict[str, np.ndarray]:
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], np.array(rows[1:], dtype=float)
    return {name: body[:, i] for i, name in enumerate(header)}


def sweep(tmp_path: Path, *args: str, name: str = "out.csv") -> tuple[int, Path]:
    out = tmp_path / name
    rc = main(["sweep", *args, "--out", str(out), "--no-progress"])
    return rc, out


# -- exact limit and agreement with `microslip loop` ----------------------------------------
def test_uncorrected_secant_is_4_over_3pi_everywhere(tmp_path: Path) -> None:
    rc, out = sweep(tmp_path, "--model", "centre", "--preset", "table2-centre",
                    "--amplitude-range", "100", "15000", "--cases", "40",
                    "--grid", "mu=0.8:1.2:3", "--grid", "E=7e4,2.1e5",
                    "--no-corrections", "--strain-energy", "secant", "--increments", "1000")
    assert rc == 0
    t = read_csv(out)
    assert list(t) == list(COLUMNS)
    assert t["loss_factor"].size == 40 * 3 * 2
    assert np.max(np.abs(t["loss_factor"] - 4.0 / (3.0 * math.pi))) < 1e-6


def test_amplitude_range_rows_are_evenly_spaced_in_order(tmp_path: Path) -> None:
    rc, out = sweep(tmp_path, "--model", "tip", "--preset", "table2-tip",
                    "--amplitude-range", "100", "8000", "--cases", "80", "--increments", "50")
    assert rc == 0
    amp = read_csv(out)["amplitude_N"]
    np.testing.assert_allclose(amp, np.linspace(100.0, 8000.0, 80), rtol=1e-14)
    assert amp[0] == 100.0 and amp[-1] == 8000.0


@pytest.mark.parametrize(("model", "extra"), [
    ("tip", ["--preset", "table2-tip", "--strain-energy", "branch"]),
    ("centre", ["--preset", "table2-centre", "--strain-energy", "stored",
                "--centre-reading", "paper"]),
    ("tip", ["--preset", "table1", "--paper-literal", "--increments", "50"]),
])
def test_rows_agree_with_microslip_loop(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                        model: str, extra: list[str]) -> None:
    rc, out = sweep(tmp_path, "--model", model, *extra, "--amplitude-range", "30", "250",
                    "--cases", "3", "--grid", "friction=0.7,0.9", "--grid", "width=20,26")
    assert rc == 0
    t = read_csv(out)
    capsys.readouterr()
    for row in (0, 5, 11):
        args = ["loop", "--model", model, *extra, "--json",
                "--amplitude", repr(float(t["amplitude_N"][row])),
                "--friction", repr(float(t["friction"][row])),
                "--width", repr(float(t["width_mm"][row]))]
        assert main(args) == 0
        ref = json.loads(capsys.readouterr().out)
        for col in ("peak_displacement_mm", "dissipated_energy_Nmm", "strain_energy_Nmm",
                    "loss_factor"):
            assert abs(t[col][row] / ref[col] - 1.0) < 1e-9, (row, col)


def test_api_rows_equal_damping_to_1e_12() -> None:
    base = preset("table2-tip")
    spec = make_sweep("tip", base, grid=[("amplitude", [2000.0, 7000.0]),
                                         ("normal_force", [15000.0, 25000.0])],
                      increments=300, options=ModelOptions(), strain_energy="branch")
    r = run_sweep(spec, progress=False)
    table = r.table()
    for i in range(4):
        p = base.replace(normal_force=float(table["normal_force_N"][i]))
        ref = damping("tip", p, float(table["amplitude_N"][i]), 300, ModelOptions(), "branch")
        assert abs(r.loss_factor[i] / ref.loss_factor - 1.0) < 1e-12


def test_chunking_does_not_change_results() -> None:
    spec = make_sweep("centre", preset("table2-centre"), grid=[("amplitude", np.linspace(
        500.0, 15000.0, 101))], samples=[("friction", Distribution("uniform", 0.8, 1.0))],
        n_samples=7, seed=11, increments=60)
    a = run_sweep(spec, chunk_size=13, progress=False)
    b = run_sweep(spec, chunk_size=100000, progress=False)
    np.testing.assert_array_equal(a.loss_factor, b.loss_factor)


# -- samples and seeds ----------------------------------------------------------------------
def test_seed_reproduces_the_file_byte_for_byte(tmp_path: Path) -> None:
    args = ["--model", "tip", "--preset", "table2-tip", "--amplitude-range", "1000", "8000",
            "--cases", "5", "--sample", "friction=normal:0.8:0.05",
            "--sample", "F_N=lognormal:20000:1000", "--samples", "40", "--increments", "40"]
    rc1, a = sweep(tmp_path, *args, "--seed", "42", name="a.csv")
    rc2, b = sweep(tmp_path, *args, "--seed", "42", name="b.csv")
    rc3, c = sweep(tmp_path, *args, "--seed", "43", name="c.csv")
    assert rc1 == rc2 == rc3 == 0
    assert a.read_bytes() == b.read_bytes()
    assert a.read_bytes() != c.read_bytes()
    t = read_csv(a)
    # common random numbers: the same 40 draws at each of the 5 amplitudes
    mu = t["friction"].reshape(5, 40)
    assert np.all(mu == mu[0]) and np.unique(mu[0]).size == 40
    assert abs(mu.mean() - 0.8) < 0.03


def test_no_seed_draws_a_fresh_one_and_reports_it(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sweep", "--model", "tip", "--preset", "table2-tip", "--sample",
                 "mu=uniform:0.7:0.9", "--samples", "5", "--increments", "20",
                 "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "friction: 5 draws, uniform(low 0.7, high 0.9), seed " in out


def test_distributions() -> None:
    rng = np.random.default_rng(3)
    x = Distribution("normal", 2.0, 0.5).draw(rng, 200000)
    assert abs(x.mean() - 2.0) < 0.01 and abs(x.std() - 0.5) < 0.01
    u = Distribution("uniform", 1.0, 3.0).draw(rng, 1000)
    assert u.min() >= 1.0 and u.max() < 3.0
    with pytest.raises(ParameterError, match="SD > 0"):
        Distribution("normal", 1.0, 0.0)
    with pytest.raises(ParameterError, match="LOW < HIGH"):
        Distribution("uniform", 2.0, 1.0)


# -- NetCDF ---------------------------------------------------------------------------------
def test_netcdf_round_trip_with_labelled_dimensions(tmp_path: Path) -> None:
    xr = pytest.importorskip("xarray")
    pytest.importorskip("h5py", reason="h5netcdf needs h5py to write NetCDF-4")
    args = ["--model", "tip", "--preset", "table2-tip", "--amplitude-range", "1000", "7000",
            "--cases", "4", "--grid", "thickness=20:30:3", "--sample",
            "friction=normal:0.8:0.02", "--samples", "6", "--seed", "5", "--increments", "30"]
    rc1, nc = sweep(tmp_path, *args, name="s.nc")
    rc2, cs = sweep(tmp_path, *args, name="s.csv")
    assert rc1 == rc2 == 0
    ds = xr.open_dataset(nc, engine="h5netcdf")
    assert ds["loss_factor"].dims == ("amplitude_N", "thickness_mm", "sample")
    assert ds["loss_factor"].shape == (4, 3, 6)
    np.testing.assert_array_equal(ds["amplitude_N"].values, np.linspace(1000.0, 7000.0, 4))
    np.testing.assert_array_equal(ds["thickness_mm"].values, [20.0, 25.0, 30.0])
    assert ds["thickness_mm"].attrs["units"] == "mm"
    assert ds["friction"].dims == ("sample",)
    assert float(ds["length_mm"]) == 50.0  # constant parameters as scalar coordinates
    assert ds.attrs["seed"] == 5 and ds.attrs["model"] == "tip"
    assert ds.attrs["strain_energy_definition"] == "secant"
    t = read_csv(cs)
    for col in ("peak_displacement_mm", "dissipated_energy_Nmm", "strain_energy_Nmm",
                "loss_factor"):
        np.testing.assert_allclose(ds[col].values.ravel(), t[col], rtol=1e-14)
    np.testing.assert_allclose(np.broadcast_to(ds["friction"].values, (4, 3, 6)).ravel(),
                               t["friction"], rtol=1e-14)
    ds.close()


# -- plots ----------------------------------------------------------------------------------
@pytest.mark.parametrize("extra", [
    ["--amplitude-range", "1000", "8000", "--cases", "30", "--grid", "mu=0.6:0.9:3",
     "--sample", "F_N=normal:20000:500"],
    ["--amplitude-range", "1000", "8000", "--cases", "30", "--grid", "mu=0.6:0.9:3"],
    ["--sample", "friction=normal:0.8:0.05", "--sample", "F_N=normal:20000:500"],
])
def test_summary_plot(tmp_path: Path, extra: list[str]) -> None:
    png = tmp_path / "s.png"
    rc = main(["sweep", "--model", "tip", "--preset", "table2-tip", *extra, "--samples", "50",
               "--seed", "1", "--increments", "30", "--plot", str(png), "--no-progress"])
    assert rc == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# -- planar: R sweep ------------------------------------------------------------------------
def test_planar_ratio_sweep(tmp_path: Path) -> None:
    from microslip.planar import paper_levels, planar_damping

    rc, out = sweep(tmp_path, "--model", "planar", "--ratio-range", "0.5", "2", "--cases", "3",
                    "--increments", "100")
    assert rc == 0
    t = read_csv(out)
    np.testing.assert_allclose(t["R"], [0.5, 1.0, 2.0], rtol=1e-12)
    at, ac = paper_levels(2.0)
    ref = planar_damping(preset("table2-tip"), preset("table2-centre"), at, ac, increments=100,
                         strain_energy="secant")
    assert abs(t["paper_loss_factor"][2] / ref.paper.loss_factor - 1.0) < 1e-12
    assert abs(t["work_loss_factor"][2] / ref.work_loss_factor - 1.0) < 1e-12


# -- parsing and one-line errors ------------------------------------------------------------
def test_parse_grid_and_sample() -> None:
    assert parse_grid("amplitude=10:1000:3:log")[1].tolist() == pytest.approx([10, 100, 1000])
    assert parse_grid("nu=0.3")[1].tolist() == [0.3]
    assert parse_sample("mu=uniform:0.4:0.6") == ("friction", Distribution("uniform", 0.4, 0.6))


@pytest.mark.parametrize(("args", "message", "code"), [
    (["--grid", "friction=-0.4:0.8:5"], "friction must be finite and in (0, inf), got -0.4 "
     "(grid friction value 0)", 1),
    (["--grid", "colour=1:2:3"], "unknown sweep parameter 'colour'", 1),
    (["--grid", "mu=0.4:0.8"], "expected NAME=START:STOP:COUNT[:log] or NAME=V1,V2,...", 1),
    (["--sample", "mu=gauss:1:2"], "unknown distribution 'gauss'", 1),
    (["--sample", "mu=normal:-1:0.1", "--seed", "1"], "a normal distribution can reach", 1),
    (["--amplitude-range", "100", "400"], "amplitude 357.576 N is at or beyond the macroslip "
     "limit of the tip model (356 N = mu F_N, friction 0.8, normal_force 445 N) (case 85 of "
     "100); microslip needs 0 < amplitude < mu F_N", 1),
    (["--grid", "mu=0.5,0.9", "--amplitude", "300"], "(case 0 of 2)", 1),
    (["--cases", "10"], "--cases sets the number of points of --amplitude-range", 1),
    (["--grid", "mu=0.5", "--sample", "mu=uniform:0.4:0.6"], "friction is given twice", 1),
    (["--amplitude", "100", "--grid", "F0=1,2"], "--amplitude conflicts", 1),
    (["--seed", "-1"], "must be in [0, 2^63)", 2),
    (["--increments", "0"], "increments must be a whole number", 1),
    (["--out", "x.txt"], "output file must end in .csv or .nc", 1),
    (["--plot", "x.gif"], "plot file must end in .png, .pdf or .svg", 1),
    (["--ratio-range", "1", "2"], "--ratio-range does not apply to --model tip", 1),
])
def test_bad_inputs_give_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                  args: list[str], message: str, code: int) -> None:
    out = tmp_path / "never.csv"
    argv = ["sweep", "--model", "tip", "--preset", "table1", "--increments", "10", *args]
    if "--out" not in args:
        argv += ["--out", str(out)]
    rc = main(argv)
    err = capsys.readouterr().err
    assert rc == code
    assert err.count("\n") == 1 and err.startswith("error: ")
    assert message in err
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(("args", "message"), [
    (["--model", "planar", "--ratio-range", "1", "2", "--grid", "mu=1,2"],
     "--grid does not apply to --model planar"),
    (["--model", "planar"], "--model planar needs --ratio-range"),
    (["--model", "planar", "--ratio-range", "0", "2"], "--ratio-range ends must be finite and > 0"),
    (["--model", "planar", "--ratio-range", "1", "2", "--samples", "3"],
     "--samples does not apply to --model planar"),
    (["--model", "planar", "--ratio-range", "1", "2", "--levels", "odd"],
     "unknown level scheme 'odd'"),
])
def test_planar_bad_inputs(capsys: pytest.CaptureFixture[str], args: list[str],
                           message: str) -> None:
    assert main(["sweep", *args, "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err


def test_write_rejects_unknown_extension(tmp_path: Path) -> None:
    spec = make_sweep("tip", preset("table1"), amplitude=100.0, increments=10)
    r = run_sweep(spec, progress=False)
    with pytest.raises(ParameterError, match=r"must end in \.csv or \.nc"):
        write_sweep(r, tmp_path / "r.json")


def test_make_sweep_rejects_contradictions() -> None:
    base = preset("table1")
    with pytest.raises(ParameterError, match=r"amplitude 100\.0 N is given but the amplitude is "
                       "also a grid axis"):
        make_sweep("tip", base, amplitude=100.0, grid=[("F0", [10.0, 20.0])])
    with pytest.raises(ParameterError, match="give an amplitude"):
        make_sweep("tip", base, grid=[("mu", [0.5])])
    with pytest.raises(ParameterError, match="grid width has no values"):
        make_sweep("tip", base, amplitude=10.0, grid=[("width", [])])
    with pytest.raises(ParameterError, match=r"at most 100000000 are allowed"):
        make_sweep("tip", base, amplitude=10.0, grid=[("width", np.linspace(1, 2, 20000)),
                                                      ("length", np.linspace(1, 2, 20000))])


def test_sweep_planar_takes_the_clamp(capsys, tmp_path):
    out = tmp_path / "r.csv"
    code, text, err = run(capsys, "sweep", "--model", "planar", "--ratio-range", "1", "1",
                          "--cases", "1", "--no-progress", "--thickness", "100", "--out", out)
    assert code == 0, err
    assert "thickness 100" in text
    code, text2, err = run(capsys, "planar", "--ratio", "1", "--thickness", "100",
                           "--strain-energy", "secant", "--increments", "1000", "--json")
    header, values = (line.split(",") for line in out.read_text().splitlines())
    assert float(values[header.index("paper_loss_factor")]) == pytest.approx(
        json.loads(text2)["paper_loss_factor"], rel=1e-12)


# --- one bad Monte-Carlo draw no longer aborts a sweep ---------------------------------------

def test_bad_draws_are_failed_rows_with_reasons_and_the_rest_is_computed(capsys, tmp_path):
    import numpy as np

    from microslip import preset
    from microslip.batch import batch_damping
    from microslip.sweep import make_sweep, run_sweep
    from microslip.sweep.parameters import Distribution

    spec = make_sweep("tip", preset("table2-tip"), amplitude=6000.0,
                      samples=[("friction", Distribution("normal", 0.5, 0.3))], n_samples=300,
                      seed=1, increments=50, check_draws=False)
    mu = spec.column("friction")
    res = run_sweep(spec, progress=False, failures="record", chunk_size=64)
    negative = mu <= 0
    beyond = ~negative & (6000.0 >= mu * 20000.0)
    assert negative.any() and beyond.any() and (~negative & ~beyond).any()
    assert sorted(res.failures) == np.flatnonzero(negative | beyond).tolist()
    assert all("friction must be finite" in res.failures[i] for i in np.flatnonzero(negative))
    assert all("macroslip" in res.failures[i] for i in np.flatnonzero(beyond))
    assert np.isnan(res.loss_factor[negative | beyond]).all()
    good = ~negative & ~beyond
    ref = batch_damping("tip", preset("table2-tip").as_dict() | {"friction": mu[good]}, 6000.0,
                        50)
    assert np.array_equal(res.loss_factor[good], ref.loss_factor)  # bit for bit
    with pytest.raises(ParameterError, match="friction must be finite"):
        run_sweep(spec, progress=False)  # the library default still stops at the first


def test_sweep_cli_summarises_failures_and_writes_nan_rows(capsys, tmp_path):
    out = tmp_path / "mc.csv"
    code, _, err = run(capsys, "sweep", "--model", "tip", "--preset", "table2-tip",
                          "--amplitude", "6000", "--sample", "friction=normal:0.5:0.3",
                          "--samples", "200", "--seed", "1", "--increments", "50",
                          "--no-progress", "--out", out, "--plot", tmp_path / "mc.png")
    assert code == 0, err
    assert err.startswith("warning: ") and err.count("\n") == 1
    assert "of 200 cases not computed (results nan)" in err and "e.g. case" in err
    rows = out.read_text().splitlines()[1:]
    failed = int(err.split("warning: ")[1].split(" of ")[0])
    assert len(rows) == 200 and sum(r.endswith(",nan") for r in rows) == failed > 0
    assert (tmp_path / "mc.png").stat().st_size > 0


def test_a_sweep_where_no_draw_can_be_computed_is_an_error_and_writes_nothing(capsys,
                                                                              tmp_path):
    one_line_error(run(capsys, "sweep", "--model", "tip", "--sample", "mu=normal:0.1:0.2",
                       "--samples", "50", "--seed", "1", "--no-progress", "--out",
                       tmp_path / "s.csv"),
                   "no case can be computed", "50 of 50", "macroslip", "use lognormal")
    assert listing(tmp_path) == []


def test_a_grid_value_beyond_the_limit_is_still_an_error_before_the_work(capsys, tmp_path):
    one_line_error(run(capsys, "sweep", "--model", "tip", "--amplitude-range", "100", "400",
                       "--cases", "4", "--no-progress", "--out", tmp_path / "s.csv"),
                   "amplitude 400 N is at or beyond the macroslip limit", "(case 3 of 4)")
    assert listing(tmp_path) == []


def test_sweep_grid_values_in_the_wrong_unit_warn(capsys):
    code, _, err = run(capsys, "sweep", "--model", "tip", "--amplitude", "100", "--grid",
                       "E=70000,2.1e11", "--increments", "20", "--no-progress")
    assert code == 0
    assert err == ("warning: --grid modulus: modulus 2.1e+11 MPa is above 1e+07 MPa: pascals "
                   "given as MPa?\n")
