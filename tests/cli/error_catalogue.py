"""The catalogue of bad inputs: each case is a small robot folder with one thing wrong.

A case lists the files to write (text, bytes, or a callable that creates the file), the command
line, the exit code it must end with and what the one-line message must say: the file, the line
where there is one, and words that tell the user what to do.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from mjcfbuild.errors import (
    EXIT_INPUT,
    EXIT_MANIFEST,
    EXIT_MODEL,
    EXIT_OUTPUT,
    EXIT_USAGE,
)
from tests.conftest import two_link_urdf
from tests.meshes.test_collada_parity import BOX, TETRAHEDRON
from tests.meshes.test_collada_parity import document as dae_document
from tests.meshes.test_collada_parity import geometry as dae_geometry
from tests.meshes.test_collada_parity import instance as dae_instance

FileContent = str | bytes | Callable[[Path], None]

MANIFEST = "name: robot\nsource:\n  urdf: robot.urdf\n"
ARG_XACRO = (
    '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
    '  <xacro:arg name="with_camera" default="true"/>\n'
    '  <link name="base"/><xacro:if value="$(arg with_camera)"><link name="camera"/></xacro:if>\n'
    "</robot>\n"
)
XACRO_OPEN = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
XACRO_MANIFEST = "name: robot\nsource:\n  xacro: robot.urdf.xacro\n"
# export-urdf of a one-joint model, keeping the velocity limits of original.urdf.
EXPORT_MODEL = (
    "<mujoco><worldbody><body name='arm'><joint name='shoulder' range='-1 1'/>"
    "<geom size='0.1'/></body></worldbody></mujoco>\n"
)
# The same model drawn by a mesh, so that the export writes a mesh folder.
EXPORT_MESH_MODEL = (
    "<mujoco><asset><mesh name='arm' file='arm.obj'/></asset><worldbody><body name='arm'>"
    "<joint name='shoulder' range='-1 1'/><geom type='mesh' mesh='arm'/></body></worldbody>"
    "</mujoco>\n"
)
OBJ = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"
EXPORT_ARGS = ["export-urdf", "model.xml", "-o", "out/robot.urdf", "--limits-from", "original.urdf"]
TETRAHEDRON_STL = """solid t
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 0.1 0
  vertex 0.1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 0.1 0 0
  vertex 0 0 0.1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 0.1
  vertex 0 0.1 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 0.1 0 0
  vertex 0 0.1 0
  vertex 0 0 0.1
 endloop
endfacet
endsolid t
"""


@dataclass
class Case:
    """One bad input and what mjcfbuild must say about it."""

    name: str
    files: dict[str, FileContent]
    code: int
    says: list[str]
    args: list[str] = field(default_factory=lambda: ["build", "robot.yaml"])
    needs_unprivileged: bool = False
    env: dict[str, str] = field(default_factory=dict)  # variables the command runs with

    def write(self, folder: Path) -> None:
        """Create the case's files under ``folder``."""
        for relative, content in self.files.items():
            path = folder / relative
            path.parent.mkdir(parents=True, exist_ok=True)
            if callable(content):
                content(path)
            elif isinstance(content, bytes):
                path.write_bytes(content)
            else:
                path.write_text(content)


