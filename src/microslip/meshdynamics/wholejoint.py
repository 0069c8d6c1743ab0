"""The whole-joint model: the interface as one rigid body with one joint (issue 23, item 4).

What an engineer can afford on a large structure: instead of a contact law at every contact
node (:mod:`.reduce`), the contact surface moves as a rigid body in its plane and carries one
joint. Three steps.

**Reduction to the interface's rigid-body motion** (a spider, RBE2; :mod:`.interface`): the
contact nodes follow the in-plane translations r1, r2 (mm) and the rotation c = R theta about
the normal through the area-weighted centroid, scaled by the interface's radius of gyration R
so that c is a length (mm) and its generalised force M / R a force (N); with ``penalty``
normal contact also the normal translation w and the two tilts. The Craig-Bampton ROM of
:func:`~.reduce.build_rom` is constrained to them (:func:`~.interface.reduce_to_interface`). A
rigid motion of the whole body is still exact (the constraint modes carry it); what is lost is
the interface's own deformation, which stiffens the structure
(:attr:`WholeJoint.stuck_frequencies`).

**The joint is the FE's own first loading of that interface**
(:func:`~.firstloading.first_loading`): the full frictional FE after the clamping step is
loaded monotonically by the studied mode's inertial pattern q M phi, from 0 to near gross
sliding, and at each increment the interface's generalised forces and displacements are
recorded: the resultant of the nodes' friction forces change sum tau_i (N; statically the
applied in-plane resultant) against the area-weighted mean displacement d = sum A_i u_i / sum
A_i (mm), both along the interface's direction of motion e in the stuck mode; and the moment
change about the normal over R (N) against the least-squares rotation c (mm). Each pair's
concave majorant (:func:`~.backbone.concave_majorant`) is the virgin curve of a
parallel-Jenkins (Iwan) operator (:func:`~microslip.dynamics.distributions.from_backbone`),
extended with its last slope to the interface's macroslip: mu F_N for the translation, mu sum
N_i rho_i / R for the rotation. Through this averaging the stuck FE has exactly the stiffness
sum lambda A_i in r1, r2 and c (no coupling: the centroid is area-weighted and lambda
uniform), so the joint's initial slope is the FE's stuck interface stiffness. The translation
joint is made two-directional by :func:`~microslip.dynamics.operators2d.circular`: **isotropic
in the plane**, the same backbone along any in-plane line (assumed; the contact's slip along
and across a long clamp differs, :func:`~microslip.dynamics.operators2d.anisotropic` would
take a second loading). The rotation carries (:data:`TORSION`) its own Iwan joint from the
same loading (``iwan``, default), or the linear stuck spring sum lambda A_i rho_i^2
(``stuck``, the classical whole-joint's torsion). The default is ``iwan`` because in a bending
mode in the contact plane the clamp carries the bending moment as a torque about the normal:
on the 24x6x2 cantilever M / R reaches 900 N near gross sliding against a resultant of 150 N,
and its secant has fallen to 1/37 of the stuck stiffness there, so a linear torsion spring
misses most of the mode's softening and damping (measured, benchmarks/joint_vs_fe.py: with it
the damping ratio is 78-100 % low, with ``iwan`` 16-88 %).

A mode whose interface resultant does not follow its mean displacement (out-of-plane bending
of a bar held on its face: the bending strain stretches the contact with a self-equilibrated
shear, the resultant even opposes the mean motion) gives no joint law; the translation
backbone is then the interface's pull test instead (:data:`~.firstloading.PULL`): equal forces
on the response set's nodes along e, the FE's own joint for a resultant load. The rigid
interface cannot represent that mode's damping at all: it comes from the distortion the
reduction removes (:attr:`~.jointbackbone.JointBackbone.source` says which loading made the
joint).

Instead of the FE's loading the translation's curve may be the paper's 1-D clamp model
(:data:`~.jointbackbone.BACKBONES` ``tip``, ``centre``;
:func:`~.jointbackbone.clamp_backbone`) on the contact patch seen along e (its length along e,
its width across, the body's thickness along the normal) behind the contact layer sum lambda
A_i, with the rotation's stuck spring: no FE run at all, what the joint of a large structure
is built from when the FE cannot be run.

A calibrated variant (:func:`~.jointbackbone.work_backbone`, ``work``) stretches the first
loading's displacements so that the joint does the interface's whole work, the distortion's
included: on the 24x6x2 cantilever's in-plane bending (benchmarks/joint_vs_fe.py) the stuck
frequency comes within 1.1 % of the full FE's (4.7 % kinematic), the frequency within 8 % and
the damping ratio 19-42 % low over the microslip range (kinematic: 15 %, and 16-88 % low), at
the price of a joint softer than the stuck interface seen through the averaging.

EPMC on the whole-joint :class:`~microslip.dynamics.structure.Structure`
(:func:`whole_joint_epmc`) uses the odd harmonics (both joints are odd; the penalty springs are
linear here). Units: N, mm, t (ROM), kg and N/m (Structure, SI), Hz.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..fe.builtin.meshmodel import MeshModel
from .firstloading import PULL, FirstLoading, first_loading
from .interface import Interface, interface, reduce_to_interface
from .jointbackbone import (
    BACKBONES,
    JointBackbone,
    clamp_backbone,
    joint_backbone,
    patch,
    shaken_down,
    work_backbone,
)
from .modes import Mode
from .reduce import SI_FACTOR, Rom

# the interface, its first loading and the joint's backbones live in their own modules
# (:mod:`.interface`, :mod:`.firstloading`, :mod:`.jointbackbone`); re-exported here, the
# whole-joint model's one entry point
__all__ = ["BACKBONES", "PULL", "TORSION", "FirstLoading", "Interface", "JointBackbone",
           "WholeJoint", "build_whole_joint", "clamp_backbone", "first_loading", "interface",
           "joint_backbone", "patch", "reduce_to_interface", "shaken_down",
           "whole_joint_epmc", "work_backbone"]

FloatArray = NDArray[np.float64]


def _torsion_iwan(backbone: JointBackbone, face: Interface) -> Any:
    return backbone.torsion()


def _torsion_stuck(backbone: JointBackbone, face: Interface) -> Any:
    return None


#: How the interface's rotation c = R theta is held: name -> (backbone, interface) -> the
#: rotation's 1-D operator, or None for the linear stuck spring sum lambda A_i rho_i^2
#: (lambda sum A_i on c) added to K_j.
TORSION: dict[str, Callable[[JointBackbone, Interface], Any]] = {
    "iwan": _torsion_iwan,
    "stuck": _torsion_stuck,
}


@dataclass(frozen=True, eq=False)
class WholeJoint:
    """The whole-joint model (:func:`build_whole_joint`).

    Attributes
    ----------
    structure : Structure
        SI matrices over (interface coordinates, fixed-interface modes); the translation
        joint on (r1, r2) and, with ``iwan`` torsion, the rotation's joint on c.
    transform : ndarray, shape (n_rom, n)
        T of :func:`reduce_to_interface`.
    face : Interface
    backbone : JointBackbone
    torsion : str
        A key of :data:`TORSION`.
    """

    structure: Any = field(repr=False)
    transform: FloatArray = field(repr=False)
    face: Interface = field(repr=False)
    backbone: JointBackbone = field(repr=False)
    torsion: str

    def stuck_frequencies(self, count: int | None = None) -> FloatArray:
        """Linear natural frequencies with the joint stuck, Hz, ascending."""
        f = np.asarray(self.structure.linear_frequencies(stuck=True))
        return f if count is None else f[:count]

    def mode_index(self, frequency_Hz: float) -> int:
        """0-based index of the stuck mode nearest (in ratio) ``frequency_Hz``: the full FE's
        mode as the whole-joint model has it."""
        f = self.stuck_frequencies()
        return int(np.argmin(np.abs(np.log(np.maximum(f, 1e-30) / frequency_Hz))))


def build_whole_joint(rom: Rom, model: MeshModel, mode: Mode, output: FloatArray, *,
                      torsion: str = "iwan", backbone: JointBackbone | str = "fe"
                      ) -> WholeJoint:
    """The whole-joint :class:`~microslip.dynamics.structure.Structure` of ``mode``: the ROM
    reduced to the interface's rigid motion (:func:`~.interface.reduce_to_interface`), the
    joint of ``backbone`` (a name of :data:`BACKBONES`, or a :class:`JointBackbone`) on it,
    the output ``output`` (n_rom,: the response set's mean displacement along the mode per
    ROM coordinate, as for :func:`~.reduce.rom_structure`) carried through T."""
    from ..dynamics.structure import JointLink, Structure

    if torsion not in TORSION:
        raise ParameterError(f"unknown torsion {torsion!r}; choose one of "
                             f"{', '.join(TORSION)}")
    if isinstance(backbone, str) and backbone not in BACKBONES:
        raise ParameterError(f"unknown backbone {backbone!r}; choose one of "
                             f"{', '.join(BACKBONES)}")
    face = interface(model)
    t, m, k = reduce_to_interface(rom, face)
    bb = (BACKBONES[backbone](model, mode, face) if isinstance(backbone, str)
          else backbone)
    n = m.shape[0]
    w = np.zeros((n, 2))
    w[0, 0] = w[1, 1] = 1.0
    links = [JointLink(bb.translation(), w)]
    rot = TORSION[torsion](bb, face)
    if rot is None:
        k = k.copy()
        k[2, 2] += bb.stuck_stiffness  # lambda sum A_i rho_i^2 / R^2 on c = R theta
    else:
        links.append(JointLink(rot, np.eye(n)[2]))
    out = np.asarray(output, dtype=float) @ t
    s = Structure(mass=m * SI_FACTOR, damping=np.zeros((n, n)), stiffness=k * SI_FACTOR,
                  joints=tuple(links), output=out)
    return WholeJoint(structure=s, transform=t, face=face, backbone=bb, torsion=torsion)


#: Amplitudes of the ladder from the first amplitude to one whose continuation failed.
LADDER = 8


def whole_joint_epmc(joint: WholeJoint, amplitudes: FloatArray, harmonics: int,
                     samples: int, frequency_Hz: float) -> tuple[Any, tuple[str, ...]]:
    """EPMC on the odd harmonics (:func:`~microslip.dynamics.modal_odd.epmc_odd`; both
    joints are odd) of the whole-joint mode nearest ``frequency_Hz`` (the full FE's stuck
    mode), at ``amplitudes`` (mm of the output).

    Returns the :class:`~microslip.dynamics.modal.ModalCurve` and warnings: if the
    continuation over the amplitudes fails, each amplitude is reached on its own by a
    ladder of :data:`LADDER` amplitudes from the first, and one that still fails (near the
    joint's macroslip) is NaN with its reason.
    """
    from ..dynamics.modal import ModalCurve
    from ..dynamics.modal_odd import epmc_odd

    a = np.asarray(amplitudes, dtype=float)
    index = joint.mode_index(frequency_Hz)
    try:
        return epmc_odd(joint.structure, a, harmonics, samples, index), ()
    except ParameterError:
        pass
    freq, zeta = np.full(a.size, np.nan), np.full(a.size, np.nan)
    warnings = []
    for i, ai in enumerate(a):
        ladder = np.geomspace(min(float(a.min()), ai), ai, LADDER if i else 1)
        try:
            c = epmc_odd(joint.structure, ladder, harmonics, samples, index)
        except ParameterError as exc:
            warnings.append(f"amplitude {i + 1} ({ai:.6g} mm): {exc}")
            continue
        freq[i], zeta[i] = c.frequency[-1], c.damping_ratio[-1]
    return ModalCurve(method="epmc", amplitude=a, frequency=freq, damping_ratio=zeta,
                      harmonics=harmonics, samples=samples), tuple(warnings)
