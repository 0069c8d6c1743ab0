"""Linear-elastic 8-node hexahedra and the vectorised assembly of the stiffness matrix.

Two elements are available (:data:`ELEMENTS`):

``C3D8``
    Trilinear displacement hexahedron, 2 x 2 x 2 Gauss integration (CalculiX's C3D8).
``C3D8I``
    The same with Wilson's incompatible bubble modes 1 - xi^2, 1 - eta^2, 1 - zeta^2, their
    x-derivatives taken with the centre Jacobian J0, condensed out at element level: exactly
    CalculiX's C3D8I (its displacements to 1e-7 on a distorted gmsh mesh, issue 33). It
    removes the parasitic shear of C3D8 in bending; on a box mesh it is exact for pure
    bending. CalculiX does not scale the modes' derivatives by det J0 / det J (Taylor's
    correction, with which the element passes the constant-strain patch test on distorted
    elements); neither does this one, so that both solvers solve the same equations on any
    mesh (on parallelepipeds det J = det J0 and the two are one; on the gmsh plate of issue
    33 Taylor's correction moves the tip by 3e-4 and W by 2 %).

Units: coordinates mm, modulus MPa, stiffness N/mm.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ...errors import ParameterError

__all__ = [
    "ELEMENTS",
    "assemble_hex8",
    "elasticity_matrix",
    "element_stiffness",
    "hex8_b_matrices",
]

FloatArray = NDArray[np.float64]

#: Natural coordinates of the 8 nodes (CalculiX's C3D8 order, :mod:`microslip.fe.hexmesh`).
NODE_XI = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
_G = 1.0 / np.sqrt(3.0)
#: 2 x 2 x 2 Gauss points (weights 1).
GAUSS = NODE_XI * _G


def elasticity_matrix(modulus: float, poisson_ratio: float) -> FloatArray:
    """Isotropic 6 x 6 matrix, Voigt order (xx, yy, zz, xy, yz, zx), engineering shear, MPa.

    >>> elasticity_matrix(1.0, 0.0).diagonal().tolist()
    [1.0, 1.0, 1.0, 0.5, 0.5, 0.5]
    """
    e, nu = float(modulus), float(poisson_ratio)
    lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    g = e / (2.0 * (1.0 + nu))
    d = np.zeros((6, 6))
    d[:3, :3] = lam
    d[np.arange(3), np.arange(3)] += 2.0 * g
    d[np.arange(3, 6), np.arange(3, 6)] = g
    return d


def _shape_derivatives(xi: FloatArray) -> FloatArray:
    """dN_a/dxi_i at points ``xi`` (n_p, 3) -> (n_p, 3, 8)."""
    s = 1.0 + xi[:, None, :] * NODE_XI[None, :, :]  # (n_p, 8, 3)
    d = np.empty((xi.shape[0], 3, 8))
    d[:, 0] = 0.125 * NODE_XI[:, 0] * s[:, :, 1] * s[:, :, 2]
    d[:, 1] = 0.125 * NODE_XI[:, 1] * s[:, :, 0] * s[:, :, 2]
    d[:, 2] = 0.125 * NODE_XI[:, 2] * s[:, :, 0] * s[:, :, 1]
    return d


def _strain_operator(dndx: FloatArray) -> FloatArray:
    """B (..., 6, 3 m) from shape-function gradients dN/dx (..., 3, m); dof order (a, comp)."""
    m = dndx.shape[-1]
    b = np.zeros((*dndx.shape[:-2], 6, m, 3))
    gx, gy, gz = dndx[..., 0, :], dndx[..., 1, :], dndx[..., 2, :]
    b[..., 0, :, 0] = gx
    b[..., 1, :, 1] = gy
    b[..., 2, :, 2] = gz
    b[..., 3, :, 0] = gy
    b[..., 3, :, 1] = gx
    b[..., 4, :, 1] = gz
    b[..., 4, :, 2] = gy
    b[..., 5, :, 0] = gz
    b[..., 5, :, 2] = gx
    return b.reshape(*dndx.shape[:-2], 6, 3 * m)


def hex8_b_matrices(coords: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Strain operators of 8-node hexahedra at the 2 x 2 x 2 Gauss points.

    Parameters
    ----------
    coords : ndarray, shape (n_e, 8, 3)
        Node coordinates of each element, mm.

    Returns
    -------
    b : ndarray, shape (n_e, 8, 6, 24)
        B at each Gauss point (element dof order: node-major, x y z).
    detj : ndarray, shape (n_e, 8)
        Jacobian determinants (Gauss weights are 1).
    jac : ndarray, shape (n_e, 8, 3, 3)
        J_ij = d x_j / d xi_i.
    """
    dndx, detj, jac = physical_derivatives(_shape_derivatives(GAUSS), coords, "C3D8")
    return _strain_operator(dndx), detj, jac


