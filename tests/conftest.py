"""Shared test set-up: tests marked ``ccx`` are skipped, with a reason, when ccx is absent."""

from __future__ import annotations

import shutil

import pytest


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if shutil.which("ccx") is not None:
        return
    skip = pytest.mark.skip(reason="CalculiX (ccx) is not on PATH; run `bash scripts/setup.sh`")
    for item in items:
        if "ccx" in item.keywords:
            item.add_marker(skip)
