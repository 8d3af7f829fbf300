"""The collision matrix task: reasons, excludes, SRDF import, keep, and incrementality."""

from __future__ import annotations

import json

import mujoco
import numpy as np

import mjcfbuild
from mjcfbuild.selfcollision.matrix import _samples, _touching
from tests.conftest import INERTIA, run_cli, write

# A chain whose first and third links overlap at the zero pose, with a visual-only mesh.
CHAIN = f"""<robot name="chain">
  <link name="a">{INERTIA}<collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision>
    <visual><geometry><mesh filename="look.obj"/></geometry></visual></link>
  <link name="b">{INERTIA}<collision><origin xyz="0 0 0.2"/><geometry><box size="0.05 0.05 0.2"/></geometry></collision></link>
  <link name="c">{INERTIA}<collision><origin xyz="0.1 0 -0.25"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="d">{INERTIA}<collision><origin xyz="0 0 1.5"/><geometry><sphere radius="0.05"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><origin xyz="0 0 0.3"/>
    <axis xyz="0 1 0"/><limit lower="-0.2" upper="0.2" effort="5" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="c"/><child link="d"/>
    <axis xyz="0 1 0"/><limit lower="-0.2" upper="0.2" effort="5" velocity="1"/></joint>
</robot>"""
LOOK = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def _robot(folder, extra: str = ""):
    write(folder / "robot.urdf", CHAIN)
    write(folder / "look.obj", LOOK)
    return write(folder / "robot.yaml", "name: chain\nsource: {urdf: robot.urdf}\n" + extra)


def _matrix(folder) -> dict:
    return json.loads((folder / "mjcf/.mjcfbuild/self_collision.json").read_text())


def _reasons(folder) -> dict:
    return {(p["body1"], p["body2"]): (p["reason"], p["exclude"]) for p in _matrix(folder)["pairs"]}


def test_pairs_touching_at_home_are_excluded_and_the_check_passes(tmp_path):
    result = mjcfbuild.build(_robot(tmp_path))
    reasons = _reasons(tmp_path)
    assert reasons[("a", "b")] == ("adjacent", True)
    assert reasons[("a", "c")] == ("home", True)
    assert reasons[("a", "d")] == ("never", False)
    # MuJoCo skips a body's parent, but not one welded to the world, as the fixed base 'a' is.
    assert _matrix(tmp_path)["excludes"] == [["a", "b"], ["a", "c"]]
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.nexclude == 2
    report = (tmp_path / "mjcf/report/report.md").read_text()
    assert "| a | c | home |" in report


def test_exclude_never_and_keep(tmp_path):
    mjcfbuild.build(
        _robot(tmp_path, "self_collision: {exclude_never: true, keep: [[b, d]], samples: 50}\n")
    )
    reasons = _reasons(tmp_path)
    assert reasons[("a", "d")] == ("never", True)
    assert reasons[("b", "d")] == ("never, kept", False)


def test_none_writes_no_excludes_and_the_check_names_the_touching_pair(tmp_path):
    code = run_cli("build", str(_robot(tmp_path, "self_collision: none\n")))
    assert code.code == 6
    assert "touch at home (a/c)" in code.stderr


def test_srdf_pairs_are_excluded_through_fused_links_with_their_reason(tmp_path):
    write(
        tmp_path / "robot.srdf",
        '<robot name="chain"><disable_collisions link1="a" link2="d" reason="Never"/>'
        '<group_state name="home" group="arm"><joint name="j1" value="0.3"/></group_state>'
        "</robot>",
    )
    result = mjcfbuild.build(_robot(tmp_path, "self_collision: {srdf: robot.srdf}\n"))
    assert _reasons(tmp_path)[("a", "d")] == ("srdf: Never", True)
    model = mujoco.MjModel.from_xml_path(str(result.robot))
    assert model.key_qpos[0][0] == 0.3  # the SRDF's home group_state


def test_an_srdf_link_that_does_not_exist_is_an_error_at_its_line(tmp_path):
    write(
        tmp_path / "robot.srdf",
        '<robot name="x">\n<disable_collisions link1="a" link2="zz"/>\n</robot>',
    )
    result = run_cli("build", str(_robot(tmp_path, "self_collision: {srdf: robot.srdf}\n")))
    assert result.code == 4
    assert "robot.srdf:2: link 'zz' is not a link of the robot" in result.stderr
    assert not (tmp_path / "mjcf/chain.xml").exists()


