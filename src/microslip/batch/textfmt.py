"""Fast, exact text formatting of float tables: each number in the fewest digits that read back.

Writing a million CSV rows one Python ``%`` at a time takes seconds; this module formats a
whole block of values in compiled code (numba, parallel) and gives byte for byte the text of
:func:`format_number`: ``"%.{n}g" % x`` with n the fewest of 15, 16 or 17 significant digits
for which ``float(text) == x`` (correctly rounded with ties to even, trailing zeros dropped,
``nan``/``inf``). Fifteen digits always survive a round trip from decimal (DBL_DIG), so 0.8
stays ``0.8``; seventeen always bring a double back bit for bit (DBL_DECIMAL_DIG), so a table
written and read again is the table computed.

How: x = M 10^(e - 16) with the integer M in [1e16, 1e17). The product y = |x| 10^(16 - e) is
formed as a double-double (Dekker's exact product of |x| with a double-double 10^p from a
table); M = round(y) is taken in 64-bit integers (M exceeds 2^53: the high part is an
integer-valued double and the low part carries the fraction). The 15- and 16-digit roundings
are taken from y directly (not from M, which would round twice) and kept when they lie within
half an ulp of x. Values within 1e-9 (relative) of a tie or of that limit, exact ties
included, are decided by Python. :func:`format_table_python` is the plain-Python reference.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from fractions import Fraction

import numpy as np
from numba import njit, prange
from numpy.typing import ArrayLike, NDArray

__all__ = ["fewest_digits", "format_number", "format_table", "format_table_python"]

_P_MIN, _P_MAX = -300, 300  # exponents of the double-double table of powers of ten
DIGITS = 17  # significant digits of every number written (round-trip exact for doubles)
_LOW = 10 ** (DIGITS - 1)  # M lies in [_LOW, 10 _LOW)
#: "00", "01", ..., "99" as bytes, for writing two digits at a time.
_PAIRS = np.frombuffer("".join(f"{i:02d}" for i in range(100)).encode(), dtype=np.uint8).copy()


@functools.cache
def _pow10_table() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    hi = np.empty(_P_MAX - _P_MIN + 1)
    lo = np.empty_like(hi)
    for k, p in enumerate(range(_P_MIN, _P_MAX + 1)):
        exact = Fraction(10) ** p
        h = float(exact)
        hi[k] = h
        lo[k] = float(exact - Fraction(h))
    return hi, lo


@njit(cache=True, inline="always")
def _split(x):
    c = 134217729.0 * x  # 2^27 + 1 (Veltkamp)
    h = c - (c - x)
    return h, x - h


@njit(cache=True, inline="always")
def _strip(m):
    nd = DIGITS
    while nd > 1:
        q = m // 10
        if m - 10 * q != 0:
            break
        m = q
        nd -= 1
    return m, nd


@njit(cache=True, inline="always")
def _fewest_digits(m, fl, t, a, ph, pl):
    """(n, m_n): the fewest significant digits n (15, 16 or 17) whose correct rounding of
    y = fl + t = a 10^p reads back as the double a, and that rounding on the 17-digit scale
    (m, the 17-digit rounding, when n = 17); (-1, m) when too close to a tie or to the
    round-trip limit to decide in double precision.

    A decimal C reads back as a when |C - y| is less than half an ulp of a (times 10^p); the
    interval below a power of two is half as wide. 17 digits always read back.
    """
    f, ex = math.frexp(a)
    h = math.ldexp(ph, ex - 54) + math.ldexp(pl, ex - 54)  # half an ulp of a, times 10^p
    n = 15
    for q in (100, 10):
        base = m - m % q
        below = float(base + q // 2 - np.int64(fl)) - t  # (base + q/2) - y
        if abs(below) < 1e-9:
            return -1, m
        c = base if below > 0 else base + q
        err = float(c - np.int64(fl)) - t  # c - y
        lim = 0.5 * h if (f == 0.5 and err < 0) else h
        if abs(abs(err) - lim) < 1e-9 * lim:
            return -1, m
        if abs(err) < lim:
            return n, c
        n += 1
    return DIGITS, m


@njit(cache=True, parallel=True)
def _decompose(x, p_hi, p_lo, mant, ndig, expo, prec, kind):
    """|x| = mant 10^(expo - ndig + 1) with ndig digits (trailing zeros stripped), the
    correct rounding of x to prec = 15, 16 or 17 significant digits, the fewest that read
    back as x.

    kind: 0 finite, 1 zero, 2 nan, 3 inf, 4 undecided (Python decides).
    """
    low = np.int64(_LOW)
    lowf = float(_LOW)
    for j in prange(x.shape[0]):
        v = x[j]
        mant[j] = 0
        ndig[j] = 1
        expo[j] = 0
        prec[j] = DIGITS
        if v != v:
            kind[j] = 2
            continue
        a = abs(v)
        if a == 0.0:
            kind[j] = 1
            continue
        if a == np.inf:
            kind[j] = 3
            continue
        kind[j] = 4
        if a > 1e290 or a < 1e-290:  # beyond the exact-product range: Python decides
            continue
        e = int(np.floor(np.log10(a)))
        down = False  # the previous try had e one too large
        for _ in range(4):
            p = DIGITS - 1 - e
            if p < -300 or p > 300:
                break
            ph = p_hi[p + 300]
            pl = p_lo[p + 300]
            yh = a * ph
            ah, al = _split(a)
            bh, bl = _split(ph)
            yl = (((ah * bh - yh) + ah * bl) + al * bh) + al * bl + a * pl
            # y = yh + yl = |x| 10^p, exact when 10^p is a double (0 <= p <= 22)
            fl = np.floor(yh)
            t = (yh - fl) + yl  # y - fl, |t| < 9: yh ~ 1e16 has an ulp of up to 16
            frac = t - np.floor(t)
            if abs(frac - 0.5) < 1e-9:  # a tie or too close to one to decide here
                break
            if yh == lowf and pl != 0.0 and abs(yl) < 1e-9:
                break
            m = np.int64(fl) + np.int64(np.floor(t + 0.5))
            if m >= 10 * low and not down:
                e += 1
                continue
            if m < 10 * low and (yh < lowf or (yh == lowf and yl < 0.0)):
                e -= 1
                down = True
                continue
            n, m = _fewest_digits(m, fl, t, a, ph, pl)
            if n < 0:  # too close to a tie or to the round-trip limit: Python decides
                break
            if m >= 10 * low:  # rounded up to the next decade: 1.000...e(e+1)
                m, e = low, e + 1
            mj, nd = _strip(m)
            mant[j] = mj
            ndig[j] = nd
            expo[j] = e
            prec[j] = n
            kind[j] = 0
            break


@njit(cache=True, inline="always")
def _field_len(nd, e, prec, kind, neg):
    s = 1 if neg else 0
    if kind == 1:
        return s + 1
    if kind == 2:
        return 3
    if kind == 3:
        return s + 3
    if -4 <= e < prec:
        if e >= 0:
            return s + (e + 1 if nd <= e + 1 else nd + 1)
        return s + 2 + (-e - 1) + nd
    ae = -e if e < 0 else e
    ne = 3 if ae >= 100 else 2
    return s + nd + (1 if nd > 1 else 0) + 2 + ne


@njit(cache=True, inline="always")
def _write_digits(buf, pos, m, nd, pairs):
    """The nd decimal digits of m (leading zeros included) at buf[pos:pos + nd]."""
    k = pos + nd
    while k - pos >= 2:
        q = m // 100
        r = m - 100 * q
        buf[k - 1] = pairs[2 * r + 1]
        buf[k - 2] = pairs[2 * r]
        m = q
        k -= 2
    if k > pos:
        buf[pos] = 48 + m % 10


@njit(cache=True, inline="always")
def _write_field(buf, pos, m, nd, e, prec, kind, neg, pairs):
    if kind == 2:
        buf[pos] = 110  # n
        buf[pos + 1] = 97  # a
        buf[pos + 2] = 110
        return pos + 3
    if neg:
        buf[pos] = 45  # -
        pos += 1
    if kind == 1:
        buf[pos] = 48
        return pos + 1
    if kind == 3:
        buf[pos] = 105  # i
        buf[pos + 1] = 110  # n
        buf[pos + 2] = 102  # f
        return pos + 3
    if -4 <= e < prec:
        if e >= 0:
            _write_digits(buf, pos, m, nd, pairs)
            if nd <= e + 1:
                for k in range(nd, e + 1):
                    buf[pos + k] = 48
                return pos + e + 1
            # move the fraction one place right and put the point after e + 1 digits
            for k in range(pos + nd, pos + e + 1, -1):
                buf[k] = buf[k - 1]
            buf[pos + e + 1] = 46  # .
            return pos + nd + 1
        buf[pos] = 48
        buf[pos + 1] = 46
        pos += 2
        for _ in range(-e - 1):
            buf[pos] = 48
            pos += 1
        _write_digits(buf, pos, m, nd, pairs)
        return pos + nd
    _write_digits(buf, pos + 1, m, nd, pairs)
    buf[pos] = buf[pos + 1]
    if nd > 1:
        buf[pos + 1] = 46
        pos += nd + 1
    else:
        pos += 1
    buf[pos] = 101  # e
    buf[pos + 1] = 45 if e < 0 else 43
    pos += 2
    ae = -e if e < 0 else e
    ne = 3 if ae >= 100 else 2
    _write_digits(buf, pos, ae, ne, pairs)
    return pos + ne


@njit(cache=True, parallel=True)
def _layout(mant, ndig, expo, prec, kind, neg, colmap, const_buf, const_off, pairs):
    """Rows of text: column c is varying column colmap[c] >= 0 of the decomposed values
    (row-major, nvar per row) or, for colmap[c] = -k - 1, the constant text
    const_buf[const_off[k]:const_off[k + 1]] on every row."""
    ncol = colmap.shape[0]
    nvar = 0
    const_len = 0
    for c in range(ncol):
        if colmap[c] >= 0:
            nvar += 1
        else:
            k = -colmap[c] - 1
            const_len += const_off[k + 1] - const_off[k]
    nrow = mant.shape[0] // nvar if nvar else 0
    lens = np.empty(nrow + 1, dtype=np.int64)
    lens[0] = 0
    for r in prange(nrow):
        total = ncol + const_len  # separators, the newline and the constant fields
        for v in range(nvar):
            j = r * nvar + v
            total += _field_len(ndig[j], expo[j], prec[j], kind[j], neg[j])
        lens[r + 1] = total
    for r in range(nrow):
        lens[r + 1] += lens[r]
    buf = np.empty(lens[nrow], dtype=np.uint8)
    for r in prange(nrow):
        pos = lens[r]
        for c in range(ncol):
            if colmap[c] >= 0:
                j = r * nvar + colmap[c]
                pos = _write_field(buf, pos, mant[j], ndig[j], expo[j], prec[j], kind[j],
                                   neg[j], pairs)
            else:
                k = -colmap[c] - 1
                for b in range(const_off[k], const_off[k + 1]):
                    buf[pos] = const_buf[b]
                    pos += 1
            buf[pos] = 44 if c < ncol - 1 else 10  # , or newline
            pos += 1
    return buf


def fewest_digits(v: float) -> int:
    """The fewest significant digits, 15 to 17, whose ``%g`` text reads back as ``v``."""
    for n in (15, 16):
        if float(f"{v:.{n}g}") == v:
            return n
    return DIGITS


def format_number(v: float) -> str:
    """``v`` as ``%.{n}g`` with n = :func:`fewest_digits` (nan and inf as ``%g`` writes them)."""
    return f"{v:.{fewest_digits(v) if math.isfinite(v) else DIGITS}g}"


def format_table_python(columns: Sequence[ArrayLike | float]) -> bytes:
    """Reference and fallback: rows of :func:`format_number` texts joined by commas."""
    arrays = [np.asarray(c, dtype=np.float64) for c in columns]
    nrow = max((a.size for a in arrays if a.ndim), default=1)
    cols = [np.broadcast_to(a.ravel() if a.ndim else a, (nrow,)).tolist() for a in arrays]
    return "".join(",".join(format_number(v) for v in row) + "\n"
                   for row in zip(*cols, strict=True)).encode()


def format_table(columns: Sequence[ArrayLike | float]) -> bytes | NDArray[np.uint8]:
    """CSV text of equal-length float columns, every value as ``"%.17g" % x``.

    A column given as a single number has that value on every row (it is formatted once).
    Returns a bytes-like object (a uint8 array, or bytes when no column varies) to hand to
    a binary file.

    >>> bytes(format_table([[1.0, 0.1, 1e-5], 0.8, [20000.0, -2.5, float("nan")]]))
    b'1,0.8,20000\\n0.1,0.8,-2.5\\n1e-05,0.8,nan\\n'
    """
    arrays = [np.asarray(c, dtype=np.float64) for c in columns]
    varying = [a.ravel() for a in arrays if a.ndim]
    if not arrays:
        return b""
    if not varying:
        return format_table_python(columns)
    nrow = varying[0].shape[0]
    if any(c.shape[0] != nrow for c in varying):
        raise ValueError("columns must have equal lengths")
    colmap = np.empty(len(arrays), dtype=np.int64)
    const_text: list[bytes] = []
    nv = 0
    for i, a in enumerate(arrays):
        if a.ndim:
            colmap[i] = nv
            nv += 1
        else:
            colmap[i] = -len(const_text) - 1
            const_text.append(format_number(float(a)).encode())
    const_off = np.cumsum([0] + [len(t) for t in const_text], dtype=np.int64)
    const_buf = np.frombuffer(b"".join(const_text) or b"\0", dtype=np.uint8)
    x = np.empty((nrow, nv))
    for i, c in enumerate(varying):
        x[:, i] = c
    flat = x.reshape(-1)
    mant = np.empty(flat.shape[0], dtype=np.int64)
    ndig = np.empty(flat.shape[0], dtype=np.int64)
    expo = np.empty(flat.shape[0], dtype=np.int64)
    prec = np.empty(flat.shape[0], dtype=np.int64)
    kind = np.empty(flat.shape[0], dtype=np.int8)
    p_hi, p_lo = _pow10_table()
    _decompose(flat, p_hi, p_lo, mant, ndig, expo, prec, kind)
    for j in np.flatnonzero(kind == 4):
        n = fewest_digits(float(flat[j]))
        s = f"{abs(float(flat[j])):.{n - 1}e}"
        digits = (s[0] + s[2:n + 1]).rstrip("0") or "0"
        mant[j] = int(digits)
        ndig[j] = len(digits)
        expo[j] = int(s[n + 2:])
        prec[j] = n
        kind[j] = 0
    neg = np.signbit(flat) & ~np.isnan(flat)
    return _layout(mant, ndig, expo, prec, kind, neg, colmap, const_buf, const_off, _PAIRS)
