"""Records: frozen dataclasses written as JSON and read back, the typed contracts between the
engine and the steps (:mod:`mjcfbuild.steps.payloads`) and between steps (the plan, the mesh
products). Standard library only."""

from __future__ import annotations

import dataclasses
import types
import typing
from dataclasses import dataclass
from typing import Any, Self


@dataclass(frozen=True)
class Record:
    """A frozen dataclass written as JSON and read back: payloads, and what steps write for
    other steps."""

    def to_dict(self) -> dict[str, Any]:
        """The record as JSON-ready data."""
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Self:
        """The record :meth:`to_dict` gave (after a JSON round trip)."""
        hints = typing.get_type_hints(cls)
        values = {}
        for item in dataclasses.fields(cls):
            if item.name in data:
                values[item.name] = _rebuild(hints[item.name], data[item.name])
        return cls(**values)


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
