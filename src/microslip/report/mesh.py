"""The report of a case of the user's own mesh (issue 34 item 3): every number about the
case's part, its loads and its modes.

A case with ``[mesh] file`` is a part, not a bar: its geometry is the mesh, and it needs no
``[geometry]``. :func:`compute_mesh_report` builds the case's assembly the way the commands
do (:func:`~.part.case_assembly`: the clamp's shorthand keys and the ``[[mesh.contact]]``,
``[[mesh.preload]]``, ``[[mesh.support]]``, ``[[mesh.material]]`` and ``[[mesh.bolt]]``
tables), checks it against the mesh (:func:`~microslip.case.meshroles.check_on_mesh`: an
error stops the report, a borderline value is one of its checks), runs ``fe --case`` at the
case's ``[[mesh.load]]`` tables (the loops, W, the model built), the modal study of the
structure when the case gives a density (:mod:`.structure`) and, only when asked
(``ReportSettings.bar``) and the case describes one, the 1-D bar report of its
``[geometry]`` (:func:`~.compute.compute_bar_report`). Units: N, mm, MPa, N·mm, kg/m^3.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..case.model import Case
from ..errors import MacroslipError, ParameterError
from ..progress import progress_bar
from .compute import ReportData, ReportSettings, compute_bar_report, report_json
from .part import _spell, case_assembly, case_density
from .structure import structure_section

if TYPE_CHECKING:
    from ..fe.assembly import Assembly

__all__ = ["MeshReport", "compute_mesh_report", "mesh_report_json"]


@dataclass(frozen=True)
class MeshReport:
    """What the report of a mesh case shows (units N, mm, MPa, N·mm).

    ``model`` is the JSON's ``model`` object of ``fe --mesh`` (what the solver built: the
    role sets' faces and areas, F / A, the contact nodes closed and open after the preload);
    ``fe`` the summary of ``fe --case --json`` at the case's loads (None without
    ``[[mesh.load]]`` tables or with ``fe_points`` off; ``fe_error`` says why a run
    stopped), ``loops`` each load's settled loop (set, force N, displacement mm);
    ``checks`` the errors (none: a check that fails stops the report) and warnings found
    on the part; ``structure`` the modal study of the case's mode (:mod:`.structure`, None
    without a density); ``bar`` the 1-D bar report of the case's ``[geometry]``, only when
    asked."""

    case: Case
    settings: ReportSettings
    model: dict[str, Any]
    fe: dict[str, Any] | None
    fe_error: str | None
    loops: list[tuple[str, Any, Any]] = field(repr=False)
    checks: list[str]
    structure: dict[str, Any] | None = None
    bar: ReportData | None = None

    @property
    def mesh_file(self) -> str:
        return str(self.case.values["mesh.file"])


def _model(mesh: Any, assembly: Assembly) -> dict[str, Any]:
    from ..fe.clamp import clamped_model

    return dict(clamped_model(mesh, assembly).describe())


def compute_mesh_report(case: Case, settings: ReportSettings, *, progress: bool = True,
                        structure: bool = True) -> MeshReport:
    """Every number of the report of the mesh case ``case`` (see the module)."""
    from ..case.meshroles import check_on_mesh
    from ..fe.errors import SolverError
    from ..fe.meshfile import read_mesh
    from ..fe.ownmesh import OwnMeshCase, loops_of, run_own_mesh

    if settings.bar and case.params is None:
        raise ParameterError(f"case {case.source}: the bar comparison (--bar) needs the bar's "
                             "geometry and clamp: give preset = \"...\" or [geometry] length, "
                             "width, thickness with the clamp values")
    assembly = case_assembly(case)
    mesh_file = str(case.values["mesh.file"])
    mesh = read_mesh(mesh_file)
    sets = tuple((case.values[k], role) for k, role in (
        ("mesh.response_set", "response set"),) if k in case.values)
    found = check_on_mesh(mesh, assembly, case.mesh_loads, sets, spell=_spell)
    found.raise_first()  # a unit mistake or a wrong set is an error, never a page
    checks = [*case.warnings, *found.warnings]
    runs = int(bool(case.mesh_loads and settings.fe_points)) + int(structure) + 1
    fe = fe_error = None
    loops: list[tuple[str, Any, Any]] = []
    with progress_bar(runs, "report", enabled=progress, unit="run") as bar:
        if case.mesh_loads and settings.fe_points:
            run_case = OwnMeshCase(mesh_file, assembly, tuple(case.mesh_loads),
                                   substeps=settings.substeps)
            try:
                done = run_own_mesh(run_case, settings.fe_solver)
                fe, loops = dict(done.summary), list(loops_of(done))
            except (SolverError, MacroslipError) as exc:
                fe_error = str(exc)
            bar.update(1)
        model = fe["model"] if fe is not None and "model" in fe else _model(mesh, assembly)
        if fe is not None:
            checks += [f"fe at the case's loads: {w}" for w in fe.get("warnings", [])]
            if not fe.get("settled", True):
                checks.append("fe at the case's loads: W per cycle did not settle (its last "
                              "cycle is shown)")
        if fe_error is not None:
            checks.append(f"fe at the case's loads did not run through: {fe_error}")
        open_nodes = int(model.get("open_after_preload", 0))
        if open_nodes:
            checks.append(f"{open_nodes} of {model['contact_nodes']} contact nodes are open "
                          "after the preload (lifted off): only the closed ones carry "
                          "friction")
        section = structure_section(case) if structure else None
        if section is not None:
            checks += [f"structure: {w}" for w in section.get("warnings", [])]
        elif structure and case_density(case, assembly) is None:
            checks.append("no density ([mesh] density, kg/m^3): the modes of the part and "
                          "their damping are left out")
        bar.update(1)
        one_d = None
        if settings.bar:
            one_d = compute_bar_report(case, settings, progress=False, structure=False)
        bar.update(1)
    return MeshReport(case=case, settings=settings, model=model, fe=fe, fe_error=fe_error,
                      loops=loops, checks=checks, structure=section, bar=one_d)


def _load_json(load: Any) -> dict[str, Any]:
    return {"set": load.set, "direction": [float(v) for v in load.direction],
            "amplitude_N": float(load.amplitude), "phase_deg": float(load.phase_deg)}


def mesh_report_json(data: MeshReport) -> dict[str, Any]:
    """Every number of the page of a mesh case as one JSON object (``report --json``):
    ``model`` that of ``fe --mesh --json``, ``fe`` the whole of ``fe --case --json`` at the
    case's loads, ``structure`` that of ``modal --mesh ... --solver all --json``, ``bar``
    the bar report's object (:func:`~.compute.report_json`; null unless asked)."""
    from dataclasses import asdict, is_dataclass

    s = data.settings
    inputs = {k: ([asdict(x) for x in v] if isinstance(v, tuple) and v and is_dataclass(v[0])
                  else v) for k, v in data.case.values.items()}
    return {
        "case_name": data.case.name,
        "kind": "mesh",
        "mesh_file": data.mesh_file,
        "units": {"force": "N", "length": "mm", "modulus": "MPa", "energy": "N·mm",
                  "density": "kg/m^3"},
        "inputs": inputs,
        "loads": [_load_json(ld) for ld in data.case.mesh_loads],
        "settings": {"fe_solver": s.fe_solver, "substeps": s.substeps,
                     "fe_points": s.fe_points, "bar": s.bar},
        "model": data.model,
        "fe": data.fe,
        "fe_error": data.fe_error,
        "checks": list(data.checks),
        "structure": data.structure,
        "bar": None if data.bar is None else report_json(data.bar),
    }
