"""Pointing errors about robot.yaml settings at their line.

Build steps name a manifest setting by its key path, like ``robot.yaml mujoco_inputs.cameras[0]``
(and, inside a raw MJCF block, the block's own line number). Positions are only worked out when
such an error is reported, so successful builds never parse the manifest twice.
"""

from __future__ import annotations

import re
from pathlib import Path

from mjcfbuild.errors import MjcfbuildError

# A key is anything but dots and brackets: a home: key may be a glob ("*finger*") or a joint
# name with characters no identifier has.
# A key with dots or brackets in it (a file name: 'torso.dae') is written ["torso.dae"].
_KEY_PART = re.compile(r'([^.\[\]]+)|\[(\d+)\]|\["([^"]*)"\]')
_BLOCK_INDICATORS = ("|", ">")


def key_path(dotted: str) -> tuple[str | int, ...] | None:
    """``mujoco_inputs.cameras[0]`` as ``("mujoco_inputs", "cameras", 0)``; None if not a path."""
    parts: list[str | int] = []
    position = 0
    for match in _KEY_PART.finditer(dotted):
        gap = dotted[position : match.start()]
        if gap not in ("", "."):
            return None
        if match.group(1):
            parts.append(match.group(1))
        elif match.group(2):
            parts.append(int(match.group(2)))
        else:
            parts.append(match.group(3))
        position = match.end()
    return tuple(parts) if parts and position == len(dotted) else None


def key_segment(key: str) -> str:
    """``key`` as a part of a dotted key path: ``.key``, or ``["key"]`` where it has dots or
    brackets (a file name)."""
    return f'["{key}"]' if re.search(r"[.\[\]]", key) and '"' not in key else f".{key}"


def key_line(manifest_file: Path | None, dotted: str) -> int | None:
    """The line of ``robot.yaml`` where the setting ``dotted`` (``source.urdf``) is written;
    None without a manifest file, or when it cannot be read or has no such key."""
    path = key_path(dotted)
    if manifest_file is None or path is None:
        return None
    from mjcfbuild.manifest.yamlpos import YamlSyntaxError, load_with_positions

    try:
        _, positions = load_with_positions(manifest_file.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, YamlSyntaxError):
        return None
    found = positions.of(path)
    return found[0] if found else None


def pinpoint(error: MjcfbuildError, manifest_label: str, manifest_file: Path) -> MjcfbuildError:
    """Give ``error`` the manifest's line and column when its file is ``LABEL KEY.PATH``."""
    location = error.location
    if location is None:
        return error
    # Steps name the manifest relative to its own folder (the same in every folder), the
    # engine as the command line gave it.
    label = next(
        (
            name
            for name in (manifest_label, manifest_file.name)
            if location.file.startswith(name + " ")
        ),
        None,
    )
    if label is None:
        return error
    path = key_path(location.file[len(label) + 1 :])
    if path is None:
        return error
    from mjcfbuild.manifest.yamlpos import YamlSyntaxError, load_with_positions

    try:
        text = manifest_file.read_text(encoding="utf-8")
        _, positions = load_with_positions(text)
    except (OSError, UnicodeDecodeError, YamlSyntaxError):  # edited since: keep the key path
        return error
    if location.line is not None and path in positions.values:
        # A line inside a block of text (raw MJCF): count from the block's first line.
        line, column = positions.values[path]
        lines = text.splitlines()
        starts_block = line <= len(lines) and lines[line - 1][column - 1 :].startswith(
            _BLOCK_INDICATORS
        )
        location.line = line + (1 if starts_block else 0) + location.line - 1
        location.column = None
    else:
        found = positions.of(path)
        if found is None:
            return error
        location.line, location.column = found
    error.message = f"{location.file[len(label) + 1 :]}: {error.message}"
    location.file = manifest_file.name
    return error
