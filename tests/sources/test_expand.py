"""xacro expansion in-process: $(find) without ROS, and every file it read recorded."""

from __future__ import annotations

import pytest

from mjcfbuild.errors import InputError, ManifestError, UsageError
from mjcfbuild.sources.expand import COMMAND_LINE, expand_xacro, read_urdf_file
from mjcfbuild.sources.packages import PackageResolver
from tests.conftest import write

MAIN = """<?xml version="1.0" encoding="utf-8"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="size" default="0.1"/>
  <xacro:property name="cfg" value="${xacro.load_yaml('$(find pkg)/config/c.yaml')}"/>
  <xacro:include filename="$(find pkg)/urdf/part.xacro"/>
  <xacro:include filename="$(find pkg)/urdf/optional.xacro" optional="true"/>
  <link name="base"><visual><geometry><box size="$(arg size) ${cfg.width} 0.1"/></geometry></visual></link>
  <xacro:part/>
</robot>
"""
PART = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part"><link name="part_$(optenv PART_SUFFIX x)"/></xacro:macro>
</robot>
"""


@pytest.fixture
def pkg(tmp_path):
    root = tmp_path / "pkg"
    write(root / "urdf" / "main.xacro", MAIN)
    write(root / "urdf" / "part.xacro", PART)
    write(root / "config" / "c.yaml", "width: 0.25\n")
    return root


def test_expansion_resolves_find_args_yaml_and_records_dependencies(pkg, monkeypatch):
    monkeypatch.delenv("PART_SUFFIX", raising=False)
    resolver = PackageResolver({"pkg": pkg}, {})
    expansion = expand_xacro(pkg / "urdf" / "main.xacro", {"size": "0.5"}, resolver)
    text = expansion.urdf.decode()
    assert 'size="0.5 0.25 0.1"' in text
    assert '<link name="part_x"/>' in text
    assert expansion.files == sorted(
        str(p)
        for p in (
            pkg / "urdf" / "main.xacro",
            pkg / "urdf" / "part.xacro",
            pkg / "config" / "c.yaml",
        )
    )
    assert expansion.missing == [str(pkg / "urdf" / "optional.xacro")]
    assert expansion.environment == {"PART_SUFFIX": None}


YAML_MAIN = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="cfg" value="${xacro.load_yaml('$(find pkg)/config/c.yaml')}"/>
  <xacro:property name="old" value="${load_yaml('$(find pkg)/config/c.yaml')}"/>
  <link name="${cfg.arm.name}_${old.leg.name}_${cfg.leg.width}_${round(cfg.turn, 6)}"/>
</robot>
"""


