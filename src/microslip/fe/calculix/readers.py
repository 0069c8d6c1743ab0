"""Readers for CalculiX result files: ``.dat`` (printed nodal values), ``.sta`` (increment
summary) and ``.frd`` (nodal results, ASCII).

The readers are strict: a file that ends in the middle of a block, a block with missing rows,
or an ``.frd`` without its closing ``9999`` record raises :class:`~microslip.fe.errors.
ResultsError`. They return named results (frozen dataclasses with numpy arrays).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import ResultsError

__all__ = [
    "DatBlock",
    "FrdBlock",
    "FrdResult",
    "StaTable",
    "read_dat",
    "read_frd",
    "read_sta",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def _open_text(path: str | os.PathLike[str]) -> str:
    p = Path(path)
    if not p.is_file():
        raise ResultsError(f"result file {p.name} is missing", p.parent)
    return p.read_text(encoding="latin-1")


@dataclass(frozen=True)
class DatBlock:
    """One printed block of a ``.dat`` file (e.g. ``displacements (vx,vy,vz)``).

    Attributes
    ----------
    quantity : str
        The block's title up to ``for set``, e.g. ``"displacements (vx,vy,vz)"``.
    nset : str
        Node set name, upper case.
    time : float
        Total time of the increment (sum over the steps), s.
    nodes : ndarray of int, shape (n,)
    values : ndarray, shape (n, k)
    """

    quantity: str
    nset: str
    time: float
    nodes: IntArray
    values: FloatArray


_DAT_HEADER = re.compile(
    r"^\s*(?P<q>[a-z][^\n]*?)\s+for set\s+(?P<set>\S+)\s+and time\s+(?P<t>\S+)\s*$")


def read_dat(path: str | os.PathLike[str], quantity: str = "displacements",
             expected_rows: int | None = None) -> list[DatBlock]:
    """Blocks of one printed quantity from a ``.dat`` file, in file order.

    Parameters
    ----------
    path : path
        The ``.dat`` file.
    quantity : str
        Start of the block title to keep (``"displacements"``, ``"forces"``, ...).
    expected_rows : int, optional
        Number of rows every block must have (the size of the node set).

    Examples
    --------
    >>> import tempfile
    >>> text = (" displacements (vx,vy,vz) for set NLOAD and time  0.1000000E+01\\n\\n"
    ...         "         5  1.000000E-03  0.000000E+00 -2.000000E-06\\n")
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = Path(d, "j.dat").write_text(text)
    ...     b = read_dat(Path(d, "j.dat"))[0]
    >>> b.nset, b.time, b.nodes.tolist(), float(b.values[0, 0])
    ('NLOAD', 1.0, [5], 0.001)
    """
    lines = _open_text(path).splitlines()
    blocks: list[DatBlock] = []
    i = 0
    while i < len(lines):
        m = _DAT_HEADER.match(lines[i])
        i += 1
        if m is None:
            continue
        title = m.group("q")
        try:
            t = float(m.group("t"))
        except ValueError:
            raise ResultsError(f"unreadable time in {Path(path).name}: {m.group('t')!r}",
                               Path(path).parent) from None
        while i < len(lines) and not lines[i].strip():
            i += 1
        ids: list[int] = []
        rows: list[list[float]] = []
        while i < len(lines) and lines[i].strip():
            parts = lines[i].split()
            try:
                ids.append(int(parts[0]))
                rows.append([float(v) for v in parts[1:]])
            except (ValueError, IndexError):
                break
            i += 1
        if not title.startswith(quantity):
            continue
        if not rows or len({len(r) for r in rows}) != 1:
            raise ResultsError(f"{Path(path).name}: empty or ragged block '{title}' at "
                               f"time {t:g}", Path(path).parent)
        if expected_rows is not None and len(rows) != expected_rows:
            raise ResultsError(f"{Path(path).name}: block '{title}' at time {t:g} has "
                               f"{len(rows)} rows, expected {expected_rows} (truncated?)",
                               Path(path).parent)
        blocks.append(DatBlock(title, m.group("set").upper(), t, np.array(ids, dtype=np.int64),
                               np.array(rows, dtype=float)))
    return blocks


@dataclass(frozen=True)
class StaTable:
    """The increment summary of a ``.sta`` file: one row per converged increment.

    Attributes
    ----------
    step, increment, attempts, iterations : ndarray of int
    total_time, step_time, increment_time : ndarray
        s.
    """

    step: IntArray
    increment: IntArray
    attempts: IntArray
    iterations: IntArray
    total_time: FloatArray
    step_time: FloatArray
    increment_time: FloatArray

    def in_step(self, step: int) -> StaTable:
        """The rows of one step."""
        k = self.step == step
        return StaTable(*(getattr(self, f)[k] for f in (
            "step", "increment", "attempts", "iterations", "total_time", "step_time",
            "increment_time")))


def read_sta(path: str | os.PathLike[str]) -> StaTable:
    """Read the increment table of a ``.sta`` file.

    Rows whose attempt column carries a letter (``1U``: an attempt that did not converge) are
    not converged increments and are left out.

    Examples
    --------
    >>> import tempfile
    >>> text = ("SUMMARY OF JOB INFORMATION\\n  STEP      INC     ATT  ITRS     TOT TIME"
    ...         "     STEP TIME      INC TIME\\n"
    ...         "     2          1     1     6  0.102500E+01  0.250000E-01  0.250000E-01\\n"
    ...         "     2          2     1U   40  0.102500E+01  0.250000E-01  0.250000E-01\\n")
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = Path(d, "j.sta").write_text(text)
    ...     s = read_sta(Path(d, "j.sta"))
    >>> s.iterations.tolist(), s.step_time.tolist()
    ([6], [0.025])
    """
    cols: list[list[float]] = []
    for line in _open_text(path).splitlines():
        parts = line.split()
        if len(parts) != 7 or not parts[0].isdigit():
            continue
        if not parts[2].isdigit():  # "1U": not converged
            continue
        try:
            cols.append([float(v) for v in parts])
        except ValueError:
            continue
    a = np.array(cols, dtype=float).reshape(-1, 7)
    ints = a[:, :4].astype(np.int64)
    return StaTable(ints[:, 0], ints[:, 1], ints[:, 2], ints[:, 3], a[:, 4], a[:, 5], a[:, 6])


@dataclass(frozen=True)
class FrdBlock:
    """One nodal result block of an ``.frd`` file.

    Attributes
    ----------
    name : str
        ``"DISP"``, ``"CONTACT"``, ``"STRESS"``, ...
    time : float
        Total time written in the block header, s.
    step : int
        Step number (from the ``1PSTEP`` record before the block; 0 if absent).
    increment : int
        Increment number within the step (idem).
    components : tuple of str
        Component names (``D1 D2 D3``; ``COPEN CSLIP1 CSLIP2 CPRESS CSHEAR1 CSHEAR2``).
    nodes : ndarray of int, shape (n,)
    values : ndarray, shape (n, len(components))
    """

    name: str
    time: float
    step: int
    increment: int
    components: tuple[str, ...]
    nodes: IntArray
    values: FloatArray


@dataclass(frozen=True)
class FrdResult:
    """An ``.frd`` file: node coordinates and the result blocks, in file order."""

    nodes: IntArray
    coords: FloatArray
    blocks: tuple[FrdBlock, ...] = field(default_factory=tuple)

    def select(self, name: str) -> list[FrdBlock]:
        """The blocks of one result name, in file order."""
        return [b for b in self.blocks if b.name == name]


def _floats(text: str, width: int = 12) -> list[float]:
    return [float(text[i:i + width]) for i in range(0, len(text.rstrip()), width)]


def read_frd(path: str | os.PathLike[str], names: tuple[str, ...] | None = None) -> FrdResult:
    """Read an ASCII ``.frd`` file; see :func:`_read_frd`. Any unreadable record (e.g. a
    line cut by a truncated write) raises :class:`ResultsError`."""
    try:
        return _read_frd(path, names)
    except (ValueError, IndexError) as exc:
        p = Path(path)
        raise ResultsError(f"{p.name} has an unreadable record ({exc}); the file is "
                           "truncated or corrupt", p.parent) from None


def _read_frd(path: str | os.PathLike[str], names: tuple[str, ...] | None = None) -> FrdResult:
    """Read an ASCII ``.frd`` file (CalculiX's result format).

    Records used: ``2C`` (node coordinates, rows `` -1`` id x y z), ``100C`` (result block
    header with the time), `` -4`` (block name), `` -5`` (component names), `` -1``/`` -2``
    (values, ids in columns 4-13 and 12-character numbers after them), `` -3`` (end of a
    block) and ``9999`` (end of file). Numbers are fixed-width, so ``-1.0E-03-2.0E-03`` with
    no blank between them is read correctly.

    Parameters
    ----------
    path : path
    names : tuple of str, optional
        Keep only blocks with these names (all by default).

    Raises
    ------
    ResultsError
        File missing, a block not closed, or no ``9999`` end record (truncated file).
    """
    p = Path(path)
    lines = _open_text(p).splitlines()
    node_ids: list[int] = []
    coords: list[list[float]] = []
    blocks: list[FrdBlock] = []
    ended = False
    pstep = (0, 0)
    i = 0
    n = len(lines)
    while i < n:
        line = lines[i]
        if line.strip() == "9999":
            ended = True
            break
        tag = line[:6].strip()
        if line.startswith("    1PSTEP"):
            parts = line.split()
            if len(parts) >= 4 and parts[2].isdigit() and parts[3].isdigit():
                pstep = (int(parts[3]), int(parts[2]))
        elif tag == "2C":
            i += 1
            while i < n and not lines[i].startswith(" -3"):
                if lines[i].startswith(" -1"):
                    node_ids.append(int(lines[i][3:13]))
                    coords.append(_floats(lines[i][13:])[:3])
                i += 1
            if i >= n:
                raise ResultsError(f"{p.name}: node block not closed (truncated)", p.parent)
        elif tag == "100CL" or line.startswith("  100C"):
            step, inc = pstep
            try:
                t = float(line[12:24])
            except ValueError:
                raise ResultsError(f"{p.name}: unreadable block header {line!r}",
                                   p.parent) from None
            i += 1
            if i >= n or not lines[i].startswith(" -4"):
                raise ResultsError(f"{p.name}: result block without a name record", p.parent)
            name = lines[i][5:13].strip()
            comps: list[str] = []
            i += 1
            while i < n and lines[i].startswith(" -5"):
                comps.append(lines[i][5:13].strip())
                i += 1
            comps = [c for c in comps if c != "ALL"]  # "ALL": a pseudo-component, no values
            ncomp = len(comps)
            ids: list[int] = []
            vals: list[list[float]] = []
            while i < n and not lines[i].startswith(" -3"):
                rec = lines[i]
                if rec.startswith(" -1"):
                    ids.append(int(rec[3:13]))
                    vals.append(_floats(rec[13:]))
                elif rec.startswith(" -2") and vals:
                    vals[-1].extend(_floats(rec[13:]))
                i += 1
            if i >= n:
                raise ResultsError(f"{p.name}: block {name} at time {t:g} not closed "
                                   "(truncated)", p.parent)
            if names is None or name in names:
                if any(len(v) != ncomp for v in vals):
                    raise ResultsError(f"{p.name}: block {name} at time {t:g} has rows with "
                                       f"other than {ncomp} values", p.parent)
                blocks.append(FrdBlock(name, t, step, inc, tuple(comps),
                                       np.array(ids, dtype=np.int64),
                                       np.array(vals, dtype=float).reshape(len(ids), ncomp)))
        i += 1
    if not ended:
        raise ResultsError(f"{p.name} has no end record (9999): the file is truncated",
                           p.parent)
    return FrdResult(np.array(node_ids, dtype=np.int64),
                     np.array(coords, dtype=float).reshape(-1, 3), tuple(blocks))
