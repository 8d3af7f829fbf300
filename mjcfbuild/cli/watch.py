"""``mjcfbuild watch``: build, then build again whenever a file the model depends on changes.

The command stays running, so each rebuild skips what starting ``mjcfbuild build`` costs
(Python, the imports, 0.3-0.4 s) and goes straight to the tasks whose inputs changed, on the
resident workers the last build left. What it watches: :mod:`mjcfbuild.engine.watched`.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild import interrupts
from mjcfbuild.cli import chosen_manifests, positive_seconds
from mjcfbuild.errors import EXIT_OK, EXIT_RESTART, EXIT_TERMINATED

if TYPE_CHECKING:
    from mjcfbuild.engine.watched import Watched

# How long a changed file must stay as it is before the build starts: an editor or exporter
# writing a large mesh is seen part-way, and building that would only be undone.
SETTLE_SECONDS = 0.05
# At most this long waiting for files that keep changing (a long export, a git checkout).
MOST_SETTLE_SECONDS = 2.0


def add_parser(commands) -> None:
    """Register the subcommand."""
    from mjcfbuild.cli.build import build_options

    parser = commands.add_parser(
        "watch",
        help="build, then build again whenever a file the model depends on changes",
        description="Build each manifest, then watch every file its build read or wrote "
        "(after a failed build: every file below the manifest's folder) and build again when "
        "one changes, in this process, until Ctrl-C. Exit code: the last build's; 75 when "
        "mjcfbuild or an installed package changed (start it again).",
    )
    build_options(parser)
    parser.add_argument(
        "--interval",
        type=positive_seconds,
        default=0.1,
        metavar="SECONDS",
        help="how often to look at the watched files (default: 0.1; less often where looking "
        "takes more than a tenth of that, as after a failed build in a large folder)",
    )
    parser.set_defaults(handler=run, dry_run=False, fail_on_change=False)


def run(args: argparse.Namespace) -> int:
    """Build the manifests, then again on each change until Ctrl-C; the last build's code, or
    :data:`EXIT_RESTART` when mjcfbuild's code or an installed package changed."""
    from mjcfbuild.cli.build import say_why_workers_are_off

    if args.verbose and not args.quiet:
        say_why_workers_are_off()
    manifests = [_Manifest(name, args) for name in chosen_manifests(args)]
    try:
        for manifest in manifests:
            manifest.build()
        # A name that is no file (misspelt): its build said so; nothing would ever build it.
        missing = [m for m in manifests if not Path(m.name).is_file()]
        if missing:
            return missing[0].code
        _say(args, f"watching {_count(manifests)} for changes (Ctrl-C to stop)")
        if _watch(manifests, args):
            return EXIT_RESTART
    except _BuildInterrupted:
        raise KeyboardInterrupt from None  # the command's: exit code 130, "interrupted"
    except KeyboardInterrupt:
        # Ctrl-C while no build runs is how the command ends: not an interruption. SIGTERM
        # (how `mjcfbuild watch &` is stopped) keeps its code, 143, as before it was handled.
        terminated = interrupts.terminated()
        interrupts.forget()
        _say(args, "stopped watching")
        if terminated:
            return EXIT_TERMINATED
    return _last_code(manifests)


class _BuildInterrupted(Exception):
    """Ctrl-C came while a build ran."""


def _watch(manifests: list[_Manifest], args: argparse.Namespace) -> bool:
    """Build each manifest again when what it depends on changes, until Ctrl-C or a change to
    mjcfbuild's own code or an installed package (then True: the command must start again,
    which a script running it in a loop tells by its exit code)."""
    looked = 0.0  # how long the last look at the files took
    while True:
        # Looking takes at most a tenth of the time: after a failed build a large folder's
        # files are all watched (a stat each: 5 us, 0.1 s for 20,000).
        time.sleep(max(args.interval, 9 * looked))
        started = time.monotonic()
        due = [(m, m.watched.changed()) for m in manifests]
        looked = time.monotonic() - started
        due = [(m, changed) for m, changed in due if changed and not m.unchanged()]
        for manifest, changed in due:
            changed = _settled(manifest.watched, changed)
            code = sorted(set(changed) & manifest.watched.code)
            if code:
                _say(
                    args,
                    f"{_shown(code)} changed: mjcfbuild or an installed package is no "
                    "longer what this command started with; start it again",
                    always=True,
                )
                return True
            named = manifest.watched.edited(changed) or changed
            _say(args, f"{_shown(named)} changed: building {manifest.name}")
            manifest.build()
            _say(args, f"watching {_count(manifests)} for changes")


