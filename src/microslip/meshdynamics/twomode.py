"""Two close modes that share the interface: coupled against decoupled joints (issue 23, item 6).

A post on a foot flange (:func:`microslip.fe.examples.post_on_plate_mesh`) bends in x and in
y at two close frequencies; a force on its top at 45 degrees excites both, and the contact
under the flange moves on an ellipse, whose shape the structure decides (the paper's
circular and elliptical loading, section 2 of Lord and Rongong 2016). Each contact node is
the 2-D Jenkins element of the full FE's law (stick slope x area, slip force mu N_i) with

* ``circular`` coupling: one circular Coulomb limit on the resultant (the full FE's own
  law, :mod:`.contact`), or
* ``decoupled``: two independent 1-D elements along x and y, the paper's decoupled sum
  (:data:`microslip.dynamics.operators2d.COUPLINGS`).

The study, all on the Craig-Bampton ROM of :mod:`.reduce` (fixed normal contact, every
contact node kept) and checked on the full FE:

1. :func:`bending_pair` (:mod:`.twomodecase`): the full FE's two lowest stuck modes, their
   directions (x, y) and their closeness;
2. :func:`forced_response` (:mod:`.twomoderesponse`): the ROM's frequency response
   (harmonic balance, continuation) to ``F cos(w t)`` on the top set along the forcing angle,
   with light linear modal damping zeta_0 in the ROM's stuck modes; from every point the
   top's first-harmonic amplitude along x and y, the interface orbit and the energy per cycle
   the joints dissipate, W_J;
3. :func:`fe_check` (:mod:`.twomodecheck`): the full FE at a point of the ROM's curve, under
   the quasi-static equivalent of the ROM's harmonic solution carried to it by the two
   bending modes, against the ROM loaded the same way with circular and with decoupled
   joints (:func:`rom_quasistatic`, :mod:`.romquasistatic`): it tests the whole chain and
   shows the decoupled joints' error on the full FE's own terms.

Units: N, mm, s, Hz, t (ROM masses; SI in the :class:`~microslip.dynamics.structure.
Structure`), N·mm for energies.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..fe.builtin.meshrun import SineCycles
from ..fe.hexmesh import HexMesh
from .romquasistatic import rom_quasistatic
from .twomodecase import (
    COUPLINGS,
    BendingPair,
    TwoModeCase,
    bending_pair,
    frequency_window,
    study_rom,
    two_mode_model,
)
from .twomodecheck import (
    CheckPoint,
    check_points,
    fe_check,
    node_orbits,
    quadrature_load,
)
from .twomoderesponse import (
    Orbit,
    Peak,
    ResponseCurve,
    energy_table,
    forced_response,
    forcing_shape,
    interface_rows,
    orbit,
    rom_system,
)

# the study's parts live in their own modules (:mod:`.twomodecase`, :mod:`.twomoderesponse`,
# :mod:`.twomodecheck`, :mod:`.romquasistatic`); re-exported here, the study's one entry point
__all__ = [
    "COUPLINGS",
    "BendingPair",
    "CheckPoint",
    "Orbit",
    "Peak",
    "ResponseCurve",
    "TwoModeCase",
    "TwoModeStudy",
    "bending_pair",
    "check_points",
    "energy_table",
    "fe_check",
    "forced_response",
    "forcing_shape",
    "interface_rows",
    "node_orbits",
    "orbit",
    "quadrature_load",
    "rom_quasistatic",
    "rom_system",
    "two_mode_model",
    "two_mode_study",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class TwoModeStudy:
    """The whole study (:func:`two_mode_study`).

    Attributes
    ----------
    case : TwoModeCase
    dof : int
        The full FE's unknowns.
    contact_nodes : int
    pair : BendingPair
    rom_dofs : int
    rom_frequencies_Hz : ndarray, shape (2,)
        The ROM's two lowest stuck frequencies (the full FE's to ~1e-9).
    frequency_range : tuple of float
        Hz.
    curves : tuple of ResponseCurve
        For each force, the circular then the decoupled curve.
    checks : tuple of CheckPoint
        At :func:`check_points` of each circular curve of the check forces that crossed
        the whole range.
    """

    case: TwoModeCase
    dof: int
    contact_nodes: int
    pair: BendingPair = field(repr=False)
    rom_dofs: int
    rom_frequencies_Hz: FloatArray = field(repr=False)
    frequency_range: tuple[float, float]
    curves: tuple[ResponseCurve, ...] = field(repr=False)
    checks: tuple[CheckPoint, ...] = field(repr=False)

    def curve(self, force: float, coupling: str) -> ResponseCurve:
        """The curve of ``force`` (N) and ``coupling``."""
        for c in self.curves:
            if c.force == force and c.coupling == coupling:
                return c
        raise ParameterError(f"no {coupling} curve at {force:g} N")

    def differences(self) -> list[dict[str, float | str]]:
        """Decoupled against circular at each force and peak that both curves passed:
        relative differences of the peak amplitude, the peak frequency and W_J at the peak
        ((decoupled - circular) / circular)."""
        out: list[dict[str, float | str]] = []
        for force in sorted({c.force for c in self.curves}):
            a, b = self.curve(force, "circular"), self.curve(force, "decoupled")
            for pa, pb in zip(a.peaks, b.peaks, strict=True):
                if not (pa.complete and pb.complete):
                    continue
                out.append({"force_N": force, "axis": pa.axis,
                            "amplitude": pb.amplitude_mm / pa.amplitude_mm - 1.0,
                            "frequency": pb.frequency_Hz / pa.frequency_Hz - 1.0,
                            "joint_energy": pb.joint_energy_Nmm / pa.joint_energy_Nmm - 1.0})
        return out


def two_mode_study(mesh: HexMesh, case: TwoModeCase, forces: Sequence[float],
                   check_forces: Sequence[float] = (),
                   frequency_range: tuple[float, float] | None = None,
                   history: SineCycles | None = None) -> TwoModeStudy:
    """Coupled against decoupled joints on the ROM at each of ``forces`` (N), and the full
    FE at :func:`check_points` of the circular curves of ``check_forces`` (a subset of
    ``forces``); ``frequency_range`` default :func:`frequency_window`."""
    bad = [f for f in check_forces if f not in forces]
    if bad:
        raise ParameterError(f"check forces must be among the forces {list(forces)} N, got "
                             f"{bad}")
    model = two_mode_model(mesh, case)
    pair = bending_pair(model, case)
    rom = study_rom(model, case)
    window = frequency_window(pair) if frequency_range is None else frequency_range
    curves = [forced_response(model, rom, case, float(f), c, window)
              for f in forces for c in COUPLINGS]
    checks = []
    for f in check_forces:
        curve = next(c for c in curves if c.force == f and c.coupling == "circular")
        if not curve.success:  # its peaks may be where the continuation stopped
            continue
        for label, i in check_points(curve).items():
            checks.append(fe_check(model, rom, pair, case, curve, i, label, history))
    return TwoModeStudy(case=case, dof=model.dof, contact_nodes=int(model.contact_nodes.size),
                        pair=pair, rom_dofs=rom.dofs,
                        rom_frequencies_Hz=rom.stuck_frequencies(2),
                        frequency_range=(float(window[0]), float(window[1])),
                        curves=tuple(curves), checks=tuple(checks))
