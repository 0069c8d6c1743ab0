"""The assembly's cards of the CalculiX mesh deck (issue 32, item 3): the bodies' contacts, the
rigid bases, the preloads, the supports and the materials of an
:class:`~microslip.fe.assembly.Assembly`, resolved against a
:class:`~microslip.fe.hexmesh.HexMesh` (:func:`resolve_assembly`) and written as cards
(:mod:`~.meshdeck` puts them in order).

What each piece becomes (names with the 1-based index of the piece, none for the first, so
that the rigid-base shorthand writes today's deck card for card):

* a contact ``Contact(face, counter)``: ``*SURFACE SCONTACT<k>`` (the face's element faces,
  slave side: its nodes), the master surface ``SCOUNTER<k>`` (the counter face's element
  faces, another body) or, with ``counter`` None, ``SBASE<k>``, the upper face of a rigid
  slab of fixed C3D8 bricks under the face (:func:`~.meshdeck.base_slab`, its elements
  ``BASE<k>``, its nodes ``NBASE<k>``); each contact its ``*SURFACE INTERACTION SI<k>`` (the
  one contact law: linear pressure-overclosure, Coulomb friction with the stick slope; the
  node-to-surface sigma_inf from that contact's mean pressure) and its ``*CONTACT PAIR``.
  Coincident nodes of a conforming interface stay distinct nodes: CalculiX has nothing to
  merge, the pair carries the interface;
* a preload ``Preload(face, force)``: ``*SURFACE SCLAMP<k>`` and, in the clamping step,
  ``*DSLOAD`` of the pressure force / area (CalculiX's consistent nodal shares of a uniform
  traction, as the clamp face's);
* a support ``Support(set, directions)``: ``*NSET NFIX<k>`` and its ``*BOUNDARY`` rows (one
  row per run of held components: ``xz`` is 1-1 and 3-3);
* materials: the shorthand's one material of every element is ``*MATERIAL BODY`` on the
  element set BODY (today's deck); otherwise material k is ``MAT<k>`` on ``*ELSET EMAT<k>``
  (the mesh's element set, or every element no other material names), with a comment naming
  the mesh's set. The bases take the first material (their nodes are all fixed).

Units: N, mm, MPa, kg/m^3 (written as t/mm^3).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...errors import ParameterError
from ..assembly import Assembly, Contact, Material, Preload, Support, as_assembly
from ..hexmesh import HexMesh, face_load
from .contactform import check_formulation
from .deck import (
    _name,
    _num,
    contact_pair_card,
    elset_card,
    material_card,
    nset_card,
    solid_section_card,
    surface_interaction_card,
)

__all__ = ["ResolvedAssembly", "ResolvedContact", "ResolvedMaterial", "ResolvedPreload",
           "boundary_rows", "contact_cards", "dsload_card", "material_cards", "preload_cards",
           "resolve_assembly", "support_cards"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: kg/m^3 to t/mm^3 (CalculiX's density in the N, mm, s system).
KG_M3_TO_T_MM3 = 1e-12


def dsload_card(surface: str, pressure: float) -> str:
    """``*DSLOAD``: uniform pressure (MPa, positive into the faces) on an element-face surface.

    >>> dsload_card("SCLAMP", 0.5)
    '*DSLOAD\\nSCLAMP, P, 0.5\\n'
    """
    return (f"*DSLOAD\n{_name('surface', surface)}, P, "
            f"{_num(pressure, 'pressure (MPa)', positive=True)}\n")


def _suffix(index: int) -> str:
    """'' for the first piece, else its 1-based index."""
    return "" if index == 1 else str(index)


@dataclass(frozen=True, eq=False)
class ResolvedContact:
    """A contact on the mesh: the slave faces, the counter faces (None: a rigid base) and the
    rigid base's slab (:class:`~.meshdeck.BaseSlab`, set by the deck writer)."""

    contact: Contact
    index: int
    faces: IntArray
    area: float
    counter_faces: IntArray | None

    @property
    def suffix(self) -> str:
        return _suffix(self.index)

    @property
    def slave(self) -> str:
        return f"SCONTACT{self.suffix}"

    @property
    def master(self) -> str:
        return f"S{'BASE' if self.on_base else 'COUNTER'}{self.suffix}"

    @property
    def interaction(self) -> str:
        return f"SI{self.suffix}"

    @property
    def on_base(self) -> bool:
        return self.counter_faces is None


@dataclass(frozen=True, eq=False)
class ResolvedPreload:
    """A preload's faces, their area (mm^2) and its surface's name."""

    preload: Preload
    index: int
    faces: IntArray
    area: float

    @property
    def surface(self) -> str:
        return f"SCLAMP{_suffix(self.index)}"

    @property
    def pressure(self) -> float:
        """force / area, MPa."""
        return self.preload.force / self.area


@dataclass(frozen=True, eq=False)
class ResolvedMaterial:
    """A material, its 0-based element rows, and its CalculiX material and element set."""

    material: Material
    elements: IntArray
    name: str
    elset: str


