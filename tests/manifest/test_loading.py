"""robot.yaml validation: what is accepted, and errors that point at the line."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import ManifestError
from mjcfbuild.manifest import load_manifest, parse_manifest


def error_of(text: str) -> ManifestError:
    with pytest.raises(ManifestError) as info:
        parse_manifest(text, "robot.yaml")
    return info.value


def test_minimal_manifest_gets_defaults():
    manifest = parse_manifest("name: arm\nsource:\n  urdf: arm.urdf\n")
    assert manifest.robot_file == "arm.xml"
    assert manifest.output.folder == "mjcf"
    assert manifest.output.scene == "scene.xml"
    assert manifest.options.fuse_static is True
    assert manifest.options.free_joint is False


def test_xacro_args_become_xacro_strings():
    manifest = parse_manifest(
        "name: arm\nsource:\n  xacro: arm.xacro\n  args: {use_pid: true, count: 3, prefix: l_}\n"
    )
    assert manifest.source.xacro_args == {"count": "3", "prefix": "l_", "use_pid": "true"}


def test_unquoted_xacro_args_pass_the_text_written():
    """As name:=value on xacro's command line: YAML read 1.10 as 1.1 and 0010 as 8 (a link
    named base_v1.10_0010 came out base_v1.1_8)."""
    manifest = parse_manifest(
        "name: arm\nsource:\n  xacro: arm.xacro\n"
        '  args: {hw_rev: 1.10, id: 0010, on: True, quoted: "007", exp: 1e3, cam: yes}\n'
    )
    assert manifest.source.xacro_args == {
        "cam": "true",  # YAML's true, given to xacro as true (xacro refuses 'yes')
        "exp": "1e3",
        "hw_rev": "1.10",
        "id": "0010",
        "on": "true",  # the key as written (YAML 1.1 reads `on` as true)
        "quoted": "007",
    }


def test_unknown_key_names_line_column_and_allowed_keys():
    error = error_of("name: arm\nsource:\n  urdf: a.urdf\n  xacor: b.xacro\n")
    assert error.location.line == 4 and error.location.column == 3
    text = error.one_line()
    assert "source.xacor: unknown key 'xacor'" in text
    assert "did you mean 'xacro'?" in text
    assert "allowed keys: args, description, read_outside, urdf, xacro" in text


def test_unknown_top_level_key():
    error = error_of("name: arm\nsource: {urdf: a.urdf}\noutputs: {folder: x}\n")
    assert error.location.line == 3
    assert "did you mean 'output'?" in error.message


def test_wrong_type_names_the_value():
    error = error_of("name: arm\nsource: {urdf: a.urdf}\noptions:\n  free_joint: maybe\n")
    assert error.location.line == 4
    assert "options.free_joint: expected true or false, got 'maybe'" in error.message


def test_missing_required_key():
    error = error_of("name: arm\n")
    assert "source: this key is required" in error.message


def test_a_key_of_a_model_in_a_union_is_named_and_pointed_at_as_written():
    """pydantic names the union's member (``SelfCollisionSettings``) in the error's place."""
    error = error_of("name: arm\nsource: {urdf: a.urdf}\nself_collision:\n  samples: 0\n")
    assert (error.location.line, error.location.column) == (4, 3)
    assert error.message == "self_collision.samples: 0 should be greater than 0"


def test_two_sources_are_refused():
    error = error_of("name: arm\nsource:\n  urdf: a.urdf\n  xacro: b.xacro\n")
    assert error.location.line == 2
    assert "exactly one of urdf, xacro, description" in error.message


def test_args_without_xacro_are_refused():
    error = error_of("name: arm\nsource:\n  urdf: a.urdf\n  args: {x: 1}\n")
    assert "args are xacro arguments" in error.message


def test_invalid_literal_lists_choices():
    error = error_of("name: arm\nsource: {urdf: a.urdf}\noptions: {link_sites: some}\n")
    assert "'some' is not allowed; use one of 'all' or 'fused'" in error.message


def test_bad_name_is_explained():
    error = error_of("name: my robot/2\nsource: {urdf: a.urdf}\n")
    assert error.location.line == 1
    assert "is not a valid name" in error.message


@pytest.mark.parametrize(
    ("value", "said"),
    [
        # were "expected a non-empty string, got True" and "is not a valid name"
        ("true", "expected a file name such as 'my_robot.urdf', written in the output folder"),
        (
            "urdf/x.urdf",
            "'urdf/x.urdf' names a folder; expected a file name such as 'x.urdf', written in "
            "the output folder",
        ),
        ("{file: a/b.urdf}", "'a/b.urdf' names a folder; expected a file name such as 'b.urdf'"),
        ("false", "got false; leave the key out for no URDF"),
    ],
)
def test_an_output_urdf_that_is_no_file_name_says_what_is_expected(value, said):
    error = error_of(f"name: a\nsource: {{urdf: a.urdf}}\noutput:\n  urdf: {value}\n")
    assert error.location.line == 4
    assert said in error.message, error.message


def test_robot_and_scene_file_must_differ():
    error = error_of("name: scene\nsource: {urdf: a.urdf}\n")
    assert "both 'scene.xml'" in error.message


def test_yaml_syntax_error_has_position():
    error = error_of("name: arm\nsource:\n  urdf: [unclosed\n")
    assert error.location.line is not None
    assert error.message.startswith("YAML syntax error")


def test_duplicate_keys_are_refused():
    error = error_of("name: arm\nname: other\nsource: {urdf: a.urdf}\n")
    assert error.location.line == 2
    assert "duplicate key 'name'" in error.message


def test_empty_and_non_mapping_manifests():
    assert "empty" in error_of("").message
    assert "mapping of keys" in error_of("- a\n- b\n").message


def test_a_bracket_left_open_above_block_items_is_the_error_with_a_hint():
    text = "name: arm\nsource: {urdf: a.urdf}\nactuators:\n  rules: [\n    - {joints: [a]}\n"
    error = error_of(text)
    assert (error.location.line, error.location.column) == (4, 10)
    assert error.message == "YAML syntax error: this '[' is not closed before line 5"
    assert error.hint is not None and error.hint.startswith("close it with ']' on its line")
    # A bracket closed on its line, or one inside quotes, is not taken for it.
    closed = "name: arm\nsource: {urdf: '[a.urdf'}\nhome: {a: 1}\nx: [\n  - 1\n"
    assert error_of(closed).location.line == 4


def test_an_undefined_alias_says_what_an_alias_is():
    error = error_of("name: arm\nsource: *nope\n")
    assert error.location.line == 2
    assert "undefined alias 'nope'" in error.message
    assert error.hint is not None and "'&name'" in error.hint


def test_more_problems_are_counted_in_the_hint():
    error = error_of("name: arm\nsource: {urdf: a.urdf}\nfoo: 1\nbar: 2\n")
    assert error.hint == "1 more problem after this one"


def test_load_manifest_reports_missing_file(tmp_path):
    with pytest.raises(ManifestError) as info:
        load_manifest(tmp_path / "nope.yaml")
    assert "manifest not found" in info.value.one_line()
    assert "mjcfbuild init" in info.value.one_line()


def test_a_missing_manifest_names_the_one_in_a_folder_above(tmp_path, monkeypatch):
    """Run from the description's urdf/ folder, the command was told to make a second
    robot.yaml with init."""
    (tmp_path / "robot.yaml").write_text("name: a\n")
    (tmp_path / "urdf" / "deeper").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "urdf")
    with pytest.raises(ManifestError) as info:
        load_manifest("robot.yaml")
    assert info.value.hint == "'../robot.yaml' is one folder up: pass its path, or run there"
    monkeypatch.chdir(tmp_path / "urdf" / "deeper")
    with pytest.raises(ManifestError) as info:
        load_manifest("robot.yaml")
    assert info.value.hint == "'../../robot.yaml' is 2 folders up: pass its path, or run there"


def test_a_urdf_or_a_mesh_given_for_the_manifest_is_named_for_what_it_is(tmp_path):
    urdf = tmp_path / "arm.urdf"
    urdf.write_text('<?xml version="1.0"?>\n<robot name="arm"><link name="a"/></robot>\n')
    with pytest.raises(ManifestError) as info:
        load_manifest(urdf)
    assert info.value.message == "this is a URDF, not a manifest"
    assert info.value.hint == f"'mjcfbuild init {urdf}' writes a robot.yaml that builds it"
    mesh = tmp_path / "base.stl"
    mesh.write_bytes(b"\0" * 80 + (0).to_bytes(4, "little"))
    with pytest.raises(ManifestError) as info:
        load_manifest(mesh)
    assert info.value.message == "this is an STL mesh, not a manifest"


def test_load_manifest_reports_non_utf8(tmp_path):
    path = tmp_path / "robot.yaml"
    path.write_bytes(b"name: r\nsource:\n  urdf: r\xe9.urdf\n")
    with pytest.raises(ManifestError) as info:
        load_manifest(path)
    assert info.value.message == "not UTF-8 text (byte 25: 0xe9)"
    assert (info.value.location.line, info.value.location.column) == (3, 10)


def test_masses_from_geometry_are_opt_in_and_density_needs_them():
    """``inertia.missing`` keeps the placeholder unless asked; a density alone would be
    silently unused, so it is refused at its section's line."""
    plain = parse_manifest("name: arm\nsource: {urdf: a.urdf}\n")
    assert (plain.inertia.missing, plain.inertia.density) == ("placeholder", 1000.0)
    asked = parse_manifest(
        "name: arm\nsource: {urdf: a.urdf}\ninertia: {missing: geometry, density: 2700}\n"
    )
    assert (asked.inertia.missing, asked.inertia.density) == ("geometry", 2700.0)
    error = error_of("name: arm\nsource: {urdf: a.urdf}\ninertia:\n  density: 2700\n")
    assert error.location.line == 3
    assert "density" in error.message and "it needs missing: geometry" in error.message
    error = error_of("name: arm\nsource: {urdf: a.urdf}\ninertia: {missing: mesh}\n")
    assert "use one of 'placeholder' or 'geometry'" in error.message