class _Manifest:
    """One watched manifest: what its builds depend on, and its last build's exit code."""

    def __init__(self, name: str, args: argparse.Namespace) -> None:
        from mjcfbuild.engine.watched import Watched

        self.name = name
        self.args = args
        self.code = EXIT_OK
        self.watched = Watched()
        self.last_good: Watched | None = None  # what the last build with a stamp watched

    def build(self) -> None:
        """Build it (the no-op fast path first, as ``mjcfbuild build``), then watch what that
        build depends on (:mod:`mjcfbuild.engine.watched`)."""
        from mjcfbuild.cli.build import build_manifest
        from mjcfbuild.engine.watched import Watched, around, from_stamp, without_stamp

        path = Path(self.name)
        before = Watched.take(around(path, self.last_good))
        try:
            self.code = build_manifest(self.name, self.args)
        except KeyboardInterrupt:
            raise _BuildInterrupted() from None
        found = from_stamp(path, not self.args.no_check) if self.code == EXIT_OK else None
        if found is not None:
            self.watched = self.last_good = found
        else:
            self.watched = without_stamp(path, self.last_good, before)

    def unchanged(self) -> bool:
        """Whether the stamp still says nothing changed (a file touched but not edited, one the
        build wrote as it recorded it); if so, watch the files as they are now."""
        from mjcfbuild.engine import stamp
        from mjcfbuild.engine.watched import from_stamp

        if self.last_good is not self.watched:
            return False
        run_check, outside = not self.args.no_check, self.args.allow_outside
        if stamp.nothing_to_do(self.name, run_check, outside) is None:
            return False
        self.watched = self.last_good = from_stamp(Path(self.name), run_check) or self.watched
        return True


def _last_code(manifests: list[_Manifest]) -> int:
    return next((m.code for m in manifests if m.code != EXIT_OK), EXIT_OK)


def _settled(watched: Watched, changed: list[str]) -> list[str]:
    """The files changed since ``watched`` was taken, once none has changed for
    :data:`SETTLE_SECONDS` and none of them is empty (or after :data:`MOST_SETTLE_SECONDS`).

    Saving truncates a file and then writes it; a program writing a large file, or one
    waiting for the CPU on a busy machine, can leave it empty for longer than the settling
    time (measured: a benchmark's URDF edit, with the last build's workers tidying up)."""
    give_up = time.monotonic() + MOST_SETTLE_SECONDS
    while time.monotonic() < give_up:
        now = watched.again()
        time.sleep(SETTLE_SECONDS)
        later = now.changed()
        changed = sorted({*changed, *later})
        if not later and not any(_empty(now, path) for path in changed):
            break
    return changed


def _empty(watched: Watched, path: str) -> bool:
    record = watched.records.get(path)
    return record is not None and record.signature is not None and record.signature[0] == 0


def _say(args: argparse.Namespace, text: str, always: bool = False) -> None:
    if always or not args.quiet:
        print(f"mjcfbuild: {text}", flush=True)


def _count(manifests: list[_Manifest]) -> str:
    """How many files are watched, not counting mjcfbuild's own and the package folders."""
    files = len(
        {
            path
            for m in manifests
            for path in m.watched.records
            if path not in m.watched.code and not path.endswith(os.sep)  # a folder's names
        }
    )
    return f"{files} file{'s' if files != 1 else ''}"


def _shown(paths: list[str]) -> str:
    """The first changed file, from the current folder where that is shorter, and how many
    more."""
    relative = os.path.relpath(paths[0])
    first = paths[0] if relative.startswith("..") else relative
    return first + (f" and {len(paths) - 1} more" if len(paths) > 1 else "")
