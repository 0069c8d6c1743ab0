"""The paper's clamped zone (the box) as an assembly on its mesh: the one built-in solver.

The box of Section 4 (the clamped zone L x w x t on a rigid base, pressed by F_N on its top
face, loaded on its end face or its mid-length section) is the mesh
:func:`~microslip.fe.examples.box_hexmesh` with the assembly :func:`box_assembly`: its
``contact`` face on the rigid base, the preload F_N on ``clamp`` whose distribution is the
clamp's pressure law along x (:class:`~microslip.fe.assembly.Preload`; none: the uniform
pressure F_N / (L w), the paper's), one material and the contact law. :func:`box_model`
builds it with :func:`~.meshmodel.build_mesh_model`, not condensed (the box's contact is a
quarter of its dofs: the full banded factor is faster there, docs/interpretation.md
section 24), and :class:`BoxLoading` steps its two loads with the loading state of every
mesh (:mod:`.meshrun`):

* *tip*: force along the bar (x) on the end face x = L, spread like a uniform traction;
* *centre*: force on the mid-length section x = L/2 (its node plane i = nx / 2), spread like
  a uniform traction over the section, along the bar (``axial``, the paper's 1-D centre
  model) or across it in the plane of the interface (``transverse``, y: the second in-plane
  component of the planar study).

The displacement reported for a load is the force-weighted mean of the nodal displacements
of its section along the load (the work-conjugate displacement: F delta is the work done).
Units: N, mm, MPa, N·mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...conventions import DEFAULT_MESH
from ...errors import MacroslipError, ParameterError
from ...models.interface import PressureLaw
from ...params import ClampParams
from ..assembly import Assembly, Contact, Material, Preload
from ..constants import DEFAULT_NORMAL_SLOPE, DEFAULT_STICK_SLOPE
from ..hexmesh import HexMesh
from ..meshload import MeshLoad
from ..result import SLIP
from .meshmodel import MeshModel, build_mesh_model
from .meshrun import _Run
from .model import CENTRE_DIRECTIONS, NewtonOptions

__all__ = ["ELEMENT", "BoxHistory", "BoxLoading", "box_assembly", "box_counts",
           "box_describe", "box_model", "box_pressure_law"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: The built-in solver's default element for the box
#: (:data:`~microslip.fe.builtin.element.ELEMENTS`).
ELEMENT = "C3D8I"


def box_assembly(params: ClampParams, *, stick_slope: float = DEFAULT_STICK_SLOPE,
                 pressure_law: PressureLaw | None = None, normal_contact: str = "fixed",
                 normal_slope: float = DEFAULT_NORMAL_SLOPE) -> Assembly:
    """The box of ``params`` as an assembly on :func:`~microslip.fe.examples.box_hexmesh`:
    ``contact`` on the rigid base, F_N on ``clamp`` (distributed by ``pressure_law`` along x;
    None or ``uniform``: the uniform pressure), the material and the contact law.

    >>> from microslip import preset
    >>> a = box_assembly(preset("table1"))
    >>> a.contact_set, a.clamp_set, a.clamp_force, a.is_shorthand
    ('contact', 'clamp', 445.0, True)
    """
    if pressure_law is not None and pressure_law.name == "uniform":
        pressure_law = None
    return Assembly(contacts=(Contact("contact"),),
                    preloads=(Preload("clamp", params.normal_force, pressure_law, "x"),),
                    materials=(Material(params.modulus, params.poisson_ratio),),
                    friction=params.friction, stick_slope=stick_slope,
                    normal_contact=normal_contact, normal_slope=normal_slope)


def box_pressure_law(model: MeshModel) -> PressureLaw | None:
    """The clamping pressure law of a box model (None: uniform)."""
    law: PressureLaw | None = model.assembly.preloads[0].distribution
    return law


def _axes(mesh: HexMesh) -> tuple[FloatArray, FloatArray, FloatArray]:
    x, y, z = (np.unique(mesh.nodes[:, c]) for c in range(3))
    return x, y, z


def box_counts(mesh: HexMesh) -> tuple[int, int, int]:
    """Elements (nx, ny, nz) of a box mesh along x, y, z."""
    x, y, z = _axes(mesh)
    return x.size - 1, y.size - 1, z.size - 1


def box_describe(mesh: HexMesh) -> dict[str, Any]:
    """Plain summary of a box mesh for reports (sizes in mm): element counts, whether it is
    graded (node planes not equally spaced), nodes, elements and the box's size."""
    axes = _axes(mesh)
    size = [float(a[-1] - a[0]) for a in axes]
    graded = any(not np.allclose(a, np.linspace(a[0], a[-1], a.size), rtol=0.0,
                                 atol=1e-12 * s) for a, s in zip(axes, size, strict=True))
    nx, ny, nz = (a.size - 1 for a in axes)
    return {"nx": nx, "ny": ny, "nz": nz, "graded": graded, "nodes": len(mesh.nodes),
            "elements": len(mesh.elements), "length_mm": size[0], "width_mm": size[1],
            "thickness_mm": size[2]}


