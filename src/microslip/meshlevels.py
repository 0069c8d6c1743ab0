"""Mesh levels shared by both FE solvers: element counts and node planes from the geometry.

A level names a resolution of the clamped zone, the same for the built-in solver (8-node
C3D8I-like hexahedra, :func:`microslip.fe.examples.box_hexmesh`) and for CalculiX (20-node C3D20R,
:mod:`microslip.fe.calculix.mesh`): :func:`level_counts` gives the element counts (nx, ny, nz) along
the length, width and thickness, :func:`level_axes` the node planes (corner nodes) along each
axis. "The same mesh" therefore means the same elements on the same planes in both solvers;
the quadratic elements of CalculiX have more nodes and degrees of freedom on it.

``coarse``, ``medium`` and ``fine`` are accuracy levels (:data:`MESH_LEVELS`): ``across``
elements over the width set the size h = w / across; the length gets
max(``min_along``, ceil(L / (aspect h))) elements (made even: a node plane at L/2 carries the
centre load), the thickness ceil(t / h) layers on a slender bar and ceil(2 t / h) on a squat
one (at most ``max_layers``: the banded factorisation costs the square of the layers).
``tiny`` and ``paper`` are fixed counts (:data:`FIXED_COUNTS`); ``"NXxNYxNZ"`` (e.g.
``"24x4x1"``) gives counts explicitly.

On a squat body (L < :data:`SQUAT_RATIO` t) the accuracy levels and explicit counts are
graded (``tiny`` and ``paper`` stay uniform, fixed meshes): the stress at the edge where the loaded
section meets the interface is singular, and uniform refinement converges there only at
order 1.3 (docs/solver.md, 8.4). Node planes crowd towards the loaded sections by the power
law of exponent :data:`GRADING`: in z towards the interface z = 0, in x towards x = L (tip
load and clamp edge) on the half L/2 .. L and towards x = L/2 (centre load) on the half
0 .. L/2; y stays uniform (the load is uniform across the width). A slender bar (the paper's
Table 1 bar, L/t = 80) keeps uniform meshes: its loop is set by the long slip zone, not by
the edge, and every Table 1 number is unchanged.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .errors import ParameterError
from .params import ClampParams

__all__ = [
    "FIXED_COUNTS",
    "GRADING",
    "LEVELS",
    "MESH_LEVELS",
    "SQUAT_RATIO",
    "MeshLevel",
    "is_graded",
    "is_mesh_spec",
    "is_squat",
    "level_axes",
    "level_counts",
    "mesh_counts",
    "parse_counts",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class MeshLevel:
    """An accuracy level: element sizes from the geometry of the clamped zone (see the module
    docstring for the rule)."""

    across: int
    aspect: float
    min_along: int
    max_layers: int

    def counts(self, length: float, width: float, thickness: float) -> tuple[int, int, int]:
        h = width / self.across
        per_h = 2.0 if is_squat(length, thickness) else 1.0
        nz = min(self.max_layers, max(1, math.ceil(per_h * thickness / h - 1e-9)))
        nx = max(self.min_along, math.ceil(length / (self.aspect * h) - 1e-9))
        return nx + nx % 2, self.across, nz


#: Accuracy levels (element aspect dx / dy as on the Table 1 bar). On the Table 1 bar they
#: give 24x4x1, 48x4x1 and 96x8x2; the built-in solver's Table 1 tip loop is converged to
#: 0.15 % on ``coarse`` and its centre loops to about 1 % on ``medium`` (docs/solver.md).
MESH_LEVELS: dict[str, MeshLevel] = {
    "coarse": MeshLevel(4, 5.0 / 3.0, 24, 4),
    "medium": MeshLevel(4, 5.0 / 6.0, 48, 6),
    "fine": MeshLevel(8, 5.0 / 6.0, 96, 8),
}

#: Fixed counts on any body: ``tiny`` for quick tests; ``paper``, 96x4x1, is the size of the
#: paper's ANSYS model (about 10 500 DOF of 20-node bricks; CalculiX C3D20R: 9 090 DOF).
FIXED_COUNTS: dict[str, tuple[int, int, int]] = {
    "tiny": (8, 2, 1),
    "paper": (96, 4, 1),
}

#: Every level name, in increasing resolution on the Table 1 bar.
LEVELS: tuple[str, ...] = ("tiny", "coarse", "medium", "fine", "paper")

#: A body with L < SQUAT_RATIO t is graded (the Table 1 bar has L/t = 80; at thickness
#: 25.4 mm, 10).
SQUAT_RATIO = 20.0
#: Exponent p of the power-law grading: n elements over a half (or the thickness) have node
#: planes at 1 - (1 - s)^p, s = 0, 1/n, ..., 1 (:func:`level_axes`); the element at the loaded
#: edge is about p/n of the half, 1/n^2 of the thickness at the interface.
GRADING = 2.0

_COUNTS = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*[xX]\s*(\d+)\s*$")


def is_squat(length: float, thickness: float) -> bool:
    """True for a squat body, L < :data:`SQUAT_RATIO` t."""
    return length < SQUAT_RATIO * thickness


def is_graded(params: ClampParams, level: str) -> bool:
    """Whether a level's mesh of this clamped zone is graded: the accuracy levels and
    ``NXxNYxNZ`` on a squat body; the fixed meshes ``tiny`` and ``paper`` stay uniform."""
    return level not in FIXED_COUNTS and is_squat(params.length, params.thickness)


def parse_counts(text: str) -> tuple[int, int, int] | None:
    """``"NXxNYxNZ"`` as counts, None if ``text`` is not of that form.

    >>> parse_counts("24x4x1"), parse_counts("coarse")
    ((24, 4, 1), None)
    """
    m = _COUNTS.match(text)
    return None if m is None else (int(m[1]), int(m[2]), int(m[3]))


def is_mesh_spec(text: str) -> bool:
    """Whether ``text`` names a mesh: a level of :data:`LEVELS` or ``NXxNYxNZ``.

    >>> is_mesh_spec("medium"), is_mesh_spec("8x2x1"), is_mesh_spec("fine-ish")
    (True, True, False)
    """
    return text in LEVELS or parse_counts(text) is not None


def level_counts(params: ClampParams, level: str) -> tuple[int, int, int]:
    """Element counts (nx, ny, nz) of a level for this clamped zone, the same for both solvers.

    >>> from microslip import preset
    >>> level_counts(preset("table1"), "fine"), level_counts(preset("table2-tip"), "coarse")
    ((96, 8, 2), (24, 4, 4))
    """
    if level in MESH_LEVELS:
        return MESH_LEVELS[level].counts(params.length, params.width, params.thickness)
    if level in FIXED_COUNTS:
        return FIXED_COUNTS[level]
    counts = parse_counts(level) if isinstance(level, str) else None
    if counts is None:
        raise ParameterError(
            f"unknown mesh {level!r}; choose one of {', '.join(LEVELS)} or NXxNYxNZ")
    return counts


def mesh_counts(params: ClampParams, spec: Any) -> tuple[tuple[int, int, int], bool]:
    """The one reading of a mesh spec for both solvers: ((nx, ny, nz), graded) of a level or
    ``"NXxNYxNZ"`` (counts and grading from the clamped zone ``params``) or of counts
    ``(nx, ny, nz)`` (uniform); each count a whole number >= 1.

    >>> from microslip import preset
    >>> mesh_counts(preset("table1"), "coarse"), mesh_counts(preset("table1"), (8, 2, 1))
    (((24, 4, 1), False), ((8, 2, 1), False))
    """
    if isinstance(spec, str):
        counts, graded = level_counts(params, spec), is_graded(params, spec)
    else:
        try:
            counts = tuple(spec)
        except TypeError:
            raise ParameterError(
                f"mesh must be a level ({', '.join(LEVELS)}), NXxNYxNZ or (nx, ny, nz), "
                f"got {spec!r}") from None
        if len(counts) != 3:
            raise ParameterError(f"mesh must be (nx, ny, nz), got {spec!r}")
        graded = False
    for name, n in zip(("nx", "ny", "nz"), counts, strict=True):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ParameterError(f"{name} must be an integer >= 1, got {n!r}")
    nx, ny, nz = (int(n) for n in counts)
    return (nx, ny, nz), graded


def _power(n: int, start: float, end: float, p: float) -> FloatArray:
    """n elements on start .. end, crowding towards ``end`` (p > 1) by the power law."""
    s = np.linspace(0.0, 1.0, n + 1)
    return np.asarray(start + (end - start) * (1.0 - (1.0 - s) ** p), dtype=float)


def level_axes(length: float, width: float, thickness: float, counts: tuple[int, int, int],
               graded: bool) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Node planes (corner nodes) along x, y and z, mm: uniform, or (``graded``) crowding
    towards x = L/2 and x = L (nx even) and towards z = 0 by the power law of :data:`GRADING`.

    >>> x, y, z = level_axes(4.0, 1.0, 1.0, (4, 1, 2), True)
    >>> x.tolist(), z.tolist()
    ([0.0, 1.5, 2.0, 3.5, 4.0], [0.0, 0.25, 1.0])
    """
    nx, ny, nz = counts
    y = np.linspace(0.0, width, ny + 1)
    if not graded:
        return np.linspace(0.0, length, nx + 1), y, np.linspace(0.0, thickness, nz + 1)
    if nx % 2:
        raise ParameterError(f"a graded mesh needs an even nx (node plane at L/2), got {nx}")
    half = nx // 2
    x = np.concatenate([_power(half, 0.0, 0.5 * length, GRADING)[:-1],
                        _power(half, 0.5 * length, length, GRADING)])
    z = thickness * np.linspace(0.0, 1.0, nz + 1) ** GRADING
    x[-1], z[-1] = length, thickness
    return x, y, z
