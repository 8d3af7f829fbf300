"""Positions recorded while loading YAML."""

from __future__ import annotations

from mjcfbuild.manifest.yamlpos import load_with_positions


def test_positions_of_keys_and_list_items():
    data, positions = load_with_positions("a:\n  b: 1\n  c:\n    - x\n    - y\n")
    assert data == {"a": {"b": 1, "c": ["x", "y"]}}
    assert positions.keys[("a", "b")] == (2, 3)
    assert positions.values[("a", "c", 1)] == (5, 7)
    # unknown deeper paths fall back to the nearest known parent
    assert positions.of(("a", "b", "deeper")) == (2, 3)


def test_anchors_and_merge_keys_still_work():
    data, _ = load_with_positions("base: &b {x: 1}\nother:\n  <<: *b\n  y: 2\n")
    assert data["other"] == {"x": 1, "y": 2}
