"""An assembly on a mesh: the bodies, how they touch, what presses them and what holds them,
as one validated parameter object that both FE solvers and the structure studies take.

A mesh of hexahedra holds one or more deformable bodies (its connected parts). The
:class:`Assembly` says

* **contacts** (:class:`Contact`): a face of one body and the face of another body it meets
  (conforming: coincident nodes, each node of the face paired with the counter face's node
  at the same place); with no counter face, the rigid flat base under the face;
* **preloads** (:class:`Preload`): a face and the force that presses it inward (a uniform
  traction F / A along the face's inward normal, consistent nodal shares; or a pressure law
  along an axis of the face, the paper's box's clamp). A bolt is the preload of its head
  face and of its nut face;
* **supports** (:class:`Support`): node sets and the directions held there (global x, y, z);
* **materials** (:class:`Material`): modulus, Poisson's ratio and density of an element set
  (a gmsh volume group or an ``*ELSET``), or of every element;
* the **contact law** of every contact: friction mu, stick slope lambda, the normal contact
  (``fixed`` or ``penalty``) and its slope.

Today's clamp (one body on the rigid base, one pressed face, one material) is its shorthand,
:func:`rigid_base`. Units: N, mm, MPa, kg/m^3, N/mm^3.

>>> a = rigid_base(contact_set="contact", clamp_set="clamp", normal_force=2000.0,
...                modulus=70000.0, poisson_ratio=0.33, friction=0.5)
>>> a.contacts[0].counter is None, a.clamp_force, a.modulus
(True, 2000.0, 70000.0)
>>> Assembly(contacts=(Contact("a", "a"),), preloads=(Preload("top", 10.0),),
...          materials=(Material(1.0, 0.3),), friction=0.3)
Traceback (most recent call last):
...
microslip.errors.ParameterError: contact a:a: a face cannot be its own counter face
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from ..conventions import (
    DEFAULT_NORMAL_CONTACT,
    DEFAULT_NORMAL_SLOPE,
    DEFAULT_STICK_SLOPE,
    DENSITY_RANGE,
    check_positive,
)
from ..errors import ParameterError

__all__ = ["DIRECTIONS", "NORMAL_CONTACT_NAMES", "Assembly", "Contact", "ContactPair",
           "Material", "Preload",
           "Shank", "Support", "as_assembly", "bolt", "rigid_base"]

#: The normal-contact readings (the built-in solver's
#: :data:`microslip.fe.builtin.normal.NORMAL_CONTACTS`; a test holds the two equal).
NORMAL_CONTACT_NAMES = ("fixed", "penalty")
#: Global directions a support may hold.
DIRECTIONS = "xyz"


def _name(what: str, value: Any) -> str:
    if not (isinstance(value, str) and value and ":" not in value):
        raise ParameterError(f"{what} must name a set of the mesh, got {value!r}")
    return value


@dataclass(frozen=True)
class Contact:
    """A contact: the nodes of ``face`` (the contact nodes, slave side) press on ``counter``
    (a face of another body, master side) or, with ``counter`` None, on the rigid flat base."""

    face: str
    counter: str | None = None

    def __post_init__(self) -> None:
        _name("a contact's face", self.face)
        if self.counter is not None:
            _name("a contact's counter face", self.counter)
            if self.counter == self.face:
                raise ParameterError(f"contact {self.label}: a face cannot be its own counter "
                                     "face")

    @property
    def label(self) -> str:
        """``FACE`` or ``FACE:COUNTER`` as ``--contact`` takes it."""
        return self.face if self.counter is None else f"{self.face}:{self.counter}"


@dataclass(frozen=True)
class Preload:
    """``force`` (N, > 0) pressing the face ``face`` inward, as a uniform traction; or, with a
    ``distribution`` (a :class:`~microslip.models.interface.PressureLaw`, mean 1), as the
    traction p(xi) F / A along the global ``axis`` (``x``, ``y`` or ``z``), xi = 0 .. 1
    across the face's extent along it: the paper's box takes the clamp's pressure law along
    its length so."""

    face: str
    force: float
    distribution: Any = None
    axis: str = "x"

    def __post_init__(self) -> None:
        _name("a preload's face", self.face)
        object.__setattr__(self, "force", check_positive(f"preload {self.face}'s force",
                                                         self.force, "N"))
        if self.distribution is not None:
            from ..models.interface import PressureLaw

            if not isinstance(self.distribution, PressureLaw):
                raise ParameterError(f"preload {self.face}: a distribution must be a "
                                     "PressureLaw (microslip.models.interface), got "
                                     f"{type(self.distribution).__name__}")
        if self.axis not in tuple(DIRECTIONS):
            raise ParameterError(f"preload {self.face}: the distribution's axis must be one "
                                 f"of x, y, z, got {self.axis!r}")

    def __repr__(self) -> str:
        more = ("" if self.distribution is None else
                f", distribution={self.distribution.name!r}, axis={self.axis!r}")
        return f"Preload(face={self.face!r}, force={self.force!r}{more})"

    def shares(self, mesh: Any, faces: Any) -> tuple[Any, Any]:
        """The nodes of ``faces`` (element, face rows of ``mesh``) and their shares of the
        force (adding up to 1): the consistent shares of a uniform traction
        (:func:`~microslip.fe.hexmesh.face_load`), or of the distribution along the axis
        (:func:`~microslip.fe.hexmesh.law_face_load`)."""
        from .hexmesh import face_load, law_face_load

        if self.distribution is None:
            nodes, share, _ = face_load(mesh, faces)
            return nodes, share
        return law_face_load(mesh, faces, self.distribution.shape, DIRECTIONS.index(self.axis))


@dataclass(frozen=True)
class Shank:
    """A bolt's shank between its ``head`` and ``nut`` faces (node sets or surfaces): a
    circular elastic beam of ``diameter`` (mm) and ``modulus`` (MPa; None: the first
    material's) between the faces' mean motions, active after the preload
    (:mod:`microslip.fe.builtin.shank`)."""

    head: str
    nut: str
    diameter: float
    modulus: float | None = None
    poisson_ratio: float = 0.3

    def __post_init__(self) -> None:
        _name("a shank's head face", self.head)
        _name("a shank's nut face", self.nut)
        if self.head == self.nut:
            raise ParameterError(f"bolt {self.head}: the head and the nut are one face")
        object.__setattr__(self, "diameter", check_positive(
            f"bolt {self.head}:{self.nut}'s diameter", self.diameter, "mm"))
        if self.modulus is not None:
            object.__setattr__(self, "modulus", check_positive(
                f"bolt {self.head}:{self.nut}'s modulus", self.modulus, "MPa"))
        nu = float(self.poisson_ratio)
        if not -1.0 < nu < 0.5:
            raise ParameterError(f"bolt {self.head}:{self.nut}'s poisson_ratio must be in "
                                 f"(-1, 0.5), got {self.poisson_ratio!r}")


#: The assembly's contact under the name the top-level API gives it (``microslip.Contact`` is
#: the 1-D models' contact).
ContactPair = Contact


def bolt(head: str, nut: str, force: float, diameter: float | None = None,
         modulus: float | None = None) -> tuple[tuple[Preload, ...], tuple[Shank, ...]]:
    """A bolt: its head and nut faces each pressed by ``force`` (N), and with ``diameter``
    (mm) a shank between them. Returns (preloads, shanks) to put into an :class:`Assembly`."""
    pre = (Preload(head, force), Preload(nut, force))
    return pre, (() if diameter is None else (Shank(head, nut, diameter, modulus),))


@dataclass(frozen=True)
class Support:
    """The nodes of ``set`` held in the global ``directions`` (a subset of ``xyz``)."""

    set: str
    directions: str = DIRECTIONS

    def __post_init__(self) -> None:
        _name("a support", self.set)
        d = str(self.directions).lower()
        if not d or any(c not in DIRECTIONS for c in d) or len(set(d)) != len(d):
            raise ParameterError(f"support {self.set}: directions must be letters of xyz, each "
                                 f"once (e.g. xyz, z, xy), got {self.directions!r}")
        object.__setattr__(self, "directions", "".join(c for c in DIRECTIONS if c in d))

    @property
    def components(self) -> tuple[int, ...]:
        """The held global components (0 x, 1 y, 2 z)."""
        return tuple(DIRECTIONS.index(c) for c in self.directions)


@dataclass(frozen=True)
class Material:
    """Linear elastic material of the element set ``elset`` (None: every element not named by
    another material). ``density`` kg/m^3 (None: not given; the modal commands need it)."""

    modulus: float
    poisson_ratio: float
    density: float | None = None
    elset: str | None = None

    def __post_init__(self) -> None:
        where = "" if self.elset is None else f" of {self.elset}"
        if self.elset is not None:
            _name("a material's element set", self.elset)
        object.__setattr__(self, "modulus", check_positive(f"modulus{where}", self.modulus,
                                                           "MPa"))
        try:
            nu = float(self.poisson_ratio)
        except (TypeError, ValueError):
            nu = math.nan
        if not (math.isfinite(nu) and -1.0 < nu < 0.5):
            raise ParameterError(f"poisson_ratio{where} must be in (-1, 0.5), got "
                                 f"{self.poisson_ratio!r}")
        object.__setattr__(self, "poisson_ratio", nu)
        if self.density is not None:
            rho = check_positive(f"density{where}", self.density, "kg/m^3")
            lo, hi = DENSITY_RANGE
            if not lo <= rho <= hi:
                hint = (" (t/mm^3? 7.85e-9 t/mm^3 is 7850 kg/m^3)" if rho < 1e-3 else
                        " (g/cm^3? 7.85 g/cm^3 is 7850 kg/m^3)" if rho < lo else "")
                raise ParameterError(f"density{where} = {rho:g} kg/m^3 is outside "
                                     f"[{lo:g}, {hi:g}] kg/m^3 of engineering materials{hint}")
            object.__setattr__(self, "density", rho)


@dataclass(frozen=True)
class Assembly:
    """The bodies of a mesh: contacts, preloads, supports, materials and the contact law.

    Attributes
    ----------
    contacts : tuple of Contact
        At least one.
    preloads : tuple of Preload
        At least one (the clamping force; a bolt's head and nut faces).
    materials : tuple of Material
        At least one; at most one without an element set (every other element).
    supports : tuple of Support
    friction : float
        mu (> 0), every contact.
    stick_slope : float
        Tangential penalty lambda, N/mm^3.
    normal_contact : {"fixed", "penalty"}
    normal_slope : float
        k_n, N/mm^3 (``penalty``).
    """

    contacts: tuple[Contact, ...]
    preloads: tuple[Preload, ...]
    materials: tuple[Material, ...]
    friction: float
    supports: tuple[Support, ...] = ()
    stick_slope: float = DEFAULT_STICK_SLOPE
    normal_contact: str = DEFAULT_NORMAL_CONTACT
    normal_slope: float = DEFAULT_NORMAL_SLOPE
    shanks: tuple[Shank, ...] = ()

    def __post_init__(self) -> None:
        for name, kind in (("contacts", Contact), ("preloads", Preload),
                           ("materials", Material), ("supports", Support),
                           ("shanks", Shank)):
            items = tuple(getattr(self, name))
            if any(not isinstance(x, kind) for x in items):
                raise ParameterError(f"{name} must be {kind.__name__} objects")
            object.__setattr__(self, name, items)
        if not self.contacts:
            raise ParameterError("an assembly needs at least one contact (--contact SET or "
                                 "--contact SET:COUNTER_SET)")
        if not self.preloads:
            raise ParameterError("an assembly needs at least one preload (--preload SET:FORCE, "
                                 "or --clamp-set with --normal-force)")
        if not self.materials:
            raise ParameterError("an assembly needs a material (--material or --modulus with "
                                 "--poisson-ratio)")
        faces = [c.face for c in self.contacts]
        twice = sorted({f for f in faces if faces.count(f) > 1})
        if twice:
            raise ParameterError(f"the face {twice[0]!r} is in two contacts; name each "
                                 "contact face once")
        sets = [m.elset for m in self.materials]
        twice_m = sorted({str(s) for s in sets if sets.count(s) > 1})
        if twice_m:
            what = "every element" if twice_m[0] == "None" else repr(twice_m[0])
            raise ParameterError(f"two materials for {what}; give each element set one")
        for name, unit in (("friction", ""), ("stick_slope", "N/mm^3"),
                           ("normal_slope", "N/mm^3")):
            object.__setattr__(self, name, check_positive(name, getattr(self, name), unit))
        if self.normal_contact not in NORMAL_CONTACT_NAMES:
            raise ParameterError(f"unknown normal contact {self.normal_contact!r}; choose one "
                                 f"of {', '.join(NORMAL_CONTACT_NAMES)}")

    # -- the shorthand's names, read by the reports and the 1-D comparisons -------------------
    @property
    def contact_set(self) -> str:
        """The first contact's face."""
        return self.contacts[0].face

    @property
    def clamp_set(self) -> str:
        """The first preload's face."""
        return self.preloads[0].face

    @property
    def clamp_force(self) -> float:
        """F_N, N: the largest preload (the force an interface carries; a bolt presses its
        head and its nut face with the same force)."""
        return max(p.force for p in self.preloads)

    @property
    def normal_force(self) -> float:
        """Alias of :attr:`clamp_force` (the shorthand's name)."""
        return self.clamp_force

    @property
    def modulus(self) -> float:
        """E of the first material, MPa."""
        return self.materials[0].modulus

    @property
    def poisson_ratio(self) -> float:
        """nu of the first material."""
        return self.materials[0].poisson_ratio

    @property
    def rigid_base_only(self) -> bool:
        """True when every contact is on the rigid base (no pair of bodies)."""
        return all(c.counter is None for c in self.contacts)

    @property
    def is_shorthand(self) -> bool:
        """One body on the rigid base, one preload, one material, no support: the clamp."""
        return (len(self.contacts) == 1 and self.rigid_base_only and len(self.preloads) == 1
                and len(self.materials) == 1 and self.materials[0].elset is None
                and not self.supports and not self.shanks)

    def set_names(self) -> tuple[str, ...]:
        """Every node set or surface the assembly names (for checks against a mesh)."""
        out: list[str] = []
        for c in self.contacts:
            out += [c.face] + ([] if c.counter is None else [c.counter])
        out += [p.face for p in self.preloads] + [s.set for s in self.supports]
        for b in self.shanks:
            out += [b.head, b.nut]
        return tuple(dict.fromkeys(out))

    def with_law(self, **law: Any) -> Assembly:
        """The same assembly with other contact-law values (``friction``, ``stick_slope``,
        ``normal_contact``, ``normal_slope``)."""
        bad = sorted(set(law) - {"friction", "stick_slope", "normal_contact", "normal_slope"})
        if bad:
            raise ParameterError(f"not a contact-law value: {', '.join(bad)}")
        return replace(self, **law)

    def describe(self) -> dict[str, Any]:
        """Plain summary for JSON."""
        return {
            "contacts": [{"face": c.face, "counter": c.counter or "rigid base"}
                         for c in self.contacts],
            "preloads": [{"face": p.face, "force_N": p.force}
                         | ({} if p.distribution is None else
                            {"distribution": p.distribution.name, "axis": p.axis})
                         for p in self.preloads],
            "supports": [{"set": s.set, "directions": s.directions} for s in self.supports],
            "shanks": [{"head": b.head, "nut": b.nut, "diameter_mm": b.diameter,
                        "modulus_MPa": b.modulus or self.modulus} for b in self.shanks],
            "materials": [{"elset": m.elset or "all", "modulus_MPa": m.modulus,
                           "poisson_ratio": m.poisson_ratio, "density_kg_m3": m.density}
                          for m in self.materials],
            "friction": self.friction, "stick_slope_N_per_mm3": self.stick_slope,
            "normal_contact": self.normal_contact,
            "normal_slope_N_per_mm3": self.normal_slope}


def rigid_base(*, contact_set: str, clamp_set: str, normal_force: float, modulus: float,
               poisson_ratio: float, friction: float,
               stick_slope: float = DEFAULT_STICK_SLOPE,
               normal_contact: str = DEFAULT_NORMAL_CONTACT,
               normal_slope: float = DEFAULT_NORMAL_SLOPE,
               density: float | None = None) -> Assembly:
    """The shorthand: one body with its face ``contact_set`` on the rigid base, pressed by
    ``normal_force`` (N) on ``clamp_set``, of one material."""
    return Assembly(contacts=(Contact(contact_set),),
                    preloads=(Preload(clamp_set, normal_force),),
                    materials=(Material(modulus, poisson_ratio, density),),
                    friction=friction, stick_slope=stick_slope, normal_contact=normal_contact,
                    normal_slope=normal_slope)


def as_assembly(clamp: Any) -> Assembly:
    """An :class:`Assembly` from an assembly or a :class:`~microslip.fe.clamp.MeshClamp`."""
    if isinstance(clamp, Assembly):
        return clamp
    to = getattr(clamp, "assembly", None)
    if to is not None and isinstance(to, Assembly):
        return to
    raise ParameterError(f"expected an Assembly or a MeshClamp, got {type(clamp).__name__}")
