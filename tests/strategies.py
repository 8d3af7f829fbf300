"""Hypothesis strategies for the fuzz tests: manifests and URDFs, valid and broken."""

from __future__ import annotations

from hypothesis import strategies as st

from mjcfbuild.urdf.model import JOINT_TYPES

# ---- numbers as they appear in XML attributes ---------------------------------------------------

BROKEN_NUMBER = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, width=32).map(repr),
    st.sampled_from(["0", "-0", "1e400", "abc", "", " ", "1,2", "0x10", "nan", "-inf", "1e-300"]),
)


def rarely(draw, one_in: int = 10) -> bool:
    """True about once in ``one_in`` draws (never in the simplest example, which shrinking
    seeks)."""
    return draw(st.integers(1, one_in)) == one_in


@st.composite
def numbers_text(draw, count: int, low: float = -3.0, high: float = 3.0) -> str:
    """``count`` numbers separated by spaces; rarely broken (wrong count, not numbers, ...)."""
    if rarely(draw, 50):
        return " ".join(draw(st.lists(BROKEN_NUMBER, min_size=count - 1, max_size=count + 1)))
    values = draw(st.lists(st.floats(low, high), min_size=count, max_size=count))
    return " ".join(f"{v:.4g}" for v in values)


def positive_numbers(count: int) -> st.SearchStrategy[str]:
    """Sizes: positive, rarely zero, negative or not numbers at all."""
    return numbers_text(count, 0.01, 0.5)


# ---- URDF ---------------------------------------------------------------------------------------

ODD_LINK_NAMES = st.sampled_from(["base", "a", "a b", "ü", "x/y", "", "l1"])


@st.composite
def geometry(draw) -> str:
    """One ``<geometry>`` element of any kind, sizes mostly sensible."""
    kind = draw(st.sampled_from(["box", "sphere", "cylinder", "capsule", "mesh"]))
    if rarely(draw):
        kind = draw(st.sampled_from(["cone", "", "box/"]))
        return f"<geometry><{kind or 'empty'}/></geometry>"
    if kind == "box":
        return f'<geometry><box size="{draw(positive_numbers(3))}"/></geometry>'
    if kind == "sphere":
        return f'<geometry><sphere radius="{draw(positive_numbers(1))}"/></geometry>'
    if kind in ("cylinder", "capsule"):
        return (
            f'<geometry><{kind} radius="{draw(positive_numbers(1))}" '
            f'length="{draw(positive_numbers(1))}"/></geometry>'
        )
    filename = "part.stl"
    if rarely(draw):
        filename = draw(st.sampled_from(["missing.stl", "../part.stl", "package://none/p.stl"]))
    scale = f' scale="{draw(positive_numbers(3))}"' if draw(st.booleans()) else ""
    return f'<geometry><mesh filename="{filename}"{scale}/></geometry>'


@st.composite
def origin(draw) -> str:
    """An ``<origin>``, absent or with a position and orientation."""
    if not draw(st.booleans()):
        return ""
    return f'<origin xyz="{draw(numbers_text(3, -0.5, 0.5))}" rpy="{draw(numbers_text(3))}"/>'


@st.composite
def inertial(draw) -> str:
    """An ``<inertial>``: absent, sensible, or rarely with odd masses and tensors."""
    if not draw(st.integers(0, 3)):
        return ""
    if rarely(draw):
        values = [draw(BROKEN_NUMBER) for _ in range(7)]
    else:
        values = [draw(positive_numbers(1)) for _ in range(4)] + [
            draw(numbers_text(1, -0.001, 0.001)) for _ in range(3)
        ]
    return (
        f'<inertial>{draw(origin())}<mass value="{values[0]}"/><inertia ixx="{values[1]}" '
        f'iyy="{values[2]}" izz="{values[3]}" ixy="{values[4]}" ixz="{values[5]}" '
        f'iyz="{values[6]}"/></inertial>'
    )


@st.composite
def link(draw, name: str) -> str:
    """A ``<link>`` with a few visuals and collisions."""
    parts = [draw(inertial())]
    for tag in draw(st.lists(st.sampled_from(["visual", "collision"]), max_size=3)):
        parts.append(f"<{tag}>{draw(origin())}{draw(geometry())}</{tag}>")
    return f'<link name="{name}">{"".join(parts)}</link>'


