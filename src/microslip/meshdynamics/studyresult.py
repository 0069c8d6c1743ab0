"""The named result of a structure study (:func:`~.modalstudy.modal_study`,
:func:`~.frfstudy.frf_study`): the JSON the command line writes, read-only, with its parts
by name and ``to_json()``.

It is a read-only mapping over that JSON as well, so ``result["verdicts"]`` and
``result.verdicts`` are the same object.

>>> r = StudyResult("modal", {"verdicts": {}, "solvers": {"fe": {}}, "warnings": []})
>>> r.solvers, r["verdicts"], len(r)
({'fe': {}}, {}, 3)
>>> r.to_json()
'{"verdicts": {}, "solvers": {"fe": {}}, "warnings": []}'
"""

from __future__ import annotations

import json
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

__all__ = ["StudyResult"]


@dataclass(frozen=True, eq=False)
class StudyResult(Mapping[str, Any]):
    """One study's output: ``kind`` (``modal`` or ``frf``) and ``data`` (the JSON keys)."""

    kind: str
    data: Mapping[str, Any]

    def __post_init__(self) -> None:
        object.__setattr__(self, "data", MappingProxyType(dict(self.data)))

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.data)

    def __len__(self) -> int:
        return len(self.data)

    @property
    def solvers(self) -> dict[str, Any]:
        """Solver name -> its curve's keys (every model run)."""
        return dict(self.data.get("solvers", {}))

    @property
    def verdicts(self) -> dict[str, Any]:
        """Model name -> its verdict against the full FE (empty without the full FE)."""
        return dict(self.data.get("verdicts", {}))

    @property
    def warnings(self) -> list[str]:
        return list(self.data.get("warnings", []))

    def to_dict(self) -> dict[str, Any]:
        """A plain (writable) deep copy of the keys (NaN kept as NaN)."""
        import copy

        return copy.deepcopy(dict(self.data))

    def to_json(self, path: str | Path | None = None, indent: int | None = None) -> str:
        """The JSON text (NaN as null, as the command line writes it); with ``path`` also
        written there, whole or not at all."""
        text = json.dumps(_plain(dict(self.data)), indent=indent)
        if path is not None:
            from ..io import atomic_write

            with atomic_write(Path(path)) as fh:
                fh.write(text + "\n")
        return text


def _plain(v: Any) -> Any:
    import math

    import numpy as np

    if isinstance(v, Mapping):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, np.ndarray):
        return _plain(v.tolist())
    if isinstance(v, (np.floating, float)):
        f = float(v)
        return None if math.isnan(f) else f
    if isinstance(v, np.integer):
        return int(v)
    return v
