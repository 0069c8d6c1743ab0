"""The structure on the user's own mesh: its linear modes, the full FE's quasi-static modal
analysis, the contact-node reduced model, the whole joint, the interface's first loading, the
two-mode study and their verdicts; the layer above the frictional FE (:mod:`microslip.fe`)
and the structural dynamics (:mod:`microslip.dynamics`), which do not import each other.

Units: mm, N, MPa, kg/m^3, Hz.
"""

from __future__ import annotations
