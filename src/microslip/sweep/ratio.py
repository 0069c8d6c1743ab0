"""The R sweep of the planar model (force ratio, paper Fig. 12): a short loop over
:func:`microslip.planar.planar_damping`. Units: N, mm, N·mm.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable

from ..models import Contact
from ..options import ModelOptions
from ..params import ClampParams
from ..planar import PAPER_STRAIN_ENERGY, RatioSweep, loss_factor_vs_ratio
from ..progress import progress as progress_iter

__all__ = ["ratio_sweep"]


def ratio_sweep(ratios: Iterable[float], *, tip_params: ClampParams | None = None,
                centre_params: ClampParams | None = None, levels: str = "base",
                increments: int = 1000, options: ModelOptions | None = None,
                strain_energy: str | None = None, phase_deg: float = 0.0,
                progress: bool = True, contact: Contact | None = None) -> RatioSweep:
    """Planar damping against the force ratio R (paper Fig. 12): one
    :func:`microslip.planar.planar_damping` per R, in a plain loop.

    Cases the reading in force cannot compute (e.g. a centre amplitude at the macroslip
    limit) are kept with NaN results and the reason. Returns a
    :class:`microslip.planar.RatioSweep`.
    """
    return loss_factor_vs_ratio(
        [float(r) for r in ratios], tip_params=tip_params, centre_params=centre_params,
        levels=levels, increments=increments, options=options,
        strain_energy=strain_energy or PAPER_STRAIN_ENERGY, phase_deg=phase_deg,
        progress=functools.partial(progress_iter, enabled=progress, unit="case"),
        contact=contact)
