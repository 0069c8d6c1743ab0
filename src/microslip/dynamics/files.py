"""Structures from files: the reduced mass, stiffness and damping matrices of the user's FE
model, and the joints' connectivity.

Two formats:

- ``.npz`` (``numpy.savez``), read with pickling disabled: arrays ``M`` and ``K``, optional
  ``C``, optional integer ``joints``: shape (n_joints, 2) for one-directional joints, rows
  ``[i, j]`` (the joint's relative displacement is q_i - q_j; ``j = -1`` for the ground),
  or (n_joints, 2, 2) for two-directional joints, one ``[i, j]`` row per direction;
  optional ``joint_stiffness`` (N/mm) and ``joint_slip_force`` (N), shape (n_joints,), both
  or neither: each joint of the file is then its own Jenkins element (circular on a
  two-directional joint), as a reduced model with every contact node writes it
  (:mod:`microslip.meshdynamics.reduce`), in place of the joint the command line names;
  or (n_joints, 3, 2) for *3-D contact joints* (a contact node with penalty normal contact,
  :class:`~.operators3d.Contact3D`: tangential 1, tangential 2, normal, in that order) with
  their laws ``joint_stiffness`` (tangential k_t, N/mm), ``joint_normal_stiffness`` (k_n,
  N/mm), ``joint_preload`` (N_0, N; signed: <= 0 for a node the clamping lifted off, minus
  k_n times its gap) and ``joint_friction`` (mu), shape (n_joints,), all
  four (``joint_slip_force`` is then mu N_0 and not given), and optionally
  ``joint_stick_force`` (N, shape (n_joints, 2): the tangential force the clamping step
  left in each, |t| <= mu N_0; zero if absent). A reader older than these
  arrays refuses such a file naming them (it never reads it as something else); every
  file without them reads as before.
- a directory with Matrix Market files ``M.mtx``, ``K.mtx`` and optional ``C.mtx``
  (:func:`scipy.io.mmread`; joints then come from the command line).

Units: the matrices are SI, mass kg, stiffness N/m, damping N·s/m (the structure's
displacements are then in mm, :mod:`.structure`).
"""

from __future__ import annotations

import os
import zipfile
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..named import readonly, result

__all__ = ["MatrixFile", "check_matrices", "joint_weights", "read_structure"]

#: Relative asymmetry |A - A^T| / max |A| tolerated as round-off.
SYMMETRY_TOLERANCE = 1e-9

#: Arrays an .npz structure file may hold.
NPZ_ARRAYS = ("M", "K", "C", "joints", "joint_stiffness", "joint_slip_force",
              "joint_normal_stiffness", "joint_preload", "joint_friction",
              "joint_stick_force")
#: The laws of 3-D contact joints, in the columns of :attr:`MatrixFile.contacts`: name,
#: unit (for the messages).
CONTACT_LAWS = (("joint_stiffness", "N/mm"), ("joint_normal_stiffness", "N/mm"),
                ("joint_preload", "N"), ("joint_friction", ""))


@result
class MatrixFile:
    """Matrices and joint connectivity read from a structure file.

    Attributes
    ----------
    mass, stiffness, damping : ndarray, shape (n, n)
        M (kg), K (N/m) and C (N·s/m; zeros if the file has none), checked.
    joints : ndarray, int, shape (n_joints, directions, 2)
        ``[i, j]`` per direction, j = -1 for the ground; (0, 1, 2) if the file has none;
        directions 3 for 3-D contact joints (tangential, tangential, normal).
    path : str
        Where they came from.
    laws : ndarray, shape (n_joints, 2), or None
        Each joint's own Jenkins element: stiffness (N/mm) and slip force (N); None if the
        file gives none.
    contacts : ndarray, shape (n_joints, 4), or None
        Each 3-D contact joint's law (:class:`~.operators3d.Contact3D`): tangential
        stiffness k_t (N/mm), normal stiffness k_n (N/mm), preload N_0 (N), friction mu;
        None unless the joints have three directions.
    stick_forces : ndarray, shape (n_joints, 2), or None
        Each 3-D contact joint's tangential stick force after clamping (N); None unless
        the joints have three directions.
    """

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    joints: np.ndarray
    path: str
    laws: np.ndarray | None = None
    contacts: np.ndarray | None = None
    stick_forces: np.ndarray | None = None