def _check_model(params: ClampParams, model: MeshModel) -> MeshModel:
    """A model given instead of a mesh must be the box of ``params``."""
    a = model.assembly
    size = box_describe(model.mesh)
    same = (a.friction == params.friction and a.clamp_force == params.normal_force
            and a.modulus == params.modulus and a.poisson_ratio == params.poisson_ratio
            and all(math.isclose(size[k], v, rel_tol=1e-12) for k, v in (
                ("length_mm", params.length), ("width_mm", params.width),
                ("thickness_mm", params.thickness))))
    if not same:
        raise ParameterError("the given model was built for other parameters")
    return model


def box_model(params: ClampParams, mesh: Any = DEFAULT_MESH, *,
              stick_slope: float = DEFAULT_STICK_SLOPE, element: str = ELEMENT,
              linear_solver: str = "banded", newton: NewtonOptions | None = None,
              pressure_law: PressureLaw | None = None, normal_contact: str = "fixed",
              normal_slope: float = DEFAULT_NORMAL_SLOPE) -> MeshModel:
    """Assemble the clamped zone and solve the clamping step.

    Parameters
    ----------
    params : ClampParams
        Geometry, material, friction and clamping force.
    mesh : str, (nx, ny, nz), HexMesh or MeshModel
        A mesh level or ``"NXxNYxNZ"`` (:func:`~microslip.fe.examples.box_hexmesh`; nx must
        be even: the mid-length section), a box mesh, or a model already built for
        ``params`` (returned as it is).
    stick_slope : float
        lambda, N/mm^3 (default 1e4, CalculiX's).
    element : str
        ``C3D8I`` or ``C3D8``.
    linear_solver : str
        ``banded`` (default), ``splu`` or ``cholmod``.
    newton : NewtonOptions, optional
    pressure_law : PressureLaw, optional
        Shape of the clamping traction along the length (default uniform, the paper's).
    normal_contact : {"fixed", "penalty"}
        :data:`~microslip.fe.builtin.normal.NORMAL_CONTACTS` (default ``fixed``, the paper's).
    normal_slope : float
        k_n of the penalty, N/mm^3 (``penalty`` only).

    Returns
    -------
    MeshModel

    Examples
    --------
    >>> from microslip import preset
    >>> m = box_model(preset("table1"), (8, 2, 1))
    >>> m.dof, round(float(m.normal_force.sum()), 6), bool(np.all(m.normal_force > 0))
    (135, 445.0, True)
    """
    from ..examples import box_hexmesh

    if not isinstance(params, ClampParams):
        raise ParameterError(f"params must be a ClampParams, got {type(params).__name__}")
    if isinstance(mesh, MeshModel):
        return _check_model(params, mesh)
    hexmesh = mesh if isinstance(mesh, HexMesh) else box_hexmesh(params, mesh)
    if "centre" not in hexmesh.node_sets:
        raise ParameterError(f"the mid-length section needs an even nx, got nx = "
                             f"{box_counts(hexmesh)[0]}")
    assembly = box_assembly(params, stick_slope=stick_slope, pressure_law=pressure_law,
                            normal_contact=normal_contact, normal_slope=normal_slope)
    return build_mesh_model(hexmesh, assembly, element=element, linear_solver=linear_solver,
                            newton=newton, condensed=False)


