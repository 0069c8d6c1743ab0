"""One entry point for an FE loop, whichever solver: :func:`run_loop` and :data:`SOLVERS`.

Each entry of the solver registry names the solver's meshes and elements, the options it
takes besides the common ones, how it runs a loop and how it turns the result into the
nodal fields of the VTU export. With ``out`` every solver writes the same files:
``result.json`` (the summary of :meth:`FELoopResult.summary`) and a VTU time series
(:mod:`microslip.fe.vtu`).
"""

from __future__ import annotations

import dataclasses
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

from ..conventions import DEFAULT_MESH
from ..energy import DEFAULT_STRAIN_ENERGY
from ..errors import ParameterError
from ..io import write_json
from ..loading import load_case
from ..meshlevels import parse_counts
from ..params import ClampParams, preset
from .constants import DEFAULT_STICK_SLOPE
from .result import FELoopResult
from .vtu import FieldSeries, write_vtu_series

__all__ = ["SOLVERS", "SolverEntry", "run_loop"]


@dataclass(frozen=True)
class SolverEntry:
    """One FE solver of :func:`run_loop`.

    Attributes
    ----------
    name : str
    description : str
    meshes : tuple of str
        Named mesh levels (:data:`~microslip.meshlevels.LEVELS`, the same for both solvers;
        ``"NXxNYxNZ"`` counts are taken too).
    elements : tuple of str
        Element types; the first is the default.
    options : tuple of str
        Keyword options the solver takes besides the common ones (e.g. ``timeout``).
    run : callable
        ``run(load_case, params, amplitude, mesh, element, stick_slope, substeps,
        strain_energy_kind, job_dir, record, **options) -> FELoopResult``.
    fields : callable
        ``fields(result) -> FieldSeries`` for the VTU export.
    """

    name: str
    description: str
    meshes: tuple[str, ...]
    elements: tuple[str, ...]
    options: tuple[str, ...]
    run: Callable[..., FELoopResult]
    fields: Callable[[FELoopResult], FieldSeries]

    @property
    def takes_timeout(self) -> bool:
        return "timeout" in self.options


def _run_builtin(load: str, params: ClampParams, amplitude: float, mesh: Any, element: str,
                 stick_slope: float, substeps: int, strain_energy_kind: str,
                 job_dir: Path | None, record: bool, **options: Any) -> FELoopResult:
    from .builtin import solve_uniaxial

    return solve_uniaxial(params, load, amplitude, mesh=mesh, stick_slope=stick_slope,
                          increments=substeps, element=element,
                          strain_energy_kind=strain_energy_kind, record=record, **options)


def _builtin_fields(result: FELoopResult) -> FieldSeries:
    from .builtin.details import BuiltinDetails

    d = result.details
    if not isinstance(d, BuiltinDetails) or d.model is None or d.u is None:
        raise ParameterError("the built-in result holds no fields: solve with record=True")
    mesh = d.model.mesh
    return FieldSeries(mesh.nodes, [("hexahedron", mesh.elements)],
                       d.model.global_vectors(d.u))


def _run_calculix(load: str, params: ClampParams, amplitude: float, mesh: Any, element: str,
                  stick_slope: float, substeps: int, strain_energy_kind: str,
                  job_dir: Path | None, record: bool, **options: Any) -> FELoopResult:
    from .calculix.boxrun import run_case
    from .calculix.case import FECase
    from .calculix.runner import find_ccx

    normal = {k: options.pop(k) for k in ("normal_slope",) if k in options}
    case = FECase(load, params, amplitude, mesh=mesh, stick_slope=stick_slope,
                  substeps=substeps, element=element, **normal)
    if not options.get("reuse"):
        find_ccx()  # one line saying how to install it, before anything is written
    if job_dir is None:
        with tempfile.TemporaryDirectory(prefix="microslip-fe-") as tmp:
            r = run_case(case, Path(tmp), strain_energy_kind=strain_energy_kind,
                             **(options | {"reuse": False}))
        return _without_job_dir(r)
    return run_case(case, job_dir, strain_energy_kind=strain_energy_kind, **options)


def _without_job_dir(r: FELoopResult) -> FELoopResult:
    return dataclasses.replace(r, job_dir=None)