def test_yaml_with_small_aliases_and_unit_tags_loads_as_xacro_loads_it(pkg):
    import xacro

    write(pkg / "urdf" / "yaml.xacro", YAML_MAIN)
    write(
        pkg / "config" / "c.yaml",
        "arm: &part {name: a, width: 1}\nleg: {<<: *part, width: 2}\nturn: !degrees 90\n",
    )
    loaders = xacro._global_symbols["load_yaml"], xacro._global_symbols["xacro"]["load_yaml"]
    expansion = expand_xacro(pkg / "urdf" / "yaml.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    assert '<link name="a_a_2_1.570796"/>' in expansion.urdf.decode()
    assert str(pkg / "config" / "c.yaml") in expansion.files
    # The bounded loader is in place only during the expansion.
    assert xacro._global_symbols["load_yaml"] is loaders[0]
    assert xacro._global_symbols["xacro"]["load_yaml"] is loaders[1]


def test_yaml_whose_aliases_expand_without_bound_names_the_yaml_file_and_line(pkg):
    from tests.cli.error_catalogue import laughs

    write(pkg / "urdf" / "yaml.xacro", YAML_MAIN)
    write(pkg / "config" / "c.yaml", laughs())
    with pytest.raises(InputError) as info:
        expand_xacro(pkg / "urdf" / "yaml.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    assert info.value.location.file == str(pkg / "config" / "c.yaml")
    assert (info.value.location.line, info.value.location.column) == (10, 10)
    assert "aliases add" in info.value.message


def test_unknown_package_in_find_names_the_file(pkg):
    with pytest.raises(InputError) as info:
        expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({}, {}))
    assert "unknown package 'pkg'" in info.value.message
    assert info.value.location.file.endswith("main.xacro")


def test_missing_include_is_an_error_naming_the_including_file(pkg):
    write(
        pkg / "urdf" / "part.xacro",
        PART.replace("<xacro:macro", '<xacro:include filename="gone.xacro"/><xacro:macro'),
    )
    with pytest.raises(InputError) as info:
        expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    error = info.value
    assert (error.location.file, error.location.line) == (str(pkg / "urdf" / "part.xacro"), 2)
    assert "included file gone.xacro not found" in error.message
    assert "did you mean" not in error.message


def test_an_include_spelt_in_another_letter_case_is_named(pkg):
    write(pkg / "urdf" / "main.xacro", MAIN.replace("urdf/part.xacro", "URDF/Part.xacro"))
    with pytest.raises(InputError) as info:
        expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    error = info.value
    assert (error.location.file, error.location.line) == (str(pkg / "urdf" / "main.xacro"), 5)
    assert "did you mean 'urdf/part.xacro'?" in error.message
    assert "letter case" in (error.hint or "")


def test_a_plain_urdf_spelt_in_another_letter_case_is_named(tmp_path):
    write(tmp_path / "robot.urdf", "<robot name='r'/>")
    with pytest.raises(InputError, match=r"did you mean 'robot\.urdf'"):
        read_urdf_file(tmp_path / "Robot.URDF")


def test_xml_error_in_included_file_has_file_and_line(pkg):
    write(pkg / "urdf" / "part.xacro", "<robot>\n<link name='a'>\n</robot>\n")
    with pytest.raises(InputError) as info:
        expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    assert info.value.location.file.endswith("part.xacro")
    assert info.value.location.line == 3
    assert info.value.message.startswith("XML error")


def test_hooks_are_restored_after_expansion(pkg):
    from xacro import substitution_args

    before = substitution_args._eval_find
    expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    assert substitution_args._eval_find is before


def test_plain_urdf_is_read_as_bytes(tmp_path):
    path = write(tmp_path / "a.urdf", '<?xml version="1.0" encoding="utf-8"?><robot name="a"/>')
    assert read_urdf_file(path).urdf.startswith(b"<?xml")
    with pytest.raises(InputError, match="not found"):
        read_urdf_file(tmp_path / "missing.urdf")


def test_every_element_knows_the_file_and_line_it_was_written_at(pkg, monkeypatch):
    monkeypatch.delenv("PART_SUFFIX", raising=False)
    expansion = expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({"pkg": pkg}, {}))
    lines = expansion.urdf.decode().splitlines()
    where = {lines[n - 1].strip(): origin for n, origin in expansion.origins.items()}
    main, part = str(pkg / "urdf" / "main.xacro"), str(pkg / "urdf" / "part.xacro")
    assert where['<link name="base">'] == (main, 7)
    assert where['<box size="0.1 0.25 0.1"/>'] == (main, 7)
    # Written in the macro's body, in the included file, called from main.xacro.
    assert where['<link name="part_x"/>'] == (part, 2)
    assert "mjcfbuild-origin" not in expansion.urdf.decode()


def test_an_argument_no_file_declares_or_uses_is_refused_with_the_closest_one(pkg):
    resolver = PackageResolver({"pkg": pkg}, {})
    source = pkg / "urdf" / "main.xacro"
    with pytest.raises(ManifestError) as info:
        expand_xacro(source, {"sise": "1"}, resolver, args_key="robot.yaml source.args")
    assert info.value.location.file == "robot.yaml source.args.sise"
    assert "did you mean 'size'?" in info.value.message
    assert "(declared: size)" in info.value.message
    with pytest.raises(UsageError) as info:
        expand_xacro(source, {"sise": "1"}, resolver, args_key=COMMAND_LINE)
    assert info.value.message.startswith("sise:=1: ")
    # Without a key (an SRDF given the source's arguments) nothing is checked.
    assert expand_xacro(source, {"sise": "1"}, resolver).urdf


def test_an_undefined_argument_names_the_line_that_uses_it(pkg):
    main = pkg / "urdf" / "main.xacro"
    main.write_text(MAIN.replace('<xacro:arg name="size" default="0.1"/>', ""))
    with pytest.raises(InputError) as info:
        expand_xacro(main, {}, PackageResolver({"pkg": pkg}, {}))
    assert (info.value.location.file, info.value.location.line) == (str(main), 7)
    assert "argument size" in info.value.message