@dataclass(frozen=True, eq=False)
class ResolvedAssembly:
    """An assembly checked against its mesh."""

    assembly: Assembly
    contacts: tuple[ResolvedContact, ...]
    preloads: tuple[ResolvedPreload, ...]
    supports: tuple[tuple[Support, IntArray], ...]
    materials: tuple[ResolvedMaterial, ...]

    @property
    def shorthand_material(self) -> bool:
        """One material of every element: today's ``BODY`` material."""
        return len(self.materials) == 1 and self.materials[0].material.elset is None

    @property
    def contact_faces(self) -> IntArray:
        """Every contact's slave faces (the nodes whose status is read back)."""
        return np.concatenate([c.faces for c in self.contacts]).astype(np.int64)


def _faces(mesh: HexMesh, name: str, what: str) -> IntArray:
    faces = mesh.faces(name)
    if faces.size == 0:
        raise ParameterError(f"{mesh.source}: set {name!r} ({what}) holds no element face")
    return faces


def _set_nodes(mesh: HexMesh, name: str, what: str) -> IntArray:
    """A node set's nodes, or a surface's nodes."""
    if name in mesh.node_sets:
        nodes = mesh.node_sets[name]
    elif name in mesh.surfaces:
        faces = mesh.surfaces[name]
        nodes = face_load(mesh, faces)[0] if len(faces) else np.zeros(0, np.int64)
    else:
        raise ParameterError(f"{mesh.source}: no set named {name!r} ({what}); the mesh has "
                             f"{', '.join(mesh.set_names()) or 'no named sets'}")
    if nodes.size == 0:
        raise ParameterError(f"{mesh.source}: set {name!r} ({what}) holds no node")
    return np.asarray(nodes, dtype=np.int64)


def _resolve_materials(mesh: HexMesh, materials: Sequence[Material]) -> list[ResolvedMaterial]:
    n_el = mesh.elements.shape[0]
    if len(materials) == 1 and materials[0].elset is None:
        return [ResolvedMaterial(materials[0], np.arange(n_el, dtype=np.int64), "BODY", "BODY")]
    owner = np.full(n_el, -1, dtype=np.int64)
    rows: list[IntArray | None] = []
    for k, m in enumerate(materials):
        if m.elset is None:
            rows.append(None)
            continue
        if m.elset not in mesh.element_sets:
            have = ", ".join(sorted(mesh.element_sets)) or "none"
            raise ParameterError(f"{mesh.source}: no element set named {m.elset!r} for a "
                                 f"material; the mesh's element sets: {have}")
        e = mesh.element_sets[m.elset]
        if e.size == 0:
            raise ParameterError(f"{mesh.source}: element set {m.elset!r} is empty")
        twice = e[owner[e] >= 0]
        if twice.size:
            other = materials[int(owner[twice[0]])].elset
            raise ParameterError(f"{mesh.source}: element {mesh.element_label(int(twice[0]))} "
                                 f"is in the element sets {other!r} and {m.elset!r}, each with "
                                 "its own material; give each element one material")
        owner[e] = k
        rows.append(e)
    rest = np.flatnonzero(owner < 0)
    default = [k for k, m in enumerate(materials) if m.elset is None]
    if rest.size and not default:
        raise ParameterError(
            f"{mesh.source}: {rest.size} element(s) (e.g. element "
            f"{mesh.element_label(int(rest[0]))}) are in no material's element set; name their "
            "set in a material, or give a material without an element set for the rest")
    out = []
    for k, (m, named) in enumerate(zip(materials, rows, strict=True)):
        e = rest if named is None else named
        if e.size:
            out.append(ResolvedMaterial(m, np.asarray(e, dtype=np.int64), f"MAT{k + 1}",
                                        f"EMAT{k + 1}"))
    return out


def resolve_assembly(mesh: HexMesh, assembly: object) -> ResolvedAssembly:
    """The assembly's sets on ``mesh``: every contact, counter and preload face must hold
    element faces, every support set nodes, every material's element set elements; a face
    and its counter face must not share nodes (one body: the pair would be glued to itself).
    ``assembly``: an :class:`Assembly` or a :class:`~microslip.fe.clamp.MeshClamp`."""
    a = as_assembly(assembly)
    if a.shanks:
        raise ParameterError("CalculiX: bolt shanks are not written into the deck yet (a beam "
                             "between the faces' mean motions needs *COUPLING and *PRE-TENSION "
                             "SECTION); run CalculiX on the assembly without shanks, or the "
                             "built-in solver alone")
    shaped = [p.face for p in a.preloads if p.distribution is not None]
    if shaped:
        raise ParameterError(f"CalculiX: the preload on {shaped[0]!r} has a pressure law "
                             "(a distribution); the deck writes uniform pressures only: run "
                             "the built-in solver alone")
    contacts = []
    for k, c in enumerate(a.contacts, start=1):
        faces = _faces(mesh, c.face, "contact face")
        area = face_load(mesh, faces)[2]
        counter = None
        if c.counter is not None:
            counter = _faces(mesh, c.counter, "counter face")
            shared = np.intersect1d(mesh.face_corners(faces), mesh.face_corners(counter))
            if shared.size:
                raise ParameterError(
                    f"{mesh.source}: contact {c.label}: the faces share {shared.size} node(s) "
                    f"(e.g. node {mesh.node_label(int(shared[0]))}): they are one body; a "
                    "contact between two bodies needs distinct (coincident) nodes on each side")
        contacts.append(ResolvedContact(c, k, faces, area, counter))
    preloads = []
    for k, p in enumerate(a.preloads, start=1):
        faces = _faces(mesh, p.face, "preload face")
        preloads.append(ResolvedPreload(p, k, faces, face_load(mesh, faces)[2]))
    supports = tuple((s, _set_nodes(mesh, s.set, "support")) for s in a.supports)
    return ResolvedAssembly(a, tuple(contacts), tuple(preloads), supports,
                            tuple(_resolve_materials(mesh, a.materials)))


