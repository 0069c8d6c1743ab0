"""The contact law of a friction node, written once: a penalty stick spring in series with a
Coulomb slider whose limit is a circle, integrated by the radial return.

Every element with this law calls :func:`circular_coulomb`: the built-in FE's Newton steps
(:func:`microslip.fe.builtin.contact.return_map`, vectorised over the contact nodes), the
2-D Jenkins elements of the harmonic-balance joints (:mod:`microslip.dynamics.kernels2d`)
and the 3-D contact element with a normal penalty (:mod:`microslip.dynamics.operators3d`),
the last two compiled by numba around it. Those modules add the element's shape (a node on
a rigid base, a 2-D element with an anisotropic spring, a limit that follows the normal
force) and nothing of the law. A second law is a second entry of :data:`CONTACT_LAWS` with
the same signature; the callers look the law up there.

This module imports neither numba nor anything of microslip: the law is plain Python whose
arithmetic (``+ - * /``, comparisons, :func:`numpy.hypot`) runs element by element on numpy
arrays and, compiled by the callers, on scalars. It is written without branches (a
condition c enters as ``c * 1.0``, a select as ``a c + b (1 - c)``, exact for c in {0, 1})
so that one text serves both.

Notes
-----
Node with tangential displacement g (mm), accumulated slip s (mm), stick stiffness k (N/mm)
and friction limit L = mu N (N)::

    t = k (g - s)                                  trial force
    stick  (|t| <= L):  f = t,            s' = s,            df/dg = k I
    slip   (|t| >  L):  f = L t / |t|,    s' = g - f / k,    df/dg = k (L/|t|) (I - n n^T)

with n = t / |t|: the closest-point projection of the trial force onto the circle (backward
Euler, Simo & Hughes 1998 Ch. 2; Wriggers 2006 Ch. 5). The slip tangent is symmetric and
positive semi-definite, its null direction n; in slip ``df/dL = n``. Units: N, mm, N/mm.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import ParameterError

__all__ = ["CONTACT_LAWS", "ContactLaw", "circular_coulomb", "get_contact_law"]


def circular_coulomb(gx: Any, gy: Any, sx: Any, sy: Any, k: Any, limit: Any) -> tuple[Any, ...]:
    """The circular Coulomb law with a penalty stick at one node or at every node.

    Parameters
    ----------
    gx, gy : float or ndarray
        Tangential displacement g, mm.
    sx, sy : float or ndarray
        Slip s at the end of the last step, mm.
    k : float or ndarray
        Stick stiffness, N/mm (> 0).
    limit : float or ndarray
        Friction limit mu N, N (>= 0).

    Returns
    -------
    tuple
        ``(fx, fy, sx_new, sy_new, t_xx, t_xy, t_yy, nx, ny, slipping)``: the friction
        force f on the base (N), the new slip (mm), the consistent tangent df/dg (N/mm,
        symmetric), the trial force's direction n (0 where the trial force is 0) and 1.0
        where the node slips, else 0.0 (``df/dlimit = slipping * n``). Arrays where the
        arguments are.

    Examples
    --------
    >>> r = circular_coulomb(3.0, 4.0, 0.0, 0.0, 1.0, 1.0)
    >>> [round(float(v), 12) for v in r]
    [0.6, 0.8, 2.4, 3.2, 0.128, -0.096, 0.072, 0.6, 0.8, 1.0]
    >>> [float(v) for v in circular_coulomb(0.5, 0.0, 0.0, 0.0, 1.0, 1.0)[:4]]  # stick
    [0.5, 0.0, 0.0, 0.0]
    """
    tx = k * (gx - sx)
    ty = k * (gy - sy)
    size = np.hypot(tx, ty)
    sl = (size > limit) * 1.0
    # limit / size in slip, 1 in stick (also for limit = inf: no inf * 0 anywhere)
    scale = (np.minimum(limit, size) * sl + (1.0 - sl)) / (size * sl + (1.0 - sl))
    fx = tx * scale
    fy = ty * scale
    pos = (size > 0.0) * 1.0
    norm = size * pos + (1.0 - pos)
    nx = tx / norm
    ny = ty / norm
    ks = k * scale
    return (fx, fy, (gx - fx / k) * sl + sx * (1.0 - sl), (gy - fy / k) * sl + sy * (1.0 - sl),
            ks * (1.0 - sl * nx * nx), -ks * sl * nx * ny, ks * (1.0 - sl * ny * ny),
            nx, ny, sl)


@dataclass(frozen=True)
class ContactLaw:
    """A contact law of a friction node (an entry of :data:`CONTACT_LAWS`).

    Attributes
    ----------
    name : str
        Its key.
    label : str
        One line for headers and docs.
    return_map : callable
        ``(gx, gy, sx, sy, k, limit) -> (fx, fy, sx_new, sy_new, t_xx, t_xy, t_yy, nx, ny,
        slipping)`` as :func:`circular_coulomb`: plain Python, element by element on arrays
        and numba-compilable on scalars.
    """

    name: str
    label: str
    return_map: Callable[..., tuple[Any, ...]]


#: The contact laws by name. A second law is one more entry (its return map with the
#: signature of :func:`circular_coulomb`), not an edit of the elements that use it.
CONTACT_LAWS: dict[str, ContactLaw] = {
    "coulomb": ContactLaw("coulomb", "penalty stick, circular Coulomb limit, radial return",
                          circular_coulomb),
}


def get_contact_law(name: str) -> ContactLaw:
    """The law named ``name``; an unknown name fails listing the known ones.

    >>> get_contact_law("coulomb").name
    'coulomb'
    """
    try:
        return CONTACT_LAWS[name]
    except KeyError:
        raise ParameterError(f"unknown contact law {name!r}; choose one of "
                             f"{', '.join(CONTACT_LAWS)}") from None
