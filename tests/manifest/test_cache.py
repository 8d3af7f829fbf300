"""The validated-manifest cache: same answers as validation, and pydantic stays unimported."""

from __future__ import annotations

import subprocess
import sys

from mjcfbuild.manifest.cache import FrozenManifest
from mjcfbuild.manifest.loading import load_manifest
from tests.conftest import EXAMPLES, write


def test_cached_manifest_reads_like_the_validated_one(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    path = EXAMPLES / "arm" / "robot.yaml"
    fresh = load_manifest(path, use_cache=True)
    cached = load_manifest(path, use_cache=True)
    assert isinstance(cached, FrozenManifest)
    assert cached.name == fresh.name
    assert cached.robot_file == fresh.robot_file == "example_arm.xml"
    assert cached.source.xacro_args == fresh.source.xacro_args == {"with_camera": "true"}
    assert cached.options.fuse_static is True and cached.packages == {"arm_description": "."}


def test_a_changed_manifest_is_validated_again(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    path = write(tmp_path / "robot.yaml", "name: a\nsource: {urdf: a.urdf}\n")
    assert load_manifest(path, use_cache=True).name == "a"
    path.write_text("name: b\nsource: {urdf: a.urdf}\n")
    assert load_manifest(path, use_cache=True).name == "b"


def test_cache_hit_does_not_import_pydantic(tmp_path):
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache"), "PATH": "/usr/bin:/bin"}
    code = (
        "import sys; from mjcfbuild.manifest.loading import load_manifest;"
        f"m = load_manifest({str(EXAMPLES / 'arm' / 'robot.yaml')!r}, use_cache=True);"
        "print(type(m).__name__, 'pydantic' in sys.modules)"
    )
    first = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    second = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert first.stdout.split() == ["Manifest", "True"]
    assert second.stdout.split() == ["FrozenManifest", "False"]


def test_lists_of_settings_in_a_cached_manifest_read_by_attribute(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    path = write(
        tmp_path / "robot.yaml",
        "name: r\nsource: {urdf: r.urdf}\n"
        "actuators:\n  rules: [{joints: ['*'], kp: 5}]\n"
        "mujoco_inputs:\n  decompose: [{mesh: base, threshold: 0.1}]\n",
    )
    fresh = load_manifest(path, use_cache=True)
    cached = load_manifest(path, use_cache=True)
    assert isinstance(cached, FrozenManifest)
    assert cached.actuators.rules[0].joints == fresh.actuators.rules[0].joints == ["*"]
    assert cached.mujoco_inputs.decompose[0].mesh == "base"
