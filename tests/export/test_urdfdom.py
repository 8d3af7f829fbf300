"""Every URDF mjcfbuild writes, judged by ROS's own parser (urdfdom's ``check_urdf`` and
``urdf_to_graphviz``, tests/urdfdom.py): accepted without a logged error, with the tree
mjcfbuild meant: each MuJoCo body a link below its parent body's link, and the root, links,
joints and joint origins mjcfbuild's reader finds in the same file."""

from __future__ import annotations

from pathlib import Path

import mujoco
import pytest

from mjcfbuild.urdf.parse import parse_urdf
from tests.conftest import copy_example, run_cli
from tests.export.handwritten import write_model
from tests.urdfdom import UrdfdomModel, require_urdfdom, same_origin, urdfdom_read


@pytest.fixture(autouse=True)
def urdfdom() -> str:
    return require_urdfdom()


def assert_urdfdom_reads_it(urdf: Path, scratch: Path) -> UrdfdomModel:
    """urdfdom accepts ``urdf`` without an error and reads the tree mjcfbuild's reader does."""
    judged = urdfdom_read(urdf, scratch)
    assert judged.accepted and judged.errors == [], judged.errors
    robot = parse_urdf(urdf.read_bytes(), str(urdf))
    assert judged.root == robot.root
    ours = {link: sorted(j.child for j in joints) for link, joints in robot.child_joints().items()}
    assert {link: sorted(kids) for link, kids in judged.children.items()} == ours
    assert set(judged.joints) == {joint.name for joint in robot.joints}
    for joint in robot.joints:
        theirs = judged.joints[joint.name]
        assert (theirs.parent, theirs.child) == (joint.parent, joint.child), joint.name
        assert same_origin(theirs, joint.origin.xyz, joint.origin.rpy), joint.name
    return judged


def assert_bodies_keep_their_tree(judged: UrdfdomModel, model_path: Path) -> None:
    """Each named body of the MJCF is a link, below the link of its parent body."""
    model = mujoco.MjModel.from_xml_path(str(model_path))
    parent_link = {kid: link for link, kids in judged.children.items() for kid in kids}

    def ancestors(link: str) -> list[str]:
        chain = []
        while link in parent_link:
            link = parent_link[link]
            chain.append(link)
        return chain

    for body in range(1, model.nbody):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body)
        assert name in judged.links(), name
        parent = int(model.body_parentid[body])
        if parent:
            above = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, parent)
            assert above in ancestors(name), (name, above)


def test_the_handwritten_models_export_is_read_by_urdfdom(tmp_path):
    model_path = write_model(tmp_path / "model")
    urdf = tmp_path / "out" / "robot.urdf"
    result = run_cli("export-urdf", str(model_path), "-o", str(urdf))
    assert result.code == 0, result.stderr
    judged = assert_urdfdom_reads_it(urdf, tmp_path / "graph")
    assert_bodies_keep_their_tree(judged, model_path)
    # What the exporter means beyond the bodies: a ball's chain of joints, sites as links.
    assert judged.joints["wrist_ball_x"].parent == "slider"
    assert judged.root == "base" and "tool" in judged.children["wrist"]

    bare = tmp_path / "bare" / "robot.urdf"
    result = run_cli("export-urdf", str(model_path), "-o", str(bare), "--no-sites")
    assert result.code == 0, result.stderr
    assert "tool" not in assert_urdfdom_reads_it(bare, tmp_path / "graph").links()


# The examples: a fixed arm, a floating quadruped, URDF and MJCF parts attached, a world root.
@pytest.mark.parametrize(
    "example", ["arm", "quadruped", "arm_gripper", "arm_mjcf_gripper", "reference_demo"]
)
def test_the_examples_urdfs_are_read_by_urdfdom(example, tmp_path):
    folder = copy_example(example, tmp_path)
    manifest = folder / "robot.yaml"
    text = manifest.read_text()
    assert "\noutput:\n" in text
    manifest.write_text(text.replace("\noutput:\n", "\noutput:\n  urdf: exported.urdf\n", 1))
    result = run_cli("build", "-q", "--no-check", cwd=folder)
    assert result.code == 0, result.stderr
    out = folder / "mjcf"
    judged = assert_urdfdom_reads_it(out / "exported.urdf", tmp_path / "graph")
    model = next(p for p in out.glob("*.xml") if p.name != "scene.xml")
    assert_bodies_keep_their_tree(judged, model)
    # The URDFs the build writes for itself (xacro's expansion, parts composed) too.
    for written in sorted((out / ".mjcfbuild").rglob("*.urdf")):
        itself = urdfdom_read(written, tmp_path / "graph")
        assert itself.accepted and itself.errors == [], (written, itself.errors)
