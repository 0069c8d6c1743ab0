"""The columns of a recorded first loading, allocated once for every model's backbone.

:func:`backbone_columns` is the set-up shared by :func:`~microslip.models.tip.tip_backbone`,
:func:`~microslip.models.centre.centre_backbone` and the two layer backbones of
:mod:`~microslip.models.layered`: the arrays of a :class:`~microslip.results.Backbone` at
rest, filled increment by increment by the caller.
"""

from __future__ import annotations

import numpy as np

from ._jit import jit

__all__ = ["backbone_columns"]


@jit(inline="always")
def backbone_columns(n, domains, width, thickness, stored):
    """``force, displacement, stored`` of shape (n + 1,) and ``slip, width, thickness`` of
    shape (n + 1, domains) for n increments: zeros, the stored energy column filled with
    ``stored`` (0, or NaN where it is not defined), and row 0 of width and thickness the
    unloaded ``width`` and ``thickness`` (mm)."""
    w = np.empty((n + 1, domains))
    t = np.empty((n + 1, domains))
    w[0, :] = width
    t[0, :] = thickness
    return (np.zeros(n + 1), np.zeros(n + 1), np.full(n + 1, stored),
            np.zeros((n + 1, domains)), w, t)
