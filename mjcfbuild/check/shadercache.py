"""Where Mesa keeps the shaders it compiles for the previews, and when it keeps none.

Mesa keeps compiled shaders in ~/.cache unless told otherwise; mjcfbuild writes only in its
output folder and its own cache, so it points Mesa at ``<cache>/mesa_shader_cache``. Mesa maps
its cache's index file into memory: on a full disk, its first store into a page of the index
that has no disk space behind it kills the process (SIGBUS), which would fail the previews
for want of a cache that only saves time. So the shader cache is turned off
(``MESA_SHADER_CACHE_DISABLE``) where its folder has little room left or its index cannot be
given the space it maps; a full cache then only makes drawing slower.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import MutableMapping
from pathlib import Path

# Room below which the shader cache is turned off: the index Mesa maps (about 1.3 MB) and
# some shaders.
ROOM_BYTES = 32 * 1024**2
FOLDER_VARIABLE = "MESA_SHADER_CACHE_DIR"
DISABLE_VARIABLE = "MESA_SHADER_CACHE_DISABLE"


def choose_shader_cache(environ: MutableMapping[str, str], default: Path) -> bool:
    """Point Mesa's shader cache at ``default`` (unless ``environ`` names a folder already),
    or turn it off where it cannot be written safely; whether it is on."""
    if environ.get(DISABLE_VARIABLE, "").lower() in ("1", "true", "yes"):
        return False
    folder = Path(environ.get(FOLDER_VARIABLE) or default)
    if _has_room(folder):
        environ[FOLDER_VARIABLE] = str(folder)
        return True
    environ[DISABLE_VARIABLE] = "true"
    return False


def _has_room(folder: Path) -> bool:
    """Whether ``folder`` can be written, has :data:`ROOM_BYTES` free, and every index Mesa
    made there has its space allocated (a sparse one would be filled through the mapping)."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        if shutil.disk_usage(folder).free < ROOM_BYTES or not os.access(folder, os.W_OK):
            return False
        for index in folder.rglob("index"):
            _allocate(index)
    except OSError:
        return False
    return True


def _allocate(path: Path) -> None:
    """Give the file ``path`` disk space for its whole length (OSError: there is none)."""
    info = path.stat()
    if info.st_blocks * 512 >= info.st_size or not hasattr(os, "posix_fallocate"):
        return
    descriptor = os.open(path, os.O_RDWR | os.O_CLOEXEC)
    try:
        os.posix_fallocate(descriptor, 0, info.st_size)
    finally:
        os.close(descriptor)
