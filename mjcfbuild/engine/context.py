"""The context a build runs in: its configuration (:mod:`mjcfbuild.graph.context`) and the
session of the build now running."""

from __future__ import annotations

from dataclasses import dataclass, field

from mjcfbuild.engine.session import BuildSession
from mjcfbuild.graph.context import DEFAULT_STEP_TIMEOUT, STATE_DIR, GraphContext
from mjcfbuild.jobs import default_jobs

__all__ = ["DEFAULT_STEP_TIMEOUT", "STATE_DIR", "BuildContext", "default_jobs"]


@dataclass(frozen=True)
class BuildContext(GraphContext):
    """A build's configuration with its :class:`BuildSession`, started when it is made."""

    session: BuildSession = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "session", BuildSession(self))

    def new_session(self) -> BuildSession:
        """Start a new build of this context: a fresh :attr:`session` (the old one closed)."""
        self.session.close()
        object.__setattr__(self, "session", BuildSession(self))
        return self.session
