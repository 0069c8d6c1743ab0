"""The two-mode study's figure (:mod:`microslip.meshdynamics.twomode`): the frequency response
of the post's top along x and y with circular and decoupled joints, and the interface's
orbit at the checked points. Units: Hz, mm (or um), N."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from .core import COLOURS, displacement_scale, new_figure, save_figure

__all__ = ["plot_two_mode"]

#: Line style of each coupling.
STYLES = {"circular": "-", "decoupled": "--"}


def _ellipse(z: Any, samples: int = 121) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 2.0 * np.pi, samples)
    e = np.exp(1j * t)
    return (np.real(complex(z[0]) * e), np.real(complex(z[1]) * e))


def plot_two_mode(curves: Sequence[Any], path: str | os.PathLike[str],
                  points: Sequence[tuple[str, int]] = (), orbit_force: float | None = None,
                  title: str = "") -> None:
    """Left: the top's first-harmonic amplitude per unit force (mm/N) along x and y against
    frequency, each force one colour, circular solid and decoupled dashed. Right: the
    interface orbit (the contact's mean tangential displacement over one period) of the
    curves of ``orbit_force`` (N; default the largest) at ``points`` (label, point index of
    its circular curve; the decoupled curve's point of nearest frequency)."""
    fig, axes = new_figure(ncols=2, width_mm=85.0)
    ax = axes[0][0]
    forces = sorted({c.force for c in curves})
    for c in curves:
        colour = COLOURS[forces.index(c.force) % len(COLOURS)]
        style = STYLES.get(c.coupling, ":")
        ax.semilogy(c.frequency_Hz, c.top_x_mm / c.force, color=colour, linestyle=style,
                    label=f"{c.force:g} N, {c.coupling}")
        ax.semilogy(c.frequency_Hz, c.top_y_mm / c.force, color=colour, linestyle=style,
                    alpha=0.5)
    ax.set_xlabel("forcing frequency (Hz)")
    ax.set_ylabel("top amplitude / force (mm/N)")
    ax.set_title("top's x (dark) and y (light) first harmonic")
    ax.legend(fontsize="x-small")
    ax = axes[0][1]
    chosen = forces[-1] if orbit_force is None else orbit_force
    top = [c for c in curves if c.force == chosen]
    largest = max(float(np.max(np.abs(c.interface_mm))) for c in top) if top else 1.0
    scale, unit = displacement_scale(largest)
    for k, (label, index) in enumerate(points):
        colour = COLOURS[k % len(COLOURS)]
        for c in top:
            i = index
            if c.coupling != "circular":
                ref = next(d for d in top if d.coupling == "circular")
                i = int(np.argmin(np.abs(c.frequency_Hz - ref.frequency_Hz[index])))
            x, y = _ellipse(c.interface_mm[i])
            ax.plot(x * scale, y * scale, color=colour, linestyle=STYLES.get(c.coupling, ":"),
                    label=f"{label} ({c.frequency_Hz[i]:.0f} Hz), {c.coupling}")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"interface x ({unit})")
    ax.set_ylabel(f"interface y ({unit})")
    ax.legend(fontsize="x-small", loc="lower right")
    ax.set_title(f"interface orbits at {chosen:g} N" if top else "")
    if title:
        fig.suptitle(title)
    save_figure(fig, path)
