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
  and them (26 coordinates) put the 24x6x2 cantilever's in-plane mode within 0.2 % in
  damping ratio and 1.2e-4 in frequency of the ROM.

Each shape is scaled to a largest boundary displacement of 1 mm (every coordinate is a
displacement in mm, as in the ROM).

Units: N, mm, s, t in the model; the structure (:meth:`InterfaceRom.structure`) in SI.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eigh

from ...blas import single_threaded_blas
from ...dynamics.modal import ModalCurve
from ...dynamics.nodecontacts import NodeContacts
from ...dynamics.structure import JointLink, Structure
from ...errors import ParameterError
from .meshmodel import MeshModel
from .reduce import SI_FACTOR, Rom, build_rom

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
    """A contact-node ROM with its boundary reduced to a few interface modes.

    Attributes
    ----------
    rom : Rom
        The Craig-Bampton model it reduces (its contact laws, its fixed-interface modes).
    shapes : ndarray, shape (n_b, n)
        G: boundary dofs (:attr:`Rom.boundary` order) per unit interface coordinate, mm/mm
        (largest entry 1).
    mass, stiffness : ndarray, shape (n + n_m, n + n_m)
        M (t) and K (N/mm, the contact removed) on ``[eta, modal coordinates]``.
    basis : str
        ``cc`` (characteristic constraint modes) or ``cc+loadingK`` (and mode K's
        first-loading shapes).
    build_s : float
        Seconds to reduce (the ROM's own build not included).
    characteristic_modes : int
        Of the shapes, the characteristic constraint modes (the first ones).
    """

    rom: Rom = field(repr=False)
    shapes: FloatArray = field(repr=False)
    mass: FloatArray = field(repr=False)
    stiffness: FloatArray = field(repr=False)
    basis: str
    build_s: float
    characteristic_modes: int = 0

    @property
    def interface_modes(self) -> int:
        """Interface coordinates n."""
        return int(self.shapes.shape[1])

    @property
    def dofs(self) -> int:
        """Coordinates: interface modes plus fixed-interface modes."""
        return int(self.mass.shape[0])

    @property
    def output(self) -> FloatArray | None:
        """(3, n + n_m): the response set's mean displacement along global x, y, z per unit
        coordinate, or None (the ROM has no response set)."""
        if self.rom.output is None:
            return None
        return np.asarray(self.rom.output @ self._transform())

    def _transform(self) -> FloatArray:
        """T (n_b + n_m, n + n_m): the ROM's coordinates per unit coordinate of this one."""
        nb, n, nm = self.shapes.shape[0], self.interface_modes, self.rom.modes
        t = np.zeros((nb + nm, n + nm))
        t[:nb, :n] = self.shapes
        t[nb:, n:] = np.eye(nm)
        return t

    def contacts(self) -> NodeContacts:
        """Every contact node's law on the interface coordinates."""
        r = self.rom
        if r.per_node == 3:
            return NodeContacts(self.shapes, r.contact_stiffness, r.slip_force,
                                normal_stiffness=r.normal_stiffness, friction=r.friction,
                                stick_force=r.stick_force)
        return NodeContacts(self.shapes, r.contact_stiffness, r.slip_force)

    def stuck_stiffness(self) -> FloatArray:
        """K with every node stuck, N/mm."""
        k = np.array(self.stiffness)
        n = self.interface_modes
        g = self.shapes
        k[:n, :n] += g.T @ (self.rom.contact_springs()[:g.shape[0], None] * g)
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
    if not (isinstance(count, (int, np.integer)) and 1 <= count <= nb):
        raise ParameterError(f"interface modes must be an integer in [1, {nb}] (the contact's "
                             f"{nb} boundary dofs), got {count!r}")
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