def test_a_home_state_the_srdf_lacks_is_an_error_at_its_robot_yaml_line(tmp_path):
    write(
        tmp_path / "robot.srdf",
        '<robot name="x">\n<group_state name="ready" group="arm">'
        '<joint name="j1" value="0.3"/></group_state>\n</robot>',
    )
    manifest = _robot(tmp_path, "self_collision:\n  srdf: robot.srdf\n  home_state: redy\n")
    result = run_cli("build", str(manifest))
    assert result.code == 3, result.stderr
    assert (
        "robot.yaml:5:3: self_collision.home_state: robot.srdf has no group_state 'redy'; "
        "did you mean 'ready'? (its group states: ready)"
    ) in result.stderr
    # Left to its default, home_state is looked for and not required.
    assert run_cli("build", str(_robot(tmp_path, "self_collision: {srdf: robot.srdf}\n"))).code == 0


def test_a_group_state_joint_the_robot_lacks_is_an_error_at_its_srdf_line(tmp_path):
    write(
        tmp_path / "robot.srdf",
        '<robot name="x">\n<group_state name="home" group="arm">\n'
        '  <joint name="j1x" value="0.3"/></group_state>\n</robot>',
    )
    result = run_cli("build", str(_robot(tmp_path, "self_collision: {srdf: robot.srdf}\n")))
    assert result.code == 4, result.stderr
    assert (
        "robot.srdf:3: group_state 'home' names joint 'j1x', which the robot does not have; "
        "did you mean 'j1'?"
    ) in result.stderr


def test_a_malformed_srdf_is_an_error(tmp_path):
    write(tmp_path / "robot.srdf", "<robot>\n<disable_collisions")
    result = run_cli("build", str(_robot(tmp_path, "self_collision: {srdf: robot.srdf}\n")))
    assert result.code == 4
    assert "robot.srdf:2" in result.stderr and "not valid XML" in result.stderr


def test_a_keep_pair_naming_a_missing_link_is_a_manifest_error(tmp_path):
    result = run_cli("build", str(_robot(tmp_path, "self_collision:\n  keep: [[a, nope]]\n")))
    assert result.code == 3
    assert "robot.yaml:4" in result.stderr and "link 'nope'" in result.stderr
    assert "self-collision matrix" not in result.stdout  # refused before any work


def test_samples_must_be_positive(tmp_path):
    result = run_cli("build", str(_robot(tmp_path, "self_collision: {samples: 0}\n")))
    assert result.code == 3
    assert "robot.yaml:3" in result.stderr and "samples" in result.stderr


def test_visual_mesh_and_joint_dynamics_edits_do_not_rerun_the_matrix(tmp_path):
    manifest = _robot(tmp_path)
    mjcfbuild.build(manifest)
    write(tmp_path / "look.obj", LOOK.replace("v 0 0 0.1", "v 0 0 0.2"))
    result = mjcfbuild.build(manifest)
    assert "assemble" in result.ran
    assert "selfcollision" not in result.ran
    # Effort, velocity and damping do not move the robot (same lines, so same line numbers).
    dynamics = CHAIN.replace(
        'effort="5" velocity="1"/></joint>',
        'effort="7" velocity="2"/><dynamics damping="0.3" friction="0.1"/></joint>',
    )
    write(tmp_path / "robot.urdf", dynamics)
    result = mjcfbuild.build(manifest)
    assert "assemble" in result.ran
    assert "selfcollision" not in result.ran
    write(
        tmp_path / "robot.urdf",
        CHAIN.replace('lower="-0.2" upper="0.2"', 'lower="-0.3" upper="0.3"'),
    )
    assert "selfcollision" in mjcfbuild.build(manifest).ran


