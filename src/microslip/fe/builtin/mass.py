"""Consistent mass of 8-node hexahedra, and the unit of density.

M_e = integral of rho N^T N over the element, 2 x 2 x 2 Gauss points (exact for a
parallelepiped: N^T N is of degree 2 in each natural coordinate). In the units of microslip
(N, mm, s) mass is in tonnes (N s^2 / mm = 1000 kg) and density in t/mm^3:
:func:`density_t_per_mm3` converts kg/m^3 (2700 kg/m^3 = 2.7e-9 t/mm^3).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...errors import ParameterError
from .element import GAUSS, NODE_XI, hex8_b_matrices

__all__ = ["KG_PER_M3", "density_t_per_mm3", "mass_matrix"]

#: One kg/m^3 in t/mm^3 (the density unit of N, mm, s).
KG_PER_M3 = 1e-12


def density_t_per_mm3(density_kg_m3: float) -> float:
    """A density in kg/m^3 as t/mm^3, checked (> 0, finite).

    >>> round(density_t_per_mm3(2700.0), 21)
    2.7e-09
    """
    if isinstance(density_kg_m3, bool) or not (
            isinstance(density_kg_m3, (int, float)) and math.isfinite(density_kg_m3)
            and density_kg_m3 > 0):
        raise ParameterError(f"density must be > 0 kg/m^3, got {density_kg_m3!r}")
    return float(density_kg_m3) * KG_PER_M3


def mass_matrix(nodes: NDArray[np.float64], elements: NDArray[np.int64],
                density: float) -> sp.csr_matrix:
    """Consistent mass (3 n_nodes square, CSR, t) of an 8-node hexahedral mesh; ``density``
    in t/mm^3. Dof order: node-major, x y z (as the stiffness of :mod:`.element`).

    >>> from microslip.fe.examples import grid_mesh
    >>> b = grid_mesh(np.linspace(0, 10, 5), np.linspace(0, 2, 3), np.array([0.0, 1.0]))
    >>> m = mass_matrix(b.nodes, b.elements, 2.0)
    >>> round(float(m.sum()) / 3, 9)  # each direction carries the whole mass, rho V
    40.0
    """
    x = np.asarray(nodes, dtype=float)
    e = np.asarray(elements, dtype=np.int64)
    if e.ndim == 2 and e.shape[1] == 20:  # quadratic hexahedra (fe.builtin.hex20)
        from .hex20 import mass_matrix20

        return mass_matrix20(x, e, density)
    if e.ndim != 2 or e.shape[1] != 8:
        raise ParameterError(f"elements must have 8 nodes each, got shape {e.shape}")
    _, detj, _ = hex8_b_matrices(x[e])  # (n_e, 8 gp); checks the Jacobians
    s = 1.0 + GAUSS[:, None, :] * NODE_XI[None, :, :]
    shape = 0.125 * s.prod(axis=2)  # N_a at each Gauss point, (8 gp, 8)
    scalar = np.einsum("eg,ga,gb->eab", density * detj, shape, shape)  # (n_e, 8, 8)
    block = np.einsum("eab,ij->eaibj", scalar, np.eye(3)).reshape(len(e), 24, 24)
    dofs = (3 * e[:, :, None] + np.arange(3)).reshape(len(e), 24)
    rows = np.repeat(dofs, 24, axis=1).ravel()
    cols = np.tile(dofs, (1, 24)).ravel()
    n = 3 * len(x)
    return sp.coo_matrix((block.ravel(), (rows, cols)), shape=(n, n)).tocsr()
