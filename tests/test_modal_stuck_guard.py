"""A reduced model whose stuck frequency misses the full FE's at zero amplitude by more than
0.1 % says so, and ``--solver all`` does not let it stand in for the contact-node ROM
(issue 35, item 1)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from microslip.meshdynamics import modalstudy
from microslip.meshdynamics.modalstudy import ROM_NODE_LIMIT, STUCK_TOLERANCE, stuck_check


def _study(nodes: int = 10) -> SimpleNamespace:
    model = SimpleNamespace(contact_nodes=np.arange(nodes), normal=None)
    return SimpleNamespace(mode=SimpleNamespace(frequency_Hz=1000.0),
                           prepared=SimpleNamespace(model=model))


def test_the_stuck_frequency_nearest_the_mode_is_checked() -> None:
    figures, warn = stuck_check(_study(), [500.0, 1000.5, 2000.0], "interface model")  # type: ignore[arg-type]
    assert figures["stuck_frequency_Hz"] == 1000.5
    assert abs(figures["stuck_frequency_error"] - 5e-4) < 1e-12 and warn == []
    figures, warn = stuck_check(_study(), [500.0, 1056.0], "interface model")  # type: ignore[arg-type]
    assert abs(figures["stuck_frequency_error"] - 0.056) < 1e-12
    assert len(warn) == 1 and "+5.60 % off the full FE's" in warn[0]


def test_a_model_that_misses_it_does_not_stand_in_for_the_rom(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    def compare(study: object, curves: object, error: float = 0.056) -> dict:
        return {"solvers": {"interface": {"interface": {"stuck_frequency_error": error}}},
                "verdicts": {"interface": {"verdict": "interface: within ...",
                                           "meets_targets": True}},
                "warnings": []}

    monkeypatch.setattr(modalstudy, "run_solvers", lambda *a, **k: {})
    monkeypatch.setattr(modalstudy, "compare_output", compare)
    _, out = modalstudy.compare_all(_study(ROM_NODE_LIMIT + 1))  # type: ignore[arg-type]
    assert out["verdicts"]["interface"]["meets_targets"] is False
    assert "does not stand in for the contact-node ROM" in out["verdicts"]["interface"]["verdict"]
    assert any(w.startswith("rom: left out") for w in out["warnings"])
    monkeypatch.setattr(modalstudy, "compare_output",
                        lambda s, c: compare(s, c, 0.5 * STUCK_TOLERANCE))
    _, out = modalstudy.compare_all(_study(ROM_NODE_LIMIT + 1))  # type: ignore[arg-type]
    assert out["verdicts"]["interface"]["meets_targets"] is True
