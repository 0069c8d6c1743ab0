"""The two-mode study's case (:mod:`.twomode`): the post-on-plate body's parameters, its
clamped full FE, the full FE's two close bending modes and the study's ROM.

Units: N, mm, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..fe.assembly import rigid_base
from ..fe.builtin.meshmodel import MeshModel, build_mesh_model
from ..fe.hexmesh import HexMesh
from .modes import Modes, linear_modes
from .reduce import Rom, build_rom

__all__ = ["COUPLINGS", "BendingPair", "TwoModeCase", "bending_pair", "frequency_window",
           "study_rom", "two_mode_model"]

FloatArray = NDArray[np.float64]

#: The two couplings compared.
COUPLINGS = ("circular", "decoupled")


@dataclass(frozen=True)
class TwoModeCase:
    """The post-on-plate case (N, mm, MPa, kg/m^3): aluminium, mu 0.5, F_N 2000 N, stick
    slope 1e4 N/mm^3, fixed normal contact; the ROM's fixed-interface modes, its linear
    modal damping ratio zeta_0, the forcing angle from x (degrees) and the harmonics."""

    contact_set: str = "contact"
    clamp_set: str = "clamp"
    top_set: str = "top"
    modulus: float = 70000.0
    poisson_ratio: float = 0.33
    density: float = 2700.0
    friction: float = 0.5
    normal_force: float = 2000.0
    stick_slope: float = 1e4
    rom_modes: int = 10
    damping_ratio: float = 0.005
    angle_deg: float = 45.0
    harmonics: int = 3

    def __post_init__(self) -> None:
        if not (math.isfinite(self.damping_ratio) and 0.0 < self.damping_ratio < 1.0):
            raise ParameterError(f"damping ratio zeta_0 must be in (0, 1), got "
                                 f"{self.damping_ratio!r}")
        if not math.isfinite(self.angle_deg):
            raise ParameterError(f"forcing angle must be finite (degrees), got "
                                 f"{self.angle_deg!r}")


def two_mode_model(mesh: HexMesh, case: TwoModeCase) -> MeshModel:
    """The clamped body of ``mesh`` (fixed normal contact, the case's law)."""
    return build_mesh_model(mesh, rigid_base(contact_set=case.contact_set, clamp_set=case.clamp_set,
                                             normal_force=case.normal_force, modulus=case.modulus,
                                             poisson_ratio=case.poisson_ratio,
                                             friction=case.friction, stick_slope=case.stick_slope))


@dataclass(frozen=True, eq=False)
class BendingPair:
    """The full FE's two lowest stuck modes (:func:`bending_pair`).

    Attributes
    ----------
    frequencies_Hz : ndarray, shape (2,)
    directions : ndarray, shape (2, 3)
        Unit direction of the top set's motion in each (global axes).
    labels : tuple of str
    separation : float
        (f2 - f1) / f1.
    modes : Modes
        The stuck modes computed (at least 6), for the loads of :func:`fe_check`.
    """

    frequencies_Hz: FloatArray
    directions: FloatArray
    labels: tuple[str, str]
    separation: float
    modes: Modes = field(repr=False)


def bending_pair(model: MeshModel, case: TwoModeCase, count: int = 6) -> BendingPair:
    """The two lowest stuck modes of the full FE, described by the top set's motion."""
    modes = linear_modes(model, case.density, count, response_set=case.top_set)
    f = np.asarray(modes.frequencies_Hz[:2])
    return BendingPair(frequencies_Hz=f, directions=np.asarray(modes.directions[:2]),
                       labels=(modes.labels[0], modes.labels[1]),
                       separation=float((f[1] - f[0]) / f[0]), modes=modes)


def study_rom(model: MeshModel, case: TwoModeCase) -> Rom:
    """The Craig-Bampton ROM of the case (``case.rom_modes`` fixed-interface modes, the top
    set as its output)."""
    return build_rom(model, case.density, modes=case.rom_modes, response_set=case.top_set)


def frequency_window(pair: BendingPair, margin: float = 0.05) -> tuple[float, float]:
    """The range through both resonances: ``(1 - margin) f1`` to ``(1 + margin) f2``, Hz."""
    f1, f2 = (float(v) for v in pair.frequencies_Hz)
    return (1.0 - margin) * f1, (1.0 + margin) * f2
