"""A contact node that ends the clamping step sliding at its friction limit is a legal state
(issue 35, item 3). The FE's clamping step lags the limits by one pass, so such a node's
force can sit above mu N_0 by a few 1e-9 of it; the penalty ROM refused it ("stick force
0.0686894 N exceeds the friction limit mu N_0 = 0.0686894 N") on ``bolt_pad.inp`` under
penalty 1e5. It now starts on its limit circle."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from microslip.fe.clamp import MeshClamp, clamped_model
from microslip.fe.meshfile import read_mesh
from microslip.meshdynamics.reduce import build_rom, clamped_stick_force, rom_structure

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _bolt_pad() -> object:
    clamp = MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
                      poisson_ratio=0.33, friction=0.5, stick_slope=1e4,
                      normal_contact="penalty", normal_slope=1e5)
    return clamped_model(read_mesh(str(EXAMPLES / "bolt_pad.inp")), clamp)


def test_a_node_sliding_at_its_limit_after_clamping_starts_on_it() -> None:
    model = _bolt_pad()
    u = np.asarray(model.u0)[model.contact_dofs]  # type: ignore[attr-defined]
    raw = model.contact_stiffness[:, None] * (u - model.slip0)  # type: ignore[attr-defined]
    limit = model.friction * np.maximum(model.preload, 0.0)  # type: ignore[attr-defined]
    assert np.any(np.hypot(*raw.T) > limit * (1.0 + 1e-9))  # the FE's state: the bug's case
    over = np.hypot(*raw.T) > limit
    t0 = clamped_stick_force(model)  # type: ignore[arg-type]
    size = np.hypot(*t0.T)
    assert np.all(size <= limit * (1.0 + 1e-12))
    np.testing.assert_allclose(size[over], limit[over], rtol=1e-12)  # on the circle
    np.testing.assert_allclose(t0[over] / size[over, None], raw[over]
                               / np.hypot(*raw[over].T)[:, None], atol=1e-12)  # same way
    np.testing.assert_array_equal(t0[~over], raw[~over])  # the others as the FE left them
    rom = build_rom(model, 2700.0, modes=4)  # type: ignore[arg-type]
    structure = rom_structure(rom)  # refused before
    # at rest the pre-slipped element stays where the clamping left it: no force change
    for link in structure.joints:
        f = link.operator.periodic_force(np.zeros((16, 3)))
        assert np.max(np.abs(f)) < 1e-12
