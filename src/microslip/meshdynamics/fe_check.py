"""The Table 1 bar reduced to its joint, against the built-in FE solver at the same motion.

The FE solver's coupled planar run (:func:`microslip.fe.builtin.coupling_study`: tip force along
the bar on the end face, centre force across it on the mid-length section) gives the joint
motion, the work-conjugate displacements (delta_tip, delta_centre) over one settled cycle,
and the energy dissipated per cycle W_FE. The reduced model keeps only those two
displacements as the structure's degrees of freedom (a static reduction: the FE loading is
quasi-static, so no modes are kept), with one two-directional joint between them and the
ground placed by the same path as ``modal`` and ``frf`` (:func:`.assemble.from_joints`);
its operators are built from the clamp's 1-D backbones (:func:`.distributions.clamp_joint`,
series spring = stick slope x width x length, the FE's contact stiffness). Driving the
joint with the FE's orbit gives its dissipation per cycle, W = closed integral of f . du,
for the circular coupling and the decoupled sum, beside the FE's; the tip force alone is the
1-D limit. Across the bar neither 1-D model is the FE's joint (the bar bends in its plane),
so the anisotropic joint (:func:`.operators2d.anisotropic`) takes the tip model along the
bar and the FE's own first loading across it (:func:`microslip.fe.builtin.fe_backbone`), its
elements paired by where they sit on the bar (``spatial``) or by slip order (``ordered``);
the FE-backbone operator on the FE's centre-only motion is the transverse 1-D limit.
docs/dynamics.md ("The reduced bar against the FE") gives the figures and
docs/interpretation.md the reading.

Units: N, mm, N·mm.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..conventions import DEFAULT_MESH
from ..dynamics.assemble import PlacedJoint, from_joints
from ..dynamics.distributions import DEFAULT_ELEMENTS, clamp_joint
from ..dynamics.files import MatrixFile
from ..dynamics.operators import IwanOperator
from ..dynamics.operators2d import PAIRINGS
from ..dynamics.structure import Structure
from ..errors import ParameterError
from ..fe.constants import DEFAULT_STICK_SLOPE
from ..jointspec import series_stiffness
from ..named import result
from ..params import ClampParams

__all__ = ["FEComparison", "cycle_work", "fe_comparison", "orbit_work", "reduced_bar"]


@result
class FEComparison:
    """Dissipation per cycle (N·mm) of the FE and of the reduced joint at the FE's motion.

    Attributes
    ----------
    fe_coupled, fe_tip_only, fe_centre_only : float
        W of the FE runs: both forces, the tip force alone, the centre force alone.
    circular, decoupled : float
        The reduced joint on the coupled FE orbit: one circular Coulomb limit (the tip
        model's elements, :class:`.operators2d.CircularIwan`), and the paper's decoupled sum
        (tip model along the bar, centre model across it).
    tip_limit : float
        The tip model's operator on the FE's tip-only motion (the 1-D limit).
    anisotropic : dict of str to float
        The anisotropic joint on the coupled FE orbit, per pairing of
        :data:`.operators2d.PAIRINGS`: tip model along the bar, the FE's first loading of
        the centre force across it.
    centre_limit : float
        The FE-backbone operator across the bar on the FE's centre-only motion (the
        transverse 1-D limit).
    orbit : ndarray, shape (n, 2)
        The coupled FE orbit (delta_tip, delta_centre) over the last cycle, mm.
    fe_force : ndarray, shape (n, 2)
        The FE's applied forces (F_tip, F_centre) at those samples, N.
    joint_force : dict of str to ndarray, shape (n, 2)
        Each reduced joint's force on that orbit, N: ``circular``, ``decoupled`` and
        ``anisotropic <pairing>``.
    tip_orbit : ndarray, shape (n,)
        delta_tip of the tip-only run over its last cycle, mm.
    series_stiffness : float
        Series spring of the joint operators, N/mm.
    """

    fe_coupled: float
    fe_tip_only: float
    fe_centre_only: float
    circular: float
    decoupled: float
    tip_limit: float
    anisotropic: dict[str, float]
    centre_limit: float
    orbit: np.ndarray
    fe_force: np.ndarray
    joint_force: dict[str, np.ndarray]
    tip_orbit: np.ndarray
    series_stiffness: float

    def summary(self) -> dict[str, Any]:
        """The figures with units, and the ratios to the FE."""
        return {"fe_coupled_Nmm": self.fe_coupled, "fe_tip_only_Nmm": self.fe_tip_only,
                "fe_centre_only_Nmm": self.fe_centre_only,
                "fe_decoupled_sum_Nmm": self.fe_tip_only + self.fe_centre_only,
                "circular_Nmm": self.circular, "decoupled_Nmm": self.decoupled,
                "tip_limit_Nmm": self.tip_limit,
                "circular_over_fe": self.circular / self.fe_coupled,
                "decoupled_over_fe": self.decoupled / self.fe_coupled,
                "tip_limit_over_fe": self.tip_limit / self.fe_tip_only,
                "anisotropic_Nmm": dict(self.anisotropic),
                "anisotropic_over_fe": {k: v / self.fe_coupled
                                        for k, v in self.anisotropic.items()},
                "centre_limit_Nmm": self.centre_limit,
                "centre_limit_over_fe": self.centre_limit / self.fe_centre_only,
                "orbit_amplitude_mm": (np.ptp(self.orbit, axis=0) / 2).tolist()}


def cycle_work(force: np.ndarray, displacement: np.ndarray) -> float:
    """Closed integral of f . du over one periodic cycle (samples without the repeated
    end point; trapezoidal, wrapping around), N·mm. Works for (n,) and (n, d) arrays."""
    f = np.asarray(force, dtype=float).reshape(len(force), -1)
    u = np.asarray(displacement, dtype=float).reshape(len(displacement), -1)
    du = np.roll(u, -1, axis=0) - u
    return float(np.sum(0.5 * (f + np.roll(f, -1, axis=0)) * du))


def reduced_bar(along: IwanOperator, across: IwanOperator | None, coupling: str,
                pairing: str | None = None) -> Structure:
    """The bar reduced to its joint: DOFs (delta_tip, delta_centre), one two-directional
    joint to the ground, ``along`` the bar and ``across`` it (None: ``along``), coupled by
    ``coupling`` with ``pairing`` (:data:`.operators2d.COUPLINGS`, the same path as
    ``modal`` and ``frf``). Mass and stiffness are the unit matrix and zero: only the joint
    matters for a prescribed motion."""
    matrices = MatrixFile(mass=np.eye(2), stiffness=np.zeros((2, 2)),
                          damping=np.zeros((2, 2)), joints=np.zeros((0, 1, 2), dtype=np.int64),
                          path="reduced Table 1 bar")
    return from_joints(matrices, [PlacedJoint(np.array([[0, -1], [1, -1]]), along, coupling,
                                              across, pairing)])


def orbit_force(structure: Structure, q: np.ndarray) -> np.ndarray:
    """The joints' closed periodic force on the DOFs, N, shape (n, n_dof), at the periodic
    DOF motion ``q`` ((n, n_dof), mm, without the repeated end point)."""
    force = np.zeros(np.shape(q))
    for link in structure.joints:
        u = q @ link.weights
        op = link.operator
        if link.directions == 1:
            f, _ = op.periodic_force(np.ascontiguousarray(u[:, 0]))
            f = f[:, None]
        else:
            f = op.periodic_force(u)
        force += f @ link.weights.T
    return force


def orbit_work(structure: Structure, q: np.ndarray) -> float:
    """Energy the joints of ``structure`` dissipate per cycle on the periodic DOF motion
    ``q`` ((n, n_dof), mm, without the repeated end point), N·mm."""
    return cycle_work(orbit_force(structure, q), q)


def fe_comparison(params: ClampParams, tip_amplitude: float, centre_amplitude: float,
                  phase_deg: float = 90.0, *, mesh: Any = DEFAULT_MESH,
                  increments_per_cycle: int = 256, cycles: int = 6,
                  stick_slope: float = DEFAULT_STICK_SLOPE,
                  elements: int = DEFAULT_ELEMENTS) -> FEComparison:
    """Run the FE's coupled planar study and the first loading across the bar, and drive
    the reduced joints with the FE's orbits."""
    from ..fe.builtin import box_model, coupling_study, fe_backbone
    from .febackbone import backbone_operator

    fem = box_model(params, mesh, stick_slope=stick_slope)
    study = coupling_study(params, tip_amplitude, centre_amplitude, phase_deg, cycles=cycles,
                           increments_per_cycle=increments_per_cycle, mesh=fem)
    if not study.coupled.converged or not study.tip_only.converged:
        raise ParameterError("the FE runs did not converge; see microslip.fe.builtin")
    series = series_stiffness(params, stick_slope)
    tip = clamp_joint("tip", params, series, elements=elements)
    centre = clamp_joint("centre", params, series, elements=elements)
    c = study.coupled.last_cycle()
    coupled = study.coupled
    orbit = np.column_stack([coupled.tip_displacement[c], coupled.centre_displacement[c]])[:-1]
    tip_orbit = study.tip_only.tip_displacement[study.tip_only.last_cycle()][:-1]
    centre_orbit = study.centre_only.centre_displacement[study.centre_only.last_cycle()][:-1]
    across = backbone_operator(fe_backbone(params, "centre", mesh=fem), "fe-across")
    zeros = np.zeros_like(centre_orbit)
    bars = {"circular": reduced_bar(tip, None, "circular"),
            "decoupled": reduced_bar(tip, centre, "decoupled")}
    bars.update({f"anisotropic {name}": reduced_bar(tip, across, "circular", name)
                 for name in PAIRINGS})
    forces = {name: orbit_force(bar, orbit) for name, bar in bars.items()}
    work = {name: cycle_work(f, orbit) for name, f in forces.items()}
    return FEComparison(
        fe_coupled=study.coupled.dissipated_energy,
        fe_tip_only=study.tip_only.dissipated_energy,
        fe_centre_only=study.centre_only.dissipated_energy,
        circular=work["circular"], decoupled=work["decoupled"],
        tip_limit=orbit_work(reduced_bar(tip, None, "decoupled"),
                             np.column_stack([tip_orbit, np.zeros_like(tip_orbit)])),
        anisotropic={name: work[f"anisotropic {name}"] for name in PAIRINGS},
        centre_limit=orbit_work(reduced_bar(across, across, "decoupled"),
                                np.column_stack([zeros, centre_orbit])),
        orbit=orbit,
        fe_force=np.column_stack([study.coupled.f_tip[c], study.coupled.f_centre[c]])[:-1],
        joint_force=forces, tip_orbit=tip_orbit, series_stiffness=series)
