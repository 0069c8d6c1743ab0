"""Named results shared by the analytical models, the planar coupling and the FE drivers.

Whatever produced a loop (an incremental model with Masing's rule, a finite-element run),
it arrives as a :class:`HysteresisLoop`, so comparison code never cares where it came from.
Units: force N, displacement and lengths mm, energy N·mm. Every result is a
:func:`microslip.named.result`: frozen, read-only arrays, identity equality, short repr.
"""

from __future__ import annotations

from dataclasses import field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .named import result
from .options import ModelOptions
from .params import ClampParams

__all__ = ["Backbone", "DampingResult", "HysteresisLoop"]

FloatArray = NDArray[np.float64]


@result
class Backbone:
    """First-loading (virgin) curve of a 1-D microslip model, increment by increment.

    Attributes
    ----------
    model : str
        A key of :data:`microslip.models.MODELS`.
    force : ndarray, shape (n + 1,)
        Applied force F_T(i) = F0 i / n, N; ``force[0] == 0``.
    displacement : ndarray, shape (n + 1,)
        Displacement of the loaded section delta_x(i), mm.
    domains : tuple of str
        Names of the slip domains (:attr:`microslip.models.ModelSpec.domains`).
    slip_length : ndarray, shape (n + 1, n_domains)
        Slip length u_i of each domain, mm.
    width, thickness : ndarray, shape (n + 1, n_domains)
        Updated cross-section w_i, t_i of each domain, mm.
    stored_energy : ndarray, shape (n + 1,)
        Elastic strain energy held in the bar at each increment, N·mm (linear fall of the
        axial force over each slip length: F_d delta_d / 3 summed over the domains).
    params : ClampParams or None
        The clamped zone used (None for the planar resultant of two models).
    options : ModelOptions or None
        The reading of the paper used (None for the planar resultant).
    """

    model: str
    force: FloatArray
    displacement: FloatArray
    domains: tuple[str, ...]
    slip_length: FloatArray
    width: FloatArray
    thickness: FloatArray
    stored_energy: FloatArray
    params: ClampParams | None = None
    options: ModelOptions | None = None

    @property
    def amplitude(self) -> float:
        """Peak force F0, N."""
        return float(self.force[-1])

    @property
    def peak_displacement(self) -> float:
        """Displacement at peak force d0, mm."""
        return float(self.displacement[-1])

    @property
    def increments(self) -> int:
        return int(self.force.shape[0] - 1)


@result
class HysteresisLoop:
    """A closed force-displacement loop, starting and ending at the positive peak.

    Attributes
    ----------
    force : ndarray, shape (m,)
        Force along the loop, N. ``force[0] == force[-1]``.
    displacement : ndarray, shape (m,)
        Displacement along the loop, mm. ``displacement[0] == displacement[-1]``.
    source : str
        What made it (``"masing"``, ``"paper-coupling"``, ``"calculix"``, ...).
    meta : dict
        Anything the producer wants to record (model name, amplitude, ...).
    """

    force: FloatArray
    displacement: FloatArray
    source: str = "masing"
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def amplitude(self) -> float:
        """Half the peak-to-peak force, N."""
        return float(0.5 * (np.max(self.force) - np.min(self.force)))

    @property
    def peak_displacement(self) -> float:
        """Half the peak-to-peak displacement, mm."""
        return float(0.5 * (np.max(self.displacement) - np.min(self.displacement)))


@result
class DampingResult:
    """Damping of one loop: dissipated energy, strain energy and loss factor (Eqs 21-23).

    Attributes
    ----------
    dissipated_energy : float
        W_d, the loop area (Eq. 21), N·mm.
    strain_energy : float
        U by the definition named in ``strain_energy_kind`` (Eq. 22), N·mm.
    strain_energy_kind : str
        Which definition of U (see :data:`microslip.energy.STRAIN_ENERGY`).
    loss_factor : float
        eta = W_d / (2 pi U) (Eq. 23), dimensionless.
    amplitude : float
        Peak force, N.
    peak_displacement : float
        Peak displacement, mm.
    loop : HysteresisLoop
    backbone : Backbone or None
    """

    dissipated_energy: float
    strain_energy: float
    strain_energy_kind: str
    loss_factor: float
    amplitude: float
    peak_displacement: float
    loop: HysteresisLoop
    backbone: Backbone | None = None

    def loop_json(self, slip_lengths: dict[str, float]) -> dict[str, Any]:
        """The energy, slip and loop keys shared by ``microslip loop --json`` and
        ``microslip fe --json`` (whatever solver made the loop); ``slip_lengths`` in mm by
        domain, the first one also reported as ``slip_length_mm``."""
        return {
            "peak_displacement_mm": self.peak_displacement,
            "dissipated_energy_Nmm": self.dissipated_energy,
            "strain_energy_Nmm": self.strain_energy,
            "strain_energy_definition": self.strain_energy_kind,
            "loss_factor": self.loss_factor,
            "slip_length_mm": next(iter(slip_lengths.values())),
            "slip_length_by_domain_mm": slip_lengths,
            "loop": {"force_N": self.loop.force, "displacement_mm": self.loop.displacement},
        }

    def summary(self) -> dict[str, float | str]:
        """Scalar results with their units in the keys."""
        return {
            "amplitude_N": self.amplitude,
            "peak_displacement_mm": self.peak_displacement,
            "dissipated_energy_Nmm": self.dissipated_energy,
            "strain_energy_Nmm": self.strain_energy,
            "strain_energy_definition": self.strain_energy_kind,
            "loss_factor": self.loss_factor,
        }
