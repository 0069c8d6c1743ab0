"""The chain on parts whose contact lifts off (issue 28 items 1-2): the EPMC reaches an
amplitude that Newton misses from the last point through amplitudes in between, an
amplitude it still misses is NaN with its reason, ``--solver all`` keeps every other solver
when one fails and its verdict says why, and (slow) ``modal --mesh examples/bracket.inp
--solver all`` runs with verdicts, the full FE's lowest amplitude at the stuck
frequency."""

from __future__ import annotations

import contextlib
import io
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import microslip.dynamics.modal as modal
from microslip.cli.main import main
from microslip.dynamics import jenkins
from microslip.dynamics.modal import epmc
from microslip.dynamics.structure import one_mode
from microslip.meshdynamics.modalstudy import _verdict

AMPS = np.geomspace(1e-3, 0.3, 6)  # mm; the joint slips from about 0.01 mm
STRUCTURE = one_mode(100.0, 2.0, 0.02, jenkins(300.0, 5.0), participation=0.7)


def _short_reach(monkeypatch: pytest.MonkeyPatch, ratio: float,
                 amplitudes: list[float]) -> None:
    """A Newton that converges only from a point less than ``ratio`` away in amplitude (the
    scale's first entry is the target amplitude, the start's the last one reached; the
    stuck mode reaches the first)."""
    real = modal.newton

    def newton(fun: Any, y0: Any, scale: Any, tol: float, max_iter: int = 12,
               factors: Any = None) -> Any:
        y, ok, jac = real(fun, y0, scale, tol, max_iter=max_iter, factors=factors)
        target = float(scale[0])
        previous = amplitudes[-1] if amplitudes else target
        if ok:
            if target / previous > ratio:
                return y0, False, jac
            amplitudes.append(target)
        return y, ok, jac

    monkeypatch.setattr(modal, "newton", newton)


def test_epmc_reaches_far_amplitudes_through_amplitudes_in_between(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """The grid's steps are a factor 3 apart; Newton here reaches only a factor 1.8: the
    EPMC halves the step in log amplitude (sqrt 3 = 1.73) and gives the same curve as an
    unrestricted Newton, to its tolerance."""
    free = epmc(STRUCTURE, AMPS, 3, 128)
    reached: list[float] = []
    _short_reach(monkeypatch, 1.8, reached)
    c = epmc(STRUCTURE, AMPS, 3, 128)
    np.testing.assert_allclose(c.frequency, free.frequency, rtol=1e-10)
    np.testing.assert_allclose(c.damping_ratio, free.damping_ratio, rtol=1e-8)
    assert len(reached) > AMPS.size  # it went through amplitudes in between
    assert set(AMPS.tolist()) <= {float(a) for a in reached}


def test_an_amplitude_still_missed_is_nan_with_its_reason(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """With halvings exhausted (Newton reaches only a factor 1.01), ``failures`` collects one
    reason per amplitude missed and those amplitudes are NaN, the next starting from the
    last point reached; without ``failures`` the first one missed raises as before."""
    monkeypatch.setattr(modal, "SUBSTEPS", 1)
    _short_reach(monkeypatch, 1.01, [])
    failures: list[str] = []
    c = epmc(STRUCTURE, AMPS, 3, 128, failures=failures)
    assert np.isfinite(c.frequency[0]) and np.isfinite(c.damping_ratio[0])
    assert np.all(np.isnan(c.frequency[1:])) and np.all(np.isnan(c.damping_ratio[1:]))
    assert failures == [f"the extended periodic motion concept did not converge at "
                        f"amplitude {a:.6g} mm" for a in AMPS[1:]]
    with pytest.raises(ValueError, match=f"did not converge at amplitude {AMPS[1]:.6g} mm"):
        epmc(STRUCTURE, AMPS, 3, 128)


FE = {"amplitude_mm": [0.01, 0.02, 0.04], "frequency_Hz": [100.0, 98.0, 95.0],
      "damping_ratio": [0.01, 0.02, 0.04]}
WHY = "the extended periodic motion concept did not converge at amplitude 0.04 mm"


def test_a_failed_solver_verdict_says_why() -> None:
    """Every amplitude failed: the verdict is the reason, and it does not meet its
    targets; failed at some: the verdict on the others, then the reason."""
    none: list[float | None] = [None, None, None]
    v = _verdict("rom", FE, {"amplitude_mm": none, "frequency_Hz": none,
                             "damping_ratio": none}, (WHY,))
    assert v["verdict"] == f"rom: {WHY}" and v["meets_targets"] is False
    assert v["points"] == 0
    part = {"amplitude_mm": [0.01, 0.02, None], "frequency_Hz": [100.0, 98.0, None],
            "damping_ratio": [0.01, 0.02, None]}
    v = _verdict("rom", FE, part, (WHY, WHY))
    assert v["points"] == 2 and v["meets_targets"] is True
    assert v["verdict"].endswith(f"meets the targets (0.5 %, 5 %); {WHY} (and 1 more "
                                 "amplitudes)")
    assert _verdict("rom", FE, part, ())["verdict"].endswith("(0.5 %, 5 %)")


BRACKET = Path(__file__).resolve().parents[1] / "examples" / "bracket.inp"


@pytest.mark.slow
def test_modal_solver_all_runs_on_the_bracket_with_verdicts() -> None:
    """A part that lifts off (49 of 91 contact nodes open after clamping, penalty): every
    solver's rows and a verdict on each; the full FE's lowest amplitude is below the first
    closing of an open node, at the stuck frequency (1e-6). Before: the ROM's EPMC stopped
    the whole command ("did not converge at amplitude 0.0026 mm")."""
    argv = ["modal", "--mesh", str(BRACKET), "--contact-set", "contact", "--clamp-set",
            "clamp", "--normal-force", "2000", "--friction", "0.5", "--stick-slope", "1e4",
            "--modulus", "70000", "--poisson-ratio", "0.33", "--density", "2700",
            "--normal-contact", "penalty", "--response-set", "response", "--mode", "1",
            "--amplitudes", "3", "--harmonics", "3", "--solver", "all", "--json"]
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert main(argv) == 0
    d = json.loads(out.getvalue())
    assert set(d["solvers"]) == {"fe", "rom", "interface", "joint"}
    assert set(d["verdicts"]) == {"rom", "interface", "joint"}
    assert all(v["verdict"] for v in d["verdicts"].values())
    fe = d["solvers"]["fe"]
    stuck = d["linear_frequencies_Hz"][0]
    assert math.isclose(fe["frequency_Hz"][0], stuck, rel_tol=1e-6)
    assert fe["damping_ratio"][0] < 1e-8  # linear: nothing slips yet
    rom = d["solvers"]["rom"]
    assert math.isclose(rom["frequency_Hz"][0], stuck, rel_tol=1e-4)
