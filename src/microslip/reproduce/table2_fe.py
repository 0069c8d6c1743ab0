"""The paper's own clamp (Table 2) against finite elements: how far are the 1-D models?

The paper computes Figs 10-12 with its 1-D models on the Table 2 zones but checks the models
against FE only on the slender Table 1 bar. Its zones are squat (L/t = 5 in the reading of
docs/interpretation.md §6) and soft (E = 10 GPa), where a bar model is out of its range. This
step runs the built-in FE solver (the same load step as the validation, :func:`microslip.fe.
run_loop`) at each of the paper's amplitude levels below macroslip, beside the paper's
rigid-foundation model and the shear-layer model at the same stick slope. Units: N, N·mm.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..energy import damping
from ..errors import MicroslipError
from ..models import Contact, get_model, macroslip_force
from ..options import ModelOptions
from ..params import preset
from ..planar import CENTRE_LEVEL_FORCE, TIP_LEVEL_FORCE
from ..planar.trajectories import PAPER_LEVELS

__all__ = ["TABLE2_FE_MESH", "TABLE2_STICK_SLOPE", "table2_fe_table"]

#: The FE mesh of this step (the built-in solver's; fine: the low levels converge slowly).
TABLE2_FE_MESH = "fine"
#: Stick slope of the FE and of the shear-layer model, N/mm^3 (a ground metal contact).
TABLE2_STICK_SLOPE = 1.0e5

_ZONES = (("tip", "table2-tip", TIP_LEVEL_FORCE), ("centre", "table2-centre", CENTRE_LEVEL_FORCE))


def table2_fe_table(*, mesh: str | None = None, stick_slope: float = TABLE2_STICK_SLOPE,
                    increments: int = 1000,
                    say: Callable[[str], None] = lambda _: None) -> dict[str, list[Any]]:
    """Columns of ``table2_fe_vs_1d.csv``: per zone and level, W_d of the FE, of the paper's
    rigid-foundation model and of the shear-layer model (physical centre reading, the one
    with a shear-layer counterpart), and their ratios to the FE. ``mesh`` default
    :data:`TABLE2_FE_MESH`."""
    from ..fe import run_loop

    mesh = mesh or TABLE2_FE_MESH
    opt = ModelOptions()
    contact = Contact.layer(stick_slope)
    cols: dict[str, list[Any]] = {k: [] for k in (
        "model", "level", "amplitude_N", "fe_dissipated_energy_Nmm",
        "rigid_dissipated_energy_Nmm", "layer_dissipated_energy_Nmm", "rigid_over_fe",
        "layer_over_fe", "fe_converged", "fe_message")}
    for model, name, unit in _ZONES:
        params = preset(name)
        limit = macroslip_force(model, params, opt)
        for level in sorted(PAPER_LEVELS):
            amplitude = level * unit
            if amplitude >= limit:
                continue
            try:
                fe, _ = run_loop(get_model(model).load_case, params, amplitude, mesh=mesh,
                                 stick_slope=stick_slope, vtu=False)
            except MicroslipError as exc:
                say(f"Table 2 FE, {model} level {level:g}: failed, {exc}")
                continue
            rigid = damping(model, params, amplitude, increments, opt).dissipated_energy
            layer = damping(model, params, amplitude, increments, opt,
                            contact=contact).dissipated_energy
            w = fe.dissipated_energy
            for key, value in (("model", model), ("level", level), ("amplitude_N", amplitude),
                               ("fe_dissipated_energy_Nmm", w),
                               ("rigid_dissipated_energy_Nmm", rigid),
                               ("layer_dissipated_energy_Nmm", layer),
                               ("rigid_over_fe", rigid / w if w > 0 else float("nan")),
                               ("layer_over_fe", layer / w if w > 0 else float("nan")),
                               ("fe_converged", bool(fe.converged)),
                               ("fe_message", str(getattr(fe, "message", "")))):
                cols[key].append(value)
    return cols
