"""``--increments`` on every command (issue 14, item 3): below the useful minimum it is
refused with the error it would give, and a costly count is warned of with its time and memory.
"""

from __future__ import annotations

import json

import pytest
from conftest import listing, one_line_error, run


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