def read_structure(path: str) -> MatrixFile:
    """Read and check a structure file (``.npz``) or Matrix Market directory."""
    if os.path.isdir(path):
        arrays = _read_mtx_dir(path)
    elif os.path.isfile(path):
        arrays = _read_npz(path)
    else:
        raise ParameterError(f"structure file {path} does not exist")
    m, k = arrays["M"], arrays["K"]
    c = arrays.get("C", np.zeros_like(m) if isinstance(m, np.ndarray) else None)
    mass, stiffness, damping = check_matrices(path, m, k, c)
    joints = _joints(path, arrays.get("joints"), mass.shape[0])
    if joints.shape[1] == 3:
        return MatrixFile(mass=mass, stiffness=stiffness, damping=damping, joints=joints,
                          path=path, contacts=_contacts(path, arrays, joints.shape[0]),
                          stick_forces=_stick(path, arrays.get("joint_stick_force"),
                                              joints.shape[0]))
    given = [name for name, _ in (*CONTACT_LAWS[1:], ("joint_stick_force", "N"))
             if name in arrays]
    if given:
        raise ParameterError(f"{path}: {', '.join(given)} belong to 3-D contact joints "
                             "(joints of shape (n, 3, 2)); the file's joints have "
                             f"{joints.shape[1]} direction(s)")
    laws = _laws(path, arrays.get("joint_stiffness"), arrays.get("joint_slip_force"),
                 joints.shape[0])
    return MatrixFile(mass=mass, stiffness=stiffness, damping=damping, joints=joints,
                      path=path, laws=laws)


def _contacts(path: str, arrays: dict[str, object], count: int) -> np.ndarray:
    """(n_joints, 4): each 3-D contact joint's k_t (N/mm), k_n (N/mm), N_0 (N) and mu,
    checked (finite and > 0)."""
    if "joint_slip_force" in arrays:
        raise ParameterError(f"{path}: 3-D contact joints take joint_preload and "
                             "joint_friction (their slip force is mu N(t)), not "
                             "joint_slip_force")
    missing = [name for name, _ in CONTACT_LAWS if name not in arrays]
    if missing:
        raise ParameterError(f"{path}: 3-D contact joints (joints of shape (n, 3, 2)) need "
                             f"{', '.join(n for n, _ in CONTACT_LAWS)}; missing "
                             f"{', '.join(missing)}")
    return np.column_stack([_positive(path, name, unit, arrays[name], count,
                                      signed=name == "joint_preload")
                            for name, unit in CONTACT_LAWS])


def _stick(path: str, a: object, count: int) -> np.ndarray:
    """(n_joints, 2): the 3-D contact joints' stick forces after clamping, N (zeros if the
    file has none); finite (each checked against its mu N_0 by the element)."""
    if a is None:
        return np.zeros((count, 2))
    arr = np.asarray(a)
    if arr.dtype.kind not in "iuf" or arr.shape != (count, 2) or not np.all(np.isfinite(arr)):
        raise ParameterError(f"{path}: joint_stick_force must be finite numbers of shape "
                             f"({count}, 2) (N), got shape {arr.shape}")
    return arr.astype(float)


def _positive(path: str, name: str, unit: str, a: object, count: int,
              signed: bool = False) -> np.ndarray:
    """One number per joint, finite and > 0 (any sign with ``signed``: a 3-D contact
    joint's preload, <= 0 where the node is open)."""
    arr = np.asarray(a)
    if arr.dtype.kind not in "iuf" or arr.shape != (count,):
        raise ParameterError(f"{path}: {name} must be {count} numbers (one per joint), "
                             f"got dtype {arr.dtype} shape {arr.shape}")
    arr = arr.astype(np.float64)
    if signed and not np.all(np.isfinite(arr)):
        raise ParameterError(f"{path}: {name} must be finite {unit} (<= 0: an open node)")
    if not np.all(np.isfinite(arr) & ((arr > 0.0) | signed)):
        raise ParameterError(f"{path}: {name} must be finite and > 0{' ' + unit if unit else ''}")
    return arr


def _laws(path: str, stiffness: object, slip_force: object, count: int) -> np.ndarray | None:
    """(n_joints, 2): each joint's Jenkins stiffness (N/mm) and slip force (N), checked."""
    if stiffness is None and slip_force is None:
        return None
    if stiffness is None or slip_force is None:
        raise ParameterError(f"{path}: joint_stiffness and joint_slip_force go together; "
                             "the file has only one of them")
    return np.column_stack([_positive(path, name, unit, a, count) for name, unit, a in (
        ("joint_stiffness", "N/mm", stiffness), ("joint_slip_force", "N", slip_force))])


