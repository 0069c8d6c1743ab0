"""Options that do nothing in the chosen mode (``planar --solver``, ``sweep --model``) are
refused with the reason, one line (issue 14, item 3); their defaults are not.
"""

from __future__ import annotations

import pytest
from conftest import listing, one_line_error, run


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