def test_an_argument_read_with_xacro_arg_is_taken_as_the_xacro_command_takes_it(tmp_path):
    """``${xacro.arg('base')}`` reads an argument no <xacro:arg> declares: the xacro command
    takes ``base:=b``, mjcfbuild refused it as not declared; without it, xacro's error was
    only "'base'"."""
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        "  <link name=\"${xacro.arg('base')}\"/>\n</robot>\n",
    )
    resolver = PackageResolver({}, {})
    expansion = expand_xacro(source, {"base": "b"}, resolver, args_key="robot.yaml source.args")
    assert b'<link name="b"/>' in expansion.urdf
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, resolver, args_key="robot.yaml source.args")
    assert (info.value.location.file, info.value.location.line) == (str(source), 2)
    assert "argument 'base' is read with xacro.arg('base') but given no value" in str(info.value)


def test_a_file_that_is_not_utf8_is_refused_as_the_xacro_command_refuses_it(tmp_path):
    source = tmp_path / "r.xacro"
    source.write_bytes(b'<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="r\xe9"/>\n')
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert info.value.location.line == 2
    assert "byte 0xe9 is not UTF-8; xacro reads every file as UTF-8" in str(info.value)


def test_a_yaml_syntax_error_in_a_file_load_yaml_reads_names_that_file_and_line(tmp_path):
    """xacro's own message named neither ("while parsing a flow sequence")."""
    write(tmp_path / "cfg.yaml", "len: 0.1\nm: [1, 2\nz: 3\n")
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="cfg" value="${xacro.load_yaml(\'cfg.yaml\')}"/>\n'
        '  <link name="${cfg.len}"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert info.value.location.file == str(tmp_path / "cfg.yaml")
    assert info.value.location.line == 3
    assert info.value.message.startswith("YAML syntax error: expected ',' or ']'")


@pytest.mark.parametrize(
    "written",
    [
        '<link name="${1/0}"/>',
        "<link name=\"${xacro.fatal('stop here')}\"/>",
        '<link name="$(env MJCFBUILD_TEST_UNSET)"/>',
        '<xacro:arg name="required"/>',
    ],
    ids=["division-by-zero", "fatal", "unset-env", "arg-without-default"],
)
def test_a_failure_outside_macros_names_its_line(tmp_path, monkeypatch, written):
    """xacro names only the expression (or nothing); the error named the file alone."""
    monkeypatch.delenv("MJCFBUILD_TEST_UNSET", raising=False)
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'  <link name="base"/>\n  {written}\n</robot>\n',
    )
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert (info.value.location.file, info.value.location.line) == (str(source), 3)


def test_an_unknown_package_in_find_has_its_line_and_the_closest_name(pkg):
    with pytest.raises(InputError) as info:
        expand_xacro(pkg / "urdf" / "main.xacro", {}, PackageResolver({"pgk": pkg}, {}))
    assert info.value.location.line == 4
    assert "unknown package 'pkg'; did you mean 'pgk'?" in info.value.message


def test_a_xacro_file_named_as_a_urdf_is_refused_not_built_as_one_link(tmp_path):
    """Read as URDF, its includes and macros would vanish and a one-link model pass every
    check (roboplan's fr3.urdf is xacro)."""
    from mjcfbuild.errors import InputError
    from mjcfbuild.sources.expand import read_urdf_file

    source = tmp_path / "arm.urdf"
    source.write_text(
        '<?xml version="1.0"?>\n<robot name="a" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="parts.xacro"/>\n  <link name="base"/>\n</robot>\n'
    )
    with pytest.raises(InputError) as refused:
        read_urdf_file(source)
    assert refused.value.location is not None and refused.value.location.line == 3
    assert "xacro:include" in str(refused.value) and "source: {xacro: arm.urdf}" in str(
        refused.value.hint
    )
    commented = tmp_path / "commented.urdf"  # talos comments a property out
    commented.write_text(
        '<robot name="a"><!-- <xacro:property name="p" value="1"/> --><link name="b"/></robot>'
    )
    assert read_urdf_file(commented).urdf.startswith(b"<robot")
    expanded = tmp_path / "expanded.urdf"  # the namespace alone, as expanded URDFs keep it
    expanded.write_text(
        '<robot name="a" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="b"/></robot>'
    )
    assert read_urdf_file(expanded).urdf.startswith(b"<robot")