@st.composite
def joint(draw, index: int, parent: str, child: str) -> str:
    """A ``<joint>`` between two links, of any type, with or without axis and limits."""
    kind = draw(st.sampled_from(["revolute", "continuous", "prismatic", "fixed", "floating"]))
    if rarely(draw):
        kind = draw(st.sampled_from([*JOINT_TYPES, "hinge", ""]))
    axis = ""
    if draw(st.booleans()):
        axis = f'<axis xyz="{draw(numbers_text(3, -1, 1))}"/>'
    limit = ""
    if kind in ("revolute", "prismatic") or rarely(draw):
        lower, upper = sorted(draw(st.lists(st.floats(-3, 3), min_size=2, max_size=2)))
        lower_text, upper_text = f"{lower:.3g}", f"{upper:.3g}"
        if rarely(draw):
            lower_text, upper_text = draw(BROKEN_NUMBER), draw(BROKEN_NUMBER)
        limit = f'<limit lower="{lower_text}" upper="{upper_text}" effort="1" velocity="1"/>'
    mimic = ""
    if index > 0 and rarely(draw):
        mimic = (
            f'<mimic joint="j{draw(st.integers(0, index))}" multiplier="{draw(numbers_text(1))}"/>'
        )
    return (
        f'<joint name="j{index}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f"{draw(origin())}{axis}{limit}{mimic}</joint>"
    )


@st.composite
def urdf_text(draw) -> str:
    """A URDF: usually a tree of links, rarely with odd names, cycles or damaged text."""
    count = draw(st.integers(1, 5))
    names = ["base"] + [f"l{i}" for i in range(1, count)]
    if rarely(draw):
        names = [draw(ODD_LINK_NAMES) for _ in range(count)]
    links = [draw(link(name)) for name in names]
    joints = []
    for index in range(1, count):
        parent = names[draw(st.integers(0, index - 1))]
        if rarely(draw):  # unknown, itself, or a later link (a cycle)
            parent = draw(st.sampled_from([*names, "nowhere"]))
        joints.append(draw(joint(index - 1, parent, names[index])))
    text = (
        '<?xml version="1.0" encoding="utf-8"?>\n<robot name="fuzz">\n'
        + "\n".join(links + joints)
        + "\n</robot>\n"
    )
    if rarely(draw):
        at = draw(st.integers(0, len(text)))
        damage = draw(
            st.sampled_from(["", "<", ">", "&", '"', "</link>", "\x00", "<!ENTITY x 'y'>"])
        )
        text = text[:at] + damage + text[at + draw(st.integers(0, 40)) :]
    return text


# ---- manifests ----------------------------------------------------------------------------------

YAML_SCALARS = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-10, 10_000),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.sampled_from(["robot.urdf", "mjcf", "all", "fused", "repair", "decompose", "../x", "1 MB"]),
)
YAML_VALUES = st.recursive(
    YAML_SCALARS,
    lambda children: st.one_of(
        st.lists(children, max_size=3),
        st.dictionaries(st.text(max_size=8), children, max_size=3),
    ),
    max_leaves=6,
)
KEY_PATHS = [
    ("name",),
    ("source", "urdf"),
    ("source", "xacro"),
    ("source", "args"),
    ("packages",),
    ("options", "free_joint"),
    ("options", "fuse_static"),
    ("options", "link_sites"),
    ("meshes", "max_faces"),
    ("meshes", "max_file_mb"),
    ("collision", "default"),
    ("collision", "decompose", "threshold"),
    ("collision", "rules"),
    ("inertia", "policy"),
    ("inertia", "min_mass"),
    ("cache", "max_size"),
    ("mujoco_inputs", "raw"),
    ("mujoco_inputs", "cameras"),
    ("mujoco_inputs", "modify"),
    ("check", "tolerances"),
    ("check", "steps"),
    ("scene", "mjcf"),
    ("output", "folder"),
    ("output", "robot"),
    ("unknown",),
    ("options", "unknown"),
]


def set_path(data: dict, path: tuple[str, ...], value) -> dict:
    """``data`` with ``value`` at ``path``, creating mappings on the way (replacing non-maps)."""
    node = data
    for key in path[:-1]:
        if not isinstance(node.get(key), dict):
            node[key] = {}
        node = node[key]
    node[path[-1]] = value
    return data


@st.composite
def manifest_data(draw) -> dict:
    """A manifest: valid to start with, then a few keys set to random values or removed."""
    data: dict = {"name": "robot", "source": {"urdf": "robot.urdf"}}
    for _ in range(draw(st.integers(0, 3))):
        path = draw(st.sampled_from(KEY_PATHS))
        if draw(st.integers(0, 5)) == 0 and path[0] in data:
            del data[path[0]]
        else:
            set_path(data, path, draw(YAML_VALUES))
    return data


VALID_OPTIONS = st.fixed_dictionaries(
    {
        "options": st.fixed_dictionaries(
            {
                "free_joint": st.booleans(),
                "fuse_static": st.booleans(),
                "link_sites": st.sampled_from(["all", "fused"]),
            }
        ),
        "collision": st.fixed_dictionaries(
            {"default": st.sampled_from(["authored", "visual", "hull", "primitive", "none"])}
        ),
        "inertia": st.fixed_dictionaries({"policy": st.sampled_from(["repair", "fail"])}),
    }
)
