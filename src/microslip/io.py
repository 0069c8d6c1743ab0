"""Writing output files so that a failure never leaves a half-written file behind."""

from __future__ import annotations

import contextlib
import csv
import json
import os
import shutil
import tempfile
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

import numpy as np

__all__ = [
    "atomic_path", "atomic_write", "check_writable", "read_csv", "staged_directory",
    "to_jsonable", "write_csv", "write_json",
]

#: Permissions asked for a new file; the process umask is applied by the kernel (never read or
#: changed here, so that threads writing files at the same time cannot race on it).
FILE_MODE = 0o666


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; move it onto ``path`` only on success."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = _new_file(target)
    try:
        yield Path(tmp)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "w") -> Iterator[IO[Any]]:
    """Open a temporary file for writing; it replaces ``path`` only if the block succeeds."""
    with atomic_path(path) as tmp, open(tmp, mode, encoding=None if "b" in mode else "utf-8",
                                        newline=None if "b" in mode else "") as fh:
        yield fh


@contextlib.contextmanager
def staged_directory(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a new, empty staging directory beside ``path``; on success its entries move into
    ``path`` (created if missing; an entry of the same name is replaced), on any failure or
    interrupt the staging directory is removed, so ``path`` is never left half-written."""
    target = Path(path).absolute()
    created = [p for p in target.parents if not p.exists()]
    target.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{target.name}.partial-", dir=target.parent))
    ok = False
    try:
        yield stage
        target.mkdir(exist_ok=True)  # the usual permissions (mkdtemp's are 0o700)
        for entry in stage.iterdir():
            dest = target / entry.name
            if dest.is_dir() and not dest.is_symlink():
                shutil.rmtree(dest)
            os.replace(entry, dest)
        ok = True
    finally:
        shutil.rmtree(stage, ignore_errors=True)
        if not ok and created:
            shutil.rmtree(created[-1], ignore_errors=True)


def _new_file(target: Path) -> Path:
    """Create an empty, uniquely named file beside ``target`` with the usual permissions
    (:data:`FILE_MODE` less the umask, as ``open`` gives), and return its path."""
    for _ in range(100):
        tmp = target.parent / f".{target.name}.{uuid.uuid4().hex[:12]}{target.suffix}"
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, FILE_MODE)
        except FileExistsError:
            continue
        os.close(fd)
        return tmp
    raise FileExistsError(f"cannot create a temporary file beside {str(target)!r}")


def check_writable(path: str | os.PathLike[str], formats: tuple[str, ...] = (),
                   what: str = "output file", directory: bool = False) -> Path:
    """Check, before any work, that ``path`` can be written; return it as a Path.

    ``formats`` are the accepted extensions (``(".png", ".pdf")``; empty: any). A file must
    not be an existing directory, a directory (``directory=True``) not an existing file; the
    nearest existing ancestor must be a directory in which a file can be created (tried with
    an empty temporary file, removed at once, so that nothing is left behind). Every failure
    is one :class:`~microslip.errors.ParameterError` line naming the path and the reason.
    """
    from .errors import ParameterError

    target = Path(path)
    name = os.fspath(path)
    if formats and target.suffix.lower() not in formats:
        allowed = " or ".join([", ".join(formats[:-1]), formats[-1]] if len(formats) > 1
                              else formats)
        raise ParameterError(f"{what} must end in {allowed}, got {name!r}")
    if target.exists() and target.is_dir() != directory:
        want, kind = ("a directory", "file") if directory else ("a file", "directory")
        raise ParameterError(f"{what} must be {want}, got the {kind} {name!r}")
    base = target if directory else target.parent
    for parent in (base, *base.parents):
        if parent.exists() or parent.is_symlink():
            break
    if not parent.is_dir():
        raise ParameterError(f"cannot write {what} {name}: {parent} is not a directory")
    try:
        os.unlink(_new_file(parent / ".microslip-write-test"))
    except OSError as exc:
        raise ParameterError(f"cannot write {what} {name}: {exc.strerror or exc} "
                             f"(in {parent})") from None
    return target


def to_jsonable(obj: Any) -> Any:
    """numpy scalars and arrays to plain Python, recursively."""
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


def write_json(path: str | os.PathLike[str], obj: Any) -> None:
    with atomic_write(path) as fh:
        json.dump(to_jsonable(obj), fh, indent=2)
        fh.write("\n")


def write_csv(path: str | os.PathLike[str], columns: dict[str, Any]) -> None:
    """Write equal-length columns as CSV; the header names carry the units."""
    names = list(columns)
    cols = [np.asarray(columns[n]).ravel() for n in names]
    rows = len(cols[0]) if cols else 0
    if any(len(c) != rows for c in cols):
        raise ValueError("CSV columns must have equal lengths")
    with atomic_write(path) as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(names)
        for i in range(rows):
            w.writerow([_fmt(c[i]) for c in cols])


def _fmt(v: Any) -> Any:
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    if isinstance(v, np.generic):
        return v.item()
    return v


def read_csv(path: str | os.PathLike[str]) -> dict[str, list[Any]]:
    """Columns of a CSV written by :func:`write_csv`: name -> values, as float where every
    value of the column parses as one, else as text."""
    with open(path, encoding="utf-8", newline="") as fh:
        reader = csv.reader(fh)
        names = next(reader)
        values = list(zip(*reader, strict=True)) or [()] * len(names)
    return {name: _column(col) for name, col in zip(names, values, strict=True)}


def _column(values: tuple[str, ...]) -> list[Any]:
    try:
        return [float(v) for v in values]
    except ValueError:
        return list(values)


#: The columns of a force-displacement loop file (written by ``loop --csv`` and ``fe --out``,
#: read by ``microslip fit``).
LOOP_COLUMNS = ("force_N", "displacement_mm")


def write_loop_csv(path: str | os.PathLike[str], force: Any, displacement: Any) -> Path:
    """A loop as CSV (:data:`LOOP_COLUMNS`, samples in their order, round-trip digits)."""
    write_csv(path, dict(zip(LOOP_COLUMNS, (force, displacement), strict=True)))
    return Path(path)
