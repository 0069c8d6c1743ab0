"""The pressure the built-in solver's clamping step leaves at the box's interface.

The clamping force F_N presses the box's top face as the traction p(x) = F_N / (L w) P(x / L)
of a :class:`~microslip.models.interface.PressureLaw` (mean of P is 1; uniform, the paper's,
by default): the distribution of the box's preload (:func:`~.box.box_assembly`,
:meth:`~microslip.fe.assembly.Preload.shares`). The z-reactions of the bottom nodes after the
clamping step are the normal forces N_i (the model's ``normal_force``).
:func:`clamping_pressure` sums them over each cross-section and divides by the section's
tributary length: the line load (N/mm) and mean pressure (MPa) along the clamped length, as a
table that :func:`~microslip.models.interface.table_law` (or ``--pressure-law
table:FILE.csv``) turns into the 1-D models' pressure law. Units: N, mm, MPa.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ParameterError
from ...models.interface import PressureLaw, table_law
from ...named import result

if TYPE_CHECKING:
    from .meshmodel import MeshModel

__all__ = ["ClampingPressure", "clamping_pressure"]

FloatArray = NDArray[np.float64]


@result
class ClampingPressure:
    """The interface pressure after the clamping step, section by section along the length.

    Attributes
    ----------
    x : ndarray, shape (nx + 1,)
        Section positions from the far end x = 0 to the loaded end x = L, mm.
    line_load : ndarray, shape (nx + 1,)
        Sum of the section's normal forces over its tributary length, N/mm.
    width : float
        Width of the interface, mm.
    node_x, node_y, node_force : ndarray, shape (n_c,)
        Every contact node: position (mm) and normal force N_i (N).
    """

    x: FloatArray
    line_load: FloatArray
    width: float
    node_x: FloatArray
    node_y: FloatArray
    node_force: FloatArray

    @property
    def pressure(self) -> FloatArray:
        """Mean pressure over the width, MPa."""
        return np.asarray(self.line_load / self.width, dtype=float)

    def law(self) -> PressureLaw:
        """The :func:`~microslip.models.interface.table_law` of this pressure (for the 1-D
        models: ``law=``)."""
        return table_law(self.x, self.pressure, float(self.x[-1]))

    def write_csv(self, path: str | Path) -> Path:
        """The table ``x_mm,pressure`` (MPa) that ``--pressure-law table:FILE.csv`` reads."""
        return _write(path, ("x_mm", "pressure"), zip(self.x, self.pressure, strict=True))

    def write_nodes_csv(self, path: str | Path) -> Path:
        """Every contact node: ``x_mm,y_mm,normal_force_N``."""
        return _write(path, ("x_mm", "y_mm", "normal_force_N"),
                      zip(self.node_x, self.node_y, self.node_force, strict=True))

    def summary(self) -> dict[str, Any]:
        p = self.pressure
        return {"clamping_pressure_MPa": {"x_mm": self.x.tolist(), "pressure": p.tolist()},
                "clamping_pressure_edge_ratio": float(max(p[0], p[-1]) / np.mean(p))}


def _write(path: str | Path, header: tuple[str, ...], rows: Any) -> Path:
    out = Path(path)
    tmp = out.with_name(out.name + ".part")
    try:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows([repr(float(v)) for v in row] for row in rows)
    except OSError as exc:
        raise ParameterError(f"cannot write {out}: {exc.strerror}") from None
    tmp.replace(out)
    return out


def clamping_pressure(model: MeshModel, width: float | None = None) -> ClampingPressure:
    """The normal forces of a clamped box model (its contact in the plane z = 0, its length
    along x) as a :class:`ClampingPressure`; ``width`` of the interface (mm; default the
    contact nodes' extent across, y)."""
    xy = model.mesh.nodes[model.contact_nodes]
    _, which = np.unique(np.round(xy[:, 0], 9), return_inverse=True)
    count = np.bincount(which)
    cols = np.bincount(which, weights=xy[:, 0]) / count
    total = np.bincount(which, weights=model.normal_force)
    edges = np.concatenate([[cols[0]], 0.5 * (cols[1:] + cols[:-1]), [cols[-1]]])
    w = float(np.ptp(xy[:, 1])) if width is None else float(width)
    return ClampingPressure(cols, total / np.diff(edges), w, xy[:, 0].copy(),
                            xy[:, 1].copy(), model.normal_force.copy())