def physical_derivatives(dn: FloatArray, coords: FloatArray, order: str
                         ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Shape-function derivatives in x (n_e, g, 3, n), det J (n_e, g) and J (n_e, g, 3, 3)
    of elements ``coords`` (n_e, n, 3) from the natural derivatives ``dn`` (g, 3, n) at g
    points. Raises :class:`ParameterError` for a non-positive Jacobian (``order``: the node
    order the element expects, named in the message)."""
    jac = np.einsum("gia,eaj->egij", dn, coords)
    detj = np.linalg.det(jac)
    if np.any(detj <= 0.0):
        bad = int(np.flatnonzero(np.any(detj <= 0.0, axis=1))[0])
        raise ParameterError(f"element {bad + 1} (1-based) has a non-positive Jacobian "
                             f"(inverted or degenerate; the nodes must follow the {order} "
                             "order)")
    dndx = np.linalg.solve(jac, np.broadcast_to(dn, (coords.shape[0], *dn.shape)))
    return dndx, detj, jac


def _stiffness_c3d8(coords: FloatArray, d: FloatArray) -> FloatArray:
    b, detj, _ = hex8_b_matrices(coords)
    return np.asarray(np.einsum("egki,kl,eglj,eg->eij", b, d, b, detj, optimize=True))


def _stiffness_c3d8i(coords: FloatArray, d: FloatArray) -> FloatArray:
    b, detj, _ = hex8_b_matrices(coords)
    # Incompatible modes phi_m = 1 - xi_m^2: dphi_m/dxi_i = -2 xi_m delta_im, to x with the
    # centre Jacobian J0 (CalculiX's C3D8I: no det J0 / det J factor, module docstring).
    dphi = np.zeros((GAUSS.shape[0], 3, 3))
    dphi[:, np.arange(3), np.arange(3)] = -2.0 * GAUSS
    dn0 = _shape_derivatives(np.zeros((1, 3)))[0]
    j0 = np.einsum("ia,eaj->eij", dn0, coords)
    dphidx = np.einsum("eij,gjm->egim", np.linalg.inv(j0), dphi)
    g = _strain_operator(dphidx)  # (e, gp, 6, 9)
    kuu = np.einsum("egki,kl,eglj,eg->eij", b, d, b, detj, optimize=True)
    kua = np.einsum("egki,kl,eglj,eg->eij", b, d, g, detj, optimize=True)
    kaa = np.einsum("egki,kl,eglj,eg->eij", g, d, g, detj, optimize=True)
    return np.asarray(kuu - kua @ np.linalg.solve(kaa, np.swapaxes(kua, 1, 2)))


#: Element formulations: name -> (stiffness function, description).
ELEMENTS: dict[str, tuple[Callable[[FloatArray, FloatArray], FloatArray], str]] = {
    "C3D8": (_stiffness_c3d8, "trilinear hexahedron, 2x2x2 Gauss (CalculiX C3D8)"),
    "C3D8I": (_stiffness_c3d8i, "trilinear hexahedron + incompatible modes (CalculiX C3D8I)"),
}


def _element_function(kind: str) -> Callable[[FloatArray, FloatArray], FloatArray]:
    try:
        return ELEMENTS[kind][0]
    except (KeyError, TypeError):
        raise ParameterError(
            f"unknown element {kind!r}; choose one of {', '.join(ELEMENTS)}") from None


def element_stiffness(coords: FloatArray, modulus: float, poisson_ratio: float,
                      kind: str = "C3D8") -> FloatArray:
    """Stiffness matrices (n_e, 24, 24) of hexahedra with node coordinates (n_e, 8, 3), N/mm.

    Element dof order: node-major (node 0 x, y, z, node 1 x, ...).

    Examples
    --------
    A unit cube stretched uniformly carries the stress E (nu = 0): the nodal forces on its
    face x = 1 add up to E times the face area.

    >>> cube = NODE_XI[None] * 0.5 + 0.5
    >>> k = element_stiffness(cube, 1000.0, 0.0)[0]
    >>> u = np.zeros(24); u[0::3] = cube[0, :, 0] * 1e-3
    >>> round(float((k @ u)[0::3][cube[0, :, 0] == 1.0].sum()), 9)
    1.0
    """
    fn = _element_function(kind)
    c = np.asarray(coords, dtype=float)
    if c.ndim != 3 or c.shape[1:] != (8, 3):
        raise ParameterError(f"element coordinates must have shape (n, 8, 3), got {c.shape}")
    return fn(c, elasticity_matrix(modulus, poisson_ratio))


def _scatter(nodes: FloatArray, elements: NDArray[np.int64], shape: NDArray[np.int64],
             first: NDArray[np.int64], modulus: float, poisson_ratio: float, kind: str
             ) -> sp.csr_matrix:
    """Global stiffness from one element matrix per class (element ``first[c]`` stands for
    class c; ``shape[e]`` is the class of element e), scattered by the connectivity."""
    ke = element_stiffness(nodes[elements[first]], modulus, poisson_ratio, kind)
    edof = (3 * elements[:, :, None] + np.arange(3)).reshape(elements.shape[0], 24)
    rows = np.repeat(edof, 24, axis=1).ravel()
    cols = np.tile(edof, (1, 24)).ravel()
    data = ke.reshape(first.size, -1)[shape].ravel()
    n = 3 * nodes.shape[0]
    k = sp.coo_matrix((data, (rows, cols)), shape=(n, n)).tocsr()
    k.sum_duplicates()
    return k


#: Two elements share one stiffness matrix when their node positions relative to their first
#: node agree to this fraction of the mesh's size (translated copies in a structured mesh).
SHAPE_TOL = 1e-12


def assemble_hex8(nodes: FloatArray, elements: NDArray[np.int64], modulus: float,
                  poisson_ratio: float, kind: str = "C3D8I") -> sp.csr_matrix:
    """Global stiffness (3 n_nodes square, CSR, N/mm) of any 8-node hexahedral mesh.

    Elements that are translated copies of each other (node positions relative to the first
    node equal to :data:`SHAPE_TOL` times the mesh size) share one element matrix, that of the
    first of them: a structured mesh (the paper's box) costs one matrix per distinct element.

    >>> from microslip import preset
    >>> from microslip.fe.examples import box_hexmesh
    >>> b = box_hexmesh(preset("table1"), (4, 2, 1))
    >>> k = assemble_hex8(b.nodes, b.elements, 1000.0, 0.3, "C3D8I")
    >>> k.shape, bool(abs(k - k.T).max() < 1e-9 * abs(k).max())
    ((90, 90), True)
    """
    x = np.asarray(nodes, dtype=float)
    e = np.asarray(elements, dtype=np.int64)
    if e.ndim != 2 or e.shape[1] != 8:
        raise ParameterError(f"elements must have 8 nodes each, got shape {e.shape}")
    rel = x[e] - x[e[:, :1]]
    size = float(np.max(np.ptp(x, axis=0))) if x.size else 1.0
    key = np.round(rel.reshape(e.shape[0], 24) / (SHAPE_TOL * max(size, 1e-300)))
    _, first, shape = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return _scatter(x, e, shape.ravel().astype(np.int64), first.astype(np.int64), modulus,
                    poisson_ratio, kind)