def _calculix_fields(result: FELoopResult) -> FieldSeries:
    from .calculix.boxrun import box_fields

    fields: FieldSeries = box_fields(result)
    return fields


def _registry() -> Mapping[str, SolverEntry]:
    from ..meshlevels import LEVELS
    from .builtin.box import ELEMENT as BUILTIN_ELEMENT
    from .builtin.element import ELEMENTS
    from .calculix.case import ELEMENT_TYPES

    return MappingProxyType({
        "builtin": SolverEntry(
            "builtin", "built-in frictional solver (docs/solver.md)", LEVELS,
            (BUILTIN_ELEMENT, *(e for e in ELEMENTS if e != BUILTIN_ELEMENT)),
            ("linear_solver", "centre_direction", "newton", "pressure_law", "normal_contact",
             "normal_slope"), _run_builtin, _builtin_fields),
        "calculix": SolverEntry(
            "calculix", "CalculiX ccx (docs/validation.md)", LEVELS, ELEMENT_TYPES,
            ("timeout", "threads", "reuse", "normal_slope", "executable"), _run_calculix,
            _calculix_fields),
    })


#: The FE solvers: name -> :class:`SolverEntry`.
SOLVERS: Mapping[str, SolverEntry] = _registry()


def _entry(solver: str) -> SolverEntry:
    if solver not in SOLVERS:
        raise ParameterError(f"unknown solver {solver!r}; choose one of {', '.join(SOLVERS)}")
    return SOLVERS[solver]


def run_loop(load: str, params: ClampParams | None = None, amplitude: float = 267.0, *,
             solver: str = "builtin", out: str | Path | None = None, vtu: bool = True,
             mesh: Any = DEFAULT_MESH, element: str | None = None,
             stick_slope: float = DEFAULT_STICK_SLOPE, substeps: int = 50,
             strain_energy_kind: str = DEFAULT_STRAIN_ENERGY,
             **options: Any) -> tuple[FELoopResult, list[Path]]:
    """Run the paper's FE load step (Section 4) of one load case with one solver.

    Parameters
    ----------
    load : str
        Load case, a name in :data:`microslip.loading.LOAD_CASES`.
    params : ClampParams, optional
        Default Table 1.
    amplitude : float
        F0, N (below mu F_N).
    solver : str
        A name in :data:`SOLVERS`.
    out : path, optional
        Directory for ``result.json`` and (``vtu``) the VTU series; CalculiX keeps its job
        files there too. None: nothing is written (CalculiX runs in a temporary directory).
    mesh, element : mesh level (or the solver's explicit mesh), element type (default: the
        solver's first).
    stick_slope : float
        lambda, N/mm^3.
    substeps : int
        Equal increments over t = 0 .. 1.25 s, a multiple of 5.
    strain_energy_kind : str
    **options
        The solver's own options (``SOLVERS[solver].options``); others raise.

    Returns
    -------
    (FELoopResult, list of Path)
        The result and the files written.
    """
    entry = _entry(solver)
    load_case(load)
    unknown = sorted(set(options) - set(entry.options))
    if unknown:
        raise ParameterError(f"option(s) {', '.join(unknown)} do not apply to the {solver} "
                             f"solver; it takes {', '.join(entry.options)}")
    if element is not None and element not in entry.elements:
        raise ParameterError(f"element {element} is not an element of the {solver} solver; "
                             f"choose one of {', '.join(entry.elements)}")
    if isinstance(mesh, str) and mesh not in entry.meshes and parse_counts(mesh) is None:
        raise ParameterError(f"mesh {mesh} is not a mesh of the {solver} solver; choose one "
                             f"of {', '.join(entry.meshes)} or NXxNYxNZ")
    job_dir = None if out is None else Path(out)
    result = entry.run(load, params or preset("table1"), amplitude, mesh,
                       element or entry.elements[0], stick_slope, substeps, strain_energy_kind,
                       job_dir, job_dir is not None and vtu, **options)
    if job_dir is None:
        return result, []
    if result.job_dir is None:
        result = dataclasses.replace(result, job_dir=job_dir)
    files = write_vtu_series(result, entry.fields(result), job_dir) if vtu else []
    write_json(job_dir / "result.json", result.summary())
    return result, [job_dir / "result.json", *files]
