"""Warnings one line per kind (mjcfbuild/warning_groups.py): which warnings are of one kind and
how a kind reads."""

from __future__ import annotations

from mjcfbuild.warning_groups import group_warnings


def test_warnings_that_differ_only_in_their_subject_are_one_line():
    boxes = [
        f"robot.urdf:{10 + i}: link 'pad{i}' visual 0 has box size 0 0 0; dropped it"
        for i in range(8)
    ]
    assert group_warnings(boxes, "all in report.md") == [
        "robot.urdf:10: 8 × link '…' visual 0 has box size 0 0 0; dropped it: "
        "pad0, pad1, pad2, ... 5 more (all in report.md)"
    ]


def test_values_that_vary_are_elided_and_those_that_agree_are_kept():
    notes = [
        f"joint '{name}' has velocity=\"0\" in the URDF (line {line}): not a limit"
        for name, line in (("a", 3), ("b", 9), ("c", 20))
    ]
    assert group_warnings(notes) == [
        "3 × joint '…' has velocity=\"0\" in the URDF (line …): not a limit: a, b, c"
    ]


def test_different_kinds_stay_apart_in_the_order_they_came():
    warnings = [
        "mesh 'a' encloses no volume; it uses shell inertia",
        "robot.urdf: undeclared XML namespace prefix(es) foo; elements using them are ignored",
        "mesh 'b' encloses no volume; it uses shell inertia",
        "the URDF's link 'x' isn't moved",
    ]
    assert group_warnings(warnings) == [
        "2 × mesh '…' encloses no volume; it uses shell inertia: a, b",
        warnings[1],
        warnings[3],
    ]


def test_the_same_sentence_at_several_places_lists_the_places():
    lines = [
        f'r.urdf:{n}: <origin xyz="1,2,3"> uses commas between numbers; read them as spaces'
        for n in (4, 8)
    ]
    assert group_warnings(lines) == [
        'r.urdf:4: 2 × <origin xyz="1,2,3"> uses commas between numbers; read them as spaces: '
        "r.urdf:4, r.urdf:8"
    ]


def test_a_single_warning_and_repeats_print_as_they_are():
    assert group_warnings(["joint 'a' has no limit", "joint 'a' has no limit"]) == [
        "joint 'a' has no limit"
    ]
    assert group_warnings([]) == []
