"""Export an FE loop for ParaView: one VTU file per state and a ``.pvd`` time collection.

Each VTU holds the solver's mesh with point data ``displacement`` (mm), ``contact_status``
(-1: not a contact point, 0 open, 1 stick, 2 slip) and ``contact_slip`` (mm), plus any
extra point or cell data a solver adds (CalculiX: ``contact_pressure``, ``contact_shear``
in MPa and the cell data ``part``, 0 bar, 1 base). The same files come from both solvers
(:func:`microslip.fe.run_loop` with ``out``). meshio is imported only here.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import MicroslipError
from ..io import atomic_path, atomic_write
from .result import FELoopResult

__all__ = ["FieldSeries", "write_vtu_series"]

FloatArray = NDArray[np.float64]


def _meshio() -> Any:
    try:
        import meshio
    except ImportError:
        raise MicroslipError("VTU export needs meshio: pip install 'microslip[fe]'") from None
    return meshio


class FieldSeries:
    """The mesh and the nodal displacements of every state of an :class:`FELoopResult`.

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Reference coordinates, mm.
    cells : sequence of (str, ndarray)
        meshio cell blocks (0-based node indices).
    displacement : ndarray, shape (k, n, 3)
        Displacement of every node at every state of ``result.time``, mm.
    point_data, cell_data : mapping, optional
        Extra data: point arrays of shape (k, n, ...) per state; cell data as meshio takes it.
    """

    def __init__(self, points: FloatArray, cells: Sequence[tuple[str, Any]],
                 displacement: FloatArray, point_data: Mapping[str, FloatArray] | None = None,
                 cell_data: Mapping[str, Any] | None = None) -> None:
        self.points, self.cells, self.displacement = points, list(cells), displacement
        self.point_data = dict(point_data or {})
        self.cell_data = dict(cell_data or {})


def _point_data(result: FELoopResult, fields: FieldSeries, k: int) -> dict[str, Any]:
    n = fields.points.shape[0]
    c = result.contact
    status = np.full(n, -1, dtype=np.int32)
    status[c.nodes] = c.status[k]
    slip = np.zeros((n, 3))
    if c.slip is not None:
        slip[c.nodes, :2] = c.slip[k]
    data = {"displacement": fields.displacement[k], "contact_status": status,
            "contact_slip": slip}
    return data | {name: v[k] for name, v in fields.point_data.items()}


def write_vtu_series(result: FELoopResult, fields: FieldSeries, out_dir: str | os.PathLike[str],
                     basename: str | None = None) -> list[Path]:
    """Write ``<basename>_<k>.vtu`` for every state k and ``<basename>.pvd`` listing them with
    their times (s); ``basename`` defaults to ``fe_<load case>``. Returns the VTU files, then
    the ``.pvd`` file; each is written atomically."""
    meshio = _meshio()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    base = basename or f"fe_{result.load_case}"
    written: list[Path] = []
    width = len(str(result.time.size - 1))
    for k in range(result.time.size):
        m = meshio.Mesh(fields.points, fields.cells, point_data=_point_data(result, fields, k),
                        cell_data=fields.cell_data)
        path = out / f"{base}_{k:0{width}d}.vtu"
        with atomic_path(path) as tmp:
            meshio.write(tmp, m, file_format="vtu")
        written.append(path)
    pvd = out / f"{base}.pvd"
    with atomic_write(pvd) as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
                 "  <Collection>\n")
        for t, path in zip(result.time, written, strict=True):
            fh.write(f'    <DataSet timestep="{t:.12g}" file="{path.name}"/>\n')
        fh.write("  </Collection>\n</VTKFile>\n")
    written.append(pvd)
    return written
