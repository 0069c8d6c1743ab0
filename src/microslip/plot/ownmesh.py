"""The loops of a run on the user's own mesh (``microslip fe --mesh FILE --plot``): each
load's force against its work-conjugate displacement over the settled cycle, one panel per
load. Units: N, mm (or um for small loops)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .core import COLOURS, displacement_scale, new_figure, save_figure

__all__ = ["plot_mesh_loops", "plot_qsma"]


def plot_mesh_loops(loops: Sequence[tuple[str, Any, Any]], works: Sequence[float],
                    path: str | os.PathLike[str], title: str = "") -> None:
    """``loops``: (set name, force N, displacement mm) per load; ``works``: each load's work
    over the cycle, N·mm (in the legend)."""
    fig, axes = new_figure(ncols=len(loops), width_mm=75.0)
    for k, ((name, force, disp), work) in enumerate(zip(loops, works, strict=True)):
        ax = axes[0][k]
        scale, unit = displacement_scale(float(np.max(np.abs(disp))) or 1.0)
        ax.plot(np.asarray(disp) * scale, force, color=COLOURS[k % len(COLOURS)],
                label=f"load on {name}: W = {work:.4g} N·mm")
        ax.set_xlabel(f"work-conjugate displacement of {name} ({unit})")
        ax.set_ylabel("load F (N)")
        ax.legend(loc="upper left", fontsize="small")
    if title:
        fig.suptitle(title)
    save_figure(fig, path)


def plot_qsma(curve: Mapping[str, Any], path: str | os.PathLike[str]) -> None:
    """Frequency (first harmonic and secant) and damping ratio against the response set's
    amplitude, from ``modal --mesh``'s JSON object ``curve``."""
    fig, axes = new_figure(ncols=2, width_mm=80.0)
    a = np.asarray(curve["amplitude_mm"], dtype=float)
    ax = axes[0][0]
    ax.semilogx(a, curve["frequency_Hz"], color=COLOURS[0], marker=".",
                label="first harmonic (as EPMC)")
    ax.semilogx(a, curve["secant_frequency_Hz"], color=COLOURS[1], marker=".",
                linestyle="--", label="secant (Lacayo and Allen)")
    ax.set_xlabel("amplitude of the response set (mm)")
    ax.set_ylabel("natural frequency f (Hz)")
    ax.legend(fontsize="small")
    ax = axes[0][1]
    ax.semilogx(a, curve["damping_ratio"], color=COLOURS[0], marker=".")
    ax.set_xlabel("amplitude of the response set (mm)")
    ax.set_ylabel("damping ratio zeta (-)")
    fig.suptitle(f"mode {curve['mode']} ({curve['label']}), full-FE quasi-static modal "
                 "analysis")
    save_figure(fig, path)
