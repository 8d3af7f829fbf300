"""Where mjcfbuild keeps what it shares between builds: the user's cache folder."""

from __future__ import annotations

import os
from pathlib import Path


def user_cache_dir() -> Path:
    """``$MJCFBUILD_CACHE_DIR``, else ``$XDG_CACHE_HOME/mjcfbuild``, else ``~/.cache/mjcfbuild``."""
    explicit = os.environ.get("MJCFBUILD_CACHE_DIR")
    if explicit:
        return Path(explicit).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "mjcfbuild"


def diff_cache_dir() -> Path:
    """Where ``mjcfbuild diff`` keeps the revisions it extracted and built, one folder per
    repository (``cache clear`` removes it)."""
    return user_cache_dir() / "diff"
