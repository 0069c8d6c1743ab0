"""Export a CalculiX run for ParaView: one VTU file per chosen time and a ``.pvd`` collection.

Each VTU holds the bar (20-node hexahedra; CalculiX's C3D20 node order is VTK's quadratic
hexahedron order) and the base (8-node hexahedra) with point data ``displacement`` (mm),
``contact_status`` (-1: not a contact point, 0 open, 1 stick, 2 slip), ``contact_pressure``
(MPa) and ``contact_shear`` (MPa), and cell data ``part`` (0 bar, 1 base). meshio is
imported only here.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import MicroslipError
from ..io import atomic_path, atomic_write
from .mesh import BarMesh, bar_mesh
from .readers import read_frd
from .results import FEResult
from .runner import JOBNAME

__all__ = ["QUARTER_TIMES", "export_vtu"]

#: The ends of each 90 degrees of the cycle (the paper's Fig. 8), s.
QUARTER_TIMES = (0.25, 0.5, 0.75, 1.0, 1.25)


def _meshio() -> Any:
    try:
        import meshio
    except ImportError:
        raise MicroslipError("VTU export needs meshio: pip install 'microslip[fe]'") from None
    return meshio


def export_vtu(result: FEResult, out_dir: str | os.PathLike[str],
               times: Sequence[float] = QUARTER_TIMES, basename: str | None = None,
               mesh: BarMesh | None = None) -> list[Path]:
    """Write ``<basename>_t<time>.vtu`` for each time and ``<basename>.pvd`` listing them.

    Parameters
    ----------
    result : FEResult
        A run whose job directory still holds ``job.frd``.
    out_dir : path
    times : sequence of float
        Step times, s; each must be a substep end.
    basename : str, optional
        Default ``fe_<model>``.
    mesh : BarMesh, optional
        The run's mesh (rebuilt from the case if not given).

    Returns
    -------
    list of Path
        The VTU files, then the ``.pvd`` file.
    """
    meshio = _meshio()
    if result.job_dir is None:
        raise MicroslipError("the FE result has no job directory to read displacements from")
    case = result.case
    mesh = mesh or bar_mesh(case.params, case.spec)
    frd = read_frd(result.job_dir / f"{JOBNAME}.frd", names=("DISP",))
    disp_blocks = frd.select("DISP")
    clamp_time = 1.0
    n_nodes = mesh.nodes.shape[0]
    cells = [("hexahedron20", mesh.elements - 1), ("hexahedron", mesh.base_elements - 1)]
    part = [np.zeros(mesh.elements.shape[0], dtype=np.int32),
            np.ones(mesh.base_elements.shape[0], dtype=np.int32)]
    contact = result.contact
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    base = basename or f"fe_{case.model}"
    written: list[Path] = []
    for t in times:
        k = contact.index(float(t))
        block = next((b for b in disp_blocks if abs(b.time - (clamp_time + t)) < 1e-6), None)
        if block is None:
            raise MicroslipError(f"job.frd has no displacements at t = {t:g} s")
        u = np.zeros((n_nodes, 3))
        u[block.nodes - 1] = block.values[:, :3]
        status = np.full(n_nodes, -1, dtype=np.int32)
        status[contact.nodes - 1] = contact.status[k]
        pressure = np.zeros(n_nodes)
        pressure[contact.nodes - 1] = contact.pressure[k]
        shear = np.zeros((n_nodes, 3))
        shear[contact.nodes - 1, :2] = contact.shear[k]
        m = meshio.Mesh(mesh.nodes, cells,
                        point_data={"displacement": u, "contact_status": status,
                                    "contact_pressure": pressure, "contact_shear": shear},
                        cell_data={"part": part})
        path = out / f"{base}_t{t:.3f}.vtu"
        with atomic_path(path) as tmp:
            meshio.write(tmp, m, file_format="vtu")
        written.append(path)
    pvd = out / f"{base}.pvd"
    with atomic_write(pvd) as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
                 "  <Collection>\n")
        for t, path in zip(times, written, strict=False):
            fh.write(f'    <DataSet timestep="{t:g}" file="{path.name}"/>\n')
        fh.write("  </Collection>\n</VTKFile>\n")
    written.append(pvd)
    return written
