"""The energies of a Masing loop from sums along its first loading (Eqs 21-23), compiled.

The low-level half of :mod:`microslip.energy`: :func:`masing_energies` is inlined by every
batch kernel (:mod:`.batch_kernels`) per case and called once by
:func:`microslip.energy.damping_from_backbone`, so both give the same W_d, U and eta bit for
bit. It lives here, under the models, so that the kernels need nothing from the layer above
them (``energy`` imports the models to compute :func:`microslip.damping`).
"""

from __future__ import annotations

import math

from ._jit import jit

__all__ = ["backbone_sums", "masing_energies"]


@jit(inline="always")
def masing_energies(f0, d0, q, q_k0, d_km1, d_k0, fr_km1, fr_k0, stored, kind):
    """W_d, U and eta of the Masing loop of one backbone from sums along the first loading.

    Parameters
    ----------
    f0, d0 : float
        Peak force (N) and displacement (mm) of the backbone F_k = f0 k/n, d_k (k = 0..n).
    q, q_k0 : float
        Q = sum_(k=1..n) (F_(k-1) + F_k)(d_k - d_(k-1)) = 2 trapz(F, d), N·mm, and the same
        sum up to k0 = ceil(n/2).
    d_km1, d_k0 : float
        d at k0 - 1 and k0, mm; ``fr_km1``, ``fr_k0`` = (k0 - 1)/n and k0/n.
    stored : float
        The model's stored energy at the peak, N·mm (used by kind ``stored``).
    kind : int
        :data:`microslip.energy.STRAIN_ENERGY_CODES` of the definition of U.

    Returns
    -------
    W_d, U, eta

    Notes
    -----
    The Masing loop at the backbone samples (:func:`microslip.hysteresis.masing_loop`) has
    descending branch F = F0 - 2 F_k, d = d0 - 2 d_k and ascending branch
    F = -F0 + 2 F_k, d = -d0 + 2 d_k. Its trapezoidal integrals are:

    - W_d = 4 (Q - F0 d0), the closed integral around the 2n + 1 points (Eq. 21;
      = 4 F0 d0 - 8 trapz(d, F) by summation by parts);
    - U secant = F0 d0 / 2, backbone = Q / 2, stored = the model's elastic energy;
    - U branch (Eq. 22): the ascending branch from its zero crossing (between k0 - 1 and
      k0, linear interpolation) to the peak:
      0.5 F(k0) (d(k0) - d_zero) + 2 (Q_n - Q_k0) - 2 F0 (d0 - d_k0);

    and eta = W_d / (2 pi U) (Eq. 23).
    """
    w = 4.0 * (q - f0 * d0)
    if kind == 0:
        u = 0.5 * f0 * d0
    elif kind == 1:
        u = 0.5 * q
    elif kind == 2:
        fa1 = -f0 + 2.0 * (f0 * fr_k0)
        fa0 = -f0 + 2.0 * (f0 * fr_km1)
        da1 = -d0 + 2.0 * d_k0
        da0 = -d0 + 2.0 * d_km1
        s = -fa0 / (fa1 - fa0)
        d_zero = da0 + s * (da1 - da0)
        u = 0.5 * fa1 * (da1 - d_zero) + 2.0 * (q - q_k0) - 2.0 * f0 * (d0 - d_k0)
    else:
        u = stored
    return w, u, w / (2.0 * math.pi * u)


@jit()
def backbone_sums(force, displacement):
    """(Q, Q_k0, d_(k0-1), d_k0, k0) of :func:`masing_energies` for a sampled backbone,
    accumulated in the order of the batch kernels."""
    n = force.shape[0] - 1
    k0 = (n + 1) // 2
    q = 0.0
    q_k0 = 0.0
    for k in range(1, n + 1):
        q += (force[k - 1] + force[k]) * (displacement[k] - displacement[k - 1])
        if k == k0:
            q_k0 = q
    return q, q_k0, displacement[max(k0 - 1, 0)], displacement[k0], k0
