"""The FE's first loading in one direction as a joint: the Masing joint whose virgin curve is
the built-in FE's backbone (:func:`microslip.fe.builtin.fe_backbone`).

It stands here, above both, because the backbone is the FE's (:mod:`microslip.fe`) and the
joint the dynamics' (:mod:`microslip.dynamics`), two layers that do not import each other.
Units: N, mm.
"""

from __future__ import annotations

from ..dynamics.distributions import from_backbone
from ..dynamics.operators import IwanOperator
from ..fe.builtin.backbone import FEBackbone, concave_majorant

__all__ = ["backbone_operator"]


def backbone_operator(backbone: FEBackbone, name: str | None = None) -> IwanOperator:
    """The Iwan operator whose virgin curve is ``backbone``'s concave majorant
    (:func:`~microslip.fe.builtin.backbone.concave_majorant`), extended with its last slope
    to mu F_N; ``name`` defaults to ``fe-<load>``."""
    keep = concave_majorant(backbone.displacement, backbone.force)
    return from_backbone(name or f"fe-{backbone.load}", backbone.displacement[keep],
                         backbone.force[keep], macroslip_force=backbone.macroslip_force)
