"""The stuck linear frequencies of a clamped mesh under refinement: the given mesh and its
refinements x2 (:func:`microslip.fe.refine.refine_mesh`), each clamped again, with Richardson's
estimate of the converged frequencies (:func:`microslip.fe.convergence.converge_frequencies`).
``modal --mesh FILE --convergence``. Units: Hz, kg/m^3.
"""

from __future__ import annotations

from typing import Any

from ..fe.convergence import FrequencyConvergence, converge_frequencies
from ..fe.hexmesh import HexMesh

__all__ = ["converge_stuck_frequencies"]


def converge_stuck_frequencies(model: Any, density_kg_m3: float, count: int,
                               levels: int = 2) -> FrequencyConvergence:
    """The lowest ``count`` stuck linear frequencies (Hz) of a clamped mesh model
    (:class:`~microslip.fe.builtin.meshmodel.MeshModel`) on its mesh and ``levels`` - 1
    refinements x2, each clamped again with the model's own sets, material and contact."""
    from ..fe.builtin.meshmodel import build_mesh_model
    from .modes import linear_modes

    def frequencies(mesh: HexMesh) -> tuple[int, Any]:
        m = model if mesh is model.mesh else build_mesh_model(mesh, model.assembly,
                                                              element=model.element)
        return m.dof, linear_modes(m, density_kg_m3, count, "stuck").frequencies_Hz

    return converge_frequencies(model.mesh, frequencies, levels)
