"""The joint inside a vibrating structure: hysteresis operators, describing function,
harmonic balance.

Units: mass kg, frequency Hz, force N, displacement mm, stiffness N/mm.
"""

from __future__ import annotations

from .. import _kernelcache  # noqa: F401  (before any kernel: the folder-stamped cache)
from .describing import DescribingFunction, amplitude_for_force, describing_function
from .distributions import clamp_joint, from_backbone, iwan4, iwan4_segalman
from .operators import HystereticOperator, IwanHistory, IwanOperator, jenkins

__all__ = [
    "DescribingFunction",
    "HystereticOperator",
    "IwanHistory",
    "IwanOperator",
    "amplitude_for_force",
    "clamp_joint",
    "describing_function",
    "from_backbone",
    "iwan4",
    "iwan4_segalman",
    "jenkins",
]
