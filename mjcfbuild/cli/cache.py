"""``mjcfbuild cache``: show, prune or clear the shared cache of meshes and decompositions."""

from __future__ import annotations

import argparse
import contextlib
import os
from pathlib import Path

from mjcfbuild.errors import UsageError


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "cache",
        help="show, prune or clear the shared cache of converted meshes and decompositions",
        description=(
            "The cache holds converted meshes and convex decompositions by content, for every "
            "build on this machine. Default folder: $MJCFBUILD_CACHE_DIR, else "
            "$XDG_CACHE_HOME/mjcfbuild, else ~/.cache/mjcfbuild; default cap: "
            "$MJCFBUILD_CACHE_MAX, else 5G."
        ),
    )
    parser.add_argument(
        "action",
        nargs="?",
        default="show",
        choices=("show", "prune", "clear"),
        help="show (default): location and size; prune: remove least recently used entries "
        "down to the cap; clear: remove everything",
    )
    parser.add_argument("--folder", help="the cache folder (default: see above)")
    parser.add_argument("--max-size", help="the cap for prune, for example 500M or 2G")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Show, prune or clear."""
    from mjcfbuild.products.store import ProductStore, parse_size

    try:
        max_bytes = parse_size(args.max_size) if args.max_size else None
    except ValueError as exc:
        raise UsageError(f"--max-size: {exc}") from None
    folder = Path(args.folder) if args.folder else None
    store = ProductStore(folder)  # its cap: the one every build prunes to
    if args.action == "prune":
        # --max-size is this prune's target, not the cache's cap.
        removed = ProductStore(folder, max_bytes).prune()
        target = f" to {_human(max_bytes)}" if max_bytes is not None else ""
        print(
            f"mjcfbuild: pruned{target}: removed {removed} cache "
            f"entr{'y' if removed == 1 else 'ies'}"
        )
    elif args.action == "clear":
        removed = store.clear()
        print(f"mjcfbuild: removed {removed} cache entr{'y' if removed == 1 else 'ies'}")
        if folder is None and _diff_folder().is_dir():  # diff's revisions: built again at need
            import shutil

            shutil.rmtree(_diff_folder(), ignore_errors=True)
            print(f"mjcfbuild: removed {_diff_folder()} (the revisions mjcfbuild diff built)")
    usage = store.usage()
    print(
        f"cache: {usage.folder}\n"
        f"entries: {usage.entries}\n"
        f"size: {_human(usage.bytes)} of {_human(store.max_bytes)} (the cap builds prune to)"
    )
    if folder is None and _diff_folder().is_dir():
        size = _size(_diff_folder())
        print(f"diff revisions: {_diff_folder()} ({_human(size)}; `cache clear` removes them)")
    _show_remotes(store.folder)
    return 0


def _diff_folder() -> Path:
    """Where ``mjcfbuild diff`` keeps the revisions it extracted and built."""
    from mjcfbuild.cachedir import diff_cache_dir

    return diff_cache_dir()


def _size(folder: Path) -> int:
    """The bytes of the files below ``folder`` (a file a running diff removes counts none)."""
    total = 0
    for root, _, names in os.walk(folder):
        for name in names:
            with contextlib.suppress(OSError):
                total += os.lstat(os.path.join(root, name)).st_size
    return total


def _show_remotes(folder: Path) -> None:
    """What remote caches gave and took, as recorded by builds using this cache."""
    import os

    from mjcfbuild.sharing.stats import read
    from mjcfbuild.sharing_settings import REMOTE_VARIABLE, redact

    configured = os.environ.get(REMOTE_VARIABLE, "").strip()
    if configured:
        print(f"remote (${REMOTE_VARIABLE}): {redact(configured)}")
    for remote, entry in sorted(read(folder).items()):
        last, total = entry.get("last_build", {}), entry.get("total", {})
        print(
            f"remote {remote}: last build {last.get('remote_hits', 0)} hits, "
            f"{last.get('remote_misses', 0)} misses, {last.get('uploaded', 0)} uploaded; "
            f"in all {total.get('remote_hits', 0)} hits, {total.get('remote_misses', 0)} misses, "
            f"{total.get('remote_rejected', 0)} rejected, {total.get('uploaded', 0)} uploaded"
        )


def _human(size: float) -> str:
    for unit in ("B", "KiB", "MiB", "GiB"):
        if size < 1024 or unit == "GiB":
            return f"{size:.0f} {unit}" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1024
    return f"{size:.1f} TiB"
