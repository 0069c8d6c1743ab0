"""Where a modal study of a mesh stops being physics (issue 34 item 2): the amplitude limits
of the automatic grid and the warnings on a result that leaves the model's validity.

The grid of :func:`~microslip.meshdynamics.case.amplitude_grid` runs from first slip towards
gross sliding; on a slender part that top can be tens of millimetres at the tip of a 4 mm
plate. :func:`grid_limit` caps it at

* :data:`SIZE_FRACTION` of the part's largest extent (the small-rotation limit: the linear
  body and the flat contact assume rotations of order a / L well below 0.1 rad), and
* with a yield strength, the amplitude at which the studied stuck mode's largest von Mises
  stress reaches it (:func:`mode_stress`; the clamping preload's own stresses are not added,
  so this is an upper bound of the elastic range).

:func:`result_warnings` flags a curve whose amplitudes pass the size limit (a range given by
the user) or whose damping ratio passes :data:`VALIDITY_DAMPING`: the interface is then near
gross sliding and the part turns on friction alone (no bolt shank carries it unless the
assembly gives one). Units: mm, MPa.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError

if TYPE_CHECKING:
    from ..fe.builtin.meshmodel import MeshModel
    from .case import PreparedStructure

__all__ = ["RESULT_MARGIN", "SIZE_FRACTION", "VALIDITY_DAMPING", "GridLimit",
           "check_yield_strength", "damping_warning",
           "grid_limit", "mode_stress", "result_warnings"]

#: The automatic grid's top at most this fraction of the part's largest extent (mm / mm).
SIZE_FRACTION = 0.01
#: Damping ratios above this carry a warning on the model's validity.
VALIDITY_DAMPING = 0.10
#: A result's amplitude is past the limit when above it by more than this factor: the grid
#: caps the stuck mode's (linear) amplitude, and the friction's softening raises the response
#: a little above it at the grid's top (4 % on bolt_pad's mode 1).
RESULT_MARGIN = 1.1
#: Elements per block of the stress recovery (bounds its memory on large meshes).
_BLOCK = 2000


def check_yield_strength(value: Any) -> float | None:
    """A yield strength in MPa, finite and > 0, or None."""
    if value is None:
        return None
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if isinstance(value, bool) or not (math.isfinite(x) and x > 0.0):
        raise ParameterError(f"yield strength must be finite and > 0 MPa, got {value!r}")
    return x


def mode_stress(model: MeshModel, shape: np.ndarray) -> float:
    """The largest von Mises stress (MPa) of the nodal displacement field ``shape``
    (n_nodes, 3; mm, global axes) on ``model``'s elements: the compatible strain at each
    element's nodes (the surface, where bending peaks: the Gauss points of a coarse mesh
    sit inside it, 20 % low on two elements through the thickness), each element's own
    material."""
    from ..fe.builtin.bodies import element_materials
    from ..fe.builtin.element import (
        NODE_XI,
        _shape_derivatives,
        _strain_operator,
        elasticity_matrix,
        physical_derivatives,
    )
    from ..fe.builtin.hex20 import NODE_XI20, shape20

    mesh = model.mesh
    dn = (_shape_derivatives(NODE_XI) if mesh.nodes_per_element == 8
          else shape20(NODE_XI20)[1])
    order = "C3D8" if mesh.nodes_per_element == 8 else "C3D20"
    u = np.asarray(shape, dtype=float)
    peak = 0.0
    for rows, mat in element_materials(mesh, model.assembly.materials):
        d = elasticity_matrix(mat.modulus, mat.poisson_ratio)
        for start in range(0, rows.size, _BLOCK):
            e = mesh.elements[rows[start:start + _BLOCK]]
            b = _strain_operator(physical_derivatives(dn, mesh.nodes[e], order)[0])
            strain = np.einsum("egij,ej->egi", b, u[e].reshape(e.shape[0], -1))
            s = strain @ d.T
            vm = np.sqrt(0.5 * ((s[..., 0] - s[..., 1]) ** 2 + (s[..., 1] - s[..., 2]) ** 2
                                + (s[..., 2] - s[..., 0]) ** 2)
                         + 3.0 * (s[..., 3] ** 2 + s[..., 4] ** 2 + s[..., 5] ** 2))
            peak = max(peak, float(vm.max()))
    return peak


@dataclass(frozen=True)
class GridLimit:
    """The amplitude limits of a study's grid (mm, on the response set's mean displacement
    along the mode): ``size_mm`` (the part's largest extent) times :data:`SIZE_FRACTION`,
    and with a ``yield_strength_MPa`` the amplitude whose stuck-mode stress reaches it."""

    size_mm: float
    size_limit_mm: float
    yield_strength_MPa: float | None = None
    yield_limit_mm: float | None = None

    @property
    def limit_mm(self) -> float:
        """The smaller of the two limits."""
        return min(x for x in (self.size_limit_mm, self.yield_limit_mm) if x is not None)

    @property
    def reason(self) -> str:
        """What the limit is, in words."""
        size = (f"{SIZE_FRACTION:g} of the part's largest extent ({self.size_mm:.4g} mm): "
                "small rotations")
        if self.yield_limit_mm is not None and self.yield_limit_mm < self.size_limit_mm:
            return (f"the stuck mode's largest von Mises stress reaches the yield strength "
                    f"{self.yield_strength_MPa:g} MPa (the elastic limit; the preload's own "
                    "stresses not added)")
        return size

    def summary(self) -> dict[str, Any]:
        return {"limit_mm": self.limit_mm, "reason": self.reason, "size_mm": self.size_mm,
                "size_fraction": SIZE_FRACTION, "size_limit_mm": self.size_limit_mm,
                "yield_strength_MPa": self.yield_strength_MPa,
                "yield_limit_mm": self.yield_limit_mm}


def grid_limit(prepared: PreparedStructure) -> GridLimit:
    """The amplitude limits of ``prepared``'s studied mode (:class:`GridLimit`)."""
    model, case = prepared.model, prepared.case
    size = float(model.size)
    strength = getattr(case, "yield_strength", None)
    at_yield = None
    if strength is not None:
        i = prepared.number - 1
        stress = mode_stress(model, prepared.stuck.shapes[i])
        motion = float(np.linalg.norm(prepared.stuck.response_motion[i]))
        at_yield = strength * motion / stress if stress > 0 else math.inf
    return GridLimit(size_mm=size, size_limit_mm=SIZE_FRACTION * size,
                     yield_strength_MPa=strength, yield_limit_mm=at_yield)


def result_warnings(limit: GridLimit, amplitude: Sequence[float | None],
                    damping_ratio: Sequence[float | None], shanks: int = 0) -> list[str]:
    """The validity warnings of one curve: amplitudes past ``limit`` (by more than
    :data:`RESULT_MARGIN`: small rotations, the elastic limit), damping ratios above
    :data:`VALIDITY_DAMPING` (``shanks``: the assembly's bolt shanks)."""
    out: list[str] = []
    a = np.array([np.nan if x is None else x for x in amplitude], dtype=float)
    z = np.array([np.nan if x is None else x for x in damping_ratio], dtype=float)
    past = np.isfinite(a) & (a > limit.limit_mm * RESULT_MARGIN)
    if np.any(past):
        out.append(f"{int(past.sum())} amplitude(s) up to a = {np.nanmax(a[past]):.4g} mm "
                   f"pass the limit of {limit.limit_mm:.4g} mm ({limit.reason}): the "
                   "linear body with its flat contact does not describe them")
    high = np.isfinite(z) & (z > VALIDITY_DAMPING)
    if np.any(high):
        k = int(np.nanargmax(np.where(high, z, np.nan)))
        out.append(damping_warning(float(z[k]), f"a = {a[k]:.4g} mm", shanks))
    return out


def damping_warning(zeta: float, where: str, shanks: int = 0) -> str:
    """The warning on a damping ratio ``zeta`` above :data:`VALIDITY_DAMPING` (``where``:
    the amplitude or force it was found at)."""
    held = ("the assembly's bolt shank(s) hold the part in the plane" if shanks else
            "no bolt shank holds the part (the preload is a pressure on faces): it turns on "
            "friction alone")
    return (f"damping ratio up to {100 * zeta:.3g} % ({where}) is above "
            f"{100 * VALIDITY_DAMPING:g} %: the interface is near gross sliding and {held}; "
            "outside the model's validity, the real joint's damping there depends on what "
            "holds the part")
