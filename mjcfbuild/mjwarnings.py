"""MuJoCo's warnings as build warnings, instead of terminal lines and a MUJOCO_LOG.TXT file.

Left alone, MuJoCo prints each warning and appends it to ``MUJOCO_LOG.TXT`` in the current
folder: a file outside the output folder, in whatever folder the user ran the build from.
"""

from __future__ import annotations

_collected: list[str] = []
_installed = False


def capture_mujoco_warnings() -> None:
    """From now on in this process, keep MuJoCo's warnings for :func:`take_mujoco_warnings`."""
    global _installed
    if not _installed:
        import mujoco

        mujoco.set_mju_user_warning(_collected.append)
        _installed = True


def take_mujoco_warnings() -> list[str]:
    """The warnings MuJoCo gave since the last call, each once, in order."""
    taken = list(dict.fromkeys(_collected))
    _collected.clear()
    return taken
