"""Names of a package resolved from their modules on first use (PEP 562), so that importing the
package stays cheap: ``import microslip`` does not pay for numba, scipy.sparse or the FE.

>>> getattr_ = lazy_names("microslip", {"closedform": ".closedform", "damping": ".energy"})
>>> getattr_("damping").__name__, getattr_("closedform").__name__
('damping', 'microslip.closedform')
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_names"]


def lazy_names(package: str, names: Mapping[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` for ``package`` (which lists ``names`` in its ``__all__`` and
    ``__dir__``): ``names`` maps a public name
    to the module (relative to ``package``) that defines it; a name equal to its module's last
    part is that module itself. A resolved name is kept in the package, so it is looked up
    once. The modules are named as strings (``importlib``): the package does not import them,
    they stay out of its import graph."""

    def __getattr__(name: str) -> Any:
        try:
            where = names[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        module = importlib.import_module(where, package)
        value = module if where.rsplit(".", 1)[-1] == name else getattr(module, name)
        setattr(sys.modules[package], name, value)
        return value

    return __getattr__
