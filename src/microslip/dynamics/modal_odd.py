"""The extended periodic motion concept on the odd harmonics only: the same curve as
:func:`~.modal.epmc` for joints whose force is odd (Iwan and circular Jenkins elements to the
ground or between DOFs, no static load), at a fraction of its cost on many DOFs.

A joint force with ``f(-u) = -f(u)`` and a rate-independent hysteresis has a steady state
with half-wave symmetry, ``u(t + T/2) = -u(t)``, when the motion has it: the balance's even
harmonics (the static one included) then vanish identically, and Newton on the odd
harmonics alone (``x = S y``, residual ``S^T r``, Jacobian ``S^T J S``) finds the same
solution as on every harmonic. The balance is built on the odd harmonics alone
(:class:`~.hb.HarmonicBalance` with ``odd``: its residual, Jacobian and AFT never touch
the even ones), so the dense solve, the cost on a reduced model with many contact DOFs,
shrinks from ``(n (2H + 1))^3`` to about ``(n (H + 1))^3``, some 6x fewer operations for
H = 7, and the balance's memory and set-up to about a quarter. Not for joints whose force
is not odd (the 3-D contact element's normal lift-off, :mod:`.operators3d`), which
:func:`epmc_odd` refuses.

Units: as :mod:`.modal`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..blas import single_threaded_blas
from ..errors import ParameterError
from .hb import DEFAULT_HB_SAMPLES
from .modal import ModalCurve, _amplitudes, _epmc
from .operators3d import Contact3D
from .structure import Structure

__all__ = ["epmc_odd"]

Array = NDArray[np.float64]


def epmc_odd(structure: Structure, amplitude: ArrayLike, harmonics: int,
             samples: int = DEFAULT_HB_SAMPLES, mode: int = 0, *,
             failures: list[str] | None = None) -> ModalCurve:
    """:func:`~.modal.epmc` restricted to the odd harmonics 1, 3, ..., <= ``harmonics``
    (the same curve for odd joint forces; see the module's notes; ``failures`` as
    there)."""
    if any(isinstance(link.operator, Contact3D) for link in structure.joints):
        raise ParameterError("the odd-harmonic EPMC needs odd joint forces; the 3-D contact "
                             "element's normal lift-off is not: use epmc")
    with single_threaded_blas():
        return _epmc_odd(structure, _amplitudes(amplitude), harmonics, samples, mode,
                         failures)


def _epmc_odd(structure: Structure, a: Array, harmonics: int, samples: int, mode: int,
              failures: list[str] | None = None) -> ModalCurve:
    return _epmc(structure, a, harmonics, samples, mode, odd=True, failures=failures)
