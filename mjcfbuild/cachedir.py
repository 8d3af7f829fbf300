"""Where mjcfbuild keeps what it shares between builds: the user's cache folder."""

from __future__ import annotations

import os
from pathlib import Path

CACHE_DIR_VARIABLE = "MJCFBUILD_CACHE_DIR"


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


def cache_dir_problem() -> str | None:
    """The warning for a ``$MJCFBUILD_CACHE_DIR`` that cannot be used (a folder that cannot
    be made or written: ``/proc/cc``, a read-only disk), naming the variable; None when it is
    unset or usable. Such a cache stores and finds nothing: every product is made again, and
    no-op builds lose their fast path. It makes the folder when it can (a build would)."""
    explicit = os.environ.get(CACHE_DIR_VARIABLE)
    if not explicit:
        return None
    folder = Path(explicit).expanduser()
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        why = "cannot create it there" if isinstance(exc, FileNotFoundError) else exc.strerror
    else:
        if os.access(folder, os.W_OK | os.X_OK):
            return None
        why = "it cannot be written"
    return (
        f"{CACHE_DIR_VARIABLE}={explicit}: {why}; builds keep no shared cache (nothing is stored "
        "or reused, every product is made again) - set it to a folder you can write, or unset "
        "it for the default"
    )