def test_the_matrix_is_cached_and_the_same_in_another_folder(tmp_path, monkeypatch):
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build

    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    mjcfbuild.build(_robot(tmp_path / "one"))
    ctx = BuildContext.from_manifest_file(_robot(tmp_path / "two"), jobs=1)
    run_build(ctx, Progress(quiet=True))
    assert ctx.session.notes["selfcollision"] == "from cache"
    assert _matrix(tmp_path / "one") == _matrix(tmp_path / "two")

    # Computed afresh (another cache, one worker), the matrix is the same.
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "other-cache"))
    mjcfbuild.build(_robot(tmp_path / "three"), jobs=1)
    assert _matrix(tmp_path / "three") == _matrix(tmp_path / "one")


def test_a_missing_srdf_is_an_error_naming_the_setting(tmp_path):
    result = run_cli("build", str(_robot(tmp_path, "self_collision: {srdf: nowhere.srdf}\n")))
    assert result.code == 4
    assert "nowhere.srdf" in result.stderr and "self_collision.srdf" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "mjcf/chain.xml").exists()


def test_an_srdf_written_as_xacro_is_expanded_with_the_robots_args(tmp_path):
    write(
        tmp_path / "robot.srdf.xacro",
        '<robot name="chain" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:property name="far" value="d"/>\n'
        '<disable_collisions link1="a" link2="${far}" reason="Never"/>\n'
        "</robot>",
    )
    mjcfbuild.build(_robot(tmp_path, "self_collision: {srdf: robot.srdf.xacro}\n"))
    assert _reasons(tmp_path)[("a", "d")] == ("srdf: Never", True)


# Every kind of joint the sampler treats differently, and a mimic follower of the first.
JOINTS = """<mujoco><compiler angle="radian"/><worldbody>
  <body name="a"><joint name="limited" range="-0.5 1.5" limited="true"/><geom size="0.1"/>
    <body name="b" pos="0 0 0.3"><joint name="hinge" limited="false"/><geom size="0.1"/>
      <body name="c" pos="0 0 0.3"><joint name="slide" type="slide" limited="false"/>
        <geom size="0.1"/>
        <body name="d" pos="0 0 0.3"><joint name="rail" type="slide" range="0 0.2" limited="true"/>
          <geom size="0.1"/>
          <body name="e" pos="0 0 0.3"><joint name="follower" range="-3 3" limited="true"/>
            <geom size="0.1"/>
          </body></body></body></body></body></worldbody>
  <equality><joint joint1="follower" joint2="limited" polycoef="0.1 2 0 0 0"/></equality>
</mujoco>"""


def test_samples_are_drawn_joint_by_joint_and_followers_placed_by_their_equality():
    model = mujoco.MjModel.from_xml_string(JOINTS)
    rows = _samples(model, np.random.default_rng(7), 3)
    rng = np.random.default_rng(7)  # the same numbers, one draw per joint and row
    for row in rows:
        limited, hinge = rng.uniform(-0.5, 1.5), rng.uniform(-np.pi, np.pi)
        rail = rng.uniform(0, 0.2)
        rng.uniform(-3, 3)  # the follower's own draw, replaced by its equality
        assert row.tolist() == [limited, hinge, 0.0, rail, 0.1 + 2 * limited]


def test_touching_pairs_are_bodies_in_contact_not_geoms_within_the_margin():
    model = mujoco.MjModel.from_xml_string("""<mujoco><worldbody>
      <body name="a"><freejoint/><geom size="0.1" margin="0.1"/><geom size="0.1" pos="0 0 0.1"/>
      </body>
      <body name="b" pos="0.15 0 0"><freejoint/><geom size="0.1"/></body>
      <body name="c" pos="-0.25 0 0"><freejoint/><geom size="0.1" margin="0.1"/></body>
    </worldbody></mujoco>""")
    data = mujoco.MjData(model)
    # a and b overlap; a and c are 0.05 apart, inside the margin: a contact, not a touch;
    # a's own two geoms overlap but are one body.
    assert _touching(model, data, model.qpos0) == {(1, 2)}
    assert any(dist > 0 for dist in data.contact.dist)  # the margin's contact was there


def test_a_verdicts_dict_holds_every_field():
    from dataclasses import asdict

    from mjcfbuild.selfcollision.matrix import PairVerdict

    verdict = PairVerdict("a", "b", "sometimes", 0.25, False)
    assert verdict.to_dict() == asdict(verdict)
    assert PairVerdict(**verdict.to_dict()) == verdict
