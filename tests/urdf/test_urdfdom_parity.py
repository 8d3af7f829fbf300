"""mjcfbuild's URDF reader against ROS's (urdfdom, through check_urdf and urdf_to_graphviz:
tests/urdfdom.py), on small URDFs written the ways real descriptions write them.

Where urdfdom accepts a file, mjcfbuild reads the same tree, joint origins, axes, limits and
masses, or refuses it, with file and line, for one of the reasons it refuses on purpose
(``DELIBERATE``: MuJoCo cannot simulate the joint). Where urdfdom refuses a file, mjcfbuild
refuses it too (a number written outside C's grammar), or reads it for a reason in
``URDFDOM_ONLY``: urdfdom is stricter there than XML, the URDF specification's words or MuJoCo's
own URDF import.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from mjcfbuild.errors import InputError
from mjcfbuild.urdf.limits import joint_range
from mjcfbuild.urdf.parse import parse_urdf
from tests.fuzzing import examples
from tests.strategies import rarely
from tests.urdfdom import require_urdfdom, same_origin, urdfdom_read

# mjcfbuild refuses these though urdfdom reads them: MuJoCo cannot simulate such a joint.
DELIBERATE = {
    "zero axis": "has a zero axis",
    "lower above upper": "above its upper limit",
    # urdfdom logs an error and drops such an <inertial> (the link's mass with it); MuJoCo's
    # import refuses it, as mjcfbuild does, rather than guess the mass or the inertia.
    "inertial without mass": "<inertial> needs <mass",
    "inertial without inertia": "<inertial> needs <inertia",
}
# urdfdom refuses these; mjcfbuild reads them, as the reason says.
URDFDOM_ONLY = {
    # XML turns a tab or line break in an attribute into a space (attribute-value
    # normalisation); urdfdom's XML parser (tinyxml2) keeps them and splits vectors at spaces.
    "tab or line break between numbers",
    # urdfdom's scalar reader stops at a trailing space; the number is unambiguous.
    "space after a number",
    # The URDF specification requires <limit> on these, and effort and velocity in it; MuJoCo's
    # import reads the joint without them (unlimited where no bound is given).
    "revolute or prismatic joint without limit",
    "limit without effort or velocity",
    # urdfdom requires the robot's name; mjcfbuild names such a robot "robot".
    "robot without a name",
    # Read with a warning (mjcfbuild.urdf.parse): real descriptions write them.
    "commas between numbers",
    # urdfdom drops the <inertial> and says so; mjcfbuild reads a missing product as 0.
    "inertia without its zero products",
    # urdfdom 3.0 knows no capsule (newer urdfdom and MuJoCo's import do); it drops the shape.
    "capsule",
}
# Numbers outside C's grammar (strtod in the C locale), which both refuse.
ODD_NUMBERS = ["1_0", "\u0661", "\uff11", "2_5.0", "0x1", "1d0", "nan", "inf", "1e400", ".", "--1"]
VALUES = [0.0, 1.0, -1.0, 0.5, -0.25, 0.001, -0.0002, 2.5, 10.0, 3.14159, 1e-5, 1234.5]
NAME_CHARACTERS = "abz_09üßΔ腕é-"


@dataclass
class Spec:
    """What a generated URDF says, beside its text: what to expect of each reader."""

    odd_allowed: bool = False  # whether numbers may be written outside C's grammar
    odd: bool = False  # whether one is
    urdfdom_only: set[str] = field(default_factory=set)
    deliberate: set[str] = field(default_factory=set)
    axes: dict[str, tuple[float, float, float]] = field(default_factory=dict)
    limits: dict[str, dict[str, float]] = field(default_factory=dict)
    masses: dict[str, float] = field(default_factory=dict)


@st.composite
def number(draw, spec: Spec, value: float | None = None, scalar: bool = False) -> tuple[str, float]:
    """A number's text in one of the ways descriptions write it, and its value."""
    if spec.odd_allowed and not spec.odd and rarely(draw, 12):  # one a document
        spec.odd = True
        return draw(st.sampled_from(ODD_NUMBERS)), float("nan")
    if value is None:
        value = draw(st.sampled_from(VALUES))
    style = draw(st.sampled_from(["repr", "e", "E", "plus", "dot", "int", "padded"]))
    text = repr(value)
    if style in ("e", "E"):
        text = f"{value:.6{style}}"
    elif style == "plus" and value >= 0:
        text = "+" + text
    elif style == "dot":
        text = text.replace("0.", ".", 1) if abs(value) < 1 else f"{value:.0f}."
    elif style == "int" and value == int(value):
        text = str(int(value))
    elif style == "padded":
        text = f"{value:012.6f}"
    if scalar and rarely(draw, 60):
        spec.urdfdom_only.add("space after a number")
        text += " "
    elif scalar and rarely(draw, 15):
        text = " " + text  # urdfdom takes a leading space
    return text, float(text)


