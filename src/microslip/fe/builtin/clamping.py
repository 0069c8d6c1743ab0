"""The clamping load of the built-in solver and the pressure it produces at the interface.

The clamping force F_N is applied on the top face z = t as the traction
p(x) = F_N / (L w) P(x / L) of a :class:`~microslip.models.interface.PressureLaw` (mean of P
is 1; uniform, the paper's, by default). Its consistent nodal forces are integrated along x
by Gauss-Legendre quadrature on every element (8 points: exact for the power laws up to
degree 15 over an element) and shared across the width by the tributary widths; they are
scaled to add up to F_N exactly (a table law whose kinks fall inside elements is otherwise
integrated to the quadrature error).

The z-reactions of the bottom nodes after the clamping step are the normal forces N_i
(:attr:`~microslip.fe.builtin.solve.FrictionModel.normal_force`). :func:`clamping_pressure`
sums them over each cross-section and divides by the section's tributary length: the line
load (N/mm) and mean pressure (MPa) along the clamped length, as a table that
:func:`~microslip.models.interface.table_law` (or ``--pressure-law table:FILE.csv``) turns
into the 1-D models' pressure law. Units: N, mm, MPa.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ...conventions import DEFAULT_MESH
from ...errors import ParameterError
from ...models.interface import PressureLaw, table_law
from ...named import result
from ...params import ClampParams
from .mesh import BoxMesh

if TYPE_CHECKING:
    from .model import FrictionModel

__all__ = ["ClampingPressure", "clamp_forces", "clamping_pressure", "fe_pressure_law"]

FloatArray = NDArray[np.float64]

#: Gauss points per element along x for the consistent clamping forces of a pressure law.
GAUSS_POINTS = 8


def _line_forces(x: FloatArray, law: PressureLaw, length: float) -> FloatArray:
    """integral of P(x / L) N_i(x) dx for the hat functions N_i on the nodes x (mm)."""
    g, gw = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    a, b = x[:-1, None], x[1:, None]
    h = b - a
    xq = a + 0.5 * h * (g + 1.0)
    pw = law.shape(xq / length) * 0.5 * h * gw
    left = np.sum(pw * (b - xq) / h, axis=1)
    right = np.sum(pw * (xq - a) / h, axis=1)
    out = np.zeros(x.size)
    out[:-1] += left
    out[1:] += right
    return out


def clamp_forces(mesh: BoxMesh, params: ClampParams, law: PressureLaw | None) -> FloatArray:
    """Nodal forces (N, > 0 pressing) of the clamping traction on the top face, in the order
    of ``mesh.face_nodes("top")``; ``law`` None is the uniform pressure F_N / (L w)."""
    w_top = mesh.face_weights("top")
    if law is None:
        return params.normal_force * w_top / (params.length * params.width)
    x = np.unique(mesh.nodes[:, 0])
    along = _line_forces(x, law, params.length)
    across = w_top.reshape(x.size, -1)[0] / (0.5 * (x[1] - x[0]))  # tributary widths, mm
    forces = np.outer(along, across).ravel()
    return params.normal_force * forces / forces.sum()


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


def clamping_pressure(model: FrictionModel) -> ClampingPressure:
    """The normal forces of a clamped model as a :class:`ClampingPressure`."""
    xy = model.mesh.nodes[model.contact_nodes]
    _, which = np.unique(np.round(xy[:, 0], 9), return_inverse=True)
    count = np.bincount(which)
    cols = np.bincount(which, weights=xy[:, 0]) / count
    total = np.bincount(which, weights=model.normal_force)
    edges = np.concatenate([[cols[0]], 0.5 * (cols[1:] + cols[:-1]), [cols[-1]]])
    return ClampingPressure(cols, total / np.diff(edges), model.params.width, xy[:, 0].copy(),
                            xy[:, 1].copy(), model.normal_force.copy())


def fe_pressure_law(params: ClampParams, mesh: Any = DEFAULT_MESH, **model_options: Any
                    ) -> PressureLaw:
    """The interface pressure of the built-in solver's clamping step as a 1-D pressure law, in
    one call: :func:`~microslip.fe.builtin.solve.build_model` (``model_options``: ``stick_slope``,
    ``pressure_law`` of the top face, ``element``, ...) then :meth:`ClampingPressure.law`.

    >>> from microslip import preset
    >>> law = fe_pressure_law(preset("table1"), (8, 2, 1))
    >>> round(float(law.cumulative(np.array([1.0]))[0]), 12)
    1.0
    """
    from .solve import build_model

    return clamping_pressure(build_model(params, mesh, **model_options)).law()
