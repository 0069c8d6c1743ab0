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
from .models import MODELS
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
    return time.perf_counter() - start


def main() -> int:
    seconds = warm_up()
    print(f"microslip: compiled kernels ready ({seconds:.1f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
