"""Compile and cache the numba kernels once (``python -m microslip.warmup``).

``scripts/setup.sh`` runs this after installing, so that a user's first sweep does not pay
the compilation (about 10 s); numba keeps the machine code in its cache next to the source.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from .batch.driver import batch_damping
from .energy import STRAIN_ENERGY, damping
from .models import MODELS, Contact
from .options import CENTRE_READINGS, POISSON_MODES, ModelOptions
from .params import preset


def warm_up() -> float:
    """Run every compiled kernel once on a tiny batch; the seconds it took."""
    start = time.perf_counter()
    amplitude = np.array([10.0, 20.0])
    for model in MODELS:
        damping(model, preset("table1"), 10.0, 4)  # the single-loop recorder and energies
        for kind in STRAIN_ENERGY:
            for poisson in POISSON_MODES:
                for reading in CENTRE_READINGS:
                    opt = ModelOptions(poisson=poisson, centre=reading)
                    batch_damping(model, preset("table1"), amplitude, increments=4,
                                  options=opt, strain_energy=kind)
        layer = Contact.layer(1e5, "parabolic")  # one compiled form for every pressure law
        damping(model, preset("table1"), 10.0, 4, contact=layer)
        batch_damping(model, preset("table1"), amplitude, increments=4, contact=layer)
    _warm_up_dynamics()
    return time.perf_counter() - start


def _warm_up_dynamics() -> None:
    """The Iwan operators' kernels (periodic, AFT, history; 1-D and circular) and the
    time steppers."""
    from .dynamics import jenkins
    from .dynamics.operators2d import circular
    from .dynamics.structure import one_mode
    from .dynamics.timeint import steady_state, transient

    joint = jenkins(100.0, 5.0)
    x = 0.1 * np.cos(np.linspace(0.0, 2.0 * np.pi, 16, endpoint=False))
    joint.periodic_force(x)
    joint.periodic_force_projected(x, np.eye(16)[:, :3])
    joint.periodic_harmonics(np.array([0.0, 0.1, 0.0]), np.eye(16, 3), np.eye(3, 16))
    joint.force_history(x)
    circular(joint).periodic_force_projected(np.column_stack([x, 0.5 * x]), np.eye(16)[:, :3])
    structure = one_mode(100.0, 1.0, 0.01, joint)
    steady_state(structure, 1.0, 100.0, periods=2, steps=16)
    transient(structure, np.ones(1), 100.0, periods=2, steps=16)


def main() -> int:
    seconds = warm_up()
    print(f"microslip: compiled kernels ready ({seconds:.1f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