def support_cards(r: ResolvedAssembly) -> str:
    """``*NSET NFIX<k>`` of every support's nodes (1-based ids: the mesh's rows + 1)."""
    return "".join(nset_card(f"NFIX{k}", nodes + 1)
                   for k, (_, nodes) in enumerate(r.supports, start=1))


def boundary_rows(r: ResolvedAssembly) -> list[tuple[str, int, int]]:
    """``*BOUNDARY`` rows (set, first dof, last dof) of the supports: each run of held
    components one row (``xz``: 1-1 and 3-3)."""
    rows: list[tuple[str, int, int]] = []
    for k, (s, _) in enumerate(r.supports, start=1):
        for d in (c + 1 for c in s.components):
            if rows and rows[-1][0] == f"NFIX{k}" and rows[-1][2] == d - 1:
                rows[-1] = (rows[-1][0], rows[-1][1], d)
            else:
                rows.append((f"NFIX{k}", d, d))
    return rows


def material_cards(r: ResolvedAssembly, density: bool = False,
                   default_density: float | None = None) -> list[str]:
    """The ``*ELSET``, ``*MATERIAL`` (with ``*DENSITY`` in t/mm^3 when ``density``) and
    ``*SOLID SECTION`` cards of the bodies, then the bases' sections (first material).
    ``default_density`` (kg/m^3) is the density of a material that gives none."""
    out = []

    def dens(m: Material) -> str:
        if not density:
            return ""
        rho = m.density if m.density is not None else default_density
        if rho is None:
            where = "every element" if m.elset is None else f"element set {m.elset!r}"
            raise ParameterError(f"the material of {where} has no density; the modes need one "
                                 "(kg/m^3)")
        return f"*DENSITY\n{rho * KG_M3_TO_T_MM3:.10g}\n"

    if r.shorthand_material:
        m = r.materials[0].material
        out += [material_card("BODY", m.modulus, m.poisson_ratio) + dens(m),
                solid_section_card("BODY", "BODY")]
    else:
        for rm in r.materials:
            m = rm.material
            where = ("every element no other material names" if m.elset is None
                     else f"the mesh's element set {m.elset}")
            out += [f"** material {rm.name}: {where}, E = {m.modulus:g} MPa, nu = "
                    f"{m.poisson_ratio:g}\n",
                    elset_card(rm.elset, rm.elements + 1),
                    material_card(rm.name, m.modulus, m.poisson_ratio) + dens(m),
                    solid_section_card(rm.elset, rm.name)]
    first = r.materials[0].name
    out += [solid_section_card(f"BASE{c.suffix}", first) for c in r.contacts if c.on_base]
    return out


def contact_cards(r: ResolvedAssembly, formulation: str) -> list[str]:
    """Each contact's ``*SURFACE INTERACTION`` (the assembly's law; node-to-surface sigma_inf
    :data:`~.contactform.N2S_TENSION_RATIO` of the contact's mean pressure, the largest
    preload over the contact face's area) and its ``*CONTACT PAIR`` (slave: the face; master:
    the counter face or the base)."""
    f = check_formulation(formulation)
    a = r.assembly
    out = []
    for c in r.contacts:
        tension = (None if f.tension_ratio is None
                   else f.tension_ratio * (a.clamp_force / c.area))
        if not c.on_base:
            out.append(f"** contact {c.index}: {c.contact.face} (slave, {c.slave}) on "
                       f"{c.contact.counter} (master, {c.master}), {f.pair}\n")
        out += [surface_interaction_card(c.interaction, a.normal_slope, a.friction,
                                         a.stick_slope, tension),
                contact_pair_card(c.interaction, c.slave, c.master, f.pair)]
    return out


def preload_cards(r: ResolvedAssembly) -> tuple[list[str], list[str]]:
    """The clamping step's comment line(s) and its ``*DSLOAD`` cards (pressure force / area
    on each preload face)."""
    if len(r.preloads) == 1:
        p = r.preloads[0]
        comments = [f"** step 1: clamping pressure F_N / A = {p.preload.force:g} N / "
                    f"{p.area:g} mm^2 on {p.preload.face}\n"]
    else:
        comments = ["** step 1: preloads F / A: " + "; ".join(
            f"{p.preload.force:g} N / {p.area:g} mm^2 on {p.preload.face}"
            for p in r.preloads) + "\n"]
    return comments, [dsload_card(p.surface, p.pressure) for p in r.preloads]
