"""An interface reduction that keeps the contact's distortion (issue 28, item 4).

The contact-node ROM (:mod:`.reduce`) keeps every contact node's dofs, so its harmonic
balance grows with the contact: n_b (2H + 1) unknowns, a dense solve of their cube per
Newton step. This model keeps a few *interface modes* instead: the boundary displacements
are ``u_b = G eta`` with G (n_b, n) a few shapes of the whole contact patch, and the
coordinates are ``[eta (n), fixed-interface modal coordinates (n_m)]``. The friction law is
still evaluated at every contact node (its own element, its own slip force) on
``G eta``, and its force and Jacobian are projected, ``G^T f`` and ``G^T J G`` per harmonic
block (:class:`~microslip.dynamics.nodecontacts.NodeContacts`): the balance has
(n + n_m) h unknowns whatever the number of contact nodes; the AFT is linear in them.

Interface shapes:

* the characteristic constraint modes of the Craig-Bampton boundary (Castanier,
  Tan and Pierre 2001; Krattiger et al. 2019), here with the contact stuck: the lowest
  eigenvectors of ``(K_bb~ + K_c) g = lambda M_bb~ g``, K_bb~ and M_bb~ the ROM's boundary
  partition (the body condensed onto its contact by the constraint modes, their mass
  included), K_c the contact's stuck slopes. With every one kept, G is square and
  invertible and the model is the contact-node ROM in other coordinates (its stuck
  frequencies equal the ROM's to round-off). Alone they converge slowly in damping: on
  the 24x6x2 cantilever's in-plane mode 40 of them leave 7 % in damping ratio near gross
  sliding, 80 still 2.5 % (the slip zone's own shape is local);
* the *first-loading shapes* of the studied mode (:func:`first_loading_shapes`): the
  boundary displacements of the ROM loaded statically by the mode's inertial load at
  rising amplitude, from first slip to near gross sliding, made orthogonal to the
  characteristic modes. They span the slip patterns the cycle passes through (Masing:
  the unloading fields are differences of first-loading ones); 10 characteristic modes
  and them (23 coordinates) put the 24x6x2 cantilever's in-plane mode within 0.2 % in
  damping ratio and 1.2e-4 in frequency of the ROM.

:func:`build_interface_rom` reduces a contact-node ROM; :func:`build_interface_model`
builds the same kind of model on the full FE directly, without the ROM's constraint modes
(the scalable path, used whenever the body is condensed onto its contact).

Each shape is scaled to a largest boundary displacement of 1 mm (every coordinate is a
displacement in mm, as in the ROM).

Units: N, mm, s, t in the model; the structure (:meth:`InterfaceRom.structure`) in SI.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import cho_factor, cho_solve, eigh

from ..blas import single_threaded_blas
from ..dynamics.modal import ModalCurve
from ..dynamics.nodecontacts import NodeContacts
from ..dynamics.structure import JointLink, Structure
from ..errors import ParameterError
from ..fe.builtin.meshmodel import MeshModel
from .modes import Mode
from .reduce import SI_FACTOR, Rom, build_rom, clamped_stick_force, full_mass

__all__ = [
    "InterfaceRom",
    "build_interface_rom",
    "characteristic_modes",
    "first_loading_shapes",
    "interface_epmc",
    "loading_shapes",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class InterfaceRom:
    """A clamped body reduced to a few interface modes and fixed-interface modes, every
    contact node keeping its own law.

    Attributes
    ----------
    shapes : ndarray, shape (n_b, n)
        G: the boundary dofs (node-major: e1, e2 (, e3) of each contact node, as
        :attr:`.reduce.Rom.boundary`) per unit interface coordinate, mm/mm (largest entry 1).
    mass, stiffness : ndarray, shape (n + n_m, n + n_m)
        M (t) and K (N/mm, the contact removed) on ``[eta, fixed-interface modal
        coordinates]``.
    output : ndarray, shape (3, n + n_m) or None
        The response set's mean displacement along global x, y, z per unit coordinate.
    contact_stiffness, slip_force, normal_stiffness : ndarray, shape (n_c,)
        lambda A_i (N/mm), mu N_i (N), k_n A_i (N/mm; zeros with ``fixed``) per node.
    friction : float
        mu.
    stick_force : ndarray, shape (n_c, 2) or None
        The clamping step's tangential force per node (``penalty``), N.
    per_node : int
        Boundary dofs per node: 2 (``fixed``) or 3 (``penalty``).
    fixed_interface_modes : int
        n_m.
    basis : str
        ``cc`` (characteristic constraint modes) or ``cc+loadingK`` (and mode K's
        first-loading shapes).
    build_s : float
        Seconds to reduce (a contact-node ROM's own build not included).
    characteristic_modes : int
        Of the shapes, the characteristic constraint modes (the first ones).
    preload : ndarray, shape (n_c,) or None
        The signed normal preload after clamping (``penalty``, N: minus k_n A_i times the
        gap at a node the clamp left open, as :attr:`.reduce.Rom.preload`); None: every node
        at slip force / mu (an open one at a zero gap).
    """

    shapes: FloatArray = field(repr=False)
    mass: FloatArray = field(repr=False)
    stiffness: FloatArray = field(repr=False)
    output: FloatArray | None = field(repr=False)
    contact_stiffness: FloatArray = field(repr=False)
    slip_force: FloatArray = field(repr=False)
    normal_stiffness: FloatArray = field(repr=False)
    friction: float
    stick_force: FloatArray | None = field(repr=False)
    per_node: int
    fixed_interface_modes: int
    basis: str
    build_s: float
    characteristic_modes: int
    preload: FloatArray | None = field(default=None, repr=False)

    @property
    def interface_modes(self) -> int:
        """Interface coordinates n."""
        return int(self.shapes.shape[1])

    @property
    def dofs(self) -> int:
        """Coordinates: interface modes plus fixed-interface modes."""
        return int(self.mass.shape[0])

    @property
    def contact_nodes(self) -> int:
        """Contact nodes, each with its own law."""
        return int(self.slip_force.size)

    def contacts(self) -> NodeContacts:
        """Every contact node's law on the interface coordinates."""
        if self.per_node == 3:
            return NodeContacts(self.shapes, self.contact_stiffness, self.slip_force,
                                normal_stiffness=self.normal_stiffness, friction=self.friction,
                                stick_force=self.stick_force, preload=self.preload)
        return NodeContacts(self.shapes, self.contact_stiffness, self.slip_force)

    def stuck_stiffness(self) -> FloatArray:
        """K with every node stuck, N/mm."""
        k = np.array(self.stiffness)
        n = self.interface_modes
        k[:n, :n] += self.contacts().stuck_stiffness
        return k

    def stuck_frequencies(self, count: int | None = None) -> FloatArray:
        """Linear natural frequencies with the contact stuck, Hz, ascending."""
        lam = eigh(self.stuck_stiffness(), self.mass, eigvals_only=True,
                   subset_by_index=None if count is None else [0, min(count, self.dofs) - 1])
        return np.asarray(np.sqrt(np.maximum(lam, 0.0)) / (2.0 * np.pi))

    def structure(self, output: FloatArray | None = None) -> Structure:
        """The model as a :class:`~microslip.dynamics.structure.Structure` (SI: kg, N/m,
        no damping): its stiffness with the nodes stuck, one joint
        (:class:`~microslip.dynamics.nodecontacts.NodeContacts`) on the interface
        coordinates; output ``output`` (n + n_m,) or the response set's mean displacement
        along global y, else the first coordinate (as :func:`.reduce.rom_structure`)."""
        n = self.interface_modes
        weights = np.zeros((self.dofs, n))
        weights[:n] = np.eye(n)
        if output is None:
            out = self.output
            output = out[1] if out is not None else np.eye(self.dofs)[0]
        k = self.stuck_stiffness()
        return Structure(mass=SI_FACTOR * self.mass, damping=np.zeros_like(self.mass),
                         stiffness=SI_FACTOR * 0.5 * (k + k.T),
                         joints=(JointLink(self.contacts(), weights),),  # type: ignore[arg-type]
                         output=np.asarray(output, dtype=float))


def characteristic_modes(rom: Rom, count: int) -> tuple[FloatArray, FloatArray]:
    """The lowest ``count`` characteristic constraint modes of the ROM's boundary with the
    contact stuck: eigenvalues (rad/s)^2 and shapes (n_b, count), each scaled to a largest
    entry of +1."""
    nb = rom.boundary.size
    count = _count(count, nb)
    k = rom.stiffness[:nb, :nb] + np.diag(rom.contact_springs()[:nb])
    lam, vec = eigh(k, rom.mass[:nb, :nb], subset_by_index=[0, int(count) - 1])
    big = np.argmax(np.abs(vec), axis=0)
    vec = vec / vec[big, np.arange(vec.shape[1])]
    return np.asarray(lam), np.asarray(vec)


#: Load levels of the first loading (:func:`first_loading_shapes`), from first slip up by
#: this factor each, while it converges and some node sticks.
LOADING_STEP = 1.2
#: Most load levels of the first loading.
LOADING_LEVELS = 16
#: Slipping share of the nodes at which the first loading stops (near gross sliding).
LOADING_STOP = 0.98
#: Newton's tolerance of a first-loading level: the residual's largest entry relative to the
#: load's (the fields are a basis; 1e-9 leaves them exact to far below its rank tolerance).
LOADING_TOLERANCE = 1e-9
#: With a clamping stick force (``penalty``), the first loading starts at most this many
#: steps below the unstressed first slip, and runs at most this many levels.
PRESTRESS_LEVELS = 8
PRESTRESS_LEVELS_MAX = 24


def first_loading_shapes(rom: Rom, mode: int, levels: int = LOADING_LEVELS) -> FloatArray:
    """The boundary displacements of the ROM's first loading by the inertial load of its
    stuck mode ``mode`` (0-based), ``q M phi``, at rising q from first slip to near gross
    sliding (n_b, levels or fewer; each column one level, mm), after the stuck response
    (whose shape is the stuck mode's on the boundary: the model keeps its stuck frequency).

    Notes
    -----
    The ROM's stiffness is block-diagonal (boundary, fixed-interface modes), so the static
    boundary equations are ``K_bb~ u + f(u) = q p_b`` with ``p = M_r phi``; each node's
    tangential force is its circular Jenkins element's (radial return from the previous
    level's slider, stiffness k_i, limit s_i = mu N_i) or, with ``penalty`` normal contact,
    the 3-D element's (:func:`_node_law`: the normal force N_0 - k_n u_n with lift-off, the
    limit mu N). Semi-smooth Newton per level (dense, n_b
    unknowns), load levels ``q_1 LOADING_STEP^k`` from the first slip q_1 while a node
    sticks (:data:`LOADING_STOP`). With ``penalty`` a second loading starts the sliders from
    the clamping step's stick force, as the 3-D elements start their cycles, and both sets
    of fields are returned (the onset of slip at the nodes the clamp left near their limit
    needs them: docs/interpretation.md §20)."""
    nb = rom.boundary.size
    springs = rom.contact_springs()
    _, vec = eigh(rom.stiffness + np.diag(springs), rom.mass, subset_by_index=[mode, mode])
    p = (rom.mass @ vec[:, 0])[:nb]
    penalty = rom.per_node == 3
    if not penalty:
        return _first_loading(rom.stiffness[:nb, :nb], p, rom.contact_stiffness,
                              rom.slip_force, None, levels)
    return _loadings(rom.stiffness[:nb, :nb], p, rom.contact_stiffness, rom.slip_force,
                     rom.normal_stiffness, rom.stick_force, rom.friction, rom.preload)


def _loadings(k_b: FloatArray, p: FloatArray, kt: FloatArray, s: FloatArray,
              kn: FloatArray | None, stick: FloatArray | None, friction: float,
              preload: FloatArray | None = None) -> FloatArray:
    """The first-loading fields: from sliders at zero, and with ``penalty`` (``kn``) also
    from the clamping step's stick force ``stick`` (n_c, 2), side by side (n_b, m);
    ``preload`` the signed normal preload (open nodes' gaps), default s / friction."""
    x = _first_loading(k_b, p, kt, s, kn, friction=friction, preload=preload)
    if kn is None or stick is None:
        return x
    return np.column_stack([x, _first_loading(k_b, p, kt, s, kn, PRESTRESS_LEVELS_MAX,
                                              stick, friction, preload)])


def _first_loading(k_b: FloatArray, p: FloatArray, kt: FloatArray, s: FloatArray,
                   kn: FloatArray | None, levels: int = LOADING_LEVELS,
                   stick: FloatArray | None = None, friction: float = 1.0,
                   preload: FloatArray | None = None) -> FloatArray:
    """The boundary fields of ``K_bb~ u + f(u) = q p`` at rising q (n_b, <= levels + 1),
    the stuck response to p (q = 1) first, mm:
    :func:`first_loading_shapes`' notes; ``kn`` the normal springs (``penalty``) or None;
    ``stick`` (n_c, 2), if given, the clamping step's tangential force the sliders start
    from (N; the 3-D elements start their cycles from it): nodes left near their limit slip
    first, and the levels start at that earlier first slip (at most
    :data:`PRESTRESS_LEVELS` steps below the unstressed one)."""
    nb = p.size
    d = 2 if kn is None else 3
    kc = np.repeat(kt[:, None], d, axis=1)
    if kn is not None:
        kc[:, 2] = kn
    open_ = s <= 0.0  # open nodes (no normal force) carry nothing: no spring, no force
    kc[open_] = 0.0
    phi_slip = s / kt
    linear = np.linalg.solve(k_b + np.diag(kc.reshape(-1)), p)
    stuck = linear.reshape(-1, d)[:, :2]
    reach = np.hypot(stuck[:, 0], stuck[:, 1])
    # first slip over the closed nodes that move (an open node's slip displacement is 0:
    # 0 / inf was 0 there, and every field of a part that lifts off was zero)
    moves = (reach > 0.0) & ~open_
    if not np.any(moves):
        return np.asarray(linear[:, None], dtype=np.float64)
    q = float(np.min(phi_slip[moves] / reach[moves]))
    t0 = np.zeros((kt.size, 2)) if stick is None else np.asarray(stick, dtype=float)
    z = -t0 / kt[:, None]  # the clamped slider: k_t (0 - z) = t0
    if stick is not None:  # first slip with the stick force: |q a - z| = phi, per node
        aa = np.einsum("ij,ij->i", stuck, stuck)
        ab = -np.einsum("ij,ij->i", stuck, z)
        cc = np.einsum("ij,ij->i", z, z) - phi_slip**2
        root = (-ab + np.sqrt(np.maximum(ab * ab - aa * cc, 0.0))) / np.where(aa > 0, aa, 1)
        first = float(np.min(np.where((aa > 0.0) & ~open_, root, np.inf)))
        q = max(min(q, first), q * LOADING_STEP ** -PRESTRESS_LEVELS)
    u = np.zeros(nb)
    # the stuck response first: its shape is the stuck mode's on the boundary (p is the
    # mode's inertial load, (K + K_c)^-1 M phi = phi / w^2), so the model keeps the stuck
    # frequency at zero amplitude whatever slips at the first level
    shapes = [linear]
    for _ in range(levels):
        q *= LOADING_STEP
        u = u * LOADING_STEP  # the previous level scaled: exact while every node sticks
        ok = False
        for _it in range(60):
            force, blocks, _, _ = _node_law(u.reshape(-1, d), z, t0, kt, kn, s, friction, preload)
            res = k_b @ u + force.reshape(-1) - q * p
            if np.max(np.abs(res)) <= LOADING_TOLERANCE * q * np.max(np.abs(p)):
                ok = True
                break
            tan = np.array(k_b)
            idx = np.arange(kt.size) * d
            for i in range(d):
                for j in range(d):
                    tan[idx + i, idx + j] += blocks[:, i, j]
            # symmetric without lift-off's coupling (fixed normal contact): Cholesky
            u = u - (_spd_solve(tan, res) if kn is None else np.linalg.solve(tan, res))
        if not ok:
            break
        _, _, slip, z = _node_law(u.reshape(-1, d), z, t0, kt, kn, s, friction, preload)
        shapes.append(u.copy())
        if np.mean(slip) >= LOADING_STOP:
            break
    return np.asarray(np.column_stack(shapes)) if shapes else np.zeros((nb, 0))


def _node_law(u: FloatArray, z: FloatArray, t0: FloatArray, kt: FloatArray,
              kn: FloatArray | None, s: FloatArray, friction: float,
              preload: FloatArray | None = None
              ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_], FloatArray]:
    """Each node's force (n_c, d; the tangential counted from the stick force t0), its
    tangent blocks (n_c, d, d), whether it slips (or is open / lifted off) and its new
    slider (n_c, 2), from the slider z of the previous level at the displacements u
    (n_c, d; mm): the circular Jenkins element (``kn`` None) or, with ``penalty``, the 3-D
    element's law, normal ``N = N_0 - k_n u_n`` with lift-off and the limit mu N."""
    n_c, d = u.shape
    ut = u[:, :2]
    t = ut - z
    r = np.hypot(t[:, 0], t[:, 1])
    e = t / np.where(r > 0.0, r, 1.0)[:, None]
    if kn is None:
        limit = s
        touching = s > 0.0
    else:
        n0 = s / friction if preload is None else preload
        normal = n0 - kn * u[:, 2]
        touching = normal > 0.0
        limit = friction * np.maximum(normal, 0.0)
    slip = touching & (kt * r > limit)
    stick = touching & ~slip
    force = np.zeros((n_c, d))
    force[:, :2] = np.where(stick[:, None], kt[:, None] * t,
                            np.where(slip[:, None], limit[:, None] * e, 0.0)) - t0
    blocks = np.zeros((n_c, d, d))
    eye = np.eye(2)[None]
    sec = np.where(slip, limit / np.where(r > 0.0, r, 1.0), 0.0)
    blocks[:, :2, :2] = (np.where(stick, kt, 0.0)[:, None, None] * eye
                         + sec[:, None, None] * (eye - e[:, :, None] * e[:, None, :]))
    z_new = np.where(stick[:, None], z, np.where(
        slip[:, None], ut - (limit / kt)[:, None] * e, ut))
    if kn is not None:
        force[:, 2] = np.where(touching, kn * u[:, 2] - np.minimum(n0, 0.0), s / friction)
        blocks[:, 2, 2] = np.where(touching, kn, 0.0)
        blocks[:, :2, 2] = np.where(slip[:, None], -friction * kn[:, None] * e, 0.0)
    return force, blocks, ~stick, z_new


