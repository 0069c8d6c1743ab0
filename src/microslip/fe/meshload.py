"""A load on a named set of the user's mesh: direction, amplitude and phase.

F(t) = A sin(2 pi t + phi) (t in cycles), a uniform traction over the set's element faces
(consistent nodal forces: :func:`microslip.fe.hexmesh.face_load`) along a fixed direction.
Several loads at phases give planar (circular, elliptical) loading on any geometry. Units: N,
degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError

__all__ = ["MeshLoad"]


@dataclass(frozen=True)
class MeshLoad:
    """One load: a set name, a unit direction, an amplitude (total force, N) and a phase.

    >>> MeshLoad.parse("tip:1,0,0:200:90")
    MeshLoad(set='tip', direction=(1.0, 0.0, 0.0), amplitude=200.0, phase_deg=90.0)
    """

    set: str
    direction: tuple[float, float, float]
    amplitude: float
    phase_deg: float = 0.0

    def __post_init__(self) -> None:
        d = np.asarray(self.direction, dtype=float)
        if d.shape != (3,) or not np.all(np.isfinite(d)):
            raise ParameterError(
                f"load on {self.set!r}: direction must be three finite numbers DX,DY,DZ, "
                f"got {self.direction!r}")
        norm = float(np.linalg.norm(d))
        if norm == 0.0:
            raise ParameterError(f"load on {self.set!r}: direction 0,0,0 has zero length; "
                                 "give a non-zero vector DX,DY,DZ")
        object.__setattr__(self, "direction", tuple(float(x) for x in d / norm))
        if not (math.isfinite(self.amplitude) and self.amplitude > 0):
            raise ParameterError(
                f"load on {self.set!r}: amplitude must be > 0 N, got {self.amplitude!r}")
        if not math.isfinite(self.phase_deg):
            raise ParameterError(
                f"load on {self.set!r}: phase must be finite (deg), got {self.phase_deg!r}")
        object.__setattr__(self, "amplitude", float(self.amplitude))
        object.__setattr__(self, "phase_deg", float(self.phase_deg))

    @classmethod
    def parse(cls, spec: str) -> MeshLoad:
        """``SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG]`` (the command line's ``--load``)."""
        parts = spec.split(":")
        if len(parts) not in (3, 4) or not parts[0]:
            raise ParameterError(
                f"--load must be SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG], got {spec!r}")
        try:
            direction = tuple(float(x) for x in parts[1].split(","))
            amplitude = float(parts[2])
            phase = float(parts[3]) if len(parts) == 4 else 0.0
        except ValueError:
            raise ParameterError(
                f"--load must be SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG] with numbers, got {spec!r}"
            ) from None
        if len(direction) != 3:
            raise ParameterError(f"--load direction must be DX,DY,DZ (three numbers), got "
                                 f"{parts[1]!r}")
        return cls(parts[0], (direction[0], direction[1], direction[2]), amplitude, phase)

    def spec(self) -> str:
        """The load as ``--load`` takes it (:meth:`parse` gives it back).

        >>> MeshLoad.parse(MeshLoad("tip", (0.0, 2.0, 0.0), 5.0, 90.0).spec())
        MeshLoad(set='tip', direction=(0.0, 1.0, 0.0), amplitude=5.0, phase_deg=90.0)
        """
        d = ",".join(repr(x) for x in self.direction)
        return f"{self.set}:{d}:{self.amplitude!r}:{self.phase_deg!r}"

    def force(self, t: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """The load's magnitude A sin(2 pi t + phi) at times t (cycles), N."""
        return self.amplitude * np.sin(2 * np.pi * np.asarray(t, dtype=float)
                                       + math.radians(self.phase_deg))
