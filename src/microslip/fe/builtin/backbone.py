"""The FE's first loading in one direction: a joint's backbone from the clamp's own physics.

A 1-D microslip model gives the backbone along the bar (the tip model is the FE's axial
joint within 0.1 %, docs/dynamics.md); across the bar the clamped zone bends in its own
plane on its friction foundation, a mechanism neither of the paper's models describes. The
built-in solver's monotonic loading of the one force, from the clamped state to just below
macroslip, is that direction's virgin curve; a Masing joint built from it
(:func:`microslip.meshdynamics.febackbone.backbone_operator`, one layer up: the FE does not
import the dynamics) then reproduces the FE's cyclic loops in that direction (tested against
the FE's settled cycles).

Units: N, mm.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...conventions import CLAMP_MODELS
from ...errors import MacroslipError, ParameterError
from ...named import result
from ...params import ClampParams
from ..constants import DEFAULT_STICK_SLOPE
from .box import BoxLoading, box_counts
from .study import DEFAULT_MESH, check_body, model_for

__all__ = ["BACKBONE_LOADS", "DEFAULT_TOP", "HULL_TOLERANCE", "FEBackbone", "concave_majorant",
           "fe_backbone"]

#: The loads a backbone can be taken along: the tip force (end face, along the bar) and the
#: centre force (mid-length section, in the ``centre_direction``).
BACKBONE_LOADS = CLAMP_MODELS

#: Largest relative gap (of mu F_N) between the FE's curve and its concave majorant that is
#: taken as the discreteness of nodal slip; a larger one is refused (not a microslip curve).
HULL_TOLERANCE = 1e-3

#: Largest force of the first loading as a fraction of mu F_N (the FE cannot reach
#: macroslip itself; the joint extends the last segment to mu F_N).
DEFAULT_TOP = 0.995


@result
class FEBackbone:
    """Virgin curve of one load of the built-in FE model.

    Attributes
    ----------
    load : str
        ``tip`` or ``centre``.
    centre_direction : str
        Direction of the centre force (``transverse``: across the bar).
    force, displacement : ndarray, shape (n + 1,)
        From (0, 0): the applied force (N) and its work-conjugate displacement (mm).
    macroslip_force : float
        mu F_N, N.
    mesh : str
        Element counts of the FE mesh, ``NXxNYxNZ``.
    stick_slope : float
        Contact stiffness of the FE, N/mm^3.
    """

    load: str
    centre_direction: str
    force: np.ndarray
    displacement: np.ndarray
    macroslip_force: float
    mesh: str
    stick_slope: float

    def summary(self) -> dict[str, Any]:
        """JSON-ready figures with units."""
        return {"load": self.load, "centre_direction": self.centre_direction,
                "mesh": self.mesh, "stick_slope_N_per_mm3": self.stick_slope,
                "macroslip_force_N": self.macroslip_force,
                "force_N": self.force.tolist(), "displacement_mm": self.displacement.tolist()}


def concave_majorant(displacement: np.ndarray, force: np.ndarray,
                     tolerance: float = HULL_TOLERANCE) -> np.ndarray:
    """Indices of the nodes of the least concave curve above ``(displacement, force)``
    (its upper convex hull, from the first node to the last).

    The FE's curve is concave but for the steps of nodes starting to slip one increment
    apart (slopes that rise by parts in 1e5 between fine increments); parallel Jenkins
    elements need a concave curve. The gap is checked: above ``tolerance`` of the last
    force the curve is refused (one line), as it is not a microslip curve.
    """
    d = np.asarray(displacement, dtype=float)
    f = np.asarray(force, dtype=float)
    hull: list[int] = []
    for i in range(d.size):  # Andrew's monotone chain, upper part (d increasing)
        while len(hull) >= 2:
            a, b = hull[-2], hull[-1]
            if (f[b] - f[a]) * (d[i] - d[a]) <= (f[i] - f[a]) * (d[b] - d[a]):
                hull.pop()
            else:
                break
        hull.append(i)
    keep = np.array(hull)
    gap = float(np.max(np.interp(d, d[keep], f[keep]) - f))
    if gap > tolerance * f[-1]:
        j = int(np.argmax(np.interp(d, d[keep], f[keep]) - f))
        raise ParameterError(f"the FE backbone is not concave: {gap:.4g} N below its concave "
                             f"majorant at {d[j]:.6g} mm (tolerance {tolerance:g} of "
                             f"{f[-1]:.6g} N)")
    return keep


def fe_backbone(params: ClampParams, load: str = "centre", *, mesh: Any = DEFAULT_MESH,
                increments: int = 200, top: float = DEFAULT_TOP,
                stick_slope: float = DEFAULT_STICK_SLOPE, element: str = "C3D8I",
                centre_direction: str = "transverse", linear_solver: str = "banded"
                ) -> FEBackbone:
    """The FE's first loading of ``load`` alone in ``increments`` equal force steps up to
    ``top`` mu F_N (a box model, :func:`~microslip.fe.builtin.box.box_model`, may be
    given as ``mesh``).

    Raises
    ------
    MacroslipError
        If an increment does not converge (the clamp slides before ``top`` mu F_N).
    """
    check_body(params, centre_direction)
    if load not in BACKBONE_LOADS:
        raise ParameterError(f"unknown backbone load {load!r}; choose one of "
                             f"{', '.join(BACKBONE_LOADS)}")
    if not (isinstance(increments, int) and 2 <= increments <= 100_000):
        raise ParameterError(f"increments must be a whole number in [2, 100000], "
                             f"got {increments!r}")
    if not (isinstance(top, float | int) and 0.0 < top < 1.0):
        raise ParameterError(f"top must be a fraction of mu F_N in (0, 1), got {top!r}")
    fem = model_for(params, mesh, stick_slope, element, linear_solver, None)
    f_ms = params.macroslip_force
    force = f_ms * float(top) * np.arange(1, increments + 1) / increments
    zero = np.zeros_like(force)
    sim = BoxLoading(params, fem, centre_direction)
    hist = sim.advance(force, zero) if load == "tip" else sim.advance(zero, force)
    if not hist.converged:
        raise MacroslipError(f"the FE first loading of the {load} force did not converge at "
                             f"{force[hist.completed]:.6g} N: {hist.message}")
    d = hist.displacement(load)
    counts = "x".join(str(n) for n in box_counts(fem.mesh))
    return FEBackbone(load=load, centre_direction=centre_direction,
                      force=np.concatenate([[0.0], force]),
                      displacement=np.concatenate([[0.0], d]),
                      macroslip_force=f_ms, mesh=counts, stick_slope=float(fem.stick_slope))
