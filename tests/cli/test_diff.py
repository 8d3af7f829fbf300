"""``mjcfbuild diff`` on a real git repo holding the example arm: each kind of edit a pull
request makes shows up in its group, with its values before and after."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, run_cli


def git(repo: Path, *args: str) -> str:
    """Run git in ``repo`` as a fixed author; its output."""
    command = ["git", "-c", "user.email=t@example.com", "-c", "user.name=t", *args]
    return subprocess.run(command, cwd=repo, check=True, capture_output=True, text=True).stdout


def new_repo(folder: Path) -> Path:
    """A git repo with the example arm committed; the arm's folder."""
    shutil.copytree(EXAMPLES / "arm", folder / "arm", ignore=shutil.ignore_patterns("mjcf"))
    (folder / ".gitignore").write_text("mjcf/\n")
    git(folder, "init", "-q", "-b", "main")
    git(folder, "add", ".")
    git(folder, "commit", "-qm", "the arm")
    return folder / "arm"


TOOL_LINK = """  <link name="tool_link">
    <inertial>
      <mass value="0.1"/>
      <inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/>
    </inertial>
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
  </link>
  <joint name="tool_joint" type="revolute">
    <parent link="wrist_link"/>
    <child link="tool_link"/>
    <origin xyz="0.05 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="5" velocity="2"/>
  </joint>

  <link name="tool0"/>"""


def edit(path: Path, old: str, new: str) -> None:
    """Replace ``old`` (which must be there) by ``new`` in ``path``."""
    text = path.read_text()
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, 1))


def scale_mesh(path: Path, factor: float) -> None:
    """Scale every vertex of the COLLADA mesh at ``path``."""
    text = path.read_text()
    found = re.search(r'(<float_array id="shape-positions-array"[^>]*>)([^<]*)<', text)
    assert found
    values = " ".join(f"{float(v) * factor:.6g}" for v in found.group(2).split())
    path.write_text(text[: found.start(2)] + values + text[found.end(2) :])


@pytest.fixture(scope="module")
def edited(tmp_path_factory):
    """The repo with a second commit making five edits (a mass, a joint limit, a mesh, a new
    link, an actuator rule) and a hold tolerance the arm cannot meet; the diff between them
    as JSON, with --write's folder."""
    folder = tmp_path_factory.mktemp("repo")
    arm = new_repo(folder)
    xacro = arm / "urdf" / "arm.urdf.xacro"
    edit(xacro, '<mass value="1.5"/>', '<mass value="2.0"/>')  # upper_arm_link
    edit(xacro, '  <link name="tool0"/>', TOOL_LINK)
    edit(arm / "config" / "joint_limits.yaml", "elbow: {lower: -2.5,", "elbow: {lower: -2.0,")
    scale_mesh(arm / "meshes" / "upper_arm.dae", 1.1)
    edit(arm / "robot.yaml", "frequency: 5", "frequency: 8")
    edit(arm / "robot.yaml", "  elbow: 1.2\n", "  elbow: 1.1\n  shoulder_pan: 0.2\n")
    edit(arm / "robot.yaml", "output:\n", "check:\n  hold_tolerance: 0.001\noutput:\n")
    git(folder, "commit", "-qam", "five edits")
    scratch, written = folder / "scratch", folder / "written"
    result = run_cli(
        "diff", "--base", "main~1", "--head", "main", "--format", "json",
        "--scratch", str(scratch), "--write", str(written), cwd=arm,
    )  # fmt: skip
    assert result.code == 0, result.stderr
    return {"arm": arm, "diff": json.loads(result.stdout), "written": written, "scratch": scratch}


def changes(diff: dict, group: str) -> dict[tuple[str, str], tuple]:
    """``(subject, what) -> (before, after)`` of one group."""
    return {(c["subject"], c["what"]): (c["before"], c["after"]) for c in diff["groups"][group]}


def test_mass_edit_is_in_masses(edited):
    masses = changes(edited["diff"], "masses")
    assert masses[("body upper_arm_link", "mass")] == (1.5, 2.0)
    before, after = masses[("robot", "total mass")]
    assert after - before == pytest.approx(0.5 + 0.1)  # the new tool link's 0.1 kg too


def test_joint_limit_edit_is_in_joint_ranges(edited):
    joints = changes(edited["diff"], "joints")
    assert joints[("joint elbow", "range")] == ([-2.5, 2.5], [-2.0, 2.5])
    assert ("actuator elbow", "ctrlrange") in changes(edited["diff"], "actuators")


def test_mesh_edit_is_in_collision_geometry(edited):
    geometry = changes(edited["diff"], "geometry")
    before, after = geometry[("body upper_arm_link", "collision geom 1: mesh upper_arm")]
    assert after["extent"][2] == pytest.approx(before["extent"][2] * 1.1, rel=1e-5)
    assert before["vertices"] == after["vertices"]


