"""The chain of parts attached to one another that cannot be placed."""

from __future__ import annotations

from mjcfbuild.compose.chain import stuck_chain


def target(part: str) -> str:
    return {"a": "b_link", "b": "c_link", "c": "a_link", "d": "nowhere"}[part]


def test_a_chain_ending_at_a_name_no_part_has_names_its_last_part():
    owner = {"b_link": "b", "c_link": "c"}
    assert stuck_chain("a", {**owner, "c_link": "d"}, target) == ("d", None)


def test_a_chain_running_into_a_cycle_gives_the_cycle_only():
    owner = {"a_link": "a", "b_link": "b", "c_link": "c", "x_link": "x"}

    def to(part: str) -> str:
        return "a_link" if part == "x" else target(part)

    assert stuck_chain("x", owner, to) == ("c", ["a", "b", "c"])
