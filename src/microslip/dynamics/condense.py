"""Harmonic balance condensed onto the joints' coordinates: Newton on the joints' harmonics
only, the linear structure solved once per frequency.

With ``u = B^T x`` the joints' displacement harmonics (B stacks every joint's participation,
:mod:`.hb` layout per joint), the balance ``D(w) x + B F(u) = P`` of :class:`~.hb.HarmonicBalance`
is, wherever the structure's dynamic stiffness D(w) is invertible,

    R(u, w) = u - B^T D^-1 P + G(w) F(u) = 0,     G(w) = B^T D(w)^-1 B   (mm),

and ``x = D^-1 (P - B F(u))``. D is block-diagonal over the harmonics: for k >= 1 the complex
``Z_k = K - k^2 w^2 M + i k w C`` acting on ``c_k - i s_k``, for k = 0 the stiffness K; so
G is one small complex matrix per harmonic (joint coordinates x joint coordinates) and
``dG/dw = -(Z^-1 B)^T Z' (Z^-1 B)`` for symmetric matrices. With M positive definite and
C diagonal in the undamped modes Phi (``Phi^T M Phi = I``, ``Phi^T K Phi = diag(w_j^2)``,
proportional damping) ``Z_k^-1 = Phi diag(1 / (w_j^2 - k^2 w^2 + i k w c_j)) Phi^T``
exactly, and G, its derivative and the forced response are modal sums (no solve per
frequency); otherwise Z_k is solved per harmonic. Used when the joints have fewer
coordinates than the structure has DOFs and D(w) is invertible for every w > 0 (K and C
symmetric positive definite); the joint forces are the same ``joint_harmonics`` calls.

Units: coefficients mm, forces N, SI matrices times 1e-3, frequency rad/s.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from .hb import HarmonicBalance
from .structure import SI_PER_MM

__all__ = ["Condensed", "condensable"]

Array = NDArray[np.float64]

#: Largest modal coupling ``|Phi^T C Phi|`` off the diagonal, relative to the largest modal
#: damping, for the damping to count as proportional (rounding of exactly proportional C).
PROPORTIONAL = 1e-12


def _definite(a: Array) -> bool:
    if not np.allclose(a, a.T, rtol=1e-12, atol=0.0):
        return False
    try:
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return False
    return True


def condensable(hb: HarmonicBalance) -> bool:
    """Whether :class:`Condensed` applies and is smaller: fewer joint coordinates than DOFs,
    M symmetric, K and C symmetric positive definite (D(w) invertible for all w > 0)."""
    s = hb.structure
    coords = sum(link.directions for link in s.joints)
    return (coords < s.dofs and np.allclose(s.mass, s.mass.T, rtol=1e-12, atol=0.0)
            and _definite(s.stiffness) and _definite(s.damping))


class Condensed:
    """The condensed balance R(u, w) of one excitation ``load`` (N, :mod:`.hb` layout)."""

    def __init__(self, hb: HarmonicBalance, load: Array) -> None:
        s = hb.structure
        self.hb = hb
        h = 2 * hb.harmonics + 1
        self._b = np.column_stack([link.weights for link in s.joints])  # (n, nb)
        nb = self._b.shape[1]
        self.size = nb * h
        self._k = s.stiffness * SI_PER_MM
        self._m = s.mass * SI_PER_MM
        self._c = s.damping * SI_PER_MM
        order = np.arange(1, hb.harmonics + 1, dtype=np.float64)
        self._order = order[:, None, None]
        p = np.asarray(load, dtype=np.float64).reshape(s.dofs, h)
        self._p = (p[:, 1::2] - 1j * p[:, 2::2]).T[:, :, None]  # (H, n, 1)
        self._rhs = np.concatenate([np.broadcast_to(self._b, (hb.harmonics, *self._b.shape)),
                                    self._p], axis=2)
        static = np.linalg.solve(self._k, np.column_stack([self._b, p[:, 0]]))
        self._static = static  # K^-1 [B | P_0], k = 0
        self._g0 = self._b.T @ static[:, :nb]
        self._u0 = self._b.T @ static[:, nb]
        # where harmonic k's (nb, nb) blocks go in the (size, size) matrices: u layout is
        # coordinate-major, [c_0, c_1, s_1, ...] per coordinate
        start = np.arange(nb) * h
        cos = start[None, :] + 2 * np.arange(1, hb.harmonics + 1)[:, None] - 1  # (H, nb)
        sin = cos + 1
        rows = np.stack([cos, cos, sin, sin], axis=1)[:, :, :, None]  # (H, 4, nb, 1)
        cols = np.stack([cos, sin, cos, sin], axis=1)[:, :, None, :]  # (H, 4, 1, nb)
        rows, cols = np.broadcast_arrays(rows, cols)
        self._flat = np.ravel_multi_index((rows, cols), (self.size, self.size)).ravel()
        self._template = np.zeros((self.size, self.size))  # the static block in place
        self._template[np.ix_(start, start)] = self._g0
        self._diagonal = (np.arange(self.size), np.arange(self.size))
        self._cos, self._sin, self._start = cos, sin, start
        self._modal = _modes(self._k, self._m, self._c)
        if self._modal is not None:
            phi = self._modal[1]
            bphi = self._b.T @ phi  # (nb, n)
            self._bphi = bphi.astype(np.complex128)
            bb = (bphi[:, None, :] * bphi[None, :, :]).reshape(nb * nb, -1).T  # (n, nb nb)
            # the per-harmonic values of _blocks, [Re G, Im G, -Im G, Re G], as the real map
            # of a complex (H, n) array viewed as (H, 2n) reals (re, im interleaved)
            e = np.zeros((bb.shape[0], 2, 4, nb * nb))
            e[:, 0, 0] = e[:, 0, 3] = e[:, 1, 1] = bb
            e[:, 1, 2] = -bb
            self._e = e.reshape(2 * bb.shape[0], 4 * nb * nb)
            self._pphi = (self._p[:, :, 0] @ phi)  # (H, n)
            w2, cj = self._modal[0], self._modal[2]
            self._order2 = order[:, None] ** 2  # (H, 1)
            self._ioc = 1j * order[:, None] * cj  # (H, n): D_k = w2 - k^2 w^2 + i w k c
            # B^T D^-1 P as the real map of D^-1 viewed as reals into _vector's layout
            c = self._pphi[:, :, None] * bphi.T[None, :, :]  # (H, n, nb)
            eu = np.zeros((hb.harmonics, w2.size, 2, self.size))
            for k in range(hb.harmonics):
                eu[k, :, 0, cos[k]] = c[k].real.T
                eu[k, :, 1, cos[k]] = -c[k].imag.T
                eu[k, :, 0, sin[k]] = -c[k].imag.T
                eu[k, :, 1, sin[k]] = -c[k].real.T
            self._eu = eu.reshape(-1, self.size)
            self._u0_vector = np.zeros(self.size)
            self._u0_vector[start] = self._u0
        self._slices = []
        offset = 0
        for link in s.joints:
            width = link.directions * h
            self._slices.append((link.operator, slice(offset, offset + width)))
            offset += width

    def _blocks(self, g: NDArray[np.complex128], static: bool = True) -> Array:
        """The real (size, size) matrix of per-harmonic complex blocks ``g`` (H, nb, nb)
        acting on ``c - i s``, and the static block G_0 (if ``static``, else zero)."""
        values = np.stack([g.real, g.imag, -g.imag, g.real], axis=1)
        return self._place(values, static)

    def _place(self, values: Array, static: bool) -> Array:
        """The real (size, size) matrix of the per-harmonic blocks ``values`` (H, 4 nb nb):
        ``[Re G, Im G, -Im G, Re G]``."""
        out = self._template.copy() if static else np.zeros((self.size, self.size))
        out.flat[self._flat] = values.ravel()
        return out

    def _vector(self, v: NDArray[np.complex128], v0: Array) -> Array:
        """The real (size,) vector of per-harmonic complex values ``v`` (H, nb): c - i s."""
        out = np.empty(self.size)
        out[self._start] = v0
        out[self._cos] = v.real
        out[self._sin] = -v.imag
        return out

    def _solve(self, omega: float) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """Z_k^-1 [B | P_k] (H, n, nb + 1) and Z_k' = dZ_k/dw (H, n, n)."""
        kw = self._order * omega
        z = self._k - kw**2 * self._m + 1j * kw * self._c
        dz = -2.0 * self._order * kw * self._m + 1j * self._order * self._c
        return np.linalg.solve(z, self._rhs), dz

    def _compliance(self, omega: float) -> tuple[Array, Array, Array, Array]:
        """The real (size, size) matrices of G and dG/dw and the real (size,) vectors of
        B^T D^-1 P and its w-derivative."""
        nb = self._b.shape[1]
        if self._modal is not None:
            d = np.empty((2, *self._ioc.shape), dtype=np.complex128)  # D^-1, its w-derivative
            np.divide(1.0, self._modal[0] + omega * (self._ioc - omega * self._order2),
                      out=d[0])
            np.multiply(-d[0] * d[0], self._ioc - 2.0 * omega * self._order2, out=d[1])
            real = d.view(np.float64)  # (2, H, 2n)
            values = real @ self._e  # (2, H, 4 nb nb)
            up = real.reshape(2, -1) @ self._eu  # (2, size)
            return (self._place(values[0], True), self._place(values[1], False),
                    up[0] + self._u0_vector, up[1])
        sol, dz = self._solve(omega)
        xb, xp = sol[:, :, :nb], sol[:, :, nb:]
        bt = self._b.T
        tb = np.swapaxes(xb, 1, 2)
        return (self._blocks(bt @ xb), self._blocks(-(tb @ dz @ xb), False),
                self._vector((bt @ xp)[:, :, 0], self._u0),
                self._vector(-(tb @ dz @ xp)[:, :, 0], np.zeros(nb)))

    def residual(self, y: Array) -> tuple[Array, Array]:
        """``R(u, w)`` (mm, (size,)) and ``[dR/du | dR/dw]`` ((size, size + 1)) at
        ``y = [u, w]``."""
        u, omega = y[:-1], float(y[-1])
        big_g, big_dg, up, dup = self._compliance(omega)
        force = np.empty(self.size)
        dforce = np.zeros((self.size, self.size))
        for operator, part in self._slices:
            force[part], dforce[part, part] = self.hb.joint_harmonics(operator, u[part])
        r = u - up + big_g @ force
        jac = np.empty((self.size, self.size + 1))
        jac[:, :-1] = big_g @ dforce
        jac[self._diagonal] += 1.0
        jac[:, -1] = big_dg @ force - dup
        return r, jac

    def amplitude(self, y: Array) -> tuple[float, Array]:
        """First-harmonic amplitude (mm) of the output coordinate o . x at ``y = [u, w]``
        and its gradient in y.

        Notes
        -----
        With Z = Z_1 symmetric and v = Z^-1 o: ``q = o . (c_1 - i s_1) = v^T (P_1 - B f_1)``
        (f_1 = F_c1 - i F_s1 the joints' first force harmonic), ``dq/du = -v^T B df_1/du``,
        ``dq/dw = -v^T Z' x_1``; A = |q|, dA = Re(conj(q) dq) / A.
        """
        u, omega = y[:-1], float(y[-1])
        force = np.empty(self.size)
        dforce = np.zeros((self.size, self.size))
        for operator, part in self._slices:
            force[part], dforce[part, part] = self.hb.joint_harmonics(operator, u[part])
        cos, sin = self._cos[0], self._sin[0]
        f1 = force[cos] - 1j * force[sin]
        z = self._k - omega**2 * self._m + 1j * omega * self._c
        dz = -2.0 * omega * self._m + 1j * self._c
        rhs = np.column_stack([self.hb.structure.output, self._p[0, :, 0] - self._b @ f1])
        sol = np.linalg.solve(z, rhs.astype(np.complex128))
        v, x1 = sol[:, 0], sol[:, 1]
        q = complex(v @ rhs[:, 1])
        a = abs(q)
        grad = np.zeros(self.size + 1)
        if a > 0.0:
            dq_du = -(v @ self._b) @ (dforce[cos] - 1j * dforce[sin])
            grad[:-1] = (q.conjugate() * dq_du).real / a
            grad[-1] = (q.conjugate() * -(v @ dz @ x1)).real / a
        return a, grad

    def joints(self, x: Array) -> Array:
        """The joints' harmonics u = B^T x of full coefficients ``x`` (mm)."""
        h = 2 * self.hb.harmonics + 1
        return np.asarray((self._b.T @ x.reshape(-1, h)).ravel())

    def coefficients(self, u: Array, omega: float) -> Array:
        """The structure's coefficients x = D^-1 (P - B F(u)) (mm, :mod:`.hb` layout)."""
        return self.along(np.append(u, omega)[None, :])[0]

    def along(self, points: Array) -> Array:
        """:meth:`coefficients` at every row ``[u, w]`` of ``points`` (m, size + 1), all
        at once: (m, n (2H + 1)), mm."""
        nb = self._b.shape[1]
        h = 2 * self.hb.harmonics + 1
        m = points.shape[0]
        force = np.empty((m, self.size))
        for i, y in enumerate(points):
            for operator, part in self._slices:
                force[i, part] = self.hb.joint_harmonics(operator, y[part])[0]
        f = force.reshape(m, nb, h)
        fc = np.swapaxes(f[:, :, 1::2] - 1j * f[:, :, 2::2], 1, 2)  # (m, H, nb)
        omega = points[:, -1]
        if self._modal is not None:
            w2, phi, cj = self._modal
            kw = self._order[None, :, :, 0] * omega[:, None, None]  # (m, H, 1)
            q = (self._pphi - fc @ self._bphi) / (w2 - kw**2 + 1j * kw * cj)
            xk = q @ phi.T  # (m, H, n)
        else:
            xk = np.array([(sol[:, :, nb:] - sol[:, :, :nb] @ fk[:, :, None])[:, :, 0]
                           for sol, fk in zip((self._solve(w)[0] for w in omega), fc,
                                              strict=True)])
        x = np.empty((m, self.hb.structure.dofs, h))
        x[:, :, 0] = self._static[:, nb] - f[:, :, 0] @ self._static[:, :nb].T
        x[:, :, 1::2] = np.swapaxes(xk.real, 1, 2)
        x[:, :, 2::2] = -np.swapaxes(xk.imag, 1, 2)
        return x.reshape(m, -1)

    def reach(self, u: Array) -> float:
        """The largest first-harmonic amplitude of the joints' coordinates, mm: what the
        continuation's norm scales the unknowns by."""
        return float(np.max(np.hypot(u[self._cos[0]], u[self._sin[0]])))


def _modes(k: Array, m: Array, c: Array) -> tuple[Array, Array, Array] | None:
    """``(w_j^2, Phi, c_j)`` of the undamped modes (mass-normalized) if M is positive
    definite and C diagonal in them (to :data:`PROPORTIONAL`), else None."""
    if not _definite(m):
        return None
    w2, phi = eigh(k, m)
    modal_c = phi.T @ c @ phi
    cj = np.diag(modal_c).copy()
    off = modal_c - np.diag(cj)
    if np.max(np.abs(off)) > PROPORTIONAL * np.max(np.abs(cj)):
        return None
    return w2, phi, cj
