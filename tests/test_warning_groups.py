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


def test_values_that_agree_are_kept_in_the_line():
    notes = [
        f"joint '{name}' has velocity=\"0\" in the URDF: not a limit" for name in ("a", "b", "c")
    ]
    assert group_warnings(notes) == [
        "3 × joint '…' has velocity=\"0\" in the URDF: not a limit: a, b, c"
    ]


def test_warnings_that_differ_in_more_than_their_subject_show_the_first_whole():
    # A subject and its line would read "joint '…' ... (line …)": the first one is shown.
    notes = [
        f"joint '{name}' has velocity=\"0\" in the URDF (line {line}): not a limit"
        for name, line in (("a", 3), ("b", 9), ("c", 20))
    ]
    assert group_warnings(notes) == [
        "joint 'a' has velocity=\"0\" in the URDF (line 3): not a limit (and 2 more like it: b, c)"
    ]


def _dropped_boxes(shapes: list[tuple[int | None, str, int, str]]) -> list[str]:
    """prepared.py's warning for each zero-sized visual box: (URDF line or None, link, visual
    index, size)."""
    return [
        ("" if line is None else f"robot.urdf:{line}: ")
        + f"link '{link}' visual {index} has box size {size}; dropped it"
        for line, link, index, size in shapes
    ]


def test_warnings_that_differ_in_their_figures_alone_list_where_they_are():
    # Only numbers vary: the line listed the visuals' indices, "(and 2 more like it: 2, 3)",
    # which name nothing a user can find; each one's URDF line does.
    boxes = _dropped_boxes(
        [(31, "base", 1, "0 0.1 0"), (35, "base", 2, "0.2 0 0"), (39, "base", 3, "0 0 0.3")]
    )
    assert group_warnings(boxes, "all in report.md") == [
        f"{boxes[0]} (and 2 more like it: robot.urdf:35, robot.urdf:39)"
    ]


def test_the_first_warnings_subject_is_not_listed_again_and_each_subject_once():
    # Link 'a' has two dropped boxes: the line read "... link 'a' ... (and 3 more like it: b,
    # a, b)".
    boxes = _dropped_boxes(
        [
            (31, "a", 0, "0 0.1 0"),
            (35, "b", 1, "0.2 0 0"),
            (39, "a", 2, "0 0 0.3"),
            (43, "b", 3, "0 0.4 0"),
        ]
    )
    assert group_warnings(boxes, "all in report.md") == [f"{boxes[0]} (and 3 more like it: b)"]


def test_warnings_with_nothing_to_tell_them_apart_by_list_no_subjects():
    # No location and the same link: the line ended "(and 2 more like it: 2, 3)" (the visuals'
    # indices); without figures it would end "like it: )". The report lists them all.
    boxes = _dropped_boxes(
        [(None, "base", 1, "0 0.1 0"), (None, "base", 2, "0.2 0 0"), (None, "base", 3, "0 0 0.3")]
    )
    assert group_warnings(boxes, "all in report.md") == [
        f"{boxes[0]} (and 2 more like it; all in report.md)"
    ]
    assert group_warnings(boxes) == [f"{boxes[0]} (and 2 more like it)"]
    # The same warnings at one line: only the first's own location, which is not listed again.
    same = _dropped_boxes([(31, "base", 1, "0 0.1 0"), (31, "base", 2, "0.2 0 0")])
    assert group_warnings(same) == [f"{same[0]} (and 1 more like it)"]


def test_inertia_repairs_read_with_their_figures():
    """Each repair's figures are its own: elided, the line read "principal moments … … … ->
    … … …" (a generated five-link arm's report)."""
    repairs = [
        "urdf/robot.urdf:4: body 'l1': principal inertia too small for a moving body; "
        "principal moments 0 0 0 -> 1e-08 1e-08 1e-08",
        "urdf/robot.urdf:7: body 'l2': principal inertia too small for a moving body; "
        "principal moments 0 1e-09 2e-09 -> 1e-08 1e-08 1e-08",
        "urdf/robot.urdf:10: body 'l3': principal inertia breaks A + B >= C; "
        "principal moments 0.01 0.01 0.05 -> 0.025000000025 0.025000000025 0.05",
        "urdf/robot.urdf:13: body 'l4': principal inertia breaks A + B >= C; "
        "principal moments 0.01 0.02 0.09 -> 0.040000000045 0.050000000045 0.09",
        "urdf/robot.urdf:16: body 'l5': principal inertia breaks A + B >= C; "
        "principal moments 0.0001 0.001 0.002 -> 0.000550000001 0.001450000001 0.002",
    ]
    assert group_warnings(repairs, "all in mjcf/report/report.md") == [
        f"{repairs[0]} (and 1 more like it: l2)",
        f"{repairs[2]} (and 2 more like it: l4, l5)",
    ]
    assert not any("…" in line for line in group_warnings(repairs))


def test_files_outside_every_package_name_the_first_uri_and_its_path():
    """genesis-world's go2: each warning quotes a URI and the path it reads, which elided read
    "'…' ('…') is outside every package folder"."""
    outside = [
        f"urdf/robot.urdf:{line}: '../meshes/{name}.dae' ('/src/go2/meshes/{name}.dae') is "
        "outside every package folder and robot.yaml's folder, and the model publishes it; move "
        "the file into the description, or set source.read_outside: true if it is meant"
        for line, name in ((4, "base"), (9, "hip"), (14, "thigh"), (19, "calf"), (24, "foot"))
    ]
    assert group_warnings(outside, "all in mjcf/report/report.md") == [
        f"{outside[0]} (and 4 more like it: ../meshes/hip.dae, ../meshes/thigh.dae, "
        "../meshes/calf.dae, ...; all in mjcf/report/report.md)"
    ]


def test_a_warning_per_mesh_file_names_the_files():
    """Each mesh's own material library is missing: the meshes are the subjects, not their
    libraries, and the line does not say 'm0.obj: 5 ×' of five files."""
    missing = [
        f"meshes/m{i}.obj: refers to 'colours.mtl' (material library), 'm{i}.mtl' (material "
        "library), not found beside it; the model shows the mesh without them (add the files, "
        "or remove the reference from the mesh)"
        for i in range(5)
    ]
    assert group_warnings(missing, "all in report.md") == [
        f"{missing[0]} (and 4 more like it: meshes/m1.obj, meshes/m2.obj, meshes/m3.obj, ...; "
        "all in report.md)"
    ]
    # The same sentence about several files lists the files.
    shared = [f"meshes/m{i}.obj: refers to 'colours.mtl', not found beside it" for i in (1, 2)]
    assert group_warnings(shared) == [
        "meshes/m1.obj: 2 × refers to 'colours.mtl', not found beside it: meshes/m1.obj, "
        "meshes/m2.obj"
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
