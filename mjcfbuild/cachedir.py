"""Where mjcfbuild keeps what it shares between builds (the user's cache folder), and how much."""

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


DEFAULT_MAX_BYTES = 5 * 1024**3
_UNITS = {"": 1, "K": 1024, "M": 1024**2, "G": 1024**3, "T": 1024**4}


def parse_size(text: str) -> int:
    """'500M', '2G', '1.5G' or a plain number of bytes."""
    value = text.strip().upper().removesuffix("B").removesuffix("I")
    unit = value[-1] if value and value[-1] in _UNITS else ""
    number = value[: -len(unit)] if unit else value
    try:
        size = float(number) * _UNITS[unit]
    except ValueError:
        raise ValueError(f"'{text}' is not a size; use a number with K, M, G or T") from None
    if size < 0:
        raise ValueError(f"'{text}' is negative")
    return int(size)


MAX_VARIABLE = "MJCFBUILD_CACHE_MAX"


def default_max_bytes() -> int:
    """``$MJCFBUILD_CACHE_MAX`` (for example ``2G``), or 5 GiB. A value that is not a size is
    a :class:`~mjcfbuild.errors.UsageError` naming the variable (exit 2, as a bad
    ``$MJCFBUILD_JOBS``), not an internal error."""
    from mjcfbuild.errors import UsageError

    text = os.environ.get(MAX_VARIABLE, "").strip()
    if not text:
        return DEFAULT_MAX_BYTES
    try:
        return parse_size(text)
    except ValueError:
        raise UsageError(
            f"{MAX_VARIABLE}={text}: not a size",
            hint="set it to a size such as 500M or 2G (bytes, with K, M, G or T), or unset "
            "it for 5G",
        ) from None