def check_matrices(path: str, m: object, k: object, c: object
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """M, K, C as read-only float arrays: square, one shape, finite, symmetric; M positive
    definite, K and C positive semi-definite. One line naming the file and the fault."""
    out = []
    n = None
    for name, a in (("M", m), ("K", k), ("C", c)):
        arr = np.asarray(a)
        if arr.dtype.kind not in "biuf" or arr.ndim != 2 or arr.shape[0] != arr.shape[1]:
            raise ParameterError(f"{path}: {name} must be a square numeric matrix, got "
                                 f"dtype {arr.dtype} shape {arr.shape}")
        n = arr.shape[0] if n is None else n
        if arr.shape != (n, n) or n == 0:
            raise ParameterError(f"{path}: {name} must have the shape of M ({n}, {n}), got "
                                 f"{arr.shape}")
        arr = arr.astype(np.float64)
        if not np.all(np.isfinite(arr)):
            raise ParameterError(f"{path}: {name} has NaN or infinite entries")
        scale = float(np.max(np.abs(arr))) if arr.size else 0.0
        asym = float(np.max(np.abs(arr - arr.T))) if arr.size else 0.0
        if asym > SYMMETRY_TOLERANCE * scale:
            raise ParameterError(f"{path}: {name} is not symmetric (largest |{name} - "
                                 f"{name}^T| = {asym:.3g}, relative {asym / scale:.2g})")
        lam = np.linalg.eigvalsh(arr)
        low = -SYMMETRY_TOLERANCE * max(scale, 1e-300) * n
        if name == "M" and not lam[0] > 0.0:
            raise ParameterError(f"{path}: M must be positive definite, its smallest "
                                 f"eigenvalue is {lam[0]:.3g} kg")
        if name != "M" and lam[0] < low:
            raise ParameterError(f"{path}: {name} must be positive semi-definite, its "
                                 f"smallest eigenvalue is {lam[0]:.3g}")
        out.append(readonly(arr))
    return out[0], out[1], out[2]


def joint_weights(joints: NDArray[np.int64] | Sequence[NDArray[np.int64]], dofs: int
                  ) -> list[np.ndarray]:
    """Participation of each joint, (dofs,) or (dofs, 2): +1 at i, -1 at j per direction."""
    out = []
    for joint in joints:
        w = np.zeros((dofs, joint.shape[0]))
        for d, (i, j) in enumerate(joint):
            w[i, d] += 1.0
            if j >= 0:
                w[j, d] -= 1.0
        out.append(w[:, 0] if joint.shape[0] == 1 else w)
    return out


def _joints(path: str, joints: object, dofs: int) -> np.ndarray:
    if joints is None:
        return np.zeros((0, 1, 2), dtype=np.int64)
    arr = np.asarray(joints)
    if arr.dtype.kind not in "iu":
        raise ParameterError(f"{path}: joints must be integer DOF indices, got dtype "
                             f"{arr.dtype}")
    if arr.ndim == 2 and arr.shape[1:] == (2,):
        arr = arr[:, None, :]
    if arr.ndim != 3 or arr.shape[1] not in (1, 2, 3) or arr.shape[2] != 2:
        raise ParameterError(f"{path}: joints must have shape (n, 2), (n, 2, 2) or (n, 3, 2) "
                             f"([i, j] per direction), got {arr.shape}")
    return check_joint_dofs(path, arr.astype(np.int64), dofs)


def check_joint_dofs(where: str, joints: np.ndarray, dofs: int) -> np.ndarray:
    """Joint DOF indices in [0, dofs), j in [-1, dofs) and j != i; read-only."""
    i, j = joints[..., 0], joints[..., 1]
    if np.any(i < 0) or np.any(i >= dofs) or np.any(j < -1) or np.any(j >= dofs):
        raise ParameterError(f"{where}: joint DOF indices must be in [0, {dofs - 1}] (j = -1 "
                             f"for the ground), got {joints.reshape(-1, 2).tolist()}")
    if np.any(i == j):
        raise ParameterError(f"{where}: a joint connects two different DOFs, got i = j")
    return readonly(joints)


def _read_npz(path: str) -> dict[str, object]:
    if not zipfile.is_zipfile(path):  # np.load would take it for a pickle or a .npy
        raise ParameterError(f"{path}: is not a readable .npz file (numpy.savez)")
    try:
        with np.load(path, allow_pickle=False) as data:
            names = list(data.files)
            arrays = {name: data[name] for name in names if name in NPZ_ARRAYS}
    except ValueError as exc:  # pickled object arrays, or not an npz file
        why = "holds pickled objects" if "pickle" in str(exc) else "is not a readable .npz"
        raise ParameterError(f"{path}: {why} (numpy arrays of numbers only)") from None
    except (OSError, zipfile.BadZipFile, EOFError):
        raise ParameterError(f"{path}: is not a readable .npz file") from None
    unknown = sorted(set(names) - set(NPZ_ARRAYS))
    if unknown:
        raise ParameterError(f"{path}: unknown array(s) {', '.join(unknown)}; a structure "
                             f"file holds {', '.join(NPZ_ARRAYS)}")
    missing = [name for name in ("M", "K") if name not in names]
    if missing:
        raise ParameterError(f"{path}: missing array(s) {', '.join(missing)}")
    return arrays


def _read_mtx_dir(path: str) -> dict[str, object]:
    from scipy.io import mmread

    out: dict[str, object] = {}
    for name in ("M", "K", "C"):
        file = os.path.join(path, f"{name}.mtx")
        if not os.path.isfile(file):
            if name == "C":
                continue
            raise ParameterError(f"{path}: missing {name}.mtx (Matrix Market)")
        try:
            a = mmread(file)
        except (ValueError, OSError, IndexError) as exc:
            raise ParameterError(f"{file}: not a readable Matrix Market file ({exc})") from None
        out[name] = a.toarray() if hasattr(a, "toarray") else np.asarray(a)
    return out
