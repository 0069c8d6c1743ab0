"""How named results are made immutable: read-only arrays, identity equality, a short repr.

Every result type of microslip is a ``@result`` class: a frozen dataclass with ``eq=False``
(two results are equal only if they are the same object; compare fields explicitly), whose
array fields are made read-only in ``__post_init__`` (copies of the caller's arrays are not
taken: the arrays are the result's own), and whose ``repr`` shows scalars and the shapes of
arrays instead of their contents.

>>> import numpy as np
>>> @result
... class R:
...     x: np.ndarray
...     name: str = "a"
>>> r = R(np.arange(3.0))
>>> r
R(x=<array (3,)>, name='a')
>>> r.x.flags.writeable
False
>>> r == R(r.x)
False
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

if TYPE_CHECKING:  # tells mypy that @result makes a frozen dataclass
    from typing_extensions import dataclass_transform
else:
    def dataclass_transform(**kwargs: Any) -> Any:
        return lambda f: f

__all__ = ["readonly", "result", "short_repr"]

T = TypeVar("T")


def readonly(a: Any) -> np.ndarray:
    """``a`` as a float-or-int ndarray that cannot be written through (a view if needed)."""
    arr = np.asarray(a)
    if arr.flags.writeable:
        arr = arr.view()
        arr.setflags(write=False)
    return arr


def _field_repr(value: Any) -> str:
    if isinstance(value, np.ndarray):
        return f"<array {value.shape}>" if value.ndim else repr(value.item())
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return f"<{type(value).__name__}>"
    return repr(value)


def short_repr(obj: Any) -> str:
    """``Name(field=value, ...)`` with arrays shown by shape and nested results by name."""
    parts = (f"{f.name}={_field_repr(getattr(obj, f.name))}"
             for f in dataclasses.fields(obj) if f.repr)
    return f"{type(obj).__name__}({', '.join(parts)})"


@dataclass_transform(frozen_default=True, eq_default=False)
def result(cls: type[T]) -> type[T]:
    """Class decorator: a frozen, ``eq=False`` dataclass with read-only arrays, short repr.

    A ``__post_init__`` the class defines itself runs after the arrays are frozen.
    """
    own_post_init = cls.__dict__.get("__post_init__")

    def __post_init__(self: Any) -> None:
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray):
                object.__setattr__(self, f.name, readonly(value))
        if own_post_init is not None:
            own_post_init(self)

    cls.__post_init__ = __post_init__  # type: ignore[attr-defined]
    cls.__repr__ = short_repr  # type: ignore[method-assign]
    return dataclasses.dataclass(frozen=True, eq=False, repr=False)(cls)
