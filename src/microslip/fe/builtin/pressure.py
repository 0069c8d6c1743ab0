"""The interface pressure of the built-in solver's clamping step as a 1-D pressure law.

A convenience above both :mod:`.box` (which builds and clamps the box, its pressure law the
distribution of its preload) and :mod:`.clamping` (which reads the normal forces back as a
:class:`~.clamping.ClampingPressure`). Units: N, mm, MPa.
"""

from __future__ import annotations

from typing import Any

from ...conventions import DEFAULT_MESH
from ...models.interface import PressureLaw
from ...params import ClampParams
from .box import box_model
from .clamping import clamping_pressure

__all__ = ["fe_pressure_law"]


def fe_pressure_law(params: ClampParams, mesh: Any = DEFAULT_MESH, **model_options: Any
                    ) -> PressureLaw:
    """The interface pressure of the built-in solver's clamping step as a 1-D pressure law, in
    one call: :func:`~microslip.fe.builtin.box.box_model` (``model_options``: ``stick_slope``,
    ``pressure_law`` of the top face, ``element``, ...) then :meth:`ClampingPressure.law`.

    >>> from microslip import preset
    >>> import numpy as np
    >>> law = fe_pressure_law(preset("table1"), (8, 2, 1))
    >>> round(float(law.cumulative(np.array([1.0]))[0]), 12)
    1.0
    """
    return clamping_pressure(box_model(params, mesh, **model_options), params.width).law()
