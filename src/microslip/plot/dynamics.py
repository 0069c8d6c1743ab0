"""The figures of structural dynamics: a joint's describing function (``microslip joint
--plot``), a mode's frequency and damping against amplitude (``microslip modal --plot``),
frequency-response curves with their backbone and joint orbits (``microslip frf --plot``),
and the clamp reduced to a two-directional joint against the FE (the reproduction's Fig. 13).

The callers compute (describing function, EPMC backbone, orbits, the FE comparison); these
functions only draw. Units: N, mm, Hz, N/mm.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .core import COLOURS, displacement_scale, log_ticks, new_figure, save_figure

if TYPE_CHECKING:
    from ..dynamics.describing import DescribingFunction
    from ..dynamics.modal import ModalCurve
    from ..dynamics.response import FrequencyResponse

__all__ = ["figure_joint_fe", "plot_describing_function", "plot_frequency_response",
           "plot_modal"]


def plot_describing_function(result: DescribingFunction, path: str | os.PathLike[str]) -> None:
    """K_eq, D_eq and eta = D_eq / K_eq against the displacement amplitude, one panel each."""
    fig, axes = new_figure(ncols=3, width_mm=60.0)
    a = result.amplitude
    for ax, y, label, colour in zip(
            axes[0], (result.stiffness, result.damping, result.loss_factor),
            ("equivalent stiffness K_eq (N/mm)", "equivalent damping D_eq (N/mm)",
             "loss factor eta = D_eq / K_eq (-)"), COLOURS, strict=False):
        ax.semilogx(a, y, color=colour, marker="." if a.size < 40 else None)
        ax.set_xlabel("displacement amplitude A (mm)")
        ax.set_ylabel(label)
        log_ticks(ax, "x")
    fig.suptitle(f"describing function of the {result.joint} joint")
    save_figure(fig, path)


def plot_modal(curve: ModalCurve, energy: ModalCurve, path: str | os.PathLike[str]) -> None:
    """Natural frequency and damping ratio against the modal amplitude; ``energy`` (the
    energy method's curve) dashed beside ``curve`` unless it is the same object."""
    fig, axes = new_figure(ncols=2, width_mm=80.0)
    for ax, attr, label in zip(axes[0], ("frequency", "damping_ratio"),
                               ("natural frequency f (Hz)", "damping ratio zeta (-)"),
                               strict=True):
        ax.semilogx(curve.amplitude, getattr(curve, attr), color=COLOURS[0],
                    label=f"{curve.method}, {curve.harmonics} harmonic(s)")
        if energy is not curve:
            ax.semilogx(energy.amplitude, getattr(energy, attr), color=COLOURS[1],
                        linestyle="--", label="energy method")
        ax.set_xlabel("modal amplitude a (mm)")
        ax.set_ylabel(label)
        ax.legend()
        log_ticks(ax, "x")
    save_figure(fig, path)


def plot_frequency_response(curves: Sequence[FrequencyResponse], backbone: ModalCurve,
                            orbits: Sequence[Sequence[Mapping[str, Any]]],
                            path: str | os.PathLike[str]) -> None:
    """The curves with the backbone (EPMC) over them; beside them the first two-directional
    joint's orbit at each curve's peak, if there is one (``orbits``: per curve, the joint
    orbits of :func:`microslip.dynamics.assemble.joint_orbits`)."""
    planar = any(orbits)
    fig, axes = new_figure(ncols=2 if planar else 1, width_mm=120.0 if not planar else 80.0)
    ax = axes[0][0]
    for c, colour in zip(curves, COLOURS * len(curves), strict=False):
        ax.plot(c.frequency, c.amplitude, color=colour, label=f"F = {c.force:g} N")
        ax.plot([c.peak_frequency], [c.peak_amplitude], "o", color=colour, markersize=3)
    ax.plot(backbone.frequency, backbone.amplitude, color="k", linestyle="--",
            label="backbone (EPMC)")
    ax.set_xlabel("excitation frequency f (Hz)")
    ax.set_ylabel("first-harmonic amplitude a (mm)")
    ax.legend()
    if planar:
        ax = axes[0][1]
        for c, found, colour in zip(curves, orbits, COLOURS * len(curves), strict=False):
            if found:
                x, y = np.append(found[0]["x_mm"], found[0]["x_mm"][0]), \
                    np.append(found[0]["y_mm"], found[0]["y_mm"][0])
                ax.plot(x, y, color=colour, label=f"F = {c.force:g} N, "
                        f"{found[0]['frequency_Hz']:.5g} Hz")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"joint {orbits[0][0]['joint'] if orbits[0] else 0} "
                      "relative displacement x (mm)")
        ax.set_ylabel("relative displacement y (mm)")
        ax.legend()
    save_figure(fig, path)


def figure_joint_fe(path: str | os.PathLike[str], ratios: Sequence[float],
                    joints: Mapping[str, str], over_fe: Mapping[str, Sequence[float]],
                    run: Any, run_ratio: float) -> None:
    """(a) W of each reduced joint over the FE's against R; (b) across the bar at one ratio:
    the FE's centre force and each joint's force against delta_centre.

    ``joints`` maps a key of ``run.joint_force`` to its label, ``over_fe`` each key to
    W_joint / W_FE at ``ratios``; ``run`` is the
    :class:`~microslip.meshdynamics.fe_check.FEComparison` drawn in (b), at R = ``run_ratio``.
    """
    fig, axes = new_figure(ncols=2, width_mm=85.0, height_mm=72.0)
    ax = axes[0, 0]
    r = np.asarray(ratios, dtype=float)
    for i, (key, label) in enumerate(joints.items()):
        ax.plot(r, over_fe[key], "os^v"[i] + "-", color=COLOURS[i], label=label)
    ax.axhline(1.0, color="0.5", lw=0.8, ls=":", label="FE (coupled 2-D friction)")
    ax.set_xscale("log", base=2)
    ax.set_xticks(r, [f"{x:g}" for x in r])
    ax.set_xlabel("Force ratio R = $A_{tip} / A_{centre}$ (-), phase 90°")
    ax.set_ylabel("$W_{joint} / W_{FE}$ per cycle (-)")
    ax.set_title("(a) reduced joint on the FE's orbit", loc="left", fontsize=8)
    ax.legend(loc="best", frameon=False, fontsize=6)
    ax = axes[0, 1]
    d = np.append(run.orbit[:, 1], run.orbit[0, 1])
    scale, unit = displacement_scale(float(np.max(np.abs(d))))
    ax.plot(scale * d, np.append(run.fe_force[:, 1], run.fe_force[0, 1]), color="k", lw=1.6,
            label="FE (applied centre force)")
    for i, (key, label) in enumerate(joints.items()):
        f = run.joint_force[key][:, 1]
        ax.plot(scale * d, np.append(f, f[0]), color=COLOURS[i], lw=0.9, label=label)
    ax.set_xlabel(f"Displacement across the bar $δ_{{centre}}$ ({unit})")
    ax.set_ylabel("Force across the bar $F_{centre}$ (N)")
    ax.set_title(f"(b) across the bar, R = {run_ratio:g}", loc="left", fontsize=8)
    ax.legend(loc="upper left", frameon=False, fontsize=6)
    save_figure(fig, path)