MACRO = (
    '  <xacro:macro name="leg" params="name size">\n'
    '    <link name="${name}"><visual><geometry><box size="${1 / size} 1 1"/>'
    "</geometry></visual></link>\n"
    "  </xacro:macro>\n"
)


@pytest.mark.parametrize(
    ("calls", "line"),
    [
        # The second call's parameter fails as xacro evaluates it: that call, not the first.
        ('  <xacro:leg name="a" size="0.1"/>\n  <xacro:leg name="b"\n    size="${1/0}"/>\n', 8),
        # The body fails for one call: the body's line.
        ('  <xacro:leg name="a" size="0.1"/>\n  <xacro:leg name="b" size="0"/>\n', 3),
    ],
    ids=["call-parameter", "macro-body"],
)
def test_a_failure_inside_a_macro_names_the_line_that_failed(tmp_path, calls, line):
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        + MACRO
        + '  <link name="base"/>\n'
        + calls
        + "</robot>\n",
    )
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert (info.value.location.file, info.value.location.line) == (str(source), line)
    assert info.value.message.startswith("xacro failed: in macro 'leg': ")


@pytest.mark.parametrize("in_macro", [True, False], ids=["in-a-macro", "in-the-file"])
def test_a_conditional_that_is_no_boolean_names_its_own_line(tmp_path, in_macro):
    body = '    <xacro:if value="maybe"><link name="x"/></xacro:if>\n'
    text = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="base"/>\n'
        + (
            '  <xacro:macro name="opt" params="">\n' + body + "  </xacro:macro>\n"
            if in_macro
            else body
        )
        + ("  <xacro:opt/>\n" if in_macro else "")
        + "</robot>\n"
    )
    source = write(tmp_path / "r.xacro", text)
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    line = 4 if in_macro else 3
    assert (info.value.location.file, info.value.location.line) == (str(source), line)
    assert 'conditional "maybe"' in info.value.message
    assert info.value.hint is not None and info.value.hint.startswith("give value= a boolean")


def test_an_include_cycle_is_named_at_the_include_that_closes_it(tmp_path):
    write(
        tmp_path / "part.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="p"/>\n  <xacro:include filename="r.xacro"/>\n</robot>\n',
    )
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="part.xacro"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert info.value.location.file == str(tmp_path / "part.xacro")
    assert info.value.location.line == 3
    assert (
        info.value.message
        == "xacro failed: include cycle: r.xacro includes part.xacro includes r.xacro"
    )


def test_an_undefined_name_gets_the_closest_parameter_or_property(tmp_path):
    source = write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="wheel_radius" value="0.1"/>\n'
        + MACRO.replace("${1 / size}", "${1 / sise + wheel_radus}")
        + '  <xacro:leg name="a" size="0.1"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as info:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert info.value.message.endswith("name 'sise' is not defined; did you mean 'size'?")
    assert info.value.location.line == 4


def test_an_attribute_xacro_leaves_a_number_is_an_error_at_its_element(tmp_path):
    """<xacro:attribute value="${2*pi}"/> leaves a float, which xacro fails to write with a
    traceback; here it was an internal error (exit 70)."""
    source = write(
        tmp_path / "r.urdf.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="base"/>\n'
        '  <link name="arm"/>\n'
        '  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>\n'
        '    <limit effort="1" lower="0" upper="1">\n'
        '      <xacro:attribute name="velocity" value="${2*pi}"/></limit></joint>\n'
        "</robot>\n",
    )
    with pytest.raises(InputError) as error:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert error.value.location is not None and error.value.location.line == 5
    assert "attribute 'velocity' of <limit> is the float 6.28" in error.value.message


def test_did_you_mean_never_names_the_name_itself():
    from mjcfbuild.sources.packages import did_you_mean

    assert did_you_mean("size", {"size", "sizes"}) == "; did you mean 'sizes'?"
    assert did_you_mean("size", {"size"}) == ""


ROBOT = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n{}\n</robot>\n'