def laughs(levels: int = 9) -> str:
    """YAML whose anchors each repeat the one before nine times: 9**(levels+1) values."""
    lines = ['l0: &l0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for level in range(1, levels + 1):
        lines.append(f"l{level}: &l{level} [{', '.join([f'*l{level - 1}'] * 9)}]")
    return "\n".join(lines) + "\n"


def urdf(replace: tuple[str, str] | None = None, extra: str = "") -> str:
    """The two-link URDF with one substitution (which must apply) and extra elements."""
    text = two_link_urdf(extra)
    if replace is not None:
        old, new = replace
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


def mesh_urdf(filename: str) -> str:
    """The two-link URDF whose arm is drawn by the mesh ``filename``."""
    visual = f'<visual><geometry><mesh filename="{filename}"/></geometry></visual>'
    return urdf(('<link name="arm">', f'<link name="arm">{visual}'))


def symlink_loop(path: Path) -> None:
    """``path`` -> ``path.loop`` -> ``path``."""
    other = path.with_name(path.name + ".loop")
    os.symlink(other.name, path)
    os.symlink(path.name, other)


def a_plain_file(path: Path) -> None:
    """A regular file where a folder is wanted."""
    path.write_text("not a folder\n")


def link_to_elsewhere(path: Path) -> None:
    """A link out of robot.yaml's tree (to nothing: a build must not even look there)."""
    path.symlink_to("/nonexistent/mjcfbuild-elsewhere")


def read_only_folder(path: Path) -> None:
    """A folder nobody may write in."""
    path.mkdir()
    path.chmod(0o555)


LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE robot [
  <!ENTITY a "hahahahahahahahahahahahahahahahahaha">
  <!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">
  <!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">
]>
<robot name="r"><link name="base"><visual><geometry><box size="1 1 1"/></geometry></visual>
<material name="&c;"/></link></robot>
"""

EXTERNAL_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<robot name="&secret;"><link name="base"/></robot>
"""

CASES: list[Case] = [
    # ---- the manifest -------------------------------------------------------------------------
    Case(
        "yaml syntax",
        {"robot.yaml": "name: robot\nsource: [urdf: robot.urdf\n"},
        EXIT_MANIFEST,
        # Where the '[' was opened, not the end of the file where PyYAML noticed.
        ["robot.yaml:2:9:", "YAML", "close the '[' opened here with ']'"],
    ),
    Case(
        "yaml tab indentation",
        {"robot.yaml": "name: robot\nsource:\n\turdf: robot.urdf\n"},
        EXIT_MANIFEST,
        ["robot.yaml:3:", "indent with spaces"],
    ),
    Case(
        "yaml key without its colon",
        {"robot.yaml": "name: robot\nsource\n  urdf: robot.urdf\n"},
        EXIT_MANIFEST,
        # PyYAML notices on line 3; the mistake is on line 2.
        ["robot.yaml:2:1: YAML syntax error", "a key needs a ':' after it"],
    ),
    Case(
        "yaml key indented deeper than its siblings",
        {"robot.yaml": MANIFEST + "options:\n  free_joint: true\n   fuse_static: true\n"},
        EXIT_MANIFEST,
        ["robot.yaml:6:", "indented deeper than the keys beside it?"],
    ),
    Case(
        "yaml key indented less than its siblings",
        {"robot.yaml": MANIFEST + "options:\n    free_joint: true\n  fuse_static: true\n"},
        EXIT_MANIFEST,
        ["robot.yaml:6:3:", "line it up with its siblings"],
    ),
    Case(
        "yaml quote not closed",
        {"robot.yaml": MANIFEST + 'home:\n  "elbow: 1\noptions: {}\n'},
        EXIT_MANIFEST,
        ["robot.yaml:5:3:", "close the quote opened here"],
    ),
    Case(
        "yaml quote not closed, with a quote lines later",
        {"robot.yaml": 'name: "arm\n' + MANIFEST.split("\n", 1)[1] + 'home: {"*": 0}\n'},
        EXIT_MANIFEST,
        ["robot.yaml:1:7:", "this quote is not closed on its line", "close the quote"],
    ),
    Case(
        "yaml single quote not closed",
        {"robot.yaml": "name: 'arm\n" + MANIFEST.split("\n", 1)[1] + "home: {'*': 0}\n"},
        EXIT_MANIFEST,
        ["robot.yaml:1:7:", "this quote is not closed on its line"],
    ),
    Case(
        "yaml duplicate key",
        {"robot.yaml": MANIFEST + "name: again\n"},
        EXIT_MANIFEST,
        ["duplicate key 'name' (first at line 1)", "remove one of them"],
    ),
    Case(
        "yaml aliases that expand to billions of values",
        {"robot.yaml": MANIFEST + laughs()},
        EXIT_MANIFEST,
        ["robot.yaml:13:10:", "aliases add", "at most 100,000", "write the repeated"],
    ),
    Case(
        "motor file aliases that expand to billions of values",
        {
            "robot.yaml": MANIFEST + "motors: {files: [drives.yaml]}\n",
            "robot.urdf": two_link_urdf(),
            "drives.yaml": laughs(),
        },
        EXIT_MANIFEST,
        ["drives.yaml:10:10:", "aliases add"],
    ),
    Case(
        "yaml read by xacro with aliases that expand to billions of values",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<xacro:property name="limits" value="${xacro.load_yaml(\'limits.yaml\')}"/>\n'
            '<link name="${limits.l0[0]}"/></robot>\n',
            "limits.yaml": laughs(),
        },
        EXIT_INPUT,
        ["limits.yaml:10:10:", "aliases add", "write the repeated"],
    ),
    Case(
        "unknown top-level key",
        {"robot.yaml": MANIFEST + "outptu:\n  folder: out\n"},
        EXIT_MANIFEST,
        ["robot.yaml:4:1", "unknown key 'outptu'", "output"],
    ),
    Case(
        "unknown nested key",
        {"robot.yaml": MANIFEST + "options:\n  free_joints: true\n"},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "free_joint"],
    ),
    Case(
        "training variant: floor contact names no link",
        {
            "robot.yaml": MANIFEST
            + "output:\n  training:\n    floor_contacts:\n      remove: [foot]\n",
            "robot.urdf": two_link_urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:7:16", "floor_contacts.remove[0]", "'foot'", "not a link"],
    ),
    Case(
        "training variant: solver setting out of range",
        {"robot.yaml": MANIFEST + "output:\n  training:\n    ls_iterations: 0\n"},
        EXIT_MANIFEST,
        ["robot.yaml:6:", "ls_iterations", "greater than or equal to 1"],
    ),
    Case(
        "wrong type",
        {"robot.yaml": MANIFEST + "options:\n  free_joint: maybe\n"},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "free_joint", "true or false", "'maybe'"],
    ),
    Case(
        "missing source", {"robot.yaml": "name: robot\n"}, EXIT_MANIFEST, ["robot.yaml", "source"]
    ),
    Case(
        "two sources",
        {"robot.yaml": MANIFEST + "  xacro: robot.urdf.xacro\n"},
        EXIT_MANIFEST,
        ["robot.yaml:2:", "one of"],
    ),
    Case("empty manifest", {"robot.yaml": ""}, EXIT_MANIFEST, ["robot.yaml", "empty"]),
    Case(
        "manifest is a list",
        {"robot.yaml": "- name: robot\n"},
        EXIT_MANIFEST,
        ["robot.yaml:1:", "mapping"],
    ),
    Case("manifest not found", {}, EXIT_MANIFEST, ["robot.yaml", "not found", "init"]),
    Case(
        "manifest in a folder, with another extension",
        {"robots/arm/robot.yaml": MANIFEST},
        EXIT_MANIFEST,
        ["error: robots/arm/robot.yml: manifest not found"],
        args=["build", "robots/arm/robot.yml"],
    ),
    Case("manifest is a folder", {"robot.yaml/keep": ""}, EXIT_MANIFEST, ["robot.yaml", "folder"]),
    Case(
        "manifest not UTF-8",
        {"robot.yaml": b"name: r\xe9bot\nsource:\n  urdf: robot.urdf\n"},
        EXIT_MANIFEST,
        ["robot.yaml", "UTF-8"],
    ),
    Case(
        "duplicate key",
        {"robot.yaml": MANIFEST + "name: other\n"},
        EXIT_MANIFEST,
        ["robot.yaml:4:1", "duplicate key 'name'"],
    ),
    Case(
        "negative number",
        {"robot.yaml": MANIFEST + "meshes:\n  max_faces: -5\n"},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "max_faces", "-5 should be greater than 3"],
    ),
    Case(
        "threshold out of range",
        {"robot.yaml": MANIFEST + "collision:\n  decompose:\n    threshold: 5\n"},
        EXIT_MANIFEST,
        ["robot.yaml:6:5", "threshold", "less than or equal to 1"],
    ),
    Case(
        "hull tolerance out of range",
        {"robot.yaml": MANIFEST + "collision:\n  decompose:\n    hull_tolerance: -0.1\n"},
        EXIT_MANIFEST,
        ["robot.yaml:6:5", "hull_tolerance", "greater than or equal to 0"],
    ),
    Case(
        "hull tolerance yes or no",
        {"robot.yaml": MANIFEST + "collision:\n  decompose:\n    hull_tolerance: no\n"},
        EXIT_MANIFEST,
        ["robot.yaml:6:5", "hull_tolerance", "0 runs CoACD on every mesh"],
    ),
    Case(
        "hull tolerance in a rule",
        {
            "robot.yaml": MANIFEST
            + "collision:\n  rules:\n    - links: [a]\n      policy: decompose\n"
            "      decompose: {hull_tolerance: 2}\n"
        },
        EXIT_MANIFEST,
        ["robot.yaml", "hull_tolerance", "less than or equal to 1"],
    ),
    Case(
        "collision rule naming no link (letter case)",
        {
            "robot.yaml": MANIFEST + "collision:\n  rules:\n    - {links: [Arm], policy: hull}\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:6:", "rule matches no link of the robot (Arm); did you mean 'arm'?"],
    ),
    Case(
        "collision rule naming no mesh",
        {
            "robot.yaml": MANIFEST
            + "collision:\n  rules:\n    - {meshes: [forarm*], policy: decompose}\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:6:", "rule matches no mesh of the robot (forarm*)", "its meshes: none"],
    ),
    Case(
        "collada_up_axis_files naming no mesh file",
        {
            "robot.yaml": MANIFEST + "meshes:\n  collada_up_axis_files: {arm.stll: ignore}\n",
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": TETRAHEDRON_STL,
        },
        EXIT_MANIFEST,
        [
            "robot.yaml:5:",
            "'arm.stll' matches no mesh file of the robot; did you mean 'arm.stl'?",
            "fix the name, or remove the entry",
        ],
    ),
    Case(
        "not a number",
        {"robot.yaml": MANIFEST + "inertia:\n  min_mass: .nan\n"},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "min_mass: expected a finite number, got nan"],
    ),
    Case(
        "infinite where a number is meant",
        {"robot.yaml": MANIFEST + "inertia:\n  min_mass: .inf\n"},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "min_mass: expected a finite number, got inf"],
    ),
    Case(
        "robot name with a slash",
        {"robot.yaml": MANIFEST.replace("robot\n", "../evil\n", 1)},
        EXIT_MANIFEST,
        ["robot.yaml:1:1", "'../evil' is not a valid name"],
    ),
    Case(
        "output file escapes the folder",
        {"robot.yaml": MANIFEST + "output:\n  robot: ../../escaped.xml\n"},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "output.robot", "not a valid name"],
    ),
    Case(
        "xacro args not a mapping",
        {"robot.yaml": XACRO_MANIFEST + "  args: [a, b]\n"},
        EXIT_MANIFEST,
        ["robot.yaml:4:3", "source.args", "mapping"],
    ),
    Case(
        "package folder missing",
        {"robot.yaml": MANIFEST + "packages:\n  my_robot: ./nowhere\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "packages.my_robot", "nowhere", "not a folder"],
    ),
    # ---- sources ------------------------------------------------------------------------------
    Case(
        "urdf not found",
        {"robot.yaml": MANIFEST},
        EXIT_INPUT,
        ["error: robot.urdf: source file not found (fix 'source.urdf' at robot.yaml:3)"],
    ),
    Case(
        "urdf spelt in another letter case",
        {"robot.yaml": MANIFEST, "Robot.URDF": urdf()},
        EXIT_INPUT,
        ["robot.urdf", "not found", "did you mean 'Robot.URDF'?"],
    ),
    Case(
        "xacro include spelt in another letter case",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '  <xacro:include filename="Arm.xacro"/>\n  <link name="base"/>\n</robot>\n',
            "arm.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n',
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:2:", "Arm.xacro", "did you mean 'arm.xacro'?"],
    ),
    Case(
        "xacro not found",
        {"robot.yaml": "# a comment first\n" + XACRO_MANIFEST},
        EXIT_INPUT,
        ["error: robot.urdf.xacro: source file not found (fix 'source.xacro' at robot.yaml:4)"],
    ),
    Case(
        "srdf not found",
        {
            "robot.yaml": MANIFEST + "self_collision:\n  srdf: config/robot.srdf\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["config/robot.srdf: SRDF not found (fix 'self_collision.srdf' at robot.yaml:5)"],
    ),
    Case(
        "init on a mesh",
        {"meshes/robot.stl": TETRAHEDRON_STL},
        EXIT_INPUT,
        ["error: meshes/robot.stl is an STL mesh, not a URDF or xacro file"],
        args=["init", "meshes/robot.stl"],
    ),
    Case(
        "mesh named as the source",
        {"robot.yaml": MANIFEST.replace("robot.urdf", "robot.stl"), "robot.stl": TETRAHEDRON_STL},
        EXIT_INPUT,
        ["error: robot.stl: this is an STL mesh, not a URDF or xacro file"],
    ),
    Case(
        # The hint keeps the folder. Before: source: {xacro: robot.urdf.xacro}, a file that
        # is not there.
        "xacro file in a folder named as urdf:",
        {
            "robot.yaml": MANIFEST.replace("robot.urdf", "urdf/robot.urdf.xacro"),
            "urdf/robot.urdf.xacro": ARG_XACRO,
        },
        EXIT_INPUT,
        ["urdf/robot.urdf.xacro:2: this file is xacro", "source: {xacro: urdf/robot.urdf.xacro}"],
    ),
    Case(
        "xacro XML syntax",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<link name="base">\n</robot>\n',
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:3", "XML"],
    ),
    Case(
        "xacro undefined property",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<link name="${base_name}"/>\n</robot>\n',
        },
        EXIT_INPUT,
        [
            "error: robot.urdf.xacro:2: xacro failed: name 'base_name' is not defined",
            "define it with <xacro:property>",
        ],
    ),
    Case(
        "xacro undefined property in a macro of an included file",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": XACRO_OPEN + '<xacro:include filename="parts/leg.xacro"/>\n'
            '<link name="base"/>\n<xacro:leg side="left"/>\n</robot>\n',
            "parts/leg.xacro": XACRO_OPEN + '<xacro:macro name="leg" params="side">\n'
            '  <link name="${side}_leg"/>\n'
            '  <link name="${sid}_foot"/>\n'
            "</xacro:macro>\n</robot>\n",
        },
        EXIT_INPUT,
        ["error: parts/leg.xacro:4: xacro failed: in macro 'leg': name 'sid' is not defined"],
    ),
    Case(
        "xacro macro called with a misspelt parameter",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": XACRO_OPEN + '<xacro:macro name="leg" params="side">\n'
            '  <link name="${side}_leg"/>\n</xacro:macro>\n<link name="base"/>\n'
            '<xacro:leg sied="left"/>\n</robot>\n',
        },
        EXIT_INPUT,
        [
            "error: robot.urdf.xacro:6: xacro failed: macro 'leg' is called with parameter 'sied',"
            " which it does not declare; did you mean 'side'? (declared: side)"
        ],
    ),
    Case(
        "xacro macro called without a parameter",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": XACRO_OPEN + '<xacro:macro name="leg" params="side">\n'
            '  <link name="${side}_leg"/>\n</xacro:macro>\n<link name="base"/>\n'
            "<xacro:leg/>\n</robot>\n",
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:6: xacro failed: macro 'leg' is called without parameter side"],
    ),
    Case(
        "xacro unknown macro",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": XACRO_OPEN
            + '<link name="base"/>\n<xacro:lge side="l"/>\n</robot>\n',
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:3: xacro failed: unknown macro name: xacro:lge", "define the macro"],
    ),
    Case(
        "xacro unknown package",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<xacro:include filename="$(find ghost_description)/a.xacro"/>\n'
            "</robot>\n",
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:2:", "ghost_description", "packages"],
    ),
    Case(
        "xacro include missing",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<xacro:include filename="parts/missing.xacro"/>\n</robot>\n',
        },
        EXIT_INPUT,
        # The path once, and the line of the include.
        [
            "error: robot.urdf.xacro:2: xacro failed: included file parts/missing.xacro not found"
            " (fix the include's filename"
        ],
    ),
    Case(
        "xacro argument without value",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<link name="$(arg prefix)base"/>\n</robot>\n',
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:2:", "substitution argument prefix", "source.args"],
    ),
    Case(
        "xacro argument misspelt in robot.yaml",
        {
            "robot.yaml": XACRO_MANIFEST + "  args:\n    with_cmaera: false\n",
            "robot.urdf.xacro": ARG_XACRO,
        },
        EXIT_MANIFEST,
        [
            "robot.yaml:5:5:",
            "'with_cmaera' is not declared",
            "did you mean 'with_camera'?",
            "declared: with_camera",
        ],
    ),
    Case(
        "xacro argument misspelt in an attached part",
        {
            "robot.yaml": MANIFEST
            + "attach:\n  - source:\n      xacro: part.urdf.xacro\n      args:\n"
            "        with_cmaera: false\n    to: arm\n    prefix: p_\n",
            "robot.urdf": two_link_urdf(),
            "part.urdf.xacro": ARG_XACRO,
        },
        EXIT_MANIFEST,
        ["robot.yaml:8:9:", "attach[0].source.args.with_cmaera", "did you mean 'with_camera'?"],
    ),
    Case(
        "mesh of an attached xacro part with a misspelt package",
        {
            "robot.yaml": MANIFEST
            + "packages:\n  gripper_description: .\n"
            + "attach:\n  - {source: {xacro: gripper.urdf.xacro}, to: arm, prefix: g_}\n",
            "robot.urdf": two_link_urdf(),
            "gripper.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="g">\n'
            '  <xacro:macro name="palm">\n'
            '    <link name="palm"><visual><geometry>\n'
            '      <mesh filename="package://gripper_descripton/palm.stl"/>\n'
            "    </geometry></visual></link>\n"
            "  </xacro:macro>\n  <xacro:palm/>\n</robot>\n",
        },
        EXIT_INPUT,
        [
            "error: gripper.urdf.xacro:4:",
            "did you mean 'gripper_description'?",
            "[expanded: mjcf/.mjcfbuild/attach/0.urdf:",
        ],
    ),
    Case(
        "joint of an attached xacro part with a misspelt type",
        {
            "robot.yaml": MANIFEST
            + "attach:\n  - {source: {xacro: gripper.urdf.xacro}, to: arm, prefix: g_}\n",
            "robot.urdf": two_link_urdf(),
            "gripper.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="g">\n'
            '  <link name="palm"/>\n  <link name="jaw"/>\n'
            '  <joint name="slide" type="prismatc">\n'
            '    <parent link="palm"/><child link="jaw"/></joint>\n</robot>\n',
        },
        EXIT_INPUT,
        ["error: gripper.urdf.xacro:4:", "prismatc", "[expanded: mjcf/.mjcfbuild/composed.urdf:"],
    ),
    Case(
        "xacro argument misspelt on convert",
        {"robot.urdf.xacro": ARG_XACRO},
        EXIT_USAGE,
        ["with_cmaera:=false:", "did you mean 'with_camera'?", "declared: with_camera"],
        args=["convert", "-u", "robot.urdf.xacro", "-o", "mjcf", "with_cmaera:=false"],
    ),
    Case(
        "xacro argument misspelt in the file",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": ARG_XACRO.replace("$(arg with_camera)", "$(arg with_camra)"),
        },
        EXIT_INPUT,
        ["robot.urdf.xacro:3:", "argument with_camra", "did you mean 'with_camera'?"],
    ),
    Case(
        "package misspelt in an included xacro's mesh",
        {
            "robot.yaml": XACRO_MANIFEST + "packages:\n  arm_description: .\n",
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '  <xacro:include filename="$(find arm_description)/parts/arm.xacro"/>\n'
            "  <xacro:arm/>\n</robot>\n",
            "parts/arm.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '  <xacro:macro name="arm">\n'
            '    <link name="base"><visual><geometry>\n'
            '      <mesh filename="package://arm_descripton/base.stl"/>\n'
            "    </geometry></visual></link>\n"
            "  </xacro:macro>\n</robot>\n",
        },
        EXIT_INPUT,
        [
            "error: parts/arm.xacro:4:",  # the <mesh> line
            "unknown package 'arm_descripton'; did you mean 'arm_description'?",
            "[expanded: mjcf/.mjcfbuild/source.urdf:",
        ],
    ),
    Case(
        # rtb-data's ROS-Industrial KUKA and ABB xacros are kinematic only: the error named
        # the expanded file in the state folder, which nobody wrote.
        "xacro robot without any <inertial>",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": XACRO_OPEN
            + '  <link name="base"/>\n  <link name="arm"/>\n'
            + '  <joint name="shoulder" type="continuous">\n'
            + '    <parent link="base"/><child link="arm"/></joint>\n</robot>\n',
        },
        EXIT_INPUT,
        [
            "error: robot.urdf.xacro: no link of the robot has a mass",
            "[expanded: mjcf/.mjcfbuild/source.urdf]",
            "add each link's <inertial>",
        ],
    ),
    Case(
        "xacro entity expansion",
        {"robot.yaml": XACRO_MANIFEST, "robot.urdf.xacro": LAUGHS},
        EXIT_INPUT,
        ["robot.urdf.xacro", "entit"],
    ),
    Case(
        "xacro included file with entities",
        {
            "robot.yaml": XACRO_MANIFEST,
            "robot.urdf.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">\n'
            '<xacro:include filename="evil.xacro"/>\n</robot>\n',
            "evil.xacro": LAUGHS,
        },
        EXIT_INPUT,
        ["evil.xacro:3", "entity declarations"],
    ),
    Case(
        "urdf malformed XML",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(("</robot>", "</robt>"))},
        EXIT_INPUT,
        ["robot.urdf:", "XML"],
    ),
    Case(
        "urdf root is not robot",
        {"robot.yaml": MANIFEST, "robot.urdf": "<?xml version='1.0'?>\n<sdf version='1.6'/>\n"},
        EXIT_INPUT,
        ["robot.urdf:2", "<robot>"],
    ),
    Case(
        "urdf entity expansion",
        {"robot.yaml": MANIFEST, "robot.urdf": LAUGHS},
        EXIT_INPUT,
        ["robot.urdf", "entit"],
    ),
    Case(
        "urdf external entity",
        {"robot.yaml": MANIFEST, "robot.urdf": EXTERNAL_ENTITY},
        EXIT_INPUT,
        ["robot.urdf", "entit"],
    ),
    Case(
        "urdf empty",
        {"robot.yaml": MANIFEST, "robot.urdf": ""},
        EXIT_INPUT,
        ["robot.urdf", "empty"],
    ),
    Case(
        "urdf symlink loop",
        {"robot.yaml": MANIFEST, "robot.urdf": symlink_loop},
        EXIT_INPUT,
        ["robot.urdf", "symbolic link loop"],
    ),
    Case(
        "unknown link",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(('<child link="arm"/>', '<child link="arn"/>')),
        },
        EXIT_INPUT,
        ["robot.urdf:11:", "'arn'", "did you mean 'arm'"],
    ),
    Case(
        "duplicate link",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(extra='<link name="arm"/>')},
        EXIT_INPUT,
        ["robot.urdf:15:", "link 'arm' is defined twice"],
    ),
    Case(
        "duplicate joint",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(
                extra='<link name="tip"/>\n<joint name="hinge" type="fixed">'
                '<parent link="arm"/><child link="tip"/></joint>'
            ),
        },
        EXIT_INPUT,
        ["robot.urdf:16:", "joint 'hinge' is defined twice"],
    ),
    Case(
        "kinematic cycle",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(
                extra='<joint name="back" type="fixed"><parent link="arm"/>'
                '<child link="base"/></joint>'
            ),
        },
        EXIT_INPUT,
        ["robot.urdf:", "cycle"],
    ),
    Case(
        "two roots",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(extra='<link name="loose"/>')},
        EXIT_INPUT,
        ["robot.urdf", "root", "loose"],
    ),
    Case(
        "link with two parents",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(
                extra='<link name="tip"/>\n<joint name="j2" type="fixed">'
                '<parent link="base"/><child link="arm"/></joint>'
            ),
        },
        EXIT_INPUT,
        ["robot.urdf:16:", "'arm' is the child of two joints"],
    ),
    Case(
        "unknown joint type",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('type="revolute"', 'type="hinge"'))},
        EXIT_INPUT,
        ["robot.urdf:11:", "unknown type 'hinge'", "revolute"],
    ),
    Case(
        "misspelt joint type",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('type="revolute"', 'type="revolte"'))},
        EXIT_INPUT,
        ["robot.urdf:11:", "unknown type 'revolte'; did you mean 'revolute'? (use one of"],
    ),
    Case(
        "bad number",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('xyz="0 0 0.1"', 'xyz="0 0 O.1"'))},
        EXIT_INPUT,
        ["robot.urdf:12:", "xyz", "'O.1' is not a number"],
    ),
    Case(
        "too few numbers",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('xyz="0 0 0.1"', 'xyz="0 0.1"'))},
        EXIT_INPUT,
        ["robot.urdf:12:", "needs 3 numbers, found 2"],
    ),
    Case(
        "infinite number",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('rpy="0 0 0.3"', 'rpy="0 0 inf"'))},
        EXIT_INPUT,
        ["robot.urdf:12:", "rpy", "not a finite number"],
    ),
    Case(
        "zero-size box",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('size="0.2 0.2 0.1"', 'size="0.2 0 0.1"'))},
        EXIT_INPUT,
        ["robot.urdf:4:", "box size 0.2 0 0.1", "positive size"],
    ),
    Case(
        "negative radius",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(
                (
                    '<geometry><cylinder radius="0.03" length="0.5"/></geometry></collision>',
                    '<geometry><cylinder radius="-0.03" length="0.5"/></geometry></collision>',
                )
            ),
        },
        EXIT_INPUT,
        ["robot.urdf:9:", "cylinder"],
    ),
    Case(
        "zero axis",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>')),
        },
        EXIT_INPUT,
        ["robot.urdf:13:", "zero axis"],
    ),
    Case(
        "lower limit above upper",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(('lower="-1.5"', 'lower="2"'))},
        EXIT_INPUT,
        ["robot.urdf:13:", "lower limit 2 above its upper limit 1.5", "(swap them; if they"],
    ),
    Case(
        "negative mass",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(
                (
                    '<link name="arm"><inertial><mass value="1"/>',
                    '<link name="arm"><inertial><mass value="-1"/>',
                )
            ),
        },
        EXIT_INPUT,
        ["robot.urdf:6:", "mass -1"],
    ),
    Case(
        "floating joint below the root",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": two_link_urdf(
                extra='<link name="tip"/><joint name="loose" type="floating"><parent '
                'link="arm"/><child link="tip"/></joint>'
            ),
        },
        EXIT_MODEL,
        ["robot.urdf:15:", "joint 'loose' is floating below link 'arm'", "make it fixed"],
    ),
    # ---- meshes -------------------------------------------------------------------------------
    Case(
        "mesh not found",
        {"robot.yaml": MANIFEST, "robot.urdf": mesh_urdf("meshes/arm.stl")},
        EXIT_INPUT,
        ["robot.urdf:6:", "meshes/arm.stl", "not found"],
    ),
    Case(
        "mesh spelt in another letter case",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.STL"),
            "meshes/arm.stl": TETRAHEDRON_STL,
        },
        EXIT_INPUT,
        ["robot.urdf:6:", "meshes/arm.STL", "did you mean 'meshes/arm.stl'?", "letter case"],
    ),
    Case(
        "mesh file empty",
        {"robot.yaml": MANIFEST, "robot.urdf": mesh_urdf("meshes/arm.stl"), "meshes/arm.stl": b""},
        EXIT_INPUT,
        ["robot.urdf:6: meshes/arm.stl: the mesh file is empty"],
    ),
    Case(
        # A text file named .stl. Before: "meshes/arm.stl: mesh has no triangles (re-export it
        # with its faces)", and no URDF line.
        "text file named as an STL mesh",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": "This is not a valid STL file.\n",
        },
        EXIT_INPUT,
        ["robot.urdf:6: meshes/arm.stl: not an STL file", "ASCII STL", "binary STL"],
    ),
    Case(
        "mesh file corrupt",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": b"\x00\x01garbage" * 20,
        },
        EXIT_INPUT,
        ["arm.stl"],
    ),
    Case(
        "mesh COLLADA corrupt",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.dae"),
            "meshes/arm.dae": "<COLLADA><library_geometries><geometry>",
        },
        EXIT_INPUT,
        ["arm.dae"],
    ),
    Case(
        "mesh COLLADA id names two sources",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.dae"),
            "meshes/arm.dae": dae_document(
                dae_geometry("tetrahedron", TETRAHEDRON, "a")
                + dae_geometry("box", BOX, "a")
                + dae_geometry("lost", TETRAHEDRON, "b", vertex_url="#a-vertices"),
                f"<node>{dae_instance('lost')}</node>",
            ),
        },
        EXIT_INPUT,
        ["arm.dae:38:", "names 2 different <vertices> elements (lines 12 and 24)"],
    ),
    Case(
        "mesh COLLADA collapsed to a point",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.dae"),
            "meshes/arm.dae": dae_document(
                dae_geometry("box", ([0.5, 0.5, 0.5] * 8, BOX[1])),
                f"<node>{dae_instance('box')}</node>",
            ),
        },
        EXIT_INPUT,
        ["arm.dae:", "all 12 faces", "collapse to a single point"],
    ),
    Case(
        "mesh format unknown",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.fbx"),
            "meshes/arm.fbx": b"Kaydara FBX Binary",
        },
        EXIT_INPUT,
        ["arm.fbx", "format"],
    ),
    Case(
        "mesh without faces",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.obj"),
            "meshes/arm.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
        },
        EXIT_INPUT,
        ["arm.obj", "faces"],
    ),
    Case(
        "mesh too large",
        {
            "robot.yaml": MANIFEST + "meshes:\n  max_file_mb: 0.0001\n",
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": TETRAHEDRON_STL * 3,
        },
        EXIT_INPUT,
        ["meshes/arm.stl", "more than meshes.max_file_mb"],
    ),
    Case(
        "mesh symlink loop",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": symlink_loop,
        },
        EXIT_INPUT,
        ["robot.urdf:6:", "meshes/arm.stl", "symbolic link loop"],
    ),
    Case(
        "mesh in unknown package",
        {"robot.yaml": MANIFEST, "robot.urdf": mesh_urdf("package://ghost/meshes/arm.stl")},
        EXIT_INPUT,
        ["robot.urdf:6:", "unknown package 'ghost'", "packages"],
    ),
    Case(
        "mesh package URI names no file in the package",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": mesh_urdf("package://arm.obj"),
            "arm.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        },
        EXIT_INPUT,
        ["robot.urdf:6:", "names package 'arm.obj' but no file in it", 'filename="arm.obj"'],
    ),
    Case(
        "mesh package name escapes",
        {"robot.yaml": MANIFEST, "robot.urdf": mesh_urdf("package://../../etc/arm.stl")},
        EXIT_INPUT,
        ["robot.urdf:6:", "'..' is no ROS package name"],
    ),
    Case(
        "mesh remote URL",
        {"robot.yaml": MANIFEST, "robot.urdf": mesh_urdf("https://example.com/arm.stl")},
        EXIT_INPUT,
        ["robot.urdf:6:", "remote file", "download"],
    ),
    # ---- MuJoCo inputs ------------------------------------------------------------------------
    Case(
        "raw MJCF malformed",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  raw: |\n    <actuator><motor joint='hinge'>\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:7:", "mujoco_inputs.raw", "malformed XML"],
    ),
    Case(
        "modify unknown element",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  modify:\n    - type: joint\n      name: elbow\n"
            "      attributes: {damping: 1}\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:", "no joint named 'elbow'", "hinge"],
    ),
    Case(
        "modify element type misspelt, in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  modify:\n    - type: jiont\n      name: hinge\n"
            "      attributes: {damping: 1}\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        [
            "robot.yaml:6:",
            "mujoco_inputs.modify[0]: modify_element: unknown element type 'jiont'; "
            "did you mean 'joint'?",
        ],
    ),
    Case(
        "modify geom class misspelt, in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  modify:\n    - {type: geom, mesh: arm, class: visul,"
            " attributes: {rgba: '1 0 0 1'}}\n",
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": TETRAHEDRON_STL,
        },
        EXIT_INPUT,
        [
            "robot.yaml:6:",
            "no geom with mesh 'arm' and class 'visul': the geoms of mesh 'arm' have class "
            "visual; did you mean 'visual'?",
        ],
    ),
    Case(
        "inputs file missing",
        {"robot.yaml": MANIFEST + "mujoco_inputs:\n  file: inputs.xml\n", "robot.urdf": urdf()},
        EXIT_INPUT,
        ["inputs.xml", "not found"],
    ),
    Case(
        "inputs file spelt in another letter case",
        {
            "robot.yaml": MANIFEST + "mujoco_inputs:\n  file: inputs.xml\n",
            "robot.urdf": urdf(),
            "Inputs.XML": "<mujoco/>\n",
        },
        EXIT_INPUT,
        ["inputs.xml", "did you mean 'Inputs.XML'?"],
    ),
    Case(
        "lidar attribute the reference converter does not have, in an inputs file",
        {
            "robot.yaml": MANIFEST + "mujoco_inputs:\n  file: inputs.xml\n",
            "robot.urdf": urdf(),
            "inputs.xml": "<mujoco_inputs>\n<processed_inputs>\n"
            "<lidar ref_site='arm' sensor_name='rf' min_angle='0' max_angle='1' "
            "angle_increment='0.1' max_range='5'/>\n</processed_inputs>\n</mujoco_inputs>\n",
        },
        EXIT_INPUT,
        ["inputs.xml:3:", "<lidar> has no attribute 'max_range'", "known attributes: "],
    ),
    Case(
        "decompose_mesh attribute misspelt, in the URDF's mujoco_inputs",
        {
            "robot.yaml": MANIFEST,
            "robot.urdf": urdf(
                extra="<mujoco_inputs>\n<processed_inputs>\n"
                "<decompose_mesh mesh_name='arm' treshold='0.1'/>\n"
                "</processed_inputs>\n</mujoco_inputs>\n"
            ),
        },
        EXIT_INPUT,
        ["robot.urdf:", "<decompose_mesh> has no attribute 'treshold'; did you mean 'threshold'?"],
    ),
    Case(
        "lidar key of the XML form in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  lidars:\n    - {sensor_name: rf, ref_site: arm, min_angle: 0,"
            " max_angle: 1, angle_increment: 0.1}\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:6:", "unknown key 'ref_site'; did you mean 'link'?"],
    ),
    Case(
        "decompose key unknown in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  decompose:\n    - {mesh: arm, threshold: 0.1, seed: 3}\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:6:", "unknown key 'seed'; allowed keys: mesh, threshold"],
    ),
    Case(
        "decompose naming no mesh of the robot, in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  decompose:\n    - {mesh: amr, threshold: 0.1}\n",
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": TETRAHEDRON_STL,
        },
        EXIT_INPUT,
        [
            "robot.yaml:6:",
            "mujoco_inputs.decompose[0]: decompose_mesh 'amr' names no mesh of the robot; "
            "did you mean 'arm'?",
            "mesh names: arm",
        ],
    ),
    Case(
        "decompose_mesh naming no mesh of the robot, in an inputs file",
        {
            "robot.yaml": MANIFEST + "mujoco_inputs:\n  file: inputs.xml\n",
            "robot.urdf": mesh_urdf("meshes/arm.stl"),
            "meshes/arm.stl": TETRAHEDRON_STL,
            "inputs.xml": "<mujoco_inputs>\n<processed_inputs>\n"
            "<decompose_mesh mesh_name='arm.stll' threshold='0.1'/>\n"
            "</processed_inputs>\n</mujoco_inputs>\n",
        },
        EXIT_INPUT,
        [
            "inputs.xml:3: decompose_mesh 'arm.stll' names no mesh of the robot; "
            "did you mean 'arm.stl'?",
            "mesh names: arm",
        ],
    ),
    Case(
        "camera attribute MuJoCo does not have, in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  cameras:\n    - name: eye\n      link: arm\n"
            "      attributes: {fovyy: 40}\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:", "camera 'eye' sets 'fovyy'", "did you mean 'fovy'?", "attributes: "],
    ),
    Case(
        "modify attribute MuJoCo does not have, in robot.yaml",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  modify:\n    - type: joint\n      name: hinge\n"
            "      attributes: {dampng: 1}\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:", "joint 'hinge' sets 'dampng'", "did you mean 'damping'?"],
    ),
    Case(
        "camera on unknown link",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  cameras:\n    - name: eye\n      link: head\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:7", "cameras[0]", "link 'head', which does not exist"],
    ),
    Case(
        "raw actuator on unknown joint",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  raw: |\n    <actuator><motor joint='elbow'/></actuator>\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:", 'joint="elbow" names a joint that does not exist'],
    ),
    # ---- names looked up: did you mean ---------------------------------------------------------
    Case(
        "home joint misspelt",
        {"robot.yaml": MANIFEST + "home:\n  hnige: 0.5\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:5:3:", "'hnige' matches no moving joint; did you mean 'hinge'?"],
    ),
    Case(
        "actuator rule joint misspelt",
        {
            "robot.yaml": MANIFEST + "actuators:\n  rules:\n    - {joints: [hnige], type: motor}\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:6:", "matches no actuated joint (hnige); did you mean 'hinge'?"],
    ),
    Case(
        "kept collision pair link misspelt",
        {
            "robot.yaml": MANIFEST + "self_collision:\n  keep: [[base, amr]]\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:5:", "link 'amr' is not a link of the robot; did you mean 'arm'?"],
    ),
    Case(
        "camera link misspelt",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  cameras:\n    - name: eye\n      link: amr\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:7", "link 'amr', which does not exist; did you mean 'arm'?"],
    ),
    Case(
        "raw actuator joint misspelt",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  raw: |\n    <actuator><motor joint='hnige'/></actuator>\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:", "names a joint that does not exist; did you mean 'hinge'?"],
    ),
    Case(
        "raw option timestep negative",
        {
            "robot.yaml": MANIFEST + "mujoco_inputs:\n  raw: |\n    <option timestep='-1'/>\n",
            "robot.urdf": urdf(),
        },
        EXIT_INPUT,
        ["robot.yaml:6:", "the timestep must be a positive number of seconds"],
    ),
    Case(
        "attached part's link misspelt",
        {
            "robot.yaml": MANIFEST
            + "attach:\n  - {source: {urdf: part.urdf}, to: amr, prefix: p_}\n",
            "robot.urdf": two_link_urdf(),
            "part.urdf": '<robot name="p"><link name="palm"/></robot>\n',
        },
        EXIT_MANIFEST,
        ["robot.yaml:", "'amr'", "did you mean 'arm'?"],
    ),
    # ---- outputs ------------------------------------------------------------------------------
    Case(
        "output folder inside a file",
        {
            "robot.yaml": MANIFEST + "output:\n  folder: taken/mjcf\n",
            "robot.urdf": urdf(),
            "taken": a_plain_file,
        },
        EXIT_OUTPUT,
        ["taken", "folder"],
    ),
    Case(
        "output folder read-only",
        {
            "robot.yaml": MANIFEST + "output:\n  folder: locked\n",
            "robot.urdf": urdf(),
            "locked": read_only_folder,
        },
        EXIT_OUTPUT,
        ["locked", "permission"],
        needs_unprivileged=True,
    ),
    Case(
        "output folder is the filesystem root",
        {"robot.yaml": MANIFEST + "output:\n  folder: /\n", "robot.urdf": urdf()},
        EXIT_OUTPUT,
        ["robot.yaml:5:", "'/' is outside", "output.allow_outside: true", "--allow-outside"],
    ),
    Case(
        "output folder above robot.yaml",
        {"robot.yaml": MANIFEST + "output:\n  folder: ../built\n", "robot.urdf": urdf()},
        EXIT_OUTPUT,
        ["robot.yaml:5:", "'../built'", "is outside", "--allow-outside"],
    ),
    Case(
        "output folder linked out of the tree",
        {
            "robot.yaml": MANIFEST + "output:\n  folder: out\n",
            "robot.urdf": urdf(),
            "out": link_to_elsewhere,
        },
        EXIT_OUTPUT,
        ["robot.yaml:5:", "'out' leads through a link to", "--allow-outside"],
    ),
    Case(
        "assets folder is a link",
        {
            "robot.yaml": MANIFEST + "output:\n  folder: out\n",
            "robot.urdf": urdf(),
            "out/assets": link_to_elsewhere,
        },
        EXIT_OUTPUT,
        ["out/assets", "symbolic link", "remove the link"],
    ),
    Case(
        "output folder that is a file",
        {"robot.yaml": MANIFEST + "output:\n  folder: robot.urdf\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:5:3", "output.folder: 'robot.urdf' is a file, not a folder"],
    ),
    Case(
        "clean of an output folder above robot.yaml",
        {"robot.yaml": MANIFEST + "output:\n  folder: ..\n", "robot.urdf": urdf()},
        EXIT_OUTPUT,
        ["robot.yaml:5:", "'..'", "is outside", "--allow-outside"],
        args=["clean"],
    ),
    Case(
        "self-collision samples beyond what a build can take",
        {
            "robot.yaml": MANIFEST + "self_collision:\n  samples: 1000000000\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:", "samples", "100000"],
    ),
    Case(
        "check configurations beyond what a build can take",
        {"robot.yaml": MANIFEST + "check:\n  configurations: 1000000000\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:5:", "configurations", "10000"],
    ),
    Case(
        "lidar of a million rays",
        {
            "robot.yaml": MANIFEST
            + "mujoco_inputs:\n  lidars:\n    - {sensor_name: rf, link: arm, min_angle: 0,"
            " max_angle: 3, angle_increment: 0.000001}\n",
            "robot.urdf": urdf(),
        },
        EXIT_MANIFEST,
        ["robot.yaml:6:", "3000001 rays", "at most 20000"],
    ),
    Case(
        "model name too long for the file system",
        {"robot.yaml": MANIFEST.replace("name: robot", "name: " + "r" * 250), "robot.urdf": urdf()},
        EXIT_OUTPUT,
        ["cannot write: file name too long for its file system", "shorten the name"],
    ),
    # ---- the command line ---------------------------------------------------------------------
    Case(
        "check tolerance not a number",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["--tolerance", "must be a positive number"],
        args=["check", "--tolerance", "nan"],
    ),
    Case(
        "build timeout negative",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["argument --timeout: must be more than 0"],
        args=["build", "--timeout=-1"],
    ),
    Case(
        "build timeout infinite (the system's timers refuse it)",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["argument --timeout: must be at most 1e+07"],
        args=["build", "--timeout", "inf"],
    ),
    Case(
        "watch interval infinite",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["argument --interval: must be at most 1e+07"],
        args=["watch", "--interval", "inf"],
    ),
    Case(
        "check tolerance negative",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["--tolerance", "must be a positive number"],
        args=["check", "--tolerance=-1"],
    ),
    Case(
        "check configurations beyond what a check can take",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["--configurations", "must be from 1 to 10000"],
        args=["check", "--configurations", "1000000000"],
    ),
    Case(
        "unknown option",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["--fast"],
        args=["build", "--fast"],
    ),
    Case(
        "zero jobs",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["at least 1"],
        args=["build", "-j", "0"],
    ),
    Case(
        "explain unknown task",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["mesh:nothing"],
        args=["explain", "mesh:nothing"],
    ),
    Case("convert without input", {}, EXIT_USAGE, ["-u", "-r"], args=["convert", "-o", "out"]),
    # A manifest given to convert. Before: "one of -u/-r is required", or with -u, -m robot.yaml
    # read as XML: "robot.yaml:1:1: malformed XML".
    *(
        Case(
            f"convert given a robot.yaml ({' '.join(args)})",
            {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
            EXIT_USAGE,
            [
                "robot.yaml is a manifest",
                "reference converter's flags",
                "mjcfbuild build robot.yaml",
            ],
            args=["convert", *args],
        )
        for args in (["robot.yaml"], ["-m", "robot.yaml"], ["-u", "robot.urdf", "-m", "robot.yaml"])
    ),
    # ---- diff (more in tests/cli/test_diff.py, with git) -----------------------------------------
    Case(
        "diff of a folder with no build",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf(), "empty/.keep": ""},
        EXIT_INPUT,
        ["empty", "no mjcfbuild build", "mjcfbuild build wrote"],
        args=["diff", "--folders", "empty", "mjcf"],
    ),
    Case(
        "diff with nothing to compare",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["--base REF", "--folders OLD NEW"],
        args=["diff"],
    ),
    Case(
        "diff outside a git repository",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_INPUT,
        ["robot.yaml", "not inside a git repository", "--folders"],
        args=["diff", "--base", "main"],
    ),
    # ---- the remote cache and the executor (more in tests/test_sharing_settings.py) -----------
    Case(
        "malformed remote cache URL",
        {"robot.yaml": MANIFEST + "cache:\n  remote: 's3://'\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:5", "bucket name", "s3://bucket/prefix"],
    ),
    Case(
        "unknown remote cache protocol",
        {"robot.yaml": MANIFEST + "cache:\n  remote: 'webdav://h/x'\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:5", "webdav://", "known:"],
    ),
    Case(
        "malformed executor in robot.yaml",
        {"robot.yaml": MANIFEST + "executor: 'dask://'\n", "robot.urdf": urdf()},
        EXIT_MANIFEST,
        ["robot.yaml:4", "dask://host:port"],
    ),
    Case(
        "malformed executor on the command line",
        {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["--executor", "not an executor", "dask://host:port"],
        args=["build", "--executor", "ray://head:10001"],
    ),
    # ---- the environment -----------------------------------------------------------------------
    *(
        Case(
            f"MJCFBUILD_CACHE_MAX that is no size ({command[0]})",
            {"robot.yaml": MANIFEST, "robot.urdf": urdf()},
            EXIT_USAGE,
            ["MJCFBUILD_CACHE_MAX=zz: not a size", "500M or 2G", "unset it"],
            args=command,
            env={"MJCFBUILD_CACHE_MAX": "zz"},
        )
        for command in (["build"], ["check"], ["cache", "show"])
    ),
    Case(
        "export-urdf over a file it did not write (the description's own URDF)",
        {"model.xml": EXPORT_MODEL, "robot.urdf": urdf()},
        EXIT_USAGE,
        ["robot.urdf already exists and was not written by export-urdf", "--force"],
        args=["export-urdf", "model.xml", "-o", "robot.urdf"],
    ),
    Case(
        # /proc refuses new folders with "no such file": not an internal error.
        "export-urdf: --mesh-folder where no folder can be made",
        {"model.xml": EXPORT_MESH_MODEL, "arm.obj": OBJ},
        EXIT_OUTPUT,
        ["/proc/mjcfbuild-meshes: cannot write the URDF export", "--mesh-folder"],
        args=[*EXPORT_ARGS[:4], "--mesh-folder", "/proc/mjcfbuild-meshes"],
    ),
    Case(
        "export-urdf: --limits-from a missing URDF",
        {"model.xml": EXPORT_MODEL},
        EXIT_INPUT,
        ["original.urdf", "not found"],
        args=EXPORT_ARGS,
    ),
    Case(
        "export-urdf: --limits-from a xacro file with an argument it does not declare",
        {"model.xml": EXPORT_MODEL, "original.urdf": ARG_XACRO},
        EXIT_USAGE,
        ["with_cmaera", "with_camera"],
        args=[*EXPORT_ARGS, "--xacro-arg", "with_cmaera:=false"],
    ),
    Case(
        "export-urdf: --xacro-arg with a URDF",
        {"model.xml": EXPORT_MODEL, "original.urdf": urdf()},
        EXIT_USAGE,
        ["--xacro-arg needs a xacro file", "original.urdf is not one"],
        args=[*EXPORT_ARGS, "--xacro-arg", "a:=1"],
    ),
    Case(
        "export-urdf: --limits-from a malformed URDF",
        {
            "model.xml": EXPORT_MODEL,
            "original.urdf": urdf(('velocity="1"', 'velocity="fast"')),
        },
        EXIT_INPUT,
        ["original.urdf:", "velocity"],
        args=EXPORT_ARGS,
    ),
]
