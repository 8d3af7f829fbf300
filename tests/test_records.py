"""Records (mjcfbuild/records.py): frozen dataclasses written as JSON and read back."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

from mjcfbuild.records import Record, plain


class Pair(NamedTuple):
    first: float
    second: float


@dataclass(frozen=True)
class Inner(Record):
    name: str
    values: list[float]


@dataclass(frozen=True)
class Outer(Record):
    label: str
    count: int
    ratio: float
    flag: bool
    missing: None
    inner: Inner
    inners: list[Inner]
    by_name: dict[str, Inner]
    shape: tuple[int, int]
    pair: Pair
    path: Path
    tags: set[str] = field(default_factory=set)


def example() -> Outer:
    inner = Inner("a", [1.0, 2.5])
    return Outer(
        label="robot",
        count=3,
        ratio=0.5,
        flag=True,
        missing=None,
        inner=inner,
        inners=[inner, Inner("b", [])],
        by_name={"a": inner},
        shape=(2, 3),
        pair=Pair(1.0, 2.0),
        path=Path("meshes/a.stl"),
        tags={"x"},
    )


def test_plain_gives_what_dataclasses_asdict_gives():
    record = example()
    made, expected = plain(record), dataclasses.asdict(record)
    assert made == expected
    assert type(made["pair"]) is Pair and type(made["shape"]) is tuple
    assert made["tags"] is not record.tags  # what is not a plain value is copied, as asdict does


def test_a_record_survives_its_json_form():
    inner = Inner("a", [1.0])
    assert Inner.from_dict(inner.to_dict()) == inner
    assert Inner.from_dict(inner.to_dict()) == inner  # the field types are read once