def _spd_solve(a: FloatArray, b: FloatArray) -> FloatArray:
    """a^-1 b by Cholesky (the first loading's tangent is symmetric and, while a node
    sticks, positive definite: half an LU's work), by LU where it is not."""
    try:
        return np.asarray(cho_solve(cho_factor(a, overwrite_a=True, check_finite=False), b,
                                    check_finite=False))
    except np.linalg.LinAlgError:
        return np.asarray(np.linalg.solve(a, b))


def loading_shapes(rom: Rom, shapes: FloatArray, mode: int) -> FloatArray:
    """The first-loading shapes of stuck mode ``mode`` (:func:`first_loading_shapes`) that
    ``shapes`` (n_b, n) do not already span (:func:`_new_directions` in M_bb~)."""
    nb = rom.boundary.size
    return _new_directions(first_loading_shapes(rom, mode), shapes, rom.mass[:nb, :nb])


def _new_directions(x: FloatArray, shapes: FloatArray, m: FloatArray) -> FloatArray:
    """The fields ``x`` made m-orthogonal to ``shapes``, then their singular vectors above
    :data:`RANK_TOLERANCE` of the fields' own norm, each scaled to a largest entry of +1."""
    if x.shape[1] == 0:
        return x
    size = float(np.linalg.norm(x, 2))
    if shapes.shape[1]:
        mg = m @ shapes
        x = x - shapes @ np.linalg.solve(shapes.T @ mg, mg.T @ x)
    u, sv, _ = np.linalg.svd(x, full_matrices=False)
    keep = int(np.sum(sv > RANK_TOLERANCE * size))  # what the shapes leave, not round-off
    u = u[:, :keep]
    return np.asarray(u / u[np.argmax(np.abs(u), axis=0), np.arange(keep)])


