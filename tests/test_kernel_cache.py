"""numba's on-disk cache of microslip's kernels is stamped with the kernel's whole folder, so a
kernel inlining an edited function of another file is rebuilt, never loaded stale."""

from __future__ import annotations

import os

from microslip import _kernelcache
from microslip.models import batch_kernels, tip
from microslip.models.compiled import compiled


def test_kernels_use_the_folder_stamped_cache():
    for kernel in (compiled(tip.tip_backbone), batch_kernels.tip_kernel):
        locator = kernel._cache._impl.locator
        assert type(locator).__name__.startswith("FolderStamped")
        assert locator.get_source_stamp() == _kernelcache._folder_stamp(
            os.path.dirname(tip.__file__))


def test_the_stamp_changes_with_any_file_of_the_folder(tmp_path):
    (tmp_path / "a.py").write_text("x = 1\n")
    (tmp_path / "b.py").write_text("y = 2\n")
    (tmp_path / "notes.txt").write_text("not code\n")
    before = _kernelcache._folder_stamp(str(tmp_path))
    (tmp_path / "notes.txt").write_text("still not code\n")
    assert _kernelcache._folder_stamp(str(tmp_path)) == before
    (tmp_path / "b.py").write_text("y = 3\n")
    assert _kernelcache._folder_stamp(str(tmp_path)) != before


def test_install_is_idempotent():
    from numba.core import caching

    impl = getattr(caching, "CacheImpl", None) or caching._CacheImpl  # renamed in numba 0.6x
    classes = list(impl._locator_classes)
    _kernelcache.install()
    assert impl._locator_classes == classes
