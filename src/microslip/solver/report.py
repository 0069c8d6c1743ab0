"""The built-in solver's 1-D result in the shape of ``microslip fe --json``.

The same keys as the CalculiX path (:meth:`microslip.fe.results.FEResult.summary`) and as
``microslip loop --json``, so that comparison code and users never care which solver ran.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..params import ClampParams
from .results import UniaxialResult

__all__ = ["slip_lengths", "uniaxial_summary"]


def slip_lengths(result: UniaxialResult, params: ClampParams, t: float = 0.25
                 ) -> dict[str, float]:
    """Slip length of each domain at time ``t`` (default the first peak), mm.

    The slipping interface area divided by the width: tip over the whole bar; centre in the
    tension half (x > L/2) and the compression half (x < L/2).
    """
    k = int(np.argmin(np.abs(result.time - t)))
    c = result.contact
    slip_area = np.where(c.slipping[k], c.area, 0.0)
    x = c.coordinates[:, 0]
    half = 0.5 * params.length
    if result.model == "tip":
        return {"tip": float(slip_area.sum() / params.width)}
    return {"tension": float(slip_area[x > half].sum() / params.width),
            "compression": float(slip_area[x < half].sum() / params.width)}


def uniaxial_summary(result: UniaxialResult, params: ClampParams,
                     strain_energy_kind: str) -> dict[str, Any]:
    """The JSON object of ``microslip fe --solver builtin`` (units in the keys)."""
    d = result.damping(strain_energy_kind)
    stats = result.stats.summary()
    return {
        "model": result.model,
        "solver": "builtin",
        "units": {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm",
                  "time": "s", "stick_slope": "N/mm^3"},
        "params": params.as_dict(),
        "options": {"mesh": stats["mesh"], "element": stats["element"],
                    "stick_slope": stats["stick_slope_N_per_mm3"],
                    "linear_solver": stats["linear_solver"],
                    "centre_direction": result.centre_direction},
        "increments": int(result.time.size - 1),
        "amplitude_N": result.amplitude,
        "macroslip_force_N": params.macroslip_force,
        **d.loop_json(slip_lengths(result, params)),
        "dof": stats["dof"],
        "wall_s": stats["wall_s"],
        "converged": result.converged,
        "iterations": stats["newton_iterations"],
        "loop_closure": result.closure,
        "loop_offset_mm": result.offset,
        "friction_dissipation_Nmm": result.friction_dissipation,
        "message": result.message,
        "job_dir": None,
    }
