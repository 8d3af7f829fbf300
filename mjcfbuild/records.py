"""Records: frozen dataclasses written as JSON and read back, the typed contracts between the
engine and the steps (:mod:`mjcfbuild.steps.payloads`) and between steps (the plan, the mesh
products). Standard library only."""

from __future__ import annotations

import copy
import dataclasses
import types
import typing
from dataclasses import dataclass
from typing import Any, Self

# Values copy.deepcopy returns as they are, which :func:`plain` need not copy either.
_ATOMIC = frozenset({str, int, float, bool, type(None)})
# Each record class's field types, read once: typing.get_type_hints costs 0.3 ms a call.
_HINTS: dict[type, dict[str, Any]] = {}


@dataclass(frozen=True)
class Record:
    """A frozen dataclass written as JSON and read back: payloads, and what steps write for
    other steps."""

    def to_dict(self) -> dict[str, Any]:
        """The record as JSON-ready data."""
        return plain(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Self:
        """The record :meth:`to_dict` gave (after a JSON round trip)."""
        hints = _HINTS.get(cls)
        if hints is None:
            hints = _HINTS[cls] = typing.get_type_hints(cls)
        values = {}
        for item in dataclasses.fields(cls):
            if item.name in data:
                values[item.name] = _rebuild(hints[item.name], data[item.name])
        return cls(**values)


def plain(value: Any) -> Any:
    """``value`` with every dataclass in it made a dict: what ``dataclasses.asdict`` gives,
    without its deep copy of every string and number (a third of planning g1's tasks)."""
    if type(value) in _ATOMIC:
        return value
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {item.name: plain(getattr(value, item.name)) for item in dataclasses.fields(value)}
    if isinstance(value, tuple) and hasattr(value, "_fields"):  # a named tuple
        return type(value)(*[plain(item) for item in value])
    if isinstance(value, list | tuple):
        return type(value)(plain(item) for item in value)
    if isinstance(value, dict):
        return type(value)((plain(key), plain(item)) for key, item in value.items())
    return copy.deepcopy(value)


def _rebuild(hint: Any, data: Any) -> Any:
    """``data`` as the type ``hint`` names, for the record field types used here."""
    if data is None:
        return None
    if isinstance(hint, type) and issubclass(hint, Record):
        return hint.from_dict(data)
    origin = typing.get_origin(hint)
    arguments = typing.get_args(hint)
    if origin in (types.UnionType, typing.Union):
        for option in arguments:
            if option is not type(None):
                return _rebuild(option, data)
    if origin is list:
        return [_rebuild(arguments[0], item) for item in data]
    if origin is tuple:
        return tuple(data)
    if origin is dict:
        return {key: _rebuild(arguments[1], item) for key, item in data.items()}
    return data