@dataclass(frozen=True, eq=False)
class BoxHistory:
    """Response of a box model to a sampled load history (one row per load sample).

    Attributes
    ----------
    f_tip, f_centre : ndarray, shape (n,)
        Applied forces, N.
    tip_displacement, centre_displacement : ndarray, shape (n,)
        Work-conjugate displacements along each load, relative to the clamped state, mm.
    iterations : ndarray of int, shape (n,)
        Newton iterations of each increment (of all its sub-increments if it was cut).
    status : ndarray of int8, shape (n, n_c)
        Contact status after each increment (:data:`~microslip.fe.result.STICK`, ``SLIP``,
        ``OPEN``).
    friction_work : ndarray, shape (n,)
        Energy dissipated by friction in each increment, N·mm.
    converged : bool
    completed : int
        Samples solved (all of them unless an increment failed).
    message : str
    wall_s : float
        Wall time of the stepping, s.
    factorisations : int
    u : ndarray, shape (n, dof) or None
        Free-dof displacements after each increment, mm (``record=True``).
    slip : ndarray, shape (n, n_c, 2)
        Slips of the contact nodes after each increment, mm.
    normal_force : ndarray, shape (n, n_c) or None
        Normal forces N_i after each increment, N (penalty normal contact; None when they are
        fixed: the model's ``normal_force``).
    """

    f_tip: FloatArray
    f_centre: FloatArray
    tip_displacement: FloatArray
    centre_displacement: FloatArray
    iterations: IntArray
    status: NDArray[np.int8]
    friction_work: FloatArray
    converged: bool
    completed: int
    message: str
    wall_s: float
    factorisations: int
    u: FloatArray | None
    slip: FloatArray
    normal_force: FloatArray | None

    @property
    def slipping(self) -> NDArray[np.bool_]:
        """(n, n_c): True where a contact node slips."""
        return np.asarray(self.status == SLIP)

    def displacement(self, component: str) -> FloatArray:
        """Work-conjugate displacement of the ``tip`` or ``centre`` load, mm."""
        return {"tip": self.tip_displacement, "centre": self.centre_displacement}[component]


class BoxLoading:
    """The tip and centre forces on a box model, continued chunk after chunk (the loading
    state of every mesh, :mod:`.meshrun`), so that a cyclic run can stop as soon as the
    energy per cycle settles."""

    def __init__(self, params: ClampParams, model: MeshModel,
                 centre_direction: str = "transverse") -> None:
        if centre_direction not in CENTRE_DIRECTIONS:
            raise ParameterError(f"unknown centre direction {centre_direction!r}; choose one "
                                 f"of {', '.join(CENTRE_DIRECTIONS)}")
        along = (1.0, 0.0, 0.0) if CENTRE_DIRECTIONS[centre_direction] == 0 else (0.0, 1.0, 0.0)
        self.params, self.model = params, model
        self.run = _Run(model, [MeshLoad("tip", (1.0, 0.0, 0.0), 1.0),
                                MeshLoad("centre", along, 1.0)], False)
        self.failed = False

    def advance(self, f_tip: Any, f_centre: Any, *, record: bool = False) -> BoxHistory:
        """Apply the next samples of the force history (one increment each).

        Parameters
        ----------
        f_tip, f_centre : array_like, shape (n,)
            Forces at each sample, N.
        record : bool
            Keep the displacements after each increment (for a VTU export).

        Returns
        -------
        BoxHistory
            Of these samples only; after a failed increment, the samples solved so far and
            ``converged=False`` (further calls raise).
        """
        if self.failed:
            raise MacroslipError("the simulation stopped at a failed increment")
        ft = np.asarray(f_tip, dtype=float)
        fc = np.asarray(f_centre, dtype=float)
        if ft.ndim != 1 or ft.shape != fc.shape:
            raise ParameterError("tip and centre force histories must be 1-D arrays of equal "
                                 "length")
        if not (np.all(np.isfinite(ft)) and np.all(np.isfinite(fc))):
            raise ParameterError("force histories must be finite")
        peak = float(np.max(np.hypot(ft, fc))) if ft.size else 0.0
        limit = self.params.macroslip_force
        if peak >= limit:
            raise MacroslipError(
                f"the resultant tangential load reaches {peak:g} N >= mu F_N = {limit:g} N "
                "(macroslip: no static equilibrium)")
        run = self.run
        first, n0, u0 = len(run.its), len(run.normal), len(run.fields)
        f0, w0 = run.stepper.factorisations, run.wall
        run.record = record
        why = run.advance(np.stack([ft, fc], axis=1), first, stop=True)
        done = len(run.its) - first
        if why is not None:
            self.failed = True
        d = run.displacements()[first:]
        normal = (None if self.model.normal is None else
                  np.array(run.normal[n0:]).reshape(done, -1))
        n_c = self.model.contact_nodes.size
        return BoxHistory(
            f_tip=ft[:done], f_centre=fc[:done], tip_displacement=d[:, 0].copy(),
            centre_displacement=d[:, 1].copy(),
            iterations=np.array(run.its[first:], dtype=np.int64),
            status=np.array(run.status[first:], dtype=np.int8).reshape(done, n_c),
            friction_work=np.array(run.works[first:]), converged=why is None,
            completed=done, message="converged" if why is None else why,
            wall_s=run.wall - w0, factorisations=run.stepper.factorisations - f0,
            u=np.array(run.fields[u0:]).reshape(done, -1) if record else None,
            slip=np.array(run.slips[first:]).reshape(done, n_c, 2), normal_force=normal)