@st.composite
def vector(draw, spec: Spec, values: list[float] | None = None) -> tuple[str, tuple[float, ...]]:
    """Three numbers with the separators descriptions use; their values."""
    drawn = [draw(number(spec, None if values is None else values[i])) for i in range(3)]
    separators = [draw(st.sampled_from([" ", " ", "  ", "   "])) for _ in range(2)]
    if rarely(draw, 12):
        separators[draw(st.integers(0, 1))] = draw(st.sampled_from(["\n      ", "\t", " \n"]))
        spec.urdfdom_only.add("tab or line break between numbers")
    elif rarely(draw, 20):  # armar6's rpy="1.5707963, 0, 0"
        separators[0] = draw(st.sampled_from([", ", ","]))
        spec.urdfdom_only.add("commas between numbers")
    ends = draw(st.sampled_from([("", ""), (" ", ""), ("", "  "), ("  ", " ")]))
    text = ends[0] + drawn[0][0] + separators[0] + drawn[1][0] + separators[1] + drawn[2][0]
    return text + ends[1], tuple(v for _, v in drawn)


@st.composite
def element(draw, tag: str, attributes: dict[str, str], inner: str = "") -> str:
    """``<tag ...>`` with its attributes in any order, and odd white space between them."""
    order = draw(st.permutations(list(attributes)))
    spaces = [draw(st.sampled_from([" ", " ", "\n    ", "  "])) for _ in order]
    written = "".join(f'{s}{k}="{attributes[k]}"' for s, k in zip(spaces, order, strict=True))
    return f"<{tag}{written}>{inner}</{tag}>" if inner else f"<{tag}{written}/>"


@st.composite
def origin(draw, spec: Spec) -> str:
    attributes = {}
    for key in draw(st.sampled_from([(), ("xyz",), ("rpy",), ("xyz", "rpy")])):
        attributes[key] = draw(vector(spec))[0]
    return draw(element("origin", attributes)) if attributes or draw(st.booleans()) else ""


@st.composite
def link(draw, spec: Spec, name: str, material: bool) -> str:
    """A link, perhaps with an inertial and a visual. What is left out is decided before the
    rest is drawn, so that ``spec`` only says what the text holds."""
    inner = ""
    if draw(st.booleans()):
        missing = draw(st.sampled_from(["mass", "inertia"])) if rarely(draw, 25) else None
        keys = ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
        if missing is None and rarely(draw, 15):
            keys = ["ixx", "iyy", "izz"]
            spec.urdfdom_only.add("inertia without its zero products")
        inner += "<inertial>" + draw(origin(spec))
        if missing is not None:  # camera and tower models in the wild
            spec.deliberate.add(f"inertial without {missing}")
        if missing != "mass":
            mass_text, mass = draw(number(spec, draw(st.sampled_from([0.5, 1.0, 2.25])), True))
            spec.masses[name] = mass
            inner += draw(element("mass", {"value": mass_text}))
        if missing != "inertia":
            inertia = {
                k: draw(number(spec, 0.01 if k in ("ixx", "iyy", "izz") else 0.0, True))[0]
                for k in keys
            }
            inner += draw(element("inertia", inertia))
        inner += "</inertial>"
    if draw(st.booleans()):
        colour = draw(element("color", {"rgba": "0.5 0.5 0.5 1"}))
        look = (
            draw(element("material", {"name": "grey"}))
            if material and draw(st.booleans())
            else draw(element("material", {"name": f"m_{name}"}, colour))
        )
        if rarely(draw, 15):
            shape = draw(element("capsule", {"radius": "0.1", "length": "0.2"}))
            spec.urdfdom_only.add("capsule")
        else:
            shape = draw(element("box", {"size": draw(vector(spec, [0.1, 0.2, 0.3]))[0]}))
        inner += f"<visual>{draw(origin(spec))}<geometry>{shape}</geometry>{look}</visual>"
    return f'<link name="{name}">{inner}</link>' if inner else draw(element("link", {"name": name}))


