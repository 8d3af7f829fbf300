"""``mjcfbuild workers``: show or stop the resident workers waiting for the next build."""

from __future__ import annotations

import argparse
import os
from pathlib import Path


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "workers",
        help="show or stop the worker processes that wait for the next build",
        description=(
            "A build leaves its worker processes running, with MuJoCo loaded and the model's "
            "meshes processed, for the next build to use. They wait "
            "$MJCFBUILD_RESIDENT_WORKERS seconds (default 900 where a build runs at a "
            "terminal; 0 turns them off; off by default in CI and git hooks) and then exit. "
            "Folder: $MJCFBUILD_RESIDENT_DIR, else $XDG_RUNTIME_DIR/mjcfbuild-<uid>, else the "
            "temporary folder's."
        ),
    )
    parser.add_argument(
        "action",
        nargs="?",
        default="show",
        choices=("show", "stop"),
        help="show (default): the waiting workers and their memory; stop: end them now",
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Show or stop the waiting workers."""
    from mjcfbuild.engine.resident import (
        answer_seconds,
        folder_problem,
        idle_seconds,
        resident_dir_path,
        resident_pids,
        shut_down,
    )

    folder = resident_dir_path(os.environ)
    problem = folder_problem(folder)
    if problem is not None:
        print(f"mjcfbuild: resident workers are off: {problem}; every build starts its own workers")
        return 0
    if args.action == "stop":
        # Each is asked over its own socket; one that takes the request and does not confirm
        # (stopped, or in a debugger) is killed only once its command line shows it is one.
        seconds = min(answer_seconds(os.environ), 2.0)
        stopped = sum(shut_down(path, folder, seconds) for path in sorted(folder.glob("*-*.sock")))
        print(f"mjcfbuild: stopped {stopped} waiting worker{'' if stopped == 1 else 's'}")
        return 0
    pids = resident_pids(folder)
    seconds = idle_seconds(os.environ)
    print(f"folder: {folder}")
    print(f"wait: {seconds:g} s" + (" (resident workers are off)" if seconds == 0 else ""))
    print(f"waiting: {len(pids)}")
    for pid in pids:
        print(f"  pid {pid}: {_megabytes(pid)}")
    return 0


def _megabytes(pid: int) -> str:
    """The memory a process holds (resident set), where the system tells it."""
    try:
        pages = int(Path(f"/proc/{pid}/statm").read_text().split()[1])
    except (OSError, IndexError, ValueError):
        return "memory unknown"
    return f"{pages * os.sysconf('SC_PAGE_SIZE') / 2**20:.0f} MB"