#: Singular values of the first-loading shapes kept, relative to their norm before the
#: characteristic modes are taken out.
RANK_TOLERANCE = 1e-8


def build_interface_rom(rom: Rom, count: int, mode: int | None = None) -> InterfaceRom:
    """The ROM ``rom`` with its boundary reduced to ``count`` characteristic constraint
    modes (at most the boundary dofs; all of them: the ROM itself in other coordinates),
    and, if ``mode`` (0-based, by stuck frequency) is given, the first-loading shapes of
    that mode besides (:func:`loading_shapes`)."""
    t0 = time.perf_counter()
    # dense solves of the boundary's size: a threaded BLAS only fights for the cores there
    # (24x6x2 on a loaded 2-core machine: the first loading 6 s, single-threaded 0.14 s)
    with single_threaded_blas():
        g = characteristic_modes(rom, count)[1]
        basis = "cc"
        if mode is not None:
            extra = loading_shapes(rom, g, mode)
            g = np.column_stack([g, extra])
            basis = f"cc+loading{mode + 1}"
    nb = rom.boundary.size
    n = g.shape[1]
    k_r, m_r = rom.stiffness, rom.mass
    size = n + rom.modes
    k = np.zeros((size, size))
    m = np.zeros((size, size))
    k_bb = g.T @ k_r[:nb, :nb] @ g
    m_bb = g.T @ m_r[:nb, :nb] @ g
    k[:n, :n] = 0.5 * (k_bb + k_bb.T)
    k[n:, n:] = k_r[nb:, nb:]
    m[:n, :n] = 0.5 * (m_bb + m_bb.T)
    m[:n, n:] = g.T @ m_r[:nb, nb:]
    m[n:, :n] = m[:n, n:].T
    m[n:, n:] = m_r[nb:, nb:]
    t = np.zeros((nb + rom.modes, size))
    t[:nb, :n] = g
    t[nb:, n:] = np.eye(rom.modes)
    return InterfaceRom(shapes=g, mass=m, stiffness=k,
                        output=None if rom.output is None else np.asarray(rom.output @ t),
                        contact_stiffness=rom.contact_stiffness, slip_force=rom.slip_force,
                        normal_stiffness=rom.normal_stiffness, friction=rom.friction,
                        stick_force=rom.stick_force, per_node=rom.per_node,
                        fixed_interface_modes=rom.modes, basis=basis,
                        build_s=time.perf_counter() - t0, characteristic_modes=int(count),
                        preload=None if rom.per_node == 2 else rom.preload)


