"""A structure from matrices and joint connectivity: joints placed, the mode to follow, the
coordinate reported, the excitation.

The reported amplitude of a many-DOF structure is the modal coordinate of the chosen stuck
mode phi (scaled so that its largest DOF displacement is 1): ``a = phi^T M q / phi^T M phi``,
mm, i.e. the largest displacement of the linear mode shape; the excitation of a mode is
``F M phi / (phi^T M phi)`` (a modal force F, N) unless DOFs are named.

Units: SI matrices (kg, N/m, N·s/m), displacements mm, forces N.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
from scipy.linalg import eigh

from ..errors import ParameterError
from ..named import readonly
from .files import MatrixFile, joint_weights
from .hb import to_time
from .operators import IwanOperator, jenkins
from .operators2d import COUPLINGS
from .operators3d import Contact3D
from .response import FrequencyResponse
from .structure import JointLink, Structure

__all__ = ["PlacedJoint", "describe_matrices", "from_joints", "from_matrices", "joint_orbits",
           "modal_output", "mode_load", "mode_shape", "with_output"]


@dataclasses.dataclass(frozen=True)
class PlacedJoint:
    """One joint of a structure: where it sits, its 1-D operator and, if it has two
    directions, how they are coupled.

    ``dofs`` is its connectivity, shape (directions, 2): ``[i, j]`` per direction, j = -1 for
    the ground (:mod:`.files`); ``coupling`` a name of :data:`~.operators2d.COUPLINGS`.
    A two-directional joint is ``operator`` along its first direction and ``transverse``
    (None: ``operator``) along its second, its elements matched by ``pairing``
    (:data:`~.operators2d.PAIRINGS`, None: the default; circular coupling only).
    A joint of three directions (tangential, tangential, normal) is a contact node's 3-D
    element, ``operator`` a :class:`~.operators3d.Contact3D` (no coupling applies).
    """

    dofs: np.ndarray
    operator: IwanOperator | Contact3D
    coupling: str = "circular"
    transverse: IwanOperator | None = None
    pairing: str | None = None


def from_matrices(matrices: MatrixFile, joints: np.ndarray, joint: IwanOperator | None,
                  coupling: str, transverse: IwanOperator | None = None,
                  pairing: str | None = None) -> Structure:
    """The structure of ``matrices`` with ``joint`` at every connectivity row of ``joints``
    ((n, directions, 2), :mod:`.files`); two-directional joints coupled by ``coupling``
    (:data:`~.operators2d.COUPLINGS`), ``transverse`` along their second direction (None:
    ``joint``) with ``pairing``. The output coordinate is set by :func:`with_output`.

    A file whose joints carry their own laws (:attr:`MatrixFile.laws`) places, on its own
    connectivity, each joint's Jenkins element (circular coupling) instead of ``joint``;
    a file of 3-D contact joints (:attr:`MatrixFile.contacts`) each joint's
    :class:`~.operators3d.Contact3D`. ``joint`` may be None only then.
    """
    own = np.array_equal(np.asarray(joints), matrices.joints)
    if matrices.contacts is not None and own:
        stick = (np.zeros((len(joints), 2)) if matrices.stick_forces is None
                 else matrices.stick_forces)
        return from_joints(matrices, [
            PlacedJoint(row, Contact3D(float(law[0]), float(law[1]), float(law[2]),
                                       float(law[3]), (float(t[0]), float(t[1]))))
            for row, law, t in zip(joints, matrices.contacts, stick, strict=True)])
    if matrices.laws is not None and own:
        return from_joints(matrices, [PlacedJoint(row, jenkins(float(k), float(s)))
                                      for row, (k, s) in zip(joints, matrices.laws,
                                                             strict=True)])
    if joint is None:
        raise ParameterError(f"{matrices.path}: its joints carry no laws of their own; give "
                             "the joint (--joint and its options)")
    return from_joints(matrices, [PlacedJoint(row, joint, coupling, transverse, pairing)
                                  for row in joints])


def from_joints(matrices: MatrixFile, joints: Sequence[PlacedJoint]) -> Structure:
    """The structure of ``matrices`` with the joints ``joints``, each with its own operator
    (several joints of a case file). The output coordinate is set by :func:`with_output`."""
    if len(joints) == 0:
        raise ParameterError(f"{matrices.path}: no joint; give --joint-dof I [J] or a "
                             "'joints' array in the file")
    links = []
    n = matrices.mass.shape[0]
    for placed in joints:
        (w,) = joint_weights([np.asarray(placed.dofs)], n)
        if isinstance(placed.operator, Contact3D) or (w.ndim == 2 and w.shape[1] == 3):
            if not isinstance(placed.operator, Contact3D) or w.ndim != 2 or w.shape[1] != 3:
                raise ParameterError("a 3-D contact element (tangential, tangential, normal) "
                                     "takes a joint of three directions, and a joint of three "
                                     "directions a 3-D contact element")
            links.append(JointLink(placed.operator, w))
            continue
        if w.ndim == 1:
            if placed.transverse is not None or placed.pairing is not None:
                raise ParameterError("a joint across (transverse) and its pairing need a "
                                     "two-directional joint ([[I, J], [K, L]])")
            links.append(JointLink(placed.operator, w))
            continue
        ops = COUPLINGS[placed.coupling](placed.operator, placed.transverse, placed.pairing)
        if len(ops) == 1:
            links.append(JointLink(ops[0], w))
        else:
            links.extend(JointLink(op, w[:, d]) for d, op in enumerate(ops))
    s = Structure(mass=matrices.mass, damping=matrices.damping, stiffness=matrices.stiffness,
                  joints=tuple(links), output=readonly(np.eye(n)[0]))
    lam = eigh(s.stuck_stiffness(), s.mass, eigvals_only=True)
    if not lam[0] > 1e-12 * lam[-1]:
        raise ParameterError(f"{matrices.path}: the structure with its joints stuck has a "
                             "zero-frequency (rigid-body) mode; fix it with a joint to the "
                             "ground or in K")
    return s


def mode_shape(structure: Structure, mode: int) -> np.ndarray:
    """Stuck mode ``mode`` (0-based by frequency), scaled to a largest entry of +1."""
    if not 0 <= mode < structure.dofs:
        raise ParameterError(f"--mode must be in [1, {structure.dofs}], got {mode + 1}")
    _, vecs = eigh(structure.stuck_stiffness(), structure.mass)
    phi = vecs[:, mode]
    return np.asarray(phi / phi[np.argmax(np.abs(phi))])


def with_output(structure: Structure, output: np.ndarray) -> Structure:
    """The same structure reporting the coordinate ``output . q``."""
    return dataclasses.replace(structure, output=readonly(np.asarray(output, dtype=float)))


def modal_output(structure: Structure, mode: int) -> np.ndarray:
    """Weights of the modal coordinate of stuck mode ``mode``: phi^T M / (phi^T M phi)."""
    phi = mode_shape(structure, mode)
    m_phi = structure.mass @ phi
    return np.asarray(m_phi / (phi @ m_phi))


def mode_load(structure: Structure, mode: int) -> np.ndarray:
    """Excitation shape of a unit modal force on stuck mode ``mode``, N per DOF."""
    return modal_output(structure, mode)


def describe_matrices(structure: Structure) -> dict[str, Any]:
    """JSON description: DOFs, linear frequencies stuck and joint-free, the joints."""
    free = structure.linear_frequencies(stuck=False)
    return {"dofs": structure.dofs,
            "stuck_frequencies_Hz": structure.linear_frequencies(stuck=True),
            "joint_free_frequencies_Hz": free,
            "joints": [{"directions": link.directions,
                        "operator": type(link.operator).__name__,
                        "participation": link.participation} for link in structure.joints]}


def joint_orbits(response: FrequencyResponse, joints: np.ndarray | Sequence[np.ndarray]
                 ) -> list[dict[str, Any]]:
    """Orbit of every two-directional joint of the connectivity ``joints`` ((n, d, 2), or
    one (d, 2) array per joint, :mod:`.files`) at the continuation point of largest
    amplitude: its relative displacement (mm) in both directions at the AFT samples of one
    period."""
    i = int(np.argmax(response.amplitude))
    h = 2 * response.harmonics + 1
    q = response.coefficients[i].reshape(-1, h)
    out = []
    for j, w in enumerate(joint_weights(joints, q.shape[0])):
        if w.ndim == 1:
            continue
        u = to_time(w.T @ q, response.samples)
        out.append({"joint": j, "frequency_Hz": float(response.frequency[i]),
                    "amplitude_mm": float(response.amplitude[i]), "x_mm": u[0],
                    "y_mm": u[1]})
    return out
