"""Rough edges of the command line (issue 14, item 3): each fixed, each tested here.

Every failure is one ``error:`` line on standard error, exit code 1, and nothing is left
behind: the checks run before the work, and files are written atomically.
"""

from __future__ import annotations

import json
import os

import pytest
from conftest import listing, one_line_error, run

from microslip.cli.main import main
from microslip.errors import ParameterError
from microslip.io import check_writable, staged_directory

# --- unwritable outputs: refused before the work, nothing left behind -----------------------

UNWRITABLE = [
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--cases", "3",
     "--no-progress", "--out", "{bad}.csv"),
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--cases", "3",
     "--no-progress", "--plot", "{bad}.png"),
    ("sweep", "--model", "planar", "--ratio-range", "1", "2", "--cases", "2",
     "--no-progress", "--out", "{bad}.csv"),
    ("loop", "--model", "tip", "--increments", "100", "--plot", "{bad}.png"),
    ("planar", "--ratio", "1", "--increments", "100", "--plot", "{bad}.png"),
    ("validate", "--out", "{bad}"),
    ("reproduce", "--out", "{bad}"),
    ("fe", "--model", "tip", "--out", "{bad}"),
]


@pytest.mark.parametrize("argv", UNWRITABLE, ids=lambda a: " ".join(a[:2]))
@pytest.mark.parametrize("where", ["under_a_file", "proc"])
def test_unwritable_outputs_are_one_line_before_the_work(capsys, tmp_path, argv, where):
    (tmp_path / "afile").write_text("x")
    bad = str(tmp_path / "afile" / "x") if where == "under_a_file" else "/proc/microslip-x"
    before = listing(tmp_path)
    one_line_error(run(capsys, *(a.format(bad=bad) for a in argv)), "cannot write")
    assert listing(tmp_path) == before


@pytest.mark.parametrize("argv", [
    ("loop", "--model", "tip", "--plot", "{d}/out.txt"),
    ("planar", "--ratio", "1", "--plot", "{d}/out.txt"),
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--plot", "{d}/out.txt"),
    ("sweep", "--model", "tip", "--amplitude-range", "100", "200", "--out", "{d}/out.txt"),
], ids=lambda a: " ".join(a[:2]))
def test_unknown_output_formats_are_refused_before_the_work(capsys, tmp_path, argv):
    allowed = ".csv" if argv[-2] == "--out" else ".png"
    one_line_error(run(capsys, *(a.format(d=tmp_path) for a in argv)), "out.txt", allowed)
    assert listing(tmp_path) == []


def test_a_plot_path_that_is_a_directory_is_refused(capsys, tmp_path):
    (tmp_path / "fig.png").mkdir()
    one_line_error(run(capsys, "loop", "--model", "tip", "--plot", tmp_path / "fig.png"),
                   "must be a file, got the directory")


def test_check_writable_names_the_reason():
    with pytest.raises(ParameterError, match="must be a directory, got the file"):
        check_writable(__file__, directory=True)
    with pytest.raises(ParameterError, match=r"must end in \.csv"):
        check_writable("x.txt", (".csv",))


def test_check_writable_creates_nothing(tmp_path):
    target = tmp_path / "a" / "b" / "c.csv"
    assert check_writable(target, (".csv",)) == target
    assert listing(tmp_path) == []


def test_write_failures_after_the_checks_are_one_line(capsys, tmp_path, monkeypatch):
    def full_disk(*args, **kwargs):
        raise OSError(28, "No space left on device", str(tmp_path / "x.png"))

    monkeypatch.setattr("microslip.plot.plot_damping", full_disk)
    one_line_error(run(capsys, "loop", "--model", "tip", "--increments", "50", "--plot",
                       tmp_path / "x.png"), "No space left on device", "x.png")


# --- an interrupted reproduce leaves no partial directory ------------------------------------

@pytest.mark.parametrize("exists", [False, True])
def test_interrupted_reproduce_leaves_no_partial_directory(capsys, tmp_path, monkeypatch,
                                                           exists):
    import microslip.reproduce as rep

    out = tmp_path / "new" / "paper"
    if exists:
        out.mkdir(parents=True)
        (out / "old.txt").write_text("kept")
    before = listing(tmp_path)

    def interrupted(out_dir, **kwargs):
        (out_dir / "fig10.png").write_bytes(b"half")
        raise KeyboardInterrupt

    monkeypatch.setattr(rep, "reproduce", interrupted)
    code, _, err = run(capsys, "reproduce", "--out", out, "--quiet")
    assert code == 130 and err == "error: interrupted\n"
    assert listing(tmp_path) == before