def first_loading_shapes(rom: Rom, mode: int, levels: int = LOADING_LEVELS) -> FloatArray:
    """The boundary displacements of the ROM's first loading by the inertial load of its
    stuck mode ``mode`` (0-based), ``q M phi``, at rising q from first slip to near gross
    sliding (n_b, levels or fewer; each column one level, mm).

    Notes
    -----
    The ROM's stiffness is block-diagonal (boundary, fixed-interface modes), so the static
    boundary equations are ``K_bb~ u + f(u) = q p_b`` with ``p = M_r phi``; each node's
    tangential force is its circular Jenkins element's (radial return from the previous
    level's slider, stiffness k_i, limit s_i = mu N_i; with ``penalty`` normal contact the
    normal dofs carry their linear spring and the limit stays mu N_0: the shapes are a
    subspace, the model's own law is exact). Semi-smooth Newton per level (dense, n_b
    unknowns), load levels ``q_1 LOADING_STEP^k`` from the first slip q_1 while a node
    sticks (:data:`LOADING_STOP`)."""
    nb, d = rom.boundary.size, rom.per_node
    springs = rom.contact_springs()
    k_b = rom.stiffness[:nb, :nb]
    kc = springs[:nb]
    _, vec = eigh(rom.stiffness + np.diag(springs), rom.mass, subset_by_index=[mode, mode])
    p = (rom.mass @ vec[:, 0])[:nb]
    kt, s = rom.contact_stiffness, rom.slip_force
    phi_slip = s / kt
    stuck = np.linalg.solve(k_b + np.diag(kc), p).reshape(-1, d)[:, :2]
    reach = np.hypot(stuck[:, 0], stuck[:, 1])
    q = float(np.min(phi_slip / np.where(reach > 0.0, reach, np.inf)))
    z = np.zeros((kt.size, 2))
    u = np.zeros(nb)
    shapes = []
    for _ in range(levels):
        q *= LOADING_STEP
        u = np.array(u)
        ok = False
        for _it in range(60):
            t = u.reshape(-1, d)[:, :2] - z
            r = np.hypot(t[:, 0], t[:, 1])
            slip = r > phi_slip
            scale = np.where(slip, phi_slip / np.where(slip, r, 1.0), 1.0)
            force = np.zeros((kt.size, d))
            force[:, :2] = (kt * scale)[:, None] * t
            if d == 3:
                force[:, 2] = rom.normal_stiffness * u.reshape(-1, d)[:, 2]
            res = k_b @ u + force.reshape(-1) - q * p
            if np.max(np.abs(res)) <= 1e-10 * q * np.max(np.abs(p)):
                ok = True
                break
            tan = np.array(k_b)
            nvec = t / np.where(r > 0.0, r, 1.0)[:, None]
            blocks = (kt * scale)[:, None, None] * (
                np.eye(2)[None] - np.where(slip, 1.0, 0.0)[:, None, None]
                * nvec[:, :, None] * nvec[:, None, :])
            idx = np.arange(kt.size) * d
            for a in range(2):
                for b in range(2):
                    tan[idx + a, idx + b] += blocks[:, a, b]
            if d == 3:
                tan[idx + 2, idx + 2] += rom.normal_stiffness
            u = u - np.linalg.solve(tan, res)
        if not ok:
            break
        t = u.reshape(-1, d)[:, :2] - z
        r = np.hypot(t[:, 0], t[:, 1])
        slip = r > phi_slip
        z[slip] = (u.reshape(-1, d)[:, :2] - phi_slip[:, None] * t / r[:, None])[slip]
        shapes.append(u.copy())
        if np.mean(slip) >= LOADING_STOP:
            break
    return np.asarray(np.column_stack(shapes)) if shapes else np.zeros((nb, 0))


def loading_shapes(rom: Rom, shapes: FloatArray, mode: int) -> FloatArray:
    """The first-loading shapes of stuck mode ``mode`` (:func:`first_loading_shapes`) that
    ``shapes`` (n_b, n) do not already span: made M_bb~-orthogonal to them, then the
    singular vectors above :data:`RANK_TOLERANCE` of the shapes' own norm, each scaled to a largest
    entry of +1 (n_b, <= :data:`LOADING_LEVELS`)."""
    nb = rom.boundary.size
    x = first_loading_shapes(rom, mode)
    if x.shape[1] == 0:
        return x
    m = rom.mass[:nb, :nb]
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
    return InterfaceRom(rom=rom, shapes=g, mass=m, stiffness=k, basis=basis,
                        build_s=time.perf_counter() - t0, characteristic_modes=int(count))


def interface_epmc(model: MeshModel, density_kg_m3: float, direction: FloatArray, mode: int,
                   amplitudes: ArrayLike, harmonics: int, samples: int, *,
                   response_set: str | None, rom_modes: int, interface_modes: int
                   ) -> tuple[InterfaceRom, ModalCurve]:
    """The interface-reduced model of ``model`` for stuck mode ``mode`` (0-based) and its
    EPMC curve at ``amplitudes`` (mm, of the response set's mean motion along the global
    ``direction``): the contact-node ROM with ``rom_modes`` fixed-interface modes, reduced
    to ``interface_modes`` characteristic constraint modes plus the mode's first-loading
    shapes; the odd-harmonic balance with ``fixed`` normal contact (odd node forces), every
    harmonic with ``penalty``."""
    from ...dynamics.modal import epmc
    from ...dynamics.modal_odd import epmc_odd

    rom = build_rom(model, density_kg_m3, modes=rom_modes, response_set=response_set)
    reduced = build_interface_rom(rom, interface_modes, mode)
    out = reduced.output
    structure = reduced.structure(None if out is None else np.asarray(direction) @ out)
    method = epmc_odd if rom.per_node == 2 else epmc
    return reduced, method(structure, np.asarray(amplitudes), harmonics, samples, mode)
