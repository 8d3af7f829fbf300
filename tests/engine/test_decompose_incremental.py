"""Decomposition acceptance on the example arm: reproducible, incremental, shared."""

from __future__ import annotations

import mjcfbuild
from tests.conftest import copy_example

RULES = """collision:
  rules:
    - links: [upper_arm_link]
      policy: decompose
      decompose: {threshold: THRESHOLD, preprocess_mode: "off"}
"""


def with_rules(folder, threshold):
    manifest = folder / "robot.yaml"
    text = manifest.read_text().split("collision:")[0]
    manifest.write_text(text + RULES.replace("THRESHOLD", str(threshold)))


def parts(folder):
    return sorted((folder / "mjcf" / "assets").glob("upper_arm_part*.obj"))


def test_decomposition_is_reproducible_incremental_and_shared(tmp_path, monkeypatch):
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    first = copy_example("arm", tmp_path / "one")
    with_rules(first, 0.05)
    result = mjcfbuild.build(first / "robot.yaml", jobs=2)
    assert "decompose:upper_arm" in result.ran
    produced = {p.name: p.read_bytes() for p in parts(first)}
    assert produced

    # A second output folder using the same meshes: the decomposition comes from the cache.
    second = copy_example("arm", tmp_path / "two")
    with_rules(second, 0.05)
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.runner import run_build

    ctx = BuildContext.from_manifest_file(second / "robot.yaml", jobs=2)
    run_build(ctx, Progress(quiet=True))
    assert ctx.session.notes["decompose:upper_arm"].startswith("from cache; ")
    assert {p.name: p.read_bytes() for p in parts(second)} == produced

    # Without the cache, decomposing again gives the same bytes.
    third = copy_example("arm", tmp_path / "three")
    with_rules(third, 0.05)
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "other-cache"))
    mjcfbuild.build(third / "robot.yaml", jobs=1)
    assert {p.name: p.read_bytes() for p in parts(third)} == produced

    # Changing the threshold reruns that decomposition and the assembly, nothing else.
    with_rules(first, 0.02)
    monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(tmp_path / "cache"))
    assert sorted(mjcfbuild.build(first / "robot.yaml", jobs=2).ran) == [
        "assemble",
        "decompose:upper_arm",
        "selfcollision",
    ]
