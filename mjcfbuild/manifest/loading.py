"""Reading ``robot.yaml`` into a validated :class:`Manifest`, with errors that point at lines."""

from __future__ import annotations

import difflib
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import ManifestError

if TYPE_CHECKING:
    from pydantic import BaseModel, ValidationError
    from pydantic_core import ErrorDetails

    from mjcfbuild.manifest.models import Manifest
    from mjcfbuild.manifest.yamlpos import Positions


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
        text = data.decode("utf-8")
    except FileNotFoundError:
        raise ManifestError(
            "manifest not found", file=path.name, hint="run 'mjcfbuild init SOURCE' to create one"
        ) from None
    except IsADirectoryError:
        raise ManifestError(
            "this is a folder, not a manifest", file=path.name, hint="pass the path of robot.yaml"
        ) from None
    except UnicodeDecodeError as exc:
        raise ManifestError(
            f"not UTF-8 text (byte {exc.start})", file=path.name, hint="save the file as UTF-8"
        ) from None
    except OSError as exc:
        raise ManifestError(f"cannot read: {exc.strerror}", file=path.name) from None
    # Errors name the manifest relative to its own folder, like every other file of a build.
    return parse_manifest(text, display_name=path.name)


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
    try:
        return Manifest.model_validate(data)
    except ValidationError as exc:
        raise manifest_error_from_validation(exc, positions, display_name) from None


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
    ``function-after[...]``): only keys and list positions that are in the manifest."""
    kept: tuple = ()
    for part in loc:
        if isinstance(part, int) or (*kept, part) in positions.keys:
            kept = (*kept, part)
        elif part not in _UNION_TAG_HINTS and "[" not in part and "-" not in part:
            kept = (*kept, part)  # a key the manifest lacks (a missing required key)
    return kept


_UNION_TAG_HINTS = {"str", "int", "float", "bool", "list", "dict", "none", "lax-or-strict"}


def _most_relevant(errors: list[ErrorDetails]) -> ErrorDetails:
    """Prefer errors about a specific key, then errors that are not just "wrong type" (of one
    member of a union, when another member's error says more), over errors about a mapping."""
    return sorted(
        errors,
        key=lambda e: (e["type"] == "model_type", e["type"].endswith("_type"), -len(e["loc"])),
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
    """What is wrong, and what would be allowed, for one pydantic error."""
    kind = error["type"]
    loc = tuple(error["loc"])
    value = error.get("input")
    if kind == "extra_forbidden":
        key = str(loc[-1]) if loc else "?"
        if loc in _REMOVED:
            return _REMOVED[loc]
        allowed = _allowed_keys(loc[:-1])
        suggestion = difflib.get_close_matches(key, allowed, n=1)
        text = f"unknown key '{key}'"
        if suggestion:
            text += f"; did you mean '{suggestion[0]}'?"
        if allowed:
            text += f" allowed keys: {', '.join(allowed)}"
        return text
    if kind == "missing":
        return "this key is required"
    if kind == "literal_error":
        expected = error.get("ctx", {}).get("expected", "")
        return f"{_show(value)} is not allowed; use one of {expected}"
    if kind in {"string_type", "string_too_short"}:
        return f"expected a non-empty string, got {_show(value)}"
    if kind == "string_pattern_mismatch":
        return (
            f"{_show(value)} is not a valid name; use letters, digits, '_', '-' and '.', "
            "starting with a letter or digit"
        )
    if kind in {"bool_type", "bool_parsing"}:
        return f"expected true or false, got {_show(value)}"
    if kind in {"int_type", "int_parsing", "float_type", "float_parsing", "int_from_float"}:
        return f"expected a number, got {_show(value)}"
    if kind in {"dict_type", "model_type", "model_attributes_type"}:
        return f"expected a mapping of keys, got {_show(value)}"
    if kind in {"list_type", "tuple_type"}:
        return f"expected a list, got {_show(value)}"
    if kind in {"greater_than", "greater_than_equal", "less_than", "less_than_equal"}:
        return error["msg"].lower().replace("input", f"{_show(value)}")
    if kind == "value_error":
        return str(error.get("ctx", {}).get("error", error["msg"]))
    return error["msg"]


def _show(value: object) -> str:
    if isinstance(value, (dict, list)):
        return "a mapping" if isinstance(value, dict) else "a list"
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _allowed_keys(loc: tuple) -> list[str]:
    """The keys the model at ``loc`` accepts, walking the manifest models."""
    import typing

    from mjcfbuild.manifest.models import Manifest

    model: type[BaseModel] | None = Manifest
    keyed = False  # the part before was a mapping of names to models (motors.define)
    for part in loc:
        if keyed:
            keyed = False
            continue
        if isinstance(part, int):  # an item of a list of models: the model itself
            continue
        if model is None:
            return []
        field = model.model_fields.get(str(part))
        if field is None:
            return []
        keyed = typing.get_origin(field.annotation) is dict
        model = _model_of(field.annotation)
    if model is None:
        return []
    return sorted(model.model_fields)


def _model_of(annotation: object) -> type[BaseModel] | None:
    from pydantic import BaseModel

    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in getattr(annotation, "__args__", ()) or ():
        found = _model_of(arg)
        if found is not None:
            return found
    return None