def test_staged_directory_publishes_on_success_only(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    (target / "keep.txt").write_text("old")
    (target / "sub").mkdir()
    (target / "sub" / "stale.txt").write_text("old")
    with staged_directory(target) as stage:
        (stage / "sub").mkdir()
        (stage / "sub" / "new.txt").write_text("new")
        (stage / "keep.txt").write_text("new")
    assert listing(tmp_path) == ["out", "out/keep.txt", "out/sub", "out/sub/new.txt"]
    assert (target / "keep.txt").read_text() == "new"


def test_staged_directory_gives_a_new_directory_the_usual_permissions(tmp_path):
    (tmp_path / "reference").mkdir()
    with staged_directory(tmp_path / "out") as stage:
        (stage / "a.txt").write_text("a")
    mode = os.stat(tmp_path / "out").st_mode
    assert mode == os.stat(tmp_path / "reference").st_mode
    assert (tmp_path / "out" / "a.txt").read_text() == "a"


# --- options that do nothing in a mode are refused with the reason ---------------------------

@pytest.mark.parametrize("argv, flag, mode", [
    (["planar", "--solver", "fe", "--tip-amplitude", "100", "--centre-amplitude", "100",
      "--plot", "x.png"], "--plot", "--solver fe"),
    (["planar", "--solver", "fe", "--tip-amplitude", "100", "--centre-amplitude", "100",
      "--strain-energy", "secant"], "--strain-energy", "--solver fe"),
    (["planar", "--ratio", "1", "--mesh", "tiny"], "--mesh", "--solver analytical"),
    (["planar", "--ratio", "1", "--cycles", "3"], "--cycles", "--solver analytical"),
    (["planar", "--ratio", "1", "--preset", "table1"], "--preset", "--solver analytical"),
    (["sweep", "--model", "planar", "--ratio-range", "1", "2", "--seed", "1"], "--seed",
     "--model planar"),
    (["sweep", "--model", "tip", "--amplitude-range", "1", "2", "--levels", "base"],
     "--levels", "--model tip"),
], ids=lambda v: v if isinstance(v, str) else None)
def test_options_a_mode_ignores_are_refused(capsys, tmp_path, argv, flag, mode):
    one_line_error(run(capsys, *argv), f"{flag} does not apply to {mode}")
    assert listing(tmp_path) == []


def test_default_values_of_other_modes_are_not_refused(capsys):
    code, _, err = run(capsys, "planar", "--ratio", "1", "--increments", "50")
    # only the validity warnings of the squat Table 2 zones, no refusal
    assert code == 0 and all(line.startswith("warning: ") for line in err.splitlines())


# --- custom geometry everywhere --------------------------------------------------------------

def test_planar_clamp_flags_change_the_zones(capsys):
    base = run(capsys, "planar", "--ratio", "1", "--increments", "100", "--json")
    longer = run(capsys, "planar", "--ratio", "1", "--increments", "100", "--json",
                 "--length", "100")
    a, b = (json.loads(r[1]) for r in (base, longer))
    assert "tip_params" not in a
    assert b["tip_params"]["length"] == b["centre_params"]["length"] == 100.0
    # Table 2's reading (interpretation.md §6): the tip zone is half the contact width
    assert b["tip_params"]["width"] == 25.0 and b["centre_params"]["width"] == 50.0
    assert b["tip_params"]["thickness"] == b["centre_params"]["thickness"] == 10.0
    # the rigid-foundation d0 ~ F0^2 / (E A q) with q = mu F_N / L: proportional to L
    ratio = b["tip"]["peak_displacement_mm"] / a["tip"]["peak_displacement_mm"]
    assert ratio == pytest.approx(2.0, rel=0.05)


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


# --- increments: a useful minimum and a cost estimate ---------------------------------------

@pytest.mark.parametrize("argv", [
    ["loop", "--model", "tip"], ["planar", "--ratio", "1"], ["reproduce", "--out", "{d}/r"],
    ["sweep", "--model", "tip", "--amplitude-range", "100", "200", "--no-progress"],
    ["sweep", "--model", "planar", "--ratio-range", "1", "2", "--no-progress"],
], ids=lambda a: a[0])
@pytest.mark.parametrize("n", [1, 9])
def test_too_few_increments_are_refused_with_the_error_they_give(capsys, tmp_path, argv, n):
    args = [a.format(d=tmp_path) for a in argv]
    one_line_error(run(capsys, *args, "--increments", n), ">= 10", f"got {n}", "1/n^2")
    assert listing(tmp_path) == []


def test_ten_increments_give_eta_one_percent_low(capsys):
    from microslip.cli.common import MIN_INCREMENTS

    etas = [json.loads(run(capsys, "loop", "--model", "centre", "--no-corrections", "--json",
                           "--increments", n)[1])["loss_factor"] for n in (MIN_INCREMENTS, 1000)]
    # the quadratic backbone's trapezoidal loop: eta (1 - 1/n^2), exactly
    assert etas[0] / etas[1] == pytest.approx((1 - 1 / MIN_INCREMENTS**2) / (1 - 1e-6),
                                              rel=1e-12)


def test_costly_increments_warn_with_time_and_memory(capsys, monkeypatch):
    import microslip.cli.common as common

    monkeypatch.setattr(common, "WARN_SECONDS", 1e-4)  # 100 increments x 2.5e-6 s > 1e-4 s
    code, out, err = run(capsys, "loop", "--model", "tip", "--increments", "100", "--json")
    assert code == 0
    expected = ("--increments 100 for 1 loading(s) takes about 0.00025 s and 2.5e-05 GB of "
                "memory; eta is within 1e-6 at 1000 increments (its error is 1/n^2)")
    assert err == f"warning: {expected}\n"
    assert json.loads(out)["warnings"] == [expected]
    monkeypatch.setattr(common, "WARN_SECONDS", 0.00026)
    assert run(capsys, "loop", "--model", "tip", "--increments", "100")[2] == ""


def test_a_sweep_warns_with_the_cost_of_all_its_cases(capsys, monkeypatch):
    import microslip.cli.common as common

    monkeypatch.setattr(common, "WARN_SECONDS", 1e-7)  # 5 cases x 20 increments x 1e-8 s
    code, _, err = run(capsys, "sweep", "--model", "tip", "--amplitude-range", "100", "200",
                       "--cases", "5", "--increments", "20", "--no-progress")
    assert code == 0
    assert err == ("warning: --increments 20 for 5 loading(s) takes about 1e-06 s; eta is "
                   "within 1e-6 at 1000 increments (its error is 1/n^2)\n")


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


# --- figures ---------------------------------------------------------------------------------

def _figure_of(monkeypatch):
    import microslip.plot.core as core

    saved = []
    monkeypatch.setattr(core, "save_figure", lambda fig, path: saved.append(fig))
    for module in ("microslip.plot.sweep",):
        monkeypatch.setattr(f"{module}.save_figure", lambda fig, path: saved.append(fig))
    return saved


def test_sweep_figure_has_eta_and_wd_panels_without_offsets(monkeypatch, tmp_path):
    from microslip import preset
    from microslip.plot.sweep import plot_sweep
    from microslip.sweep import make_sweep, run_sweep

    saved = _figure_of(monkeypatch)
    spec = make_sweep("tip", preset("table2-tip"), grid=[("amplitude", [1000.0, 1000.5, 1001.0]),
                      ("normal_force", [15000.0, 20000.0])], increments=50)
    plot_sweep(run_sweep(spec, progress=False), tmp_path / "s.png")
    (fig,) = saved
    fig.canvas.draw()
    eta_ax, wd_ax = fig.axes
    assert "Loss factor" in eta_ax.get_ylabel() and "$W_d$ (N·mm)" in wd_ax.get_ylabel()
    for ax in fig.axes:
        assert ax.yaxis.get_major_formatter().get_offset() == ""
    labels = [t.get_text() for t in eta_ax.get_legend().get_texts()]
    assert labels == ["normal force = 15000 N", "normal force = 20000 N"]  # the unit once


def test_sweep_figure_bands_carry_the_series_colour(monkeypatch, tmp_path):
    from matplotlib.colors import to_hex

    from microslip import preset
    from microslip.plot.core import COLOURS
    from microslip.plot.sweep import plot_sweep
    from microslip.sweep import make_sweep, run_sweep
    from microslip.sweep.parameters import Distribution

    saved = _figure_of(monkeypatch)
    spec = make_sweep("tip", preset("table2-tip"), grid=[("amplitude", [1000.0, 4000.0])],
                      samples=[("friction", Distribution("uniform", 0.7, 0.9))], n_samples=20,
                      seed=2, increments=50)
    plot_sweep(run_sweep(spec, progress=False), tmp_path / "s.png")
    legend = saved[0].axes[0].get_legend()
    patches = [h for h in legend.legend_handles if hasattr(h, "get_facecolor")
               and not hasattr(h, "get_xdata")]
    assert patches and {to_hex(p.get_facecolor(), keep_alpha=False) for p in patches} == {
        COLOURS[0].lower()}


def test_small_loops_are_drawn_in_micrometres(monkeypatch, tmp_path):
    import microslip.plot.core as core
    from microslip import damping, preset

    saved = []
    monkeypatch.setattr(core, "save_figure", lambda fig, path: saved.append(fig))
    result = damping("tip", preset("table1"), 267.0, 100)
    core.plot_damping(result, tmp_path / "x.png")
    ax = saved[0].axes[0]
    assert ax.get_xlabel() == "Displacement δ (µm)"
    x = ax.get_lines()[0].get_xdata()
    assert max(abs(x)) == pytest.approx(1000 * max(abs(result.loop.displacement)), rel=1e-15)
    saved[0].canvas.draw()
    assert ax.xaxis.get_major_formatter().get_offset() == ""


# --- implausible units and the stated default amplitude --------------------------------------

def test_sweep_grid_values_in_the_wrong_unit_warn(capsys):
    code, _, err = run(capsys, "sweep", "--model", "tip", "--amplitude", "100", "--grid",
                       "E=70000,2.1e11", "--increments", "20", "--no-progress")
    assert code == 0
    assert err == ("warning: --grid modulus: modulus 2.1e+11 MPa is above 1e+07 MPa: pascals "
                   "given as MPa?\n")


def test_the_case_default_amplitude_is_stated_as_a_fraction_of_the_slip_limit(capsys,
                                                                              tmp_path):
    path = tmp_path / "c.toml"
    path.write_text('preset = "table1"\n[contact]\nfriction = 0.5\n[clamping]\n'
                    "normal_force = 12000\n[load]\namplitude_fraction = 0.25\n")
    code, out, err = run(capsys, "loop", "--case", path, "--model", "tip", "--increments",
                         "20")
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0] == f"case file {path}"
    assert lines[1] == ("  amplitude F0 = 0.25 x the slip limit mu F_N = 0.25 x 0.5 x 12000 N "
                        "= 1500 N (load.amplitude_fraction)")
    assert "amplitude F0                   1500 N" in out