def build_interface_model(model: MeshModel, density_kg_m3: float, count: int,
                          fixed_modes: int, mode: Mode | None = None,
                          response_set: str | None = None) -> InterfaceRom:
    """The interface-reduced model built on the full FE directly, without the contact-node
    ROM's constraint modes (the scalable path; needs the body condensed onto its contact,
    ``model.reduced``, as :func:`~.meshmodel.build_mesh_model` does on meshes of 1000 dofs
    and more).

    Notes
    -----
    The ROM needs one solve with K_ii per boundary dof (its constraint modes, for K_bb~ and
    M_bb~); on 94k dofs with 1650 boundary dofs that is out of reach. Here

    * K_bb~ is the condensed body's S (:mod:`.condense`, computed at the model's set-up);
    * the interface shapes are the *static* characteristic modes, the lowest eigenvectors
      of ``(S + K_c) g = lambda M_bb g`` (M_bb the boundary block of the mass, the
      constraint modes' own mass left out: a basis, not a model; with every one kept the
      span is the whole boundary and the model is the ROM's), plus the first-loading shapes
      of ``mode``'s inertial load, the full FE's stuck mode condensed onto the boundary,
      ``p_b = (M phi)_b - K_bi K_ii^-1 (M phi)_i``;
    * the shapes are lifted into the body by ``Y = -K_ii^-1 K_ib G`` (n solves, with the
      condensed body's own factor of K_ii) and the fixed-interface modes Phi are the lowest
      of ``(K_ii, M_ii)`` through the same factor; the model is the Galerkin projection on
      ``[[G, 0], [Y, Phi]]`` (the Craig-Bampton basis restricted to ``u_b = G eta``).
    """
    from .reduce import _boundary, _interface_modes, _response_rows

    t0 = time.perf_counter()
    red = model.reduced
    if red is None:
        raise ParameterError("the direct interface model needs the body condensed onto its "
                             "contact (build the model with condensed=True)")
    b, per_node = _boundary(model)
    pos = np.searchsorted(red.keep, b)
    if not np.array_equal(red.keep[pos], b):
        raise ParameterError("the condensed body does not keep the contact's boundary dofs")
    inner = red.interior
    m_full = full_mass(model, density_kg_m3)
    k_full = model.stiffness.tocsr()
    kt = np.asarray(model.contact_stiffness, dtype=float)
    kn = None if per_node == 2 else np.asarray(model.normal.stiffness, dtype=float)  # type: ignore[union-attr]
    laws = NodeContacts(np.zeros((b.size, 1)), kt, model.friction_limit,
                        normal_stiffness=kn, friction=model.friction,
                        stick_force=None if kn is None else clamped_stick_force(model),
                        preload=None if kn is None else model.preload)
    with single_threaded_blas():
        s_b = red.stiffness[np.ix_(pos, pos)]
        m_bb = m_full[b][:, b].toarray()
        _, g = eigh(s_b + np.diag(laws.node_springs()), m_bb,
                    subset_by_index=[0, _count(count, b.size) - 1])
        g = g / g[np.argmax(np.abs(g), axis=0), np.arange(g.shape[1])]
        basis = "cc"
        k_ib = k_full[inner][:, b].tocsc()
        if mode is not None:
            load = m_full @ mode.vector
            p = load[b] - k_ib.T @ red.solver.solve(load[inner])
            x = _loadings(s_b, p, kt, model.friction_limit, kn, laws.stick_force,
                          float(model.friction), laws.preload)
            g = np.column_stack([g, _new_directions(x, g, m_bb)])
            basis = f"cc+loading{mode.number}"
        n = g.shape[1]
        y = -red.solver.solve(np.asarray(k_ib @ g))
        k_ii = k_full[inner][:, inner].tocsc()
        m_ii = m_full[inner][:, inner].tocsc()
        freq, phi = _interface_modes(k_ii, m_ii, fixed_modes, None, red.solver)
        phi = phi / np.max(np.abs(phi), axis=0) * np.sign(
            phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])])
        m_ib = m_full[inner][:, b]
        mu = np.einsum("ij,ij->j", phi, m_ii @ phi)
        size = n + phi.shape[1]
        k = np.zeros((size, size))
        m = np.zeros((size, size))
        k_eta = g.T @ s_b @ g
        k[:n, :n] = 0.5 * (k_eta + k_eta.T)
        k[n:, n:] = np.diag(mu * (2.0 * np.pi * freq) ** 2)
        mib_g = np.asarray(m_ib @ g)
        cross = mib_g.T @ y  # G^T M_bi Y
        m_eta = g.T @ m_bb @ g + cross + cross.T + y.T @ (m_ii @ y)
        m[:n, :n] = 0.5 * (m_eta + m_eta.T)
        m[:n, n:] = mib_g.T @ phi + (m_ii @ y).T @ phi
        m[n:, :n] = m[:n, n:].T
        m[n:, n:] = np.diag(mu)
    out = None
    if response_set is not None:
        rows = _response_rows(model, response_set, b, inner)
        local = np.zeros((3, size))
        for c in range(3):
            local[c, :n] = rows.boundary[c] @ g + y[rows.interior[c]].sum(axis=0)
            local[c, n:] = phi[rows.interior[c]].sum(axis=0)
        out = np.asarray(model.rotation.T @ (local / rows.nodes))
    return InterfaceRom(shapes=g, mass=m, stiffness=k, output=out, contact_stiffness=kt,
                        slip_force=np.asarray(model.friction_limit, dtype=float),
                        normal_stiffness=np.zeros_like(kt) if kn is None else kn,
                        friction=float(model.friction),
                        stick_force=laws.stick_force, per_node=per_node,
                        fixed_interface_modes=int(phi.shape[1]), basis=basis,
                        build_s=time.perf_counter() - t0, characteristic_modes=int(count),
                        preload=laws.preload)


