"""``output.package: true`` on the example arm, in a git repo: the Menagerie-grade folder."""

from __future__ import annotations

import hashlib
import json
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

from mjcfbuild.package.format import format_problems
from tests.conftest import EXAMPLES, run_cli


def git(repo: Path, *args: str) -> str:
    command = ["git", "-c", "user.email=t@example.com", "-c", "user.name=t", *args]
    return subprocess.run(command, cwd=repo, check=True, capture_output=True, text=True).stdout


@pytest.fixture(scope="module")
def packaged(tmp_path_factory):
    """The arm with output.package on, committed and built; its folder."""
    import shutil

    top = tmp_path_factory.mktemp("repo")
    arm = top / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\n")
    (top / ".gitignore").write_text("mjcf/\n")
    git(top, "init", "-q", "-b", "main")
    git(top, "remote", "add", "origin", "https://example.com/arm_description.git")
    git(top, "add", ".")
    git(top, "commit", "-qm", "arm")
    result = run_cli("build", cwd=arm)
    assert result.code == 0, result.stderr
    return arm


def test_the_folder_has_what_menageries_folder_test_asks(packaged):
    folder = packaged / "mjcf" / "package"
    names = {path.name for path in folder.iterdir()}
    assert {"README.md", "LICENSE", "CHANGELOG.md", "scene.xml", "example_arm.xml"} <= names
    assert {"example_arm.png", "assets"} <= names
    assert (folder / "LICENSE").read_bytes() == (EXAMPLES / "arm" / "LICENSE").read_bytes()
    assert (folder / "example_arm.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_every_scene_loads_and_steps_from_the_folder(packaged):
    import mujoco

    folder = packaged / "mjcf" / "package"
    scenes = sorted(folder.glob("scene*.xml"))
    assert scenes
    for scene in scenes:
        model = mujoco.MjModel.from_xml_path(str(scene))
        data = mujoco.MjData(model)
        mujoco.mj_resetDataKeyframe(model, data, 0)
        for _ in range(200):
            mujoco.mj_step(model, data)
        assert not any(data.warning[k].number for k in range(len(data.warning)))


def test_the_model_passes_the_format_check_with_kinematics_exact(packaged):
    import mujoco

    packaged_model = packaged / "mjcf" / "package" / "example_arm.xml"
    assert format_problems(packaged_model.read_bytes()) == []
    built = mujoco.MjModel.from_xml_path(str(packaged / "mjcf" / "example_arm.xml"))
    model = mujoco.MjModel.from_xml_path(str(packaged_model))
    for name in ("body_pos", "body_quat", "body_ipos", "body_mass", "jnt_axis", "jnt_range"):
        assert np.array_equal(getattr(built, name), getattr(model, name)), name
    for name in ("site_pos", "site_quat", "geom_pos", "geom_quat", "key_qpos"):
        assert np.array_equal(getattr(built, name), getattr(model, name)), name
    # gains carry 4 digits: the <dcmotor>s' motor constants and controller gains (kp, kv)
    for column in (0, 4, 6):
        assert np.allclose(
            model.actuator_gainprm[:, column], built.actuator_gainprm[:, column], rtol=1e-3
        )
    controllers = re.findall(r'controller="([^"]+)"', packaged_model.read_text())
    assert len(controllers) == 5
    for numbers in controllers:
        assert all(len(n.replace(".", "").lstrip("0")) <= 4 for n in numbers.split()), numbers


def test_readme_says_where_the_model_comes_from(packaged):
    import mujoco

    readme = (packaged / "mjcf" / "package" / "README.md").read_text()
    commit = git(packaged, "rev-parse", "HEAD").strip()
    assert f"- revision: `{commit}` of https://example.com/arm_description.git" in readme
    assert f"MuJoCo {mujoco.__version__}" in readme and "mjcfbuild 0." in readme
    assert "```yaml\n# yaml-language-server" in readme and "  package: true\n```" in readme
    assert "- MuJoCo Menagerie's model test: no warnings" in readme
    assert "5 actuators (dcmotor position servos)" in readme


def test_changelog_grows_when_the_model_changes_and_not_otherwise(packaged):
    changelog = packaged / "mjcf" / "package" / "CHANGELOG.md"
    first = changelog.read_text()
    assert first.startswith("# Changelog\n\n## ") and "packaged by mjcfbuild" in first
    assert run_cli("build", cwd=packaged).code == 0
    assert changelog.read_text() == first  # nothing changed: no entry
    limits = packaged / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("elbow: {lower: -2.5,", "elbow: {lower: -2.0,"))
    result = run_cli("build", cwd=packaged)
    assert result.code == 0, result.stderr
    text = changelog.read_text()
    assert text.endswith(first[len("# Changelog\n\n") :])  # the old entries stay, below
    newest = text.split("\n## ")[1]
    assert "+ local changes" in newest.splitlines()[0]
    assert "- joint elbow: range \\[-2.5 2.5] -> \\[-2 2.5]" in newest  # no link can open


def test_without_a_license_file_the_build_warns_and_the_readme_says_so(tmp_path):
    import shutil

    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf", "LICENSE"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\ncheck:\n  enabled: false\n")
    result = run_cli("build", cwd=arm)
    assert result.code == 0, result.stderr
    assert "no LICENSE found in the description package" in result.stderr
    folder = arm / "mjcf" / "package"
    assert not (folder / "LICENSE").exists()
    assert "No license file was found" in (folder / "README.md").read_text()


