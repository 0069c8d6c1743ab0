"""The structure of a mesh as one typed case, and what every study of it starts from.

:class:`StructureCase` holds what the user states (the mesh, its clamp, the density, the
mode, the response set and the reduced models' settings), validated once;
:func:`prepare_structure` reads the mesh, clamps it and computes its stuck and free linear modes
(:class:`PreparedStructure`); :func:`amplitude_grid` is the one amplitude grid every modal
solver runs on and :func:`structure_rom` the contact-node ROM, built once per study with
the rows of every output set. Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..conventions import BACKBONE_NAMES, DEFAULT_INTERFACE_MODES, DEFAULT_ROM_MODES, MAX_MODE
from ..errors import ParameterError
from ..fe.assembly import Assembly
from ..fe.clamp import MeshClamp

if TYPE_CHECKING:
    from ..fe.builtin.meshmodel import MeshModel
    from ..fe.hexmesh import HexMesh
    from .limits import GridLimit
    from .modes import Mode, Modes
    from .reduce import Rom

__all__ = [
    "BACKBONE_NAMES",
    "DEFAULT_ROM_MODES",
    "MAX_AMPLITUDES",
    "MAX_MODE",
    "OnStructure",
    "PreparedStructure",
    "StructureCase",
    "amplitude_grid",
    "limited_grid",
    "modal_damping",
    "prepare_structure",
    "structure_rom",
]

#: Most amplitudes of one grid.
MAX_AMPLITUDES = 200


@dataclass(frozen=True)
class StructureCase:
    """The structure of a mesh with its clamp: what a modal or forced-response study of it
    needs beyond the solver's own settings.

    Attributes
    ----------
    mesh : str, Path or HexMesh
        A hexahedral mesh file (.inp, .msh, .vtu, ...) or a mesh already read.
    clamp : Assembly or MeshClamp
        The assembly (:class:`microslip.fe.assembly.Assembly`), or the clamp on the rigid
        base as its shorthand (:class:`microslip.fe.clamp.MeshClamp`); kept as the
        assembly.
    density : float
        rho, kg/m^3 (> 0).
    mode : int
        The mode studied, 1-based by stuck frequency, in [1, :data:`MAX_MODE`].
    response_set : str, optional
        The node set whose mean displacement along the mode is the amplitude.
    rom_modes : int
        Fixed-interface modes of the contact-node ROM (>= 1).
    backbone : str
        The whole joint's backbone, one of :data:`BACKBONE_NAMES`.
    interface_modes : int
        Characteristic constraint modes of the interface-reduced model (>= 1; the studied
        mode's first-loading shapes come on top).
    element : str, optional
        ``hex20`` runs an 8-node mesh as 20-node hexahedra
        (:func:`~microslip.fe.promote.as_element`), ``hex8`` refuses a 20-node mesh; None:
        as the file.
    yield_strength : float, optional
        MPa (> 0): the automatic amplitude grid stops where the studied stuck mode's
        largest von Mises stress reaches it (:mod:`.limits`); None: at the size limit only.
    """

    mesh: Any
    clamp: Assembly | MeshClamp
    density: float
    mode: int = 1
    response_set: str | None = None
    rom_modes: int = DEFAULT_ROM_MODES
    backbone: str = "fe"
    interface_modes: int = DEFAULT_INTERFACE_MODES
    element: str | None = None
    yield_strength: float | None = None

    def __post_init__(self) -> None:
        from ..fe.assembly import as_assembly
        from .limits import check_yield_strength

        object.__setattr__(self, "yield_strength", check_yield_strength(self.yield_strength))

        object.__setattr__(self, "clamp", as_assembly(self.clamp))
        try:
            rho = float(self.density)
        except (TypeError, ValueError):
            rho = math.nan
        if not (math.isfinite(rho) and rho > 0.0):
            raise ParameterError(f"density must be > 0 kg/m^3 and finite, got "
                                 f"{self.density!r}")
        object.__setattr__(self, "density", rho)
        if isinstance(self.mode, bool) or not isinstance(self.mode, int | np.integer) or not (
                1 <= self.mode <= MAX_MODE):
            raise ParameterError(f"mode must be in [1, {MAX_MODE}] with a mesh, got "
                                 f"{self.mode}")
        if isinstance(self.rom_modes, bool) or not isinstance(
                self.rom_modes, int | np.integer) or self.rom_modes < 1:
            raise ParameterError(f"rom_modes must be >= 1, got {self.rom_modes}")
        if isinstance(self.interface_modes, bool) or not isinstance(
                self.interface_modes, int | np.integer) or self.interface_modes < 1:
            raise ParameterError(f"interface_modes must be in [1, the contact's boundary dofs],"
                                 f" got {self.interface_modes}")
        if self.backbone not in BACKBONE_NAMES:
            raise ParameterError(f"unknown backbone {self.backbone!r}; choose one of "
                                 f"{', '.join(BACKBONE_NAMES)}")
        from ..fe.promote import ELEMENT_ORDERS

        if self.element is not None and self.element not in ELEMENT_ORDERS:
            raise ParameterError(f"element must be one of {', '.join(ELEMENT_ORDERS)}, got "
                                 f"{self.element!r}")
        if self.response_set is not None and not (isinstance(self.response_set, str)
                                                  and self.response_set):
            raise ParameterError(f"response_set must name a node set, got "
                                 f"{self.response_set!r}")

    @property
    def mesh_name(self) -> str:
        """The mesh as the output names it: the path as given, or the mesh's source."""
        if isinstance(self.mesh, str | Path):
            return str(self.mesh)
        return str(getattr(self.mesh, "source", "mesh"))


@dataclass(frozen=True)
class PreparedStructure:
    """What every study of a mesh structure starts from: the case, the clamped model
    (:class:`~microslip.fe.builtin.meshmodel.MeshModel`) and its stuck and free linear modes
    (:class:`~microslip.meshdynamics.modes.Modes`, at least six and up to the mode
    studied, described by the response set)."""

    case: StructureCase
    model: MeshModel
    stuck: Modes
    free: Modes

    @property
    def number(self) -> int:
        """The mode studied, 1-based."""
        return int(self.case.mode)

    @property
    def mode(self) -> Mode:
        """The studied stuck mode (:class:`~microslip.meshdynamics.modes.Mode`)."""
        return self.stuck.select(self.number)


class OnStructure:
    """What a study on a :class:`PreparedStructure` (its ``prepared``) reads of it: the case,
    the mode number and the studied stuck mode."""

    prepared: PreparedStructure

    @property
    def case(self) -> StructureCase:
        return self.prepared.case

    @property
    def number(self) -> int:
        return self.prepared.number

    @property
    def mode(self) -> Mode:
        return self.prepared.mode


def read_structure_mesh(case: StructureCase, sets: Sequence[str] = ()) -> HexMesh:
    """The case's mesh, read if a path, with its role sets (and the response set and
    ``sets``) checked."""
    from ..fe.meshcheck import check_assembly, check_set
    from ..fe.meshfile import read_mesh

    mesh = read_mesh(case.mesh) if isinstance(case.mesh, str | Path) else case.mesh
    if case.response_set:  # named as what it is (not "the set of a load")
        check_set(mesh, case.response_set, "response set")
    check_assembly(mesh, case.clamp, sets)
    from ..fe.promote import as_element

    return as_element(mesh, case.element)


def clamped(case: StructureCase, sets: Sequence[str] = ()) -> MeshModel:
    """Read and check the mesh (:func:`read_structure_mesh`), build the body on its base and
    solve the clamping step."""
    from ..fe.clamp import clamped_model

    return clamped_model(read_structure_mesh(case, sets), case.clamp)


def prepare_structure(case: StructureCase, sets: Sequence[str] = ()) -> PreparedStructure:
    """Clamp the case's mesh (:func:`clamped`; ``sets``: more node sets to check, a load
    set, say) and compute its stuck and free linear modes."""
    from .modes import linear_modes

    model = clamped(case, sets)
    n = max(6, case.mode)
    stuck = linear_modes(model, case.density, n, "stuck", case.response_set)
    free = linear_modes(model, case.density, n, "free", case.response_set)
    return PreparedStructure(case=case, model=model, stuck=stuck, free=free)


def amplitude_grid(prepared: PreparedStructure, count: int,
                   amplitude_range: tuple[float, float] | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The modal forces q and the amplitudes (mm) of the one grid of a modal study.

    From first slip to near gross sliding (:func:`~microslip.meshdynamics.qsma.
    qsma_amplitudes`) but no further than the physical limits of :func:`~.limits.grid_limit`
    (:func:`limited_grid`), or log-uniform over ``amplitude_range`` (mm). Linear through the
    stuck mode, the response set's amplitude is a = q r / omega^2 at modal force q (r its
    motion per unit modal coordinate)."""
    forces, amplitudes, _, _ = limited_grid(prepared, count, amplitude_range)
    return forces, amplitudes


def limited_grid(prepared: PreparedStructure, count: int,
                 amplitude_range: tuple[float, float] | None = None
                 ) -> tuple[np.ndarray, np.ndarray, GridLimit, tuple[str, ...]]:
    """:func:`amplitude_grid` with its limits (:class:`~.limits.GridLimit`) and what the
    limits did to it, in words: the automatic grid's top lowered to the limit (issue 34
    item 2), or a first slip already past it (the grid then kept, and said)."""
    from .limits import grid_limit
    from .qsma import qsma_amplitudes

    if isinstance(count, bool) or not isinstance(count, int | np.integer) or not (
            1 <= count <= MAX_AMPLITUDES):
        raise ParameterError(f"amplitudes must be in [1, {MAX_AMPLITUDES}] with a mesh, got "
                             f"{count}")
    number = prepared.number
    mode = prepared.mode
    scale = float(np.linalg.norm(prepared.stuck.response_motion[number - 1])) / (
        2 * math.pi * mode.frequency_Hz) ** 2
    if amplitude_range is None:
        forces = qsma_amplitudes(prepared.model, mode, count)
        limit = grid_limit(prepared)
        cap = limit.limit_mm / scale
        notes: tuple[str, ...] = ()
        if forces[-1] > cap and forces[0] < cap:
            notes = (f"the automatic grid stops at a = {limit.limit_mm:.4g} mm "
                     f"({limit.reason}), not at {forces[-1] * scale:.4g} mm near gross "
                     "sliding",)
            forces = np.geomspace(forces[0], cap, count) if count > 1 else forces
        elif forces[-1] > cap:
            notes = (f"first slip, at a = {forces[0] * scale:.4g} mm, is already past the "
                     f"limit of {limit.limit_mm:.4g} mm ({limit.reason}): the whole "
                     "microslip range of this mode is outside the linear model",)
        return forces, forces * scale, limit, notes
    lo, hi = amplitude_range
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ParameterError(f"amplitude-range must satisfy 0 < MIN <= MAX (mm), got "
                             f"{lo:g} {hi:g}")
    amplitudes = np.geomspace(lo, hi, count)
    return amplitudes / scale, amplitudes, grid_limit(prepared), ()


def structure_rom(prepared: PreparedStructure, output_sets: Sequence[str] = ()) -> Rom:
    """The contact-node ROM of the prepared structure (the case's ``rom_modes``), its output
    rows the response set's, with the rows of every set of ``output_sets`` too
    (:attr:`~microslip.meshdynamics.reduce.Rom.outputs`): one build for the whole study."""
    from . import reduce

    case = prepared.case
    return reduce.build_rom(prepared.model, case.density, modes=case.rom_modes,
                            response_set=case.response_set, output_sets=tuple(output_sets))


def set_rows(rom: Rom, name: str, response_set: str | None) -> np.ndarray:
    """The (3, n_rom) mean displacement rows of the set ``name`` on the ROM's coordinates."""
    if name == response_set:
        assert rom.output is not None
        return np.asarray(rom.output)
    return np.asarray(rom.outputs[name])


def check_damping_ratio(value: Any) -> float:
    """A structural (modal) damping ratio in [0, 1), dimensionless."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if isinstance(value, bool) or not (math.isfinite(x) and 0.0 <= x < 1.0):
        raise ParameterError(f"damping ratio must be in [0, 1), got {value!r}")
    return x


def modal_damping(structure: Any, zeta: float) -> Any:
    """``structure`` (:class:`~microslip.dynamics.structure.Structure`) with the structural
    damping that gives each of its stuck linear modes the ratio ``zeta``: C = M Phi diag(2
    zeta omega_i) Phi^T M over the modes of K + the joints' stuck stiffness (mass-normalised
    Phi), added to its own C. In the stuck limit a mode's EPMC damping ratio is then its own
    plus ``zeta`` exactly; with slip, approximately (the slipping shape mixes modes, each
    damped at its own omega_i)."""
    from dataclasses import replace

    from scipy.linalg import eigh

    zeta = check_damping_ratio(zeta)
    if zeta == 0.0:
        return structure
    m = np.asarray(structure.mass, dtype=float)
    lam, phi = eigh(structure.stuck_stiffness(), m)
    omega = np.sqrt(np.maximum(lam, 0.0))
    mp = m @ phi
    c = (mp * (2.0 * zeta * omega)) @ mp.T
    return replace(structure, damping=np.asarray(structure.damping) + 0.5 * (c + c.T))