def test_new_link_is_in_bodies_and_joints(edited):
    structure = changes(edited["diff"], "structure")
    assert structure[("body tool_link", "added")] == (None, "child of wrist_link")
    assert structure[("joint tool_joint", "added")] == (None, "hinge on tool_link")
    assert changes(edited["diff"], "actuators")[("actuator tool_joint", "added")][0] is None
    # the new link's pairs join the collision matrix
    assert any("tool_link" in subject for subject, _ in changes(edited["diff"], "matrix"))


def test_actuator_rule_change_is_in_actuators(edited):
    actuators = changes(edited["diff"], "actuators")
    kp_before, kp_after = actuators[("actuator left_finger_joint", "kp")]
    # kp grows with the square of the frequency: 5 Hz -> 8 Hz
    assert kp_after / kp_before == pytest.approx((8 / 5) ** 2, rel=1e-6)


def test_home_edits_are_in_home_with_where_they_came_from(edited):
    home = {(c["subject"], c["what"]): c for c in edited["diff"]["groups"]["home"]}
    elbow = home[("joint elbow", "qpos")]
    assert (elbow["before"], elbow["after"], elbow["note"]) == (1.2, 1.1, "set by robot.yaml")
    pan = home[("joint shoulder_pan", "qpos")]
    assert (pan["before"], pan["after"], pan["note"]) == (0.0, 0.2, "set by zero -> robot.yaml")
    assert home[("actuator elbow", "ctrl")]["after"] == 1.1


def test_a_check_that_now_fails_is_in_checks(edited):
    checks = changes(edited["diff"], "checks")
    assert checks[("check", "result")] == ("passed", "failed")
    _, failure = checks[("check", "new failure")]
    assert "hold_tolerance 0.001" in failure


def test_only_the_edited_link_moved_nothing_else(edited):
    # the edits move no link: the kinematics group is absent, not full of rounding noise
    assert "kinematics" not in edited["diff"]["groups"]


def test_written_markdown_and_pictures_side_by_side(edited):
    from PIL import Image

    written = edited["written"]
    markdown = (written / "diff.md").read_text()
    assert "#### Masses and inertias" in markdown
    assert "| body upper_arm_link | mass | 1.5 | 2 |" in markdown
    assert json.loads((written / "diff.json").read_text()) == edited["diff"]
    pictures = sorted(p.name for p in (written / "previews").glob("*.png"))
    assert pictures and all(f"](previews/{name})" in markdown for name in pictures)
    base = edited["scratch"] / "base" / "out" / "report" / "previews" / pictures[0]
    with Image.open(base) as one, Image.open(written / "previews" / pictures[0]) as pair:
        assert pair.width > 2 * one.width and pair.height == one.height


def test_build_folders_give_the_same_diff(edited):
    scratch = edited["scratch"]
    result = run_cli(
        "diff", "--folders", str(scratch / "base" / "out"), str(scratch / "head" / "out"),
        "--format", "json",
    )  # fmt: skip
    assert result.code == 0, result.stderr
    assert json.loads(result.stdout)["groups"] == edited["diff"]["groups"]


def test_text_output_names_groups_and_values(edited):
    scratch = edited["scratch"]
    result = run_cli(
        "diff", "--folders", str(scratch / "base" / "out"), str(scratch / "head" / "out")
    )
    assert "Joint ranges and limits (1)\n  joint elbow: range [-2.5 2.5] -> [-2 2.5]\n" in (
        result.stdout
    )
    assert "  body upper_arm_link: mass 1.5 -> 2\n" in result.stdout


def test_unchanged_model_says_no_model_changes(tmp_path):
    arm = new_repo(tmp_path)
    # A comment in the URDF changes the sources, not the model: the working tree (head by
    # default) is built in place and compared with the commit.
    edit(arm / "urdf" / "arm.urdf.xacro", "<robot ", "<!-- reworded -->\n<robot ")
    result = run_cli("diff", "--base", "main", "--scratch", str(tmp_path / "scratch"), cwd=arm)
    assert result.code == 0, result.stderr
    assert result.stdout.splitlines()[1:] == ["no model changes"]
    assert (arm / "mjcf" / "example_arm.xml").is_file()  # the working tree's own build
    markdown = run_cli(
        "diff", "--folders", str(tmp_path / "scratch" / "base" / "out"), str(arm / "mjcf"),
        "--format", "markdown",
    )  # fmt: skip
    assert "**no model changes**" in markdown.stdout


def test_a_revision_that_does_not_exist_is_a_usage_error(tmp_path):
    arm = new_repo(tmp_path)
    result = run_cli("diff", "--base", "no-such-branch", cwd=arm)
    assert result.code == 2
    assert result.stderr.count("\n") == 1 and "no git revision 'no-such-branch'" in result.stderr
    assert "Traceback" not in result.stderr


