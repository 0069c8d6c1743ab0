"""The clamp on a mesh: the nine values that put a mesh on its rigid base and clamp it, as one
validated parameter object that both FE solvers and the structure studies take.

Units: N, MPa, N/mm^3.

>>> clamp = MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
...                   poisson_ratio=0.33, friction=0.5)
>>> clamp.normal_contact, clamp.normal_slope, clamp.stick_slope
('fixed', 100000.0, 10000.0)
>>> MeshClamp("contact", "clamp", normal_force=-1.0, modulus=70000.0, poisson_ratio=0.33,
...           friction=0.5)
Traceback (most recent call last):
...
microslip.errors.ParameterError: normal_force must be > 0 (N), got -1.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..conventions import check_positive
from ..errors import ParameterError
from .constants import DEFAULT_NORMAL_CONTACT, DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE

if TYPE_CHECKING:
    from .assembly import Assembly
    from .builtin.meshmodel import MeshModel
    from .hexmesh import HexMesh

__all__ = ["NORMAL_CONTACT_NAMES", "MeshClamp", "clamped_model"]

#: The normal-contact readings a clamp on a mesh names (the built-in solver's
#: :data:`microslip.fe.builtin.normal.NORMAL_CONTACTS`; a test holds the two equal).
NORMAL_CONTACT_NAMES = ("fixed", "penalty")


@dataclass(frozen=True)
class MeshClamp:
    """A mesh's clamp: the face on the rigid base, the clamped face, the clamping force, the
    material and the contact law.

    Attributes
    ----------
    contact_set, clamp_set : str
        Node sets or surfaces of the mesh: the flat face on the rigid base, and the face that
        carries the clamping pressure.
    normal_force : float
        F_N, N (> 0).
    modulus : float
        E, MPa (> 0).
    poisson_ratio : float
        nu, in (-1, 0.5).
    friction : float
        mu (> 0).
    stick_slope : float
        Tangential penalty lambda, N/mm^3 (> 0).
    normal_contact : {"fixed", "penalty"}
        :data:`~microslip.fe.constants.DEFAULT_NORMAL_CONTACT` unless named.
    normal_slope : float
        Normal penalty k_n, N/mm^3 (> 0; used by ``penalty``).
    """

    contact_set: str
    clamp_set: str
    normal_force: float
    modulus: float
    poisson_ratio: float
    friction: float
    stick_slope: float = DEFAULT_STICK_SLOPE
    normal_contact: str = DEFAULT_NORMAL_CONTACT
    normal_slope: float = DEFAULT_NORMAL_SLOPE

    def __post_init__(self) -> None:
        for name in ("contact_set", "clamp_set"):
            value = getattr(self, name)
            if not (isinstance(value, str) and value):
                raise ParameterError(f"{name} must name a set of the mesh, got {value!r}")
        for name, unit in (("normal_force", "N"), ("modulus", "MPa"), ("friction", ""),
                           ("stick_slope", "N/mm^3"), ("normal_slope", "N/mm^3")):
            object.__setattr__(self, name, check_positive(name, getattr(self, name), unit))
        try:
            nu = float(self.poisson_ratio)
        except (TypeError, ValueError):
            nu = math.nan
        if not (math.isfinite(nu) and -1.0 < nu < 0.5):
            raise ParameterError(f"poisson_ratio must be in (-1, 0.5), got "
                                 f"{self.poisson_ratio!r}")
        object.__setattr__(self, "poisson_ratio", nu)
        if self.normal_contact not in NORMAL_CONTACT_NAMES:
            raise ParameterError(f"unknown normal contact {self.normal_contact!r}; choose one "
                                 f"of {', '.join(NORMAL_CONTACT_NAMES)}")

    @property
    def assembly(self) -> Assembly:
        """This clamp as the :class:`~microslip.fe.assembly.Assembly` it is shorthand for:
        one body on the rigid base, one preload, one material."""
        from .assembly import rigid_base

        return rigid_base(**self.model_options())

    def model_options(self) -> dict[str, Any]:
        """The keyword arguments of
        :func:`~microslip.fe.builtin.meshmodel.build_mesh_model` (and of the CalculiX mesh
        run) this clamp gives."""
        return {"contact_set": self.contact_set, "clamp_set": self.clamp_set,
                "normal_force": self.normal_force, "modulus": self.modulus,
                "poisson_ratio": self.poisson_ratio, "friction": self.friction,
                "stick_slope": self.stick_slope, "normal_contact": self.normal_contact,
                "normal_slope": self.normal_slope}


def clamped_model(mesh: HexMesh, clamp: MeshClamp | Assembly, **options: Any) -> MeshModel:
    """The body of ``mesh`` on its rigid base, clamped by ``clamp``: the built-in solver's
    :class:`~microslip.fe.builtin.meshmodel.MeshModel` after the clamping step (``options``:
    ``element``, ``linear_solver``, ``newton``, ``condensed`` of
    :func:`~microslip.fe.builtin.meshmodel.build_mesh_model`)."""
    from .assembly import as_assembly
    from .builtin.meshmodel import build_mesh_model

    return build_mesh_model(mesh, as_assembly(clamp), **options)
