"""The Python API for scripts and notebooks."""

from __future__ import annotations

import pytest

import mjcfbuild
from mjcfbuild.errors import BuildFailed, ManifestError
from tests.conftest import simple_manifest, two_link_urdf, write


def test_load_manifest_and_build(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    path = simple_manifest(tmp_path)
    manifest = mjcfbuild.load_manifest(path)
    assert manifest.name == "robot"
    result = mjcfbuild.build(path, jobs=1)
    assert result.ok and result.robot == tmp_path / "mjcf" / "robot.xml"
    assert result.robot.exists() and result.scene.exists()


def test_build_a_manifest_object_against_a_folder(tmp_path):
    write(tmp_path / "robot.urdf", two_link_urdf())
    manifest = mjcfbuild.load_manifest(
        simple_manifest(tmp_path, extra="output:\n  folder: built\n")
    )
    result = mjcfbuild.build(manifest, base_dir=tmp_path)
    assert (tmp_path / "built" / "robot.xml").exists() and result.ran


def test_failures_raise_with_every_error(tmp_path):
    write(tmp_path / "robot.urdf", "<robot name='r'>")
    with pytest.raises(BuildFailed) as info:
        mjcfbuild.build(simple_manifest(tmp_path))
    assert info.value.errors and "malformed XML" in info.value.one_line()
    with pytest.raises(ManifestError):
        mjcfbuild.build(write(tmp_path / "bad.yaml", "name: x\n"))


def test_importing_mjcfbuild_does_not_import_heavy_libraries():
    import subprocess
    import sys

    code = (
        "import sys, mjcfbuild, mjcfbuild.cli, mjcfbuild.engine.runner, mjcfbuild.manifest;"
        "heavy = [m for m in ('mujoco', 'trimesh', 'numpy', 'coacd', 'lxml', 'fsspec', 's3fs', 'dask', 'distributed') if m in sys.modules];"
        "print(','.join(heavy))"
    )
    output = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert output.stdout.strip() == ""
