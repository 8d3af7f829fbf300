"""What the user sees while a build runs, and the record of what each task did.

On a terminal one status line is redrawn in place; elsewhere (CI logs, pre-commit) each task
that runs prints one plain line when it finishes. doit calls a reporter object; the
:class:`Progress` behind it lives across both stages of a build, so the summary counts each
task once.

The model is announced the moment the tasks that write it (the model and its assets, the
scene) have finished, one of them having run: a line naming the files to open, printed while
the check, previews, tuning report and page still run. doit reports a task's end from its
main thread before it hands out the tasks that depend on it, so the line always comes before
any task that reads the model starts.
"""

from __future__ import annotations

import shutil
import sys
import threading
import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, TextIO

from doit.exceptions import UnmetDependency

RAN, UP_TO_DATE, FAILED, BLOCKED = "ran", "up to date", "failed", "blocked"


@dataclass
class Progress:
    """Outcomes and durations of tasks, and the live display."""

    stream: TextIO = field(default_factory=lambda: sys.stdout)
    quiet: bool = False
    live: bool | None = None
    status: dict[str, str] = field(default_factory=dict)
    durations: dict[str, float] = field(default_factory=dict)
    titles: dict[str, str] = field(default_factory=dict)
    failure_messages: dict[str, str] = field(default_factory=dict)
    notes: dict[str, str] = field(default_factory=dict)
    total: int = 0
    prefix: str = ""  # before each printed line: which robot, where several share an output

    def __post_init__(self) -> None:
        if self.live is None:
            self.live = not self.quiet and getattr(self.stream, "isatty", lambda: False)()
        self._running: dict[str, float] = {}
        self._lock = threading.Lock()
        self._line_shown = False
        self._model_tasks: frozenset[str] = frozenset()
        self._model_line = ""
        self._since = time.perf_counter()
        self.model_ready: float | None = None  # seconds from the build's start to the model

    def announce_model(self, tasks: Iterable[str], line: str, since: float) -> None:
        """Print ``line`` (with the seconds from ``since``, a ``perf_counter``) once every one
        of ``tasks`` has finished well and one of them ran: the model is written."""
        with self._lock:
            self._model_tasks = frozenset(tasks)
            self._model_line = line
            self._since = since
            self._announce()

    def _announce(self) -> None:
        outcomes = [self.status.get(name) for name in self._model_tasks]
        if not outcomes or self.model_ready is not None or RAN not in outcomes:
            return
        if any(outcome not in (RAN, UP_TO_DATE) for outcome in outcomes):
            return
        self.model_ready = time.perf_counter() - self._since
        if self.quiet:
            return
        self.clear()
        self.stream.write(f"{self.prefix}{self._model_line} ({self.model_ready:.2f} s)\n")
        self.stream.flush()
        self._redraw()

    def known(self, names: list[str]) -> None:
        """The tasks of the current stage (for the [done/total] counter)."""
        with self._lock:
            self.total = max(self.total, len({*self.status, *names}))

    def started(self, name: str, title: str) -> None:
        with self._lock:
            self.titles[name] = title
            self._running[name] = time.perf_counter()
            self._redraw()

    def finished(self, name: str, outcome: str, seconds: float | None = None) -> None:
        with self._lock:
            start = self._running.pop(name, None)
            if start is not None:
                self.durations[name] = (
                    seconds if seconds is not None else time.perf_counter() - start
                )
            if self.status.get(name) == RAN and outcome == UP_TO_DATE:
                return  # ran in the planning stage, checked again in the build stage
            self.status[name] = outcome
            if start is not None and not self.quiet and not self.live:
                self._print_line(name, outcome)
            self._redraw()
            self._announce()

    def _print_line(self, name: str, outcome: str) -> None:
        done = sum(1 for s in self.status.values() if s != BLOCKED)
        title = self.titles.get(name, name)
        details = [f"{self.durations.get(name, 0.0):.2f} s"]
        if name in self.notes:
            details.append(self.notes[name])
        mark = "" if outcome == RAN else f" {outcome.upper()}"
        self.stream.write(
            f"{self.prefix}[{done}/{self.total}] {title} ({', '.join(details)}){mark}\n"
        )
        self.stream.flush()

    def _redraw(self) -> None:
        if not self.live:
            return
        done = sum(1 for s in self.status.values() if s != BLOCKED)
        total = max(self.total, 1)
        filled = int(20 * min(done, total) / total)
        bar = "#" * filled + "-" * (20 - filled)
        running = ", ".join(self.titles.get(n, n) for n in self._running)
        text = f"[{bar}] {done}/{self.total} {running}"
        width = shutil.get_terminal_size((100, 20)).columns - 1
        self.stream.write("\r\x1b[2K" + text[:width])
        self.stream.flush()
        self._line_shown = True

    def clear(self) -> None:
        """Remove the live line before the summary is printed."""
        if self.live and self._line_shown:
            self.stream.write("\r\x1b[2K")
            self.stream.flush()
            self._line_shown = False

    def names(self, outcome: str) -> list[str]:
        """Tasks with ``outcome``, in the order they finished."""
        return [name for name, status in self.status.items() if status == outcome]

    def slowest(self, count: int = 3) -> list[tuple[str, float]]:
        """The tasks that took longest, with their seconds."""
        ran = [
            (self.titles.get(n, n), self.durations[n])
            for n in self.names(RAN)
            if n in self.durations
        ]
        return sorted(ran, key=lambda item: -item[1])[:count]


class ProgressReporter:
    """The doit reporter interface, forwarding to a :class:`Progress`.

    ``task`` arguments are doit's untyped ``Task`` objects, hence ``Any``.
    """

    def __init__(self, progress: Progress, timings: dict[str, float]) -> None:
        self.progress = progress
        self.timings = timings  # measured inside each task's action, exact in parallel too

    def initialize(self, tasks: dict[str, Any], selected_tasks: list[str]) -> None:
        self.progress.known(list(tasks))

    def get_status(self, task: Any) -> None:
        pass

    def execute_task(self, task: Any) -> None:
        self.progress.started(task.name, task.title())

    def add_failure(self, task: Any, fail: Any) -> None:
        outcome = BLOCKED if isinstance(fail, UnmetDependency) else FAILED
        self.progress.finished(task.name, outcome, self.timings.get(task.name))
        if outcome == FAILED:
            self.progress.failure_messages[task.name] = fail.get_msg().strip()

    def add_success(self, task: Any) -> None:
        self.progress.finished(task.name, RAN, self.timings.get(task.name))

    def skip_uptodate(self, task: Any) -> None:
        self.progress.finished(task.name, UP_TO_DATE)

    def skip_ignore(self, task: Any) -> None:
        self.progress.finished(task.name, UP_TO_DATE)

    def cleanup_error(self, exception: BaseException) -> None:
        pass

    def runtime_error(self, msg: str) -> None:
        self.progress.failure_messages["(doit)"] = msg

    def teardown_task(self, task: Any) -> None:
        pass

    def complete_run(self) -> None:
        pass
