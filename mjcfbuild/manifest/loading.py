"""Reading ``robot.yaml`` into a validated :class:`Manifest`, with errors that point at lines."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from mjcfbuild.errors import ManifestError

if TYPE_CHECKING:
    from pydantic import ValidationError
    from pydantic_core import ErrorDetails

    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.manifest.yamlpos import Positions


def _not_found_hint(path: Path) -> str:
    """What to do about a manifest that is not there: the one of that name in a folder above,
    where there is one (a command run from the description's urdf/ folder), else init."""
    import os

    folder = path.absolute().parent
    for up, above in enumerate(list(folder.parents)[:4], 1):
        found = above / path.name
        if found.is_file():
            how_far = "one folder" if up == 1 else f"{up} folders"
            return f"'{os.path.relpath(found)}' is {how_far} up: pass its path, or run there"
    return "run 'mjcfbuild init SOURCE' to create one"


def load_manifest(path: str | Path) -> Manifest:
    """Read and validate a manifest file.

    Raises :class:`ManifestError` with ``file:line:column`` for unreadable files, YAML syntax
    errors and every kind of validation error.
    """
    path = Path(path)
    # Like every other error about the manifest, these name it relative to its own folder;
    # callers show it relative to the current one (ManifestError.relocate).
    try:
        data = path.read_bytes()
        _refuse_other_kinds(path, data)
        text = data.decode("utf-8")
    except FileNotFoundError:
        raise ManifestError(
            "manifest not found", file=path.name, hint=_not_found_hint(path)
        ) from None
    except IsADirectoryError:
        raise ManifestError(
            "this is a folder, not a manifest", file=path.name, hint="pass the path of robot.yaml"
        ) from None
    except UnicodeDecodeError as exc:
        before = exc.object[: exc.start]
        raise ManifestError(
            f"not UTF-8 text (byte {exc.start}: 0x{exc.object[exc.start]:02x})",
            file=path.name,
            line=before.count(b"\n") + 1,
            column=exc.start - (before.rfind(b"\n") + 1) + 1,
            hint="save the file as UTF-8",
        ) from None
    except OSError as exc:
        raise ManifestError(f"cannot read: {exc.strerror}", file=path.name) from None
    # Errors name the manifest relative to its own folder, like every other file of a build.
    return parse_manifest(text, display_name=path.name)


def _refuse_other_kinds(path: Path, data: bytes) -> None:
    """Refuse a file that is plainly not a manifest (a URDF, a mesh, an image...) by what it
    is, rather than by the YAML or UTF-8 error reading it as one would give."""
    import shlex

    from mjcfbuild.sources.kind import not_a_manifest

    kind = not_a_manifest(path, data)
    if kind is None:
        return
    description = kind in ("a URDF", "a xacro file")
    raise ManifestError(
        f"this is {kind}, not a manifest",
        file=path.name,
        hint=f"'mjcfbuild init {shlex.quote(str(path))}' writes a robot.yaml that builds it"
        if description
        else "pass the path of robot.yaml",
    )


def parse_manifest(text: str, display_name: str = "robot.yaml") -> Manifest:
    """Validate manifest text; ``display_name`` is the file name used in error messages."""
    from pydantic import ValidationError

    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.manifest.yamlpos import YamlSyntaxError, load_with_positions

    try:
        data, positions = load_with_positions(text)
    except YamlSyntaxError as exc:
        raise ManifestError(
            exc.message, file=display_name, line=exc.line, column=exc.column, hint=exc.hint
        ) from None
    if data is None:
        raise ManifestError(
            "the manifest is empty",
            file=display_name,
            hint="it needs at least 'name' and 'source'; 'mjcfbuild init' writes a starting one",
        )
    if not isinstance(data, dict):
        raise ManifestError(
            "the manifest must be a mapping of keys (name, source, ...)",
            file=display_name,
            line=1,
            column=1,
        )
    _args_as_written(data, positions)
    try:
        return Manifest.model_validate(data)
    except ValidationError as exc:
        raise manifest_error_from_validation(exc, positions, display_name) from None


def _args_as_written(data: dict, positions: Positions) -> None:
    """Give every xacro argument written as an unquoted number (``source.args``, an
    ``attach:`` part's ``args``) the text written: ``name:=value`` on xacro's command line
    passes text, where YAML read ``1.10`` as 1.1 and ``0010`` as 8 (a link named
    base_v1.10_0010 came out base_v1.1_8). Booleans stay as they were: ``yes``, ``on`` and
    ``TRUE`` are YAML's true, which xacro is given as ``true``."""
    for path, text in positions.plain.items():
        if not _is_args_value(path):
            continue
        parent: Any = data
        for key in path[:-1]:
            parent = parent[key]
        value = parent.get(path[-1]) if isinstance(parent, dict) else None
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[path[-1]] = text


def _is_args_value(path: tuple) -> bool:
    """Whether ``path`` is that of a xacro argument's value in robot.yaml."""
    match path:
        case ("source", "args", str()) | ("attach", int(), "source", "args", str()):
            return True
    return False


def manifest_error_from_validation(
    exc: ValidationError, positions: Positions, display_name: str
) -> ManifestError:
    """Turn the first pydantic error into a one-line, positioned :class:`ManifestError`."""
    errors = exc.errors(include_url=False)
    for item in errors:
        item["loc"] = _real_keys(tuple(item["loc"]), positions)
    error = _most_relevant(errors)
    loc = tuple(error["loc"])
    where = positions.of(loc)
    line, column = where if where else (None, None)
    message = f"{_dotted(loc)}: {describe(error)}" if loc else describe(error)
    more = sum(1 for other in errors if not _related(tuple(other["loc"]), loc))
    hint = f"{more} more problem{'s' if more > 1 else ''} after this one" if more else None
    return ManifestError(message, file=display_name, line=line, column=column, hint=hint)


def _related(a: tuple, b: tuple) -> bool:
    """Whether one location contains the other (errors of one union, or of one key)."""
    shorter = min(len(a), len(b))
    return a[:shorter] == b[:shorter]


def _real_keys(loc: tuple, positions: Positions) -> tuple:
    """``loc`` without the names pydantic gives the members of a union (``constrained-str``,
    ``function-after[...]``, a model's class name: ``SelfCollisionSettings``): only keys and
    list positions that are in the manifest."""
    kept: tuple = ()
    for part in loc:
        if isinstance(part, int) or (*kept, part) in positions.keys:
            kept = (*kept, part)
        elif _is_field_name(part):
            kept = (*kept, part)  # a key the manifest lacks (a missing required key)
    return kept


_UNION_TAG_HINTS = {"str", "int", "float", "bool", "list", "dict", "none", "lax-or-strict"}


def _is_field_name(part: str) -> bool:
    """Whether ``part`` of a pydantic location can be a key: not a union member's tag, which
    is a type (``str``), a validator (``function-after[...]``) or a class (``Settings``);
    robot.yaml's keys are snake_case."""
    return (
        part not in _UNION_TAG_HINTS
        and "[" not in part
        and "-" not in part
        and not (part[:1].isupper())
    )


def _most_relevant(errors: list[ErrorDetails]) -> ErrorDetails:
    """Prefer errors about a specific key, then errors that are not just "wrong type" (of one
    member of a union, when another member's error says more), over errors about a mapping;
    a key given but unknown over one missing beside it (a misspelt key: ``mesh_name`` for
    ``mesh`` says which to write)."""
    return sorted(
        errors,
        key=lambda e: (
            e["type"] == "model_type",
            e["type"].endswith("_type"),
            -len(e["loc"]),
            e["type"] == "missing",
        ),
    )[0]


def _dotted(loc: tuple) -> str:
    text = ""
    for part in loc:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


# Keys earlier versions accepted, and what replaced them.
_REMOVED = {
    ("ros2_control",): (
        "the ros2_control section is gone: actuators and a home keyframe are built by default "
        "(from <ros2_control> too); tune them with actuators: and home: (docs/simulation.md)"
    ),
}


def describe(error: ErrorDetails) -> str:
    """What is wrong, and what would be allowed, for one pydantic error of robot.yaml."""
    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.schema_errors import describe_error

    return describe_error(error, Manifest, _REMOVED)
