"""MuJoCo errors while simulating, as one line naming what ran and what to do.

MuJoCo stops a simulation it cannot go on with (``mj_stackAlloc: out of memory`` when the
contacts outgrow the arena, for one) by raising ``mujoco.FatalError`` from Python. Such a
stop says something about the model, not about mjcfbuild: the check reports it as a failure,
and a step that simulates raises it as a :class:`~mjcfbuild.errors.CheckError`, never as an
internal error.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator


class SimulationStopped(Exception):
    """MuJoCo stopped a simulation; ``line`` says which, why and what to do."""

    def __init__(self, line: str) -> None:
        super().__init__(line)
        self.line = line


@contextlib.contextmanager
def simulating(what: str) -> Iterator[None]:
    """Run the simulation ``what`` (e.g. "1 s of pseudorandom control"): a MuJoCo error in it
    raises :class:`SimulationStopped`."""
    import mujoco

    try:
        yield
    except (mujoco.FatalError, mujoco.UnexpectedError) as exc:
        raise SimulationStopped(stopped_line(what, str(exc))) from None


def stopped_line(what: str, error: str) -> str:
    """The line for MuJoCo's ``error`` (its first line) stopping ``what``."""
    first = error.strip().splitlines()[0] if error.strip() else "an error"
    if "out of memory" in error or "arena" in error:
        hint = (
            'give the model more memory with <size memory="..."/> in mujoco_inputs raw, '
            "or fewer colliding geoms; see docs/mujoco_inputs.md"
        )
    else:
        hint = "simulate the model in MuJoCo's viewer to see where it goes wrong"
    return f"MuJoCo stopped {what}: {first} ({hint})"
