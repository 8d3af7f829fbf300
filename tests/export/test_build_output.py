"""``output.urdf`` in robot.yaml: the build writes a URDF of the model, incrementally."""

from __future__ import annotations

import pytest

from tests.conftest import run_cli

yourdfpy = pytest.importorskip("yourdfpy")


def with_urdf_output(arm, text: str = "  urdf: example_arm.urdf\n"):
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + text)


def test_build_writes_the_urdf_and_rebuilds_only_what_changed(arm):
    with_urdf_output(arm)
    first = run_cli("build", "-q", "--no-check", cwd=arm)
    assert first.code == 0, first.stderr
    urdf = arm / "mjcf" / "example_arm.urdf"
    robot = yourdfpy.URDF.load(str(urdf), load_meshes=True, build_scene_graph=True)
    assert "elbow" in robot.actuated_joint_names and "tool0" in robot.link_map
    meshes = sorted(p.name for p in (arm / "mjcf" / "example_arm_meshes").iterdir())
    assert "upper_arm.obj" in meshes and "upper_arm.mtl" in meshes

    again = run_cli("build", "--no-check", cwd=arm)
    assert "0 run" in again.stdout

    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text().replace(
            "  urdf: example_arm.urdf\n",
            "  urdf:\n    file: example_arm.urdf\n    sites: false\n"
            "    asset_prefix: package://arm_description/mjcf/example_arm_meshes/\n",
        )
    )
    changed = run_cli("build", "--no-check", cwd=arm)
    assert "export example_arm.urdf" in changed.stdout and "1 run" in changed.stdout
    text = urdf.read_text()
    assert "package://arm_description/mjcf/example_arm_meshes/upper_arm.obj" in text
    assert '<link name="tool0"/>' not in text


def test_meshes_an_export_no_longer_uses_are_removed(arm):
    with_urdf_output(arm)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    folder = arm / "mjcf" / "example_arm_meshes"
    assert (folder / "base.obj").exists()
    xacro = arm / "urdf" / "arm.urdf.xacro"
    text = xacro.read_text()
    # the base is drawn by a cylinder instead of its mesh
    start = text.index('<mesh filename="package://arm_description/meshes/base.stl"')
    end = text.index("/>", start) + 2
    xacro.write_text(text[:start] + '<cylinder radius="0.08" length="0.1"/>' + text[end:])
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == 0, result.stderr
    assert not (folder / "base.obj").exists() and not (folder / "base.mtl").exists()
    assert (folder / "upper_arm.obj").exists()


def test_clean_removes_the_urdf_and_its_meshes(arm):
    with_urdf_output(arm)
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    result = run_cli("clean", cwd=arm)
    assert result.code == 0 and "example_arm.urdf" in result.stdout
    assert not (arm / "mjcf").exists()


def test_mesh_folder_may_not_be_one_the_build_uses(arm):
    with_urdf_output(arm, "  urdf:\n    file: arm.urdf\n    meshes: assets\n")
    result = run_cli("build", cwd=arm)
    assert result.code == 3
    assert "'assets' is used by the build" in result.stderr
