"""Real builds killed (kill -9) or interrupted (Ctrl-C) at chosen moments recover: the next
build finishes, its outputs are byte-identical to a clean build's, and converted meshes and
decompositions that were finished are not redone."""

from __future__ import annotations

import filecmp
import re

import pytest

from tests.conftest import copy_example, run_cli

pytestmark = pytest.mark.slow

RULES = "collision:\n  rules:\n    - links: [upper_arm_link]\n      policy: decompose\n"
MOMENTS = [
    ("mesh", "kill"),
    ("mesh", "interrupt"),
    ("decompose", "kill"),
    ("decompose", "interrupt"),
    ("assemble", "kill"),
    ("assemble", "interrupt"),
    ("write:example_arm.xml", "kill"),
    ("write:scene.xml", "kill"),
]


def arm_with_decomposition(folder):
    arm = copy_example("arm", folder)
    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + RULES)
    return arm


def outputs(folder):
    return sorted(
        str(p.relative_to(folder))
        for p in folder.rglob("*")
        if p.is_file() and not {".mjcfbuild", "report"} & set(p.relative_to(folder).parts)
    )


@pytest.fixture(scope="module")
def clean_build(tmp_path_factory):
    arm = arm_with_decomposition(tmp_path_factory.mktemp("clean"))
    result = run_cli(
        "build", "-q", "-j", "2", cwd=arm, env={"MJCFBUILD_CACHE_DIR": str(arm.parent / "cache")}
    )
    assert result.code == 0, result.stderr
    return arm / "mjcf"


@pytest.mark.parametrize(("point", "action"), MOMENTS, ids=[f"{p}-{a}" for p, a in MOMENTS])
def test_interrupted_build_recovers(tmp_path, clean_build, point, action):
    arm = arm_with_decomposition(tmp_path)
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    stopped = run_cli(
        "build", "-j", "2", cwd=arm, env={**env, "MJCFBUILD_FAILPOINT": f"{point}:{action}"}
    )
    assert stopped.code == (130 if action == "interrupt" else -9), stopped.stdout + stopped.stderr

    again = run_cli("build", "-j", "2", cwd=arm, env=env)
    assert again.code == 0, again.stdout + again.stderr
    # Work finished before the stop is not redone: it is up to date or comes from the cache.
    redone = [
        line
        for line in again.stdout.splitlines()
        if re.search(r"\] (mesh|decompose) ", line) and "from cache" not in line
    ]
    finished_before = re.findall(r"\] ((?:mesh|decompose) \S+)", stopped.stdout)
    for title in finished_before:
        assert not any(title in line for line in redone), (title, again.stdout)

    built = arm / "mjcf"
    assert not list(built.rglob("*.mjcfbuild-tmp"))
    assert outputs(built) == outputs(clean_build)
    _, mismatch, errors = filecmp.cmpfiles(built, clean_build, outputs(built), shallow=False)
    assert mismatch == [] and errors == []
