"""Compile and cache the numba kernels the first command needs (``python -m microslip.warmup``).

``scripts/setup.sh`` runs this after installing. The first command of the Quickstart is
``microslip reproduce``; what it runs compiled is compiled here, once per machine (numba
keeps the machine code in its cache next to the source):

* the models' kernels (:mod:`microslip.models.compiled`): its tables and validation run
  thousands of loops, beyond the plain-Python budget of one process
  (:data:`microslip.models.PLAIN_STEPS`);
* the Iwan operators' kernels (1-D and circular 2-D, periodic, harmonic, history), the 3-D
  contact element and the time steppers of the joint and structure studies.

Not here: a single ``microslip loop`` (or :func:`microslip.damping` at its default 1000
increments) runs the models as plain Python and needs no compiled code; the batch engine's
parallel kernels (``microslip sweep``, :func:`microslip.batch_damping`) are compiled by the
first command that uses them (about 30 s of CPU), once, and cached. Time: about 50 s of CPU,
about a minute on an idle 2-core machine, several minutes on a loaded one (the message says
how long it took).
"""

from __future__ import annotations

import sys
import time

import numpy as np


def warm_up() -> float:
    """Run every kernel the first ``reproduce`` compiles once on a tiny case; the seconds it
    took."""
    start = time.perf_counter()
    _warm_up_models()
    _warm_up_dynamics()
    return time.perf_counter() - start


def _warm_up_models() -> None:
    """The models' compiled kernels: rigid and layered backbones, the Masing sums, the
    shear-layer curves of the validity checks."""
    from .energy import damping
    from .models import MODELS, Contact, compiled  # noqa: F401  (compiled from here on)
    from .models.interface import virgin_curve
    from .params import preset

    p = preset("table1")
    for model, spec in MODELS.items():
        damping(model, p, 10.0, 4)
        for law in ("uniform", "parabolic"):
            contact = Contact.layer(1e5, law)
            damping(model, p, 10.0, 4, contact=contact)
            virgin_curve(spec.load_case, p, np.array([1.0, 2.0]), stick_slope=1e5,
                         law=contact.law)


def _warm_up_dynamics() -> None:
    """The Iwan operators' kernels (periodic, AFT, history; 1-D and circular), the 3-D
    contact element and the time steppers."""
    from .dynamics import jenkins
    from .dynamics.operators2d import circular
    from .dynamics.operators3d import Contact3D
    from .dynamics.structure import one_mode
    from .dynamics.timeint import steady_state, transient

    joint = jenkins(100.0, 5.0)
    x = 0.1 * np.cos(np.linspace(0.0, 2.0 * np.pi, 16, endpoint=False))
    joint.periodic_force(x)
    joint.periodic_force_projected(x, np.eye(16)[:, :3])
    joint.periodic_harmonics(np.array([0.0, 0.1, 0.0]), np.eye(16, 3), np.eye(3, 16))
    joint.force_history(x)
    circular(joint).periodic_force_projected(np.column_stack([x, 0.5 * x]), np.eye(16)[:, :3])
    Contact3D(100.0, 100.0, 10.0, 0.5).periodic_force(np.column_stack([x, 0.5 * x, 0.1 * x]))
    structure = one_mode(100.0, 1.0, 0.01, joint)
    steady_state(structure, 1.0, 100.0, periods=2, steps=16)
    transient(structure, np.ones(1), 100.0, periods=2, steps=16)


def main() -> int:
    seconds = warm_up()
    print(f"microslip: compiled kernels ready ({seconds:.1f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