# --- Ctrl-C: prompt, one line, nothing left ---------------------------------------------------

@pytest.mark.parametrize("argv, made", [
    (["sweep", "--model", "tip", "--amplitude-range", "10", "300", "--cases", "2000000",
      "--no-progress", "--out", "{d}/big.csv"], "big.csv"),
    (["reproduce", "--out", "{d}/paper", "--quiet", "--increments", "200000"], "paper"),
], ids=["sweep", "reproduce"])
def test_ctrl_c_stops_promptly_and_leaves_nothing(tmp_path, argv, made):
    """Both runs first warn of their cost: the interrupt comes a second after, in the work."""
    import signal
    import subprocess
    import sys
    import time

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    args = [a.format(d=tmp_path) for a in argv]
    proc = subprocess.Popen([sys.executable, "-m", "microslip", *args], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stderr is not None
    warning = proc.stderr.readline()
    assert warning.startswith("warning: --increments")
    time.sleep(1.0)
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert time.perf_counter() - t0 < 5.0
    assert proc.returncode == 130 and err == "error: interrupted\n", err[-2000:]
    assert not (tmp_path / made).exists() and listing(tmp_path) == []


def test_an_interrupt_wrapped_by_a_library_is_still_an_interrupt(capsys, monkeypatch):
    """numba and others may re-raise Ctrl-C as their own error: still one line, exit 130."""
    import microslip.cli.loop as loop

    def wrapped(*args, **kwargs):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise RuntimeError("compilation failed") from exc

    monkeypatch.setattr(loop, "damping", wrapped)
    assert main(["loop", "--model", "tip"]) == 130
    assert capsys.readouterr().err == "error: interrupted\n"
