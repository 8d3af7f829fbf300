"""Safety: a build writes in its output folder and its cache and nowhere else, whatever names the
inputs use; and two builds of one output folder take turns."""

from __future__ import annotations

import fcntl
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import INERTIA, run_cli
from tests.meshes.samples import ascii_stl, checker_png

pytestmark = pytest.mark.slow

HOSTILE_URDF = f"""<?xml version="1.0"?>
<robot name="../../../robot_escape">
  <material name="../../paint/red"><color rgba="1 0 0 1"/></material>
  <link name="../../../tmp/base">{INERTIA}
    <visual><geometry><mesh filename="meshes/sub/../../../outside/part.stl"/></geometry></visual>
    <collision><geometry><mesh filename="package://outside_pkg/part.stl"/></geometry></collision>
  </link>
  <link name="/etc/passwd">{INERTIA}
    <visual><geometry><mesh filename="meshes/..obj"/></geometry>
      <material name="../../paint/red"/></visual>
    <visual><geometry><mesh filename="meshes/with space;$(touch x).obj"/></geometry></visual>
  </link>
  <joint name="../joint" type="revolute">
    <parent link="../../../tmp/base"/><child link="/etc/passwd"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""
TEXTURED_OBJ = (
    "mtllib ../../outside/looks.mtl\n"
    "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nvt 0 0\nvt 1 0\nvt 0 1\n"
    "usemtl skin\nf 1/1 3/2 2/3\nf 1/1 2/2 4/3\nf 1/1 4/2 3/3\nf 2/1 3/2 4/3\n"
)


def hostile_description(root: Path) -> Path:
    """A description whose names all try to leave the output folder; its folder."""
    outside = root / "outside"
    outside.mkdir()
    ascii_stl(outside / "part.stl")
    checker_png(outside / "skin.png")
    (outside / "looks.mtl").write_text("newmtl skin\nKd 1 1 1\nmap_Kd ../outside/skin.png\n")
    description = root / "description"
    meshes = description / "meshes"
    meshes.mkdir(parents=True)
    (meshes / "..obj").write_text(TEXTURED_OBJ)
    (meshes / "with space;$(touch x).obj").write_text(TEXTURED_OBJ)
    (description / "robot.urdf").write_text(HOSTILE_URDF)
    (description / "robot.yaml").write_text(
        "name: robot\nsource:\n  urdf: robot.urdf\npackages:\n  outside_pkg: ../outside\n"
        "options:\n  link_sites: all\n"
    )
    return description


def tree(root: Path) -> dict[str, bytes | None]:
    """Every file under ``root`` with its bytes (folders as None)."""
    result: dict[str, bytes | None] = {}
    for folder, folders, files in os.walk(root):
        for name in folders:
            result[str((Path(folder) / name).relative_to(root))] = None
        for name in files:
            path = Path(folder) / name
            result[str(path.relative_to(root))] = path.read_bytes()
    return result


def test_nothing_is_written_outside_the_output_folder_and_the_cache(tmp_path):
    description = hostile_description(tmp_path)
    home, temporary = tmp_path / "home", tmp_path / "tmp"
    home.mkdir()
    temporary.mkdir()
    before = tree(tmp_path)
    env = {
        "HOME": str(home),
        "TMPDIR": str(temporary),
        "MJCFBUILD_CACHE_DIR": str(tmp_path / "cache"),
        "XDG_CACHE_HOME": str(home / ".cache"),
    }
    result = run_cli("build", "-q", cwd=description, env=env)
    assert result.code == 0, result.stderr
    after = tree(tmp_path)
    allowed = ("description/mjcf", "cache")
    changed = sorted(
        key
        for key in set(before) | set(after)
        if before.get(key, b"") != after.get(key, b"") and not key.startswith(allowed)
    )
    assert changed == []
    outputs = [p for p in (description / "mjcf").rglob("*") if p.is_file()]
    assert any(p.suffix == ".png" for p in outputs)  # the texture from outside was copied in
    model = (description / "mjcf" / "robot.xml").read_text()
    files = re.findall(r'file="([^"]*)"', model)
    assert files and all("/" not in name and not name.startswith(".") for name in files)


def test_two_builds_of_one_output_folder_take_turns(arm):
    """While one build holds the output folder, a second one waits, then builds it whole."""
    state = arm / "mjcf" / ".mjcfbuild"
    state.mkdir(parents=True)
    with open(state / "lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # as a running build does
        waiting = subprocess.Popen(
            [sys.executable, "-m", "mjcfbuild", "build", "-j", "1"],
            cwd=arm,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        first_line = waiting.stdout.readline()
        assert first_line.startswith("mjcfbuild: waiting for another build of mjcf")
        time.sleep(1.0)
        assert waiting.poll() is None
        assert not (arm / "mjcf" / "example_arm.xml").exists()
        fcntl.flock(held, fcntl.LOCK_UN)
    out, err = waiting.communicate(timeout=300)
    assert waiting.returncode == 0, err
    assert (arm / "mjcf" / "example_arm.xml").exists()
    assert "built example_arm.xml" in out
