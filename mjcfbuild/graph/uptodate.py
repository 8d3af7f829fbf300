"""The up-to-date checks every task carries besides its file dependencies.

* :class:`ParamsUnchanged` - the task's parameters and the versions of the tools it uses are
  the ones of its last successful run (stored in full, so ``explain`` can say which changed).
* :func:`outputs_intact` - every file the task wrote still has the bytes it wrote; doit
  itself only checks that targets exist, so a hand-edited model would otherwise survive.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

from mjcfbuild.graph.hashes import HashCache


class ParamsUnchanged:
    """True when ``params`` equal the ones saved by the last successful run."""

    KEY = "_params"

    def __init__(self, params: dict) -> None:
        # Normalise through JSON so tuples and lists compare equal after a round trip.
        self.params = json.loads(json.dumps(params, sort_keys=True))

    def configure_task(self, task: Any) -> None:
        """Save the parameters with the task's values when it succeeds (doit hook)."""
        task.value_savers.append(lambda: {self.KEY: self.params})

    def __call__(self, task: Any, values: dict) -> bool:
        return values.get(self.KEY) == self.params

    def changes(self, values: dict) -> list[str]:
        """Dotted names of the parameters that differ from the saved ones."""
        return _differences(values.get(self.KEY), self.params, "")

    def __repr__(self) -> str:
        return "parameters"


def _differences(old: object, new: object, prefix: str) -> list[str]:
    if isinstance(old, dict) and isinstance(new, dict):
        result = []
        for key in sorted(set(old) | set(new)):
            result += _differences(old.get(key), new.get(key), f"{prefix}.{key}" if prefix else key)
        return result
    return [] if old == new else [prefix or "(all)"]


# The checks below are functions carrying a `reason` attribute for `explain` (engine/status.py);
# mypy does not know attributes set on a function, hence the attr-defined ignores.


def outputs_intact(hashes: HashCache, out_dir: Path) -> Callable:
    """An uptodate check: the outputs recorded by the last run still have their bytes (those
    of the output folder ``out_dir``, named by where they are in it)."""

    def check(task: Any, values: dict) -> bool | None:
        outputs = values.get("outputs")
        if outputs is None:
            check.reason = "it has not run in this output folder yet"  # type: ignore[attr-defined]
            return False
        for path, digest in outputs.items():
            try:
                if hashes.md5(path) != digest:
                    check.reason = _changed_output(path, out_dir)  # type: ignore[attr-defined]
                    return False
            except OSError:
                check.reason = f"output deleted since it was built: {path}"  # type: ignore[attr-defined]
                return False
        return True

    check.reason = ""  # type: ignore[attr-defined]
    return check


def _changed_output(path: str, out_dir: Path) -> str:
    """Why a task whose output ``path`` no longer holds what its last run wrote is stale. The
    build's own records and report pictures change only when a build is cut short, and no
    build stops at them; a published output may have been edited by hand."""
    import os

    from mjcfbuild.ownership import STATE_DIR

    first = Path(os.path.relpath(path, out_dir)).parts[0]
    if first in (STATE_DIR, "report"):
        return f"output changed since its task last finished (a build cut short): {path}"
    return (
        f"output edited since it was built: {path} (a build stops at it unless git has it in HEAD)"
    )


def always_stale(reason: str) -> Callable:
    """An uptodate check that is always false, carrying the reason for ``explain``."""

    def check(task: Any, values: dict) -> bool:
        return False

    check.reason = reason  # type: ignore[attr-defined]
    return check


def planned_meshes_exist(plan: Path) -> Callable:
    """An uptodate check of the plan task: every mesh file the last plan found still exists.

    A mesh deleted after a build makes the plan run again, which names the URDF line that
    refers to it, the same error a clean build gives (doit alone would fail the mesh task with
    its own "Dependent file ... does not exist").
    """

    def check(task: Any, values: dict) -> bool:
        from mjcfbuild.steps.plan_record import read_plan

        try:
            meshes = read_plan(plan).meshes
        except (OSError, ValueError, KeyError, TypeError):
            return True  # no plan yet: the task runs anyway for its missing target
        for mesh in meshes:
            if not Path(mesh.path).is_file():
                check.reason = f"mesh file gone since the last plan: {mesh.path}"  # type: ignore[attr-defined]
                return False
        return True

    check.reason = ""  # type: ignore[attr-defined]
    return check
