"""The operators of a joint specification: what the dynamics builds from a
:class:`~microslip.jointspec.JointSpec` of the command line or of a case file.

:func:`joint_operator` is the joint's 1-D operator (along its first direction); a
two-directional joint is built from it by its coupling
(:data:`microslip.dynamics.operators2d.COUPLINGS`), with the joint across of
:func:`transverse_operator` (:data:`TRANSVERSE`) where the spec names one.

Units: N, mm, N/mm, N/mm^3.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache
from typing import TYPE_CHECKING

from ..conventions import CLAMP_MODELS, DEFAULT_MESH
from ..conventions import TRANSVERSE as TRANSVERSE_NAMES
from ..dynamics.distributions import clamp_joint, iwan4_segalman
from ..dynamics.operators import IwanOperator, jenkins
from ..errors import ParameterError
from ..jointspec import JointSpec
from ..params import ClampParams

if TYPE_CHECKING:
    from ..options import ModelOptions

__all__ = ["TRANSVERSE", "across_operator", "joint_operator", "transverse_operator"]


def joint_operator(spec: JointSpec, options: ModelOptions | None = None) -> IwanOperator:
    """The 1-D joint operator of a joint table (a two-directional joint is built from it by
    its coupling, :data:`microslip.dynamics.operators2d.COUPLINGS`)."""
    v = spec.values
    elements = spec.elements
    if spec.model == "jenkins":
        return jenkins(v["stiffness"], v["slip_force"])
    if spec.model == "iwan":
        return iwan4_segalman(v["stiffness"], v["slip_force"], v["chi"], v["beta"], elements)
    assert spec.clamp is not None and spec.series_stiffness is not None
    return clamp_joint(spec.model, spec.clamp, spec.series_stiffness, elements=elements,
                       options=options)


#: A joint across: (clamp, series spring N/mm, elements, model options, stick slope N/mm^3
#: or None, FE mesh) -> its 1-D operator.
Across = Callable[[ClampParams, float, int, "ModelOptions | None", "float | None", str],
                  IwanOperator]


def _clamp_model(model: str) -> Across:
    def build(clamp: ClampParams, series: float, elements: int,
              options: ModelOptions | None, stick_slope: float | None, fe_mesh: str
              ) -> IwanOperator:
        return clamp_joint(model, clamp, series, elements=elements, options=options)
    return build


def _fe(clamp: ClampParams, series: float, elements: int, options: ModelOptions | None,
        stick_slope: float | None, fe_mesh: str) -> IwanOperator:
    if stick_slope is None:
        raise ParameterError("the FE joint across needs the contact stick slope (N/mm^3), not "
                             "a series stiffness")
    return _fe_across(clamp, fe_mesh, stick_slope)


@lru_cache(maxsize=8)
def _fe_across(clamp: ClampParams, mesh: str, stick_slope: float) -> IwanOperator:
    """The FE's first loading of the centre force across the bar as a 1-D joint (cached:
    an FE run, the same for the structure and its description)."""
    from ..fe.builtin import fe_backbone
    from .febackbone import backbone_operator

    return backbone_operator(fe_backbone(clamp, "centre", mesh=mesh, stick_slope=stick_slope))


#: Transverse name (:data:`microslip.conventions.TRANSVERSE`) -> the 1-D joint across a bar:
#: ``tip``, ``centre`` the clamp's 1-D model
#: behind the same series spring; ``fe`` the built-in FE's first loading of the centre force
#: across the bar (:func:`microslip.fe.builtin.fe_backbone`, its contact compliance inside).
TRANSVERSE: dict[str, Across] = dict(zip(
    TRANSVERSE_NAMES, (*(_clamp_model(m) for m in CLAMP_MODELS), _fe), strict=True))


def across_operator(transverse: str, clamp: ClampParams, series: float, *, elements: int,
                    options: ModelOptions | None = None, stick_slope: float | None = None,
                    fe_mesh: str | None = None) -> IwanOperator:
    """The 1-D joint across (:data:`TRANSVERSE`) of a clamp with the series spring
    ``series`` (N/mm) from the contact stick slope ``stick_slope`` (N/mm^3)."""
    return TRANSVERSE[transverse](clamp, series, elements, options, stick_slope,
                                  DEFAULT_MESH if fe_mesh is None else fe_mesh)


def transverse_operator(spec: JointSpec, options: ModelOptions | None = None
                        ) -> IwanOperator | None:
    """The 1-D joint across a joint table (its second direction), None without
    ``transverse``."""
    if spec.transverse is None:
        return None
    assert spec.clamp is not None and spec.series_stiffness is not None
    return across_operator(spec.transverse, spec.clamp, spec.series_stiffness,
                           elements=spec.elements,
                           options=options, stick_slope=spec.stick_slope,
                           fe_mesh=spec.fe_mesh)