def test_an_error_in_a_revision_names_its_file_as_git_shows_it(tmp_path):
    """A revision that did not build named the copy in the scratch folder, which the user
    never made; ``<commit>:<path>`` is what ``git show`` takes."""
    arm = new_repo(tmp_path)
    edit(arm / "urdf" / "arm.urdf.xacro", "<robot ", "<robotx ")
    git(tmp_path, "commit", "-qam", "broken")
    commit = git(tmp_path, "rev-parse", "HEAD").strip()[:10]
    git(tmp_path, "checkout", "-q", "HEAD~1", "--", "arm/urdf/arm.urdf.xacro")
    result = run_cli("diff", "--base", "HEAD", "-q", cwd=arm)
    assert result.code == 4, result.stderr
    named = f"mjcfbuild: error: {commit}:arm/urdf/arm.urdf.xacro:"
    assert any(line.startswith(named) for line in result.stderr.splitlines()), result.stderr
    line = int(result.stderr.split(named)[1].split(":")[0])
    shown = git(tmp_path, "show", f"{commit}:arm/urdf/arm.urdf.xacro").splitlines()
    assert shown[line - 1] == "</robot>"  # where the tag opened as <robotx> is closed


def test_a_folder_without_a_build_is_an_input_error(tmp_path):
    (tmp_path / "empty").mkdir()
    result = run_cli("diff", "--folders", str(tmp_path / "empty"), str(tmp_path / "empty"))
    assert result.code == 4
    assert result.stderr.count("\n") == 1 and "no mjcfbuild build in this folder" in result.stderr


def test_outside_a_git_repo_is_an_input_error(arm):
    result = run_cli("diff", "--base", "main", cwd=arm)
    assert result.code == 4
    assert result.stderr.count("\n") == 1 and "not inside a git repository" in result.stderr


def test_nothing_to_compare_is_a_usage_error(arm):
    result = run_cli("diff", cwd=arm)
    assert result.code == 2 and "--base REF" in result.stderr


def test_a_robot_that_stood_and_now_falls(tmp_path):
    """The quadruped stands at home; servos too weak to carry it make it fall: the diff says
    so in its checks, beside the gains that did it."""
    shutil.copytree(
        EXAMPLES / "quadruped", tmp_path / "quadruped", ignore=shutil.ignore_patterns("mjcf")
    )
    git(tmp_path, "init", "-q", "-b", "main")
    git(tmp_path, "add", ".")
    git(tmp_path, "commit", "-qm", "quadruped")
    robot = tmp_path / "quadruped"
    weak = '  rules:\n    - {joints: ["*knee*", "*thigh*"], kp: 2, kv: 0.1}\n'
    (robot / "robot.yaml").write_text((robot / "robot.yaml").read_text() + "actuators:\n" + weak)
    git(tmp_path, "commit", "-qam", "weak servos")
    result = run_cli(
        "diff", "--base", "main~1", "--head", "main", "--format", "json",
        "--scratch", str(tmp_path / "scratch"), cwd=robot,
    )  # fmt: skip
    assert result.code == 0, result.stderr
    groups = json.loads(result.stdout)["groups"]
    checks = {(c["subject"], c["what"]): c for c in groups["checks"]}
    stand = checks[("stand test", "robot")]
    assert (stand["before"], stand["after"]) == ("stands", "falls")
    assert checks[("check", "result")]["after"] == "failed"
    kp = {c["subject"]: c["after"] for c in groups["actuators"] if c["what"] == "kp"}
    assert kp["actuator front_left_knee_joint"] == 2.0


def test_commits_made_within_one_second_diff_correctly(tmp_path, monkeypatch):
    """``git archive`` stamps every file with its commit's second: a same-size edit committed
    in the same second as the previous commit keeps each file's size and time, and a scratch
    folder built for one revision must not be taken as current for the next."""
    for variable in ("GIT_AUTHOR_DATE", "GIT_COMMITTER_DATE"):  # a script, a rebase
        monkeypatch.setenv(variable, "2026-01-01T00:00:00Z")
    arm = new_repo(tmp_path)
    xacro = arm / "urdf" / "arm.urdf.xacro"
    for before, after in (("1.5", "2.5"), ("2.5", "3.5")):  # the same size: only bytes differ
        edit(xacro, f'<mass value="{before}"/>', f'<mass value="{after}"/>')
        git(tmp_path, "commit", "-qam", f"mass {after}")
    scratch = tmp_path / "scratch"

    def mass_change(base: str, head: str) -> tuple:
        result = run_cli(
            "diff", "--base", base, "--head", head, "--format", "json",
            "--scratch", str(scratch), cwd=arm,
        )  # fmt: skip
        assert result.code == 0, result.stderr
        return changes(json.loads(result.stdout), "masses")[("body upper_arm_link", "mass")]

    assert mass_change("main~2", "main~1") == (1.5, 2.5)
    # Each side's scratch folder holds the previous pair's build; now the next commit's files.
    assert mass_change("main~1", "main") == (2.5, 3.5)


def test_a_warning_both_sides_give_is_printed_once_beside_each_sides_own(capsys):
    from mjcfbuild.cli.diff import _print_warnings

    _print_warnings({"main": ["r.urdf:3: shared", "r.urdf:4: old"], "HEAD": ["r.urdf:3: shared"]})
    assert capsys.readouterr().err.splitlines() == [
        "mjcfbuild: warning: main and HEAD: r.urdf:3: shared",
        "mjcfbuild: warning: main: r.urdf:4: old",
    ]
