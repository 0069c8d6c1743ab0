"""The bar reduced to a two-directional joint, against the built-in FE at the same motion.

A structural-dynamics user puts the clamp into a structure as one joint with two in-plane
directions. This step says how well each joint of microslip reproduces the FE's coupled
dissipation on the Table 1 bar (:func:`microslip.meshdynamics.fe_check.fe_comparison`): the
isotropic circular joint and the paper's decoupled sum built from the 1-D models, and the
anisotropic joint with the FE's own first loading across the bar, at the force ratios of
:data:`JOINT_FE_RATIOS`, phase 90 degrees, largest resultant 0.75 mu F_N. It writes
``joint2d_vs_fe.csv``, ``fig13_joint2d_vs_fe.png`` and the report's section.
Units: N, mm, N·mm.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import MicroslipError
from ..params import preset

__all__ = [
    "JOINTS",
    "JOINT_FE_MESH",
    "JOINT_FE_RATIOS",
    "joint_fe_figure",
    "joint_fe_section",
    "joint_fe_study",
]

#: Force ratios R = A_tip / A_centre of the study (ellipses at 90 degrees).
JOINT_FE_RATIOS = (1.0, 2.0, 4.0)
#: The FE mesh of the study (docs/dynamics.md: coarse and medium agree within 0.4 %).
JOINT_FE_MESH = "medium"
#: Largest resultant force of each ellipse as a fraction of mu F_N.
PEAK_FRACTION = 0.75
#: Reduced joints compared, in the order of the table: key of ``joint_force`` -> label.
JOINTS = {"anisotropic spatial": "anisotropic, spatial pairing",
          "anisotropic ordered": "anisotropic, ordered pairing",
          "circular": "isotropic circular (tip model)",
          "decoupled": "decoupled sum (tip + centre model)"}


def _col(key: str, suffix: str) -> str:
    """Column name of a joint's figure: ``anisotropic spatial`` -> ``anisotropic_spatial_Nmm``."""
    return f"{key.replace(' ', '_')}_{suffix}"


def joint_fe_study(*, mesh: Any = None, ratios: Sequence[float] = JOINT_FE_RATIOS,
                   say: Callable[[str], None] = lambda _: None
                   ) -> tuple[dict[str, list[Any]], list[Any]]:
    """Columns of ``joint2d_vs_fe.csv`` and the comparisons (one per ratio that ran);
    ``mesh`` default :data:`JOINT_FE_MESH`."""
    from ..fe.builtin.study import amplitudes_for_ratio
    from ..meshdynamics.fe_check import cycle_work, fe_comparison

    params = preset("table1")
    peak = PEAK_FRACTION * params.macroslip_force
    cols: dict[str, list[Any]] = {k: [] for k in (
        "R", "tip_amplitude_N", "centre_amplitude_N", "fe_dissipated_energy_Nmm",
        *(_col(k, "Nmm") for k in JOINTS), *(_col(k, "over_fe") for k in JOINTS))}
    runs = []
    for ratio in ratios:
        at, ac = amplitudes_for_ratio(ratio, 90.0, peak)
        try:
            r = fe_comparison(params, at, ac, 90.0, mesh=mesh or JOINT_FE_MESH)
        except MicroslipError as exc:
            say(f"joint against FE, R = {ratio:g}: failed, {exc}")
            continue
        runs.append(r)
        cols["R"].append(ratio)
        cols["tip_amplitude_N"].append(at)
        cols["centre_amplitude_N"].append(ac)
        cols["fe_dissipated_energy_Nmm"].append(r.fe_coupled)
        for key in JOINTS:
            w = cycle_work(r.joint_force[key], r.orbit)
            cols[_col(key, "Nmm")].append(w)
            cols[_col(key, "over_fe")].append(w / r.fe_coupled)
    return cols, runs


def joint_fe_figure(path: str | Path, cols: dict[str, list[Any]], runs: list[Any]) -> None:
    """(a) W of each joint over the FE's against R; (b) across the bar at the R nearest 1:
    the FE's centre force and each joint's force against delta_centre
    (:func:`microslip.plot.dynamics.figure_joint_fe`)."""
    from ..plot.dynamics import figure_joint_fe

    r = np.asarray(cols["R"], dtype=float)
    nearest = int(np.argmin(np.abs(np.log(r))))
    figure_joint_fe(path, cols["R"], JOINTS, {k: cols[_col(k, "over_fe")] for k in JOINTS},
                    runs[nearest], float(r[nearest]))


def joint_fe_section(cols: dict[str, list[Any]]) -> str:
    """The report's section, computed from the columns."""
    header = ["R", "A_t (N)", "A_c (N)", "W FE (N·mm)", *(f"{v} / FE" for v in JOINTS.values())]
    rows = [[f"{cols['R'][i]:g}", f"{cols['tip_amplitude_N'][i]:.4g}",
             f"{cols['centre_amplitude_N'][i]:.4g}",
             f"{cols['fe_dissipated_energy_Nmm'][i]:.4g}",
             *(f"{cols[_col(k, 'over_fe')][i]:.3f}" for k in JOINTS)]
            for i in range(len(cols["R"]))]
    table = "\n".join(["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
                       *("| " + " | ".join(row) + " |" for row in rows)])
    worst = {k: max(abs(x - 1.0) for x in cols[_col(k, "over_fe")]) for k in JOINTS}
    best = min(worst, key=worst.__getitem__)
    return (
        "A structure model carries the clamp as one joint with two in-plane directions "
        "(`microslip modal`/`frf` with a two-directional joint). Each reduced joint is driven "
        "by the FE's settled coupled orbit (δ_tip, δ_centre) of the Table 1 bar, ellipses at "
        f"90° with the largest resultant {PEAK_FRACTION:g} μF_N, `{JOINT_FE_MESH}` mesh, and "
        "its dissipation per cycle is compared with the FE's (`joint2d_vs_fe.csv`, "
        "`fig13_joint2d_vs_fe.png`; docs/dynamics.md, \"The reduced bar against the FE\"). "
        "The anisotropic joint takes the tip model along the bar and the FE's own first "
        "loading across it (the bar bends in its plane there, which no 1-D model describes).\n"
        f"\n{table}\n\n"
        f"Largest deviation from the FE over these ratios: "
        + ", ".join(f"{JOINTS[k]} {100 * w:.1f} %" for k, w in worst.items())
        + f". Closest: {JOINTS[best]}.\n")