@pytest.mark.parametrize(
    ("body", "line", "says"),
    [
        (
            '<xacro:include filename="hand.xacro" ns="grip"/>\n<link name="base"/>\n'
            '<xacro:grip.finger prefix="a" parnet="base"/>',
            4,
            "did you mean 'parent'?",
        ),
        ('<link name="base">\n<xacro:insert_block name="nope"/></link>', 3, 'block "nope"'),
        (
            '<link name="base"/>\n<xacro:property name="a" value="${b}"/>\n'
            '<xacro:property name="b" value="${a}"/>\n<link name="${a}"/>',
            3,
            "circular variable definition",
        ),
        (
            '<xacro:arg name="arm_id" default="fr3"/>\n<link name="base"/>\n'
            '<link name="$(optenv ARM_ID_UNSET $(arg arm_id))_link0"/>',
            4,
            "invalid expression: $(arg arm_id",
        ),
    ],
    ids=["namespaced-call", "undefined-block", "circular-property", "nested-substitution"],
)
def test_failures_xacro_names_no_line_for_are_placed(tmp_path, body, line, says):
    """xacro's message gave no line for these (a call of a macro from an ns= include, an
    undefined block); a circular property was placed at the <robot> line."""
    write(
        tmp_path / "hand.xacro",
        ROBOT.format(
            '<xacro:macro name="finger" params="prefix parent"><link name="${prefix}f"/>'
            "</xacro:macro>"
        ),
    )
    source = write(tmp_path / "r.urdf.xacro", ROBOT.format(body))
    with pytest.raises(InputError) as error:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert error.value.location is not None
    assert (error.value.location.file, error.value.location.line) == (str(source), line)
    assert says in error.value.message


DECLARED = '<?xml version="1.0" encoding="utf-8"?>\n' + ROBOT


@pytest.mark.parametrize(
    ("body", "line", "says"),
    [
        (
            '<xacro:macro name="wheel" params="n"><link name="${n}"/></xacro:macro>\n'
            '<xacro:wheeel n="w1"/>',
            4,
            "unknown macro name: xacro:wheeel; did you mean 'wheel'?",
        ),
        (
            '<link name="base"/>\n<link name="$(dirname)/tool"/>',
            4,
            "$(dirname) cannot be substituted: xacro 2.1.1 does not know the file's name there",
        ),
        (
            '<link name="base"/>\n<link name="$(eval 2 *)"/>',
            4,
            "$(eval ...) is not a Python expression: invalid syntax",
        ),
        ('<link name="base"/>\n<link name="$(dirnam)"/>', 4, "unknown substitution $(dirnam)"),
        (
            '<xacro:property name="v" value="$(eval 1 +)"/>\n<link name="base"/>\n'
            '<link name="${v}"/>',
            3,
            "$(eval ...) is not a Python expression",
        ),
        (
            '<!-- link names are l_ + size + 1 -->\n<xacro:property name="size" value="s"/>\n'
            '<link name="l_${size + 1}"/>',
            5,
            "can only concatenate str",
        ),
    ],
    ids=[
        "misspelt-macro",
        "dirname",
        "eval-syntax",
        "unknown-command",
        "eval-in-property",
        "token",
    ],
)
def test_substitution_and_macro_failures_are_one_clean_line_at_their_line(
    tmp_path, body, line, says
):
    """A misspelt macro call had no "did you mean"; $(dirname) and $(eval) errors printed
    xacro's text twice, with "<class '...SubstitutionException'>" and no line; a short
    expression was placed at the first line holding its text anywhere (<?xml version)."""
    source = write(tmp_path / "r.urdf.xacro", DECLARED.format(body))
    with pytest.raises(InputError) as error:
        expand_xacro(source, {}, PackageResolver({}, {}))
    text = error.value.one_line()
    assert error.value.location is not None
    assert (error.value.location.file, error.value.location.line) == (str(source), line), text
    assert says in error.value.message and "<class" not in text, text
    assert text.count(says) == 1, text  # xacro printed its text twice


def test_a_missing_xacro_namespace_declaration_is_said_with_the_line_to_add(tmp_path):
    """xacro's own message says to check for xmlns:xacro; mjcfbuild said only 'unbound
    prefix'."""
    source = write(
        tmp_path / "r.urdf.xacro",
        '<?xml version="1.0"?>\n<robot name="r">\n  <xacro:arg name="n" default="x"/>\n</robot>\n',
    )
    with pytest.raises(InputError) as error:
        expand_xacro(source, {}, PackageResolver({}, {}))
    assert error.value.one_line() == (
        f"{source}:3:3: XML error: unbound prefix (declare xacro's namespace on the root "
        'element: xmlns:xacro="http://www.ros.org/wiki/xacro")'
    )