def _count(count: int, nb: int) -> int:
    if not (isinstance(count, (int, np.integer)) and 1 <= count <= nb):
        raise ParameterError(f"interface modes must be an integer in [1, {nb}] (the contact's "
                             f"{nb} boundary dofs), got {count!r}")
    return int(count)


def interface_epmc(model: MeshModel, density_kg_m3: float, mode: Mode, amplitudes: ArrayLike,
                   harmonics: int, samples: int, *, response_set: str | None, rom_modes: int,
                   interface_modes: int, rom: Rom | None = None, damping_ratio: float = 0.0
                   ) -> tuple[InterfaceRom, ModalCurve]:
    """The interface-reduced model of ``model`` for its stuck mode ``mode`` and its EPMC
    curve at ``amplitudes`` (mm, of the response set's mean motion along the mode's
    direction): ``interface_modes`` characteristic constraint modes plus the mode's
    first-loading shapes and ``rom_modes`` fixed-interface modes, built on the full FE
    directly (:func:`build_interface_model`) when the body is condensed onto its contact,
    else through the contact-node ROM (:func:`build_interface_rom`); the odd-harmonic
    balance with ``fixed`` normal contact (odd node forces), every harmonic with
    ``penalty``. ``rom``: the study's contact-node ROM of ``model`` where one is built already
    (the ROM route then reduces it instead of building another). ``damping_ratio``: a
    structural damping ratio on every stuck mode (:func:`~.case.modal_damping`)."""
    if model.free_free:
        raise ParameterError(
            "the interface model of a free-free assembly is not built yet (it reduces the "
            "contact-node ROM, whose Craig-Bampton basis would need the six rigid-body modes "
            "set aside): the full FE's QSMA (--solver fe) is the answer here")
    from ..dynamics.modal import epmc
    from ..dynamics.modal_odd import epmc_odd

    if model.reduced is not None:
        reduced = build_interface_model(model, density_kg_m3, interface_modes, rom_modes,
                                        mode, response_set)
    else:
        if rom is None:
            rom = build_rom(model, density_kg_m3, modes=rom_modes, response_set=response_set)
        reduced = build_interface_rom(rom, interface_modes, mode.number - 1)
    out = reduced.output
    structure = reduced.structure(None if out is None else np.asarray(mode.direction) @ out)
    if damping_ratio:
        from .case import modal_damping

        structure = modal_damping(structure, damping_ratio)
    method = epmc_odd if reduced.per_node == 2 else epmc
    return reduced, method(structure, np.asarray(amplitudes), harmonics, samples,
                           mode.number - 1)
