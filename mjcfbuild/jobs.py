"""How many tasks a build runs at once where it is not told: read in one place, by every
command (right after parsing, before any fast path) and by the Python API.

Its own module, not the build context's: the no-op fast path reads it and imports nothing more.
"""

from __future__ import annotations

import os

JOBS_VARIABLE = "MJCFBUILD_JOBS"


def default_jobs() -> int:
    """The tasks a build runs at once where it is not told (``-j``, ``jobs=``):
    ``$MJCFBUILD_JOBS``, else one per CPU the process may use. A value that is not a whole
    number above 0 is a :class:`~mjcfbuild.errors.UsageError`."""
    from mjcfbuild.errors import UsageError

    value = os.environ.get(JOBS_VARIABLE, "").strip()
    if value:
        if not value.isdecimal() or int(value) < 1:
            raise UsageError(
                f"{JOBS_VARIABLE}={value}: not a number of jobs",
                hint="set it to how many tasks a build runs at once (1 or more), or unset it "
                "for one per CPU",
            )
        return int(value)
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not Linux
        return max(1, os.cpu_count() or 1)