@st.composite
def joint(draw, spec: Spec, name: str, parent: str, child: str) -> str:
    kind = draw(
        st.sampled_from(["revolute", "continuous", "prismatic", "fixed", "floating", "planar"])
    )
    inner = draw(origin(spec))
    inner += draw(element("parent", {"link": parent})) + draw(element("child", {"link": child}))
    moves = kind not in ("fixed", "floating")
    if not rarely(draw, 4):
        zero = moves and rarely(draw, 40)
        values = [0.0, 0.0, 0.0] if zero else [draw(st.sampled_from(VALUES)) for _ in range(3)]
        if zero:
            spec.deliberate.add("zero axis")
        elif not any(values):
            values = [0.0, 0.0, 1.0]
        # urdfdom reads no axis of a fixed or floating joint, and mjcfbuild only warns about one
        # it cannot read: what such an axis says is no one's business (a spec of its own).
        text, axis = draw(vector(spec if moves else Spec(odd_allowed=True), values))
        if moves:
            spec.axes[name] = axis  # type: ignore[assignment]
        inner += draw(element("axis", {"xyz": text}))
    elif moves:
        spec.axes[name] = (1.0, 0.0, 0.0)
    bounded = kind in ("revolute", "prismatic")
    if not rarely(draw, 20 if bounded else 2):
        attributes, values = {}, {}
        for key in ("lower", "upper", "effort", "velocity"):
            if not rarely(draw, 8 if key in ("effort", "velocity") else 3):
                attributes[key], values[key] = draw(number(spec, scalar=True))
            elif key in ("effort", "velocity"):
                spec.urdfdom_only.add("limit without effort or velocity")
        bounds = values.get("lower", 0.0), values.get("upper", 0.0)  # a missing one is 0
        if bounded and ("lower" in values or "upper" in values) and bounds[0] > bounds[1]:
            spec.deliberate.add("lower above upper")
        spec.limits[name] = values
        inner += draw(element("limit", attributes))
    elif bounded:
        spec.urdfdom_only.add("revolute or prismatic joint without limit")
    return f'<joint name="{name}" type="{kind}">{inner}</joint>'


@st.composite
def robot(draw) -> tuple[str, Spec]:
    """A URDF text of one to four links, and what it says."""
    spec = Spec(odd_allowed=rarely(draw, 5))
    names = draw(
        st.lists(
            st.text(NAME_CHARACTERS, min_size=1, max_size=5), min_size=1, max_size=4, unique=True
        )
    )
    links = ["l" + n for n in names]
    parents = [draw(st.integers(0, i - 1)) for i in range(1, len(links))]
    material = draw(st.booleans())
    link_texts = [draw(link(spec, name, material)) for name in links]
    joint_texts = [
        draw(joint(spec, f"j{links[i + 1][1:]}", links[p], links[i + 1]))
        for i, p in enumerate(parents)
    ]
    parts = [*draw(st.permutations(link_texts)), *draw(st.permutations(joint_texts))]
    if draw(st.booleans()):
        parts = parts[len(links) :] + parts[: len(links)]  # joints before links
    if material:
        parts.insert(0, '<material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>')
    if rarely(draw, 12):
        spec.urdfdom_only.add("robot without a name")
        head = "<robot>"
    else:
        head = '<robot name="parity">'
    newline = draw(st.sampled_from(["\n", "\n  ", ""]))
    return '<?xml version="1.0"?>\n' + head + newline + newline.join(parts) + "\n</robot>\n", spec


@pytest.fixture(scope="module")
def folder() -> Path:
    require_urdfdom()
    return Path(tempfile.mkdtemp(prefix="mjcfbuild-urdfdom-"))


