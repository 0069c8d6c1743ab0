"""The joint inside a vibrating structure: hysteresis operators, describing function,
harmonic balance.

Units: mass kg, frequency Hz, force N, displacement mm, stiffness N/mm.
"""

from __future__ import annotations

from .operators import HystereticOperator, IwanHistory, IwanOperator, jenkins

__all__ = ["HystereticOperator", "IwanHistory", "IwanOperator", "jenkins"]