def test_the_packaged_model_passes_the_check_against_its_urdf_to_1e12(packaged):
    import re

    result = run_cli(
        "check", "--urdf", "mjcf/.mjcfbuild/source.urdf",
        "--mjcf", "mjcf/package/example_arm.xml", cwd=packaged,
    )  # fmt: skip
    assert result.code == 0, result.stdout + result.stderr
    found = re.search(r"link poses\s+max (\S+) m, (\S+) rad", result.stdout)
    assert found and float(found.group(1)) < 1e-12 and float(found.group(2)) < 1e-11


def test_files_the_user_put_in_the_package_stay_and_stale_copies_go(tmp_path):
    """A rebuild removes only the copies an earlier package made (an asset the model dropped, a
    LICENSE the description no longer has), never a file the user added (issue 40)."""
    import shutil

    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\ncheck:\n  enabled: false\n")
    assert run_cli("build", cwd=arm).code == 0
    folder = arm / "mjcf" / "package"
    assert (folder / "LICENSE").is_file()
    (folder / "assets" / "my_texture.png").write_bytes(b"mine")
    stale = folder / "assets" / "gone.obj"
    stale.write_bytes(b"v 0 0 0\n")
    # As an earlier package would have left it: copied by the step, recorded as the build's.
    copies = arm / "mjcf/.mjcfbuild/package_copies.json"
    copies.write_text(copies.read_text().replace('"files": [', '"files": [\n  "assets/gone.obj",'))
    written = arm / "mjcf/.mjcfbuild/written.json"
    record = json.loads(written.read_text())
    record["files"]["package/assets/gone.obj"] = hashlib.md5(b"v 0 0 0\n").hexdigest()
    written.write_text(json.dumps(record))
    (arm / "LICENSE").unlink()  # the package task reruns: it has no license to copy
    assert run_cli("build", cwd=arm).code == 0
    assert (folder / "assets" / "my_texture.png").read_bytes() == b"mine"
    assert not stale.exists()
    assert not (folder / "LICENSE").exists()  # the copy of the license that went
    # A license the user wrote into the package themselves stays.
    (folder / "LICENSE").write_text("mine\n")
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.1"))  # a new model
    result = run_cli("build", cwd=arm)
    assert result.code == 0 and "package" in result.stdout, result.stdout
    assert (folder / "LICENSE").read_text() == "mine\n"


def test_a_build_without_the_check_leaves_no_picture_of_an_earlier_model(tmp_path):
    """The picture comes from the check's previews: a build without them kept the last
    picture, of a model the package no longer holds, and the README still listed it."""
    import shutil

    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\n")
    assert run_cli("build", "-q", cwd=arm).code == 0
    folder = arm / "mjcf" / "package"
    picture = folder / "example_arm.png"
    assert picture.is_file() and "`example_arm.png`" in (folder / "README.md").read_text()
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.1"))  # a new model
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert not picture.exists()
    assert "example_arm.png" not in (folder / "README.md").read_text()
    assert run_cli("build", "-q", cwd=arm).code == 0
    assert picture.is_file()


def test_a_commit_alone_leaves_the_package_up_to_date(tmp_path):
    """The package's README names the revision as of its last change: committing the built
    package moved HEAD on, and check --up-to-date called the package stale forever after
    ('parameters changed: provenance.revision') while build called it up to date; a fresh
    clone's check found the README's revision line differing."""
    import shutil

    top = tmp_path / "repo"
    arm = top / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\ncheck:\n  enabled: false\n")
    git(top, "init", "-q", "-b", "main")
    git(top, "add", ".")
    git(top, "commit", "-qm", "arm")
    assert run_cli("build", "-q", cwd=arm).code == 0
    readme = (arm / "mjcf" / "package" / "README.md").read_text()
    built_from = git(top, "rev-parse", "HEAD").strip()
    assert f"- revision: `{built_from}`" in readme
    git(top, "add", ".")
    git(top, "commit", "-qm", "model")  # HEAD moves on
    result = run_cli("check", "--up-to-date", cwd=arm)
    assert result.code == 0, result.stderr
    assert "0 run" in run_cli("build", cwd=arm).stdout
    assert (arm / "mjcf" / "package" / "README.md").read_text() == readme
    clone = tmp_path / "clone"
    subprocess.run(["git", "clone", "-q", str(top), str(clone)], check=True)
    result = run_cli("check", "--up-to-date", cwd=clone / "arm")
    assert result.code == 0, result.stderr
    # A change to the model rewrites the package, with the revision it is built from then.
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.1"))
    assert run_cli("build", "-q", cwd=arm).code == 0
    readme = (arm / "mjcf" / "package" / "README.md").read_text()
    assert f"- revision: `{git(top, 'rev-parse', 'HEAD').strip()} + local changes`" in readme


def test_a_license_added_later_reaches_the_package_on_the_next_build(tmp_path):
    """The build warns that the description has no LICENSE; one added where it looks was
    missed by the next build's no-op stamp (and watch), which knew only the files it read."""
    import shutil

    from tests.conftest import file_clock_past_changes

    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf", "LICENSE"))
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "  package: true\ncheck:\n  enabled: false\n")
    file_clock_past_changes(arm)
    first = run_cli("build", cwd=arm)
    assert first.code == 0 and "no LICENSE found" in first.stderr, first.stderr
    assert "0 run" in run_cli("build", cwd=arm).stdout  # the stamp answers
    (arm / "LICENSE").write_text("the arm's license\n")
    result = run_cli("build", cwd=arm)
    assert result.code == 0, result.stderr
    assert (arm / "mjcf" / "package" / "LICENSE").read_text() == "the arm's license\n"
    assert "No license file was found" not in (arm / "mjcf" / "package" / "README.md").read_text()