@settings(max_examples=examples(150), deadline=None, suppress_health_check=list(HealthCheck))
@given(robot())
def test_mjcfbuild_reads_what_urdfdom_reads(folder, generated):
    text, spec = generated
    path = folder / "parity.urdf"
    path.write_text(text, encoding="utf-8")
    judged = urdfdom_read(path, folder)
    verdict = "refuses" if not judged.accepted else "drops" if judged.errors else "accepts"
    if spec.odd:
        event("a number outside C's grammar")
    try:
        ours = parse_urdf(text.encode("utf-8"), "parity.urdf")
    except InputError as error:
        event(f"urdfdom {verdict}, mjcfbuild refuses")
        for reason in spec.deliberate:
            event(f"deliberate: {reason}")
        where = error.location
        assert where is not None and where.file == "parity.urdf" and where.line, error
        reasons = [why for why, words in DELIBERATE.items() if words in error.message]
        if judged.accepted and not judged.errors:
            # urdfdom reads it: mjcfbuild refuses only on purpose.
            assert reasons and set(reasons) <= spec.deliberate, error.one_line()
        else:  # urdfdom refuses it, or drops what it cannot read (an <inertial>) and says so
            assert spec.odd or (reasons and set(reasons) <= spec.deliberate), error.one_line()
        return
    event(f"urdfdom {verdict}, mjcfbuild reads")
    for reason in spec.urdfdom_only:
        event(f"urdfdom only: {reason}")
    assert not spec.odd, "mjcfbuild read a number urdfdom cannot"
    assert not spec.deliberate
    if not judged.accepted or judged.errors:
        # urdfdom refuses it (or drops an element it cannot read, and says so) only for a
        # reason mjcfbuild reads past on purpose (URDFDOM_ONLY).
        assert spec.urdfdom_only, judged.errors
        assert spec.urdfdom_only <= URDFDOM_ONLY
    if judged.accepted:
        assert judged.root == ours.root
        children = {name: sorted(j.child for j in js) for name, js in ours.child_joints().items()}
        assert {name: sorted(kids) for name, kids in judged.children.items()} == children
        for joint in ours.joints:
            theirs = judged.joints[joint.name]
            assert (theirs.parent, theirs.child) == (joint.parent, joint.child)
            assert same_origin(theirs, joint.origin.xyz, joint.origin.rpy), joint.name
    # Either way, the numbers are the ones written (urdfdom keeps an axis as written).
    for joint in ours.joints:
        if joint.name in spec.axes:
            assert joint.axis == spec.axes[joint.name], joint.name
        written = spec.limits.get(joint.name)
        if written is None:
            assert joint.limit is None
            continue
        assert joint.limit is not None
        for key in ("lower", "upper", "effort", "velocity"):
            assert getattr(joint.limit, key) == written.get(key), (joint.name, key)
        bounds = joint_range(joint)
        if bounds is not None:  # urdfdom: a missing bound is 0, as mjcfbuild reads it
            assert bounds == (written.get("lower", 0.0), written.get("upper", 0.0))
    assert {link.name: link.inertial.mass for link in ours.links if link.inertial} == spec.masses


def test_an_element_given_twice_is_read_as_urdfdom_reads_it_with_a_warning(tmp_path):
    """urdfdom reads the first of a repeated <parent>, <origin> or shape; so does mjcfbuild,
    with a warning at the second (MuJoCo's own import refuses the file)."""
    inertia = '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
    path = tmp_path / "twice.urdf"
    path.write_text(
        f'<robot name="r">\n<link name="a"><inertial><mass value="1"/>{inertia}</inertial>\n'
        '<collision><geometry><sphere radius="0.1"/>\n<box size="1 1 1"/></geometry>'
        "</collision></link>\n"
        f'<link name="b"><inertial><mass value="2"/>{inertia}</inertial></link>\n'
        f'<link name="c"><inertial><mass value="3"/>{inertia}</inertial></link>\n'
        '<joint name="j" type="fixed"><parent link="a"/>\n<parent link="c"/><child link="b"/>'
        '<origin xyz="1 0 0"/>\n<origin xyz="2 0 0"/></joint>\n'
        '<joint name="k" type="fixed"><parent link="a"/><child link="c"/></joint>\n</robot>\n',
        encoding="utf-8",
    )
    judged = urdfdom_read(path, tmp_path / "graph")
    ours = parse_urdf(path.read_bytes(), "twice.urdf")
    assert judged.accepted and not judged.errors
    for joint in ours.joints:
        theirs = judged.joints[joint.name]
        assert (theirs.parent, theirs.child) == (joint.parent, joint.child)
        assert same_origin(theirs, joint.origin.xyz, joint.origin.rpy), joint.name
    assert [link.collisions[0].geometry.kind for link in ours.links if link.collisions] == [
        "sphere"
    ]
    assert [w.split(": ")[0] for w in ours.warnings] == [
        "twice.urdf:4",
        "twice.urdf:8",
        "twice.urdf:9",
    ]
    assert "joint 'j' has 2 <parent> elements: only the first (line 7) is read" in ours.warnings[1]
    assert "MuJoCo's own import refuses the file" in ours.warnings[2]
