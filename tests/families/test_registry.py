"""The task families' registry: every family declared once, the engine's tables derived from
it, and a new family added with its module and one line of the registry."""

from __future__ import annotations

import importlib
import json
import shutil
from pathlib import Path

import pytest

import mjcfbuild
from mjcfbuild.engine import stamp
from mjcfbuild.engine.context import BuildContext
from mjcfbuild.engine.tasks import build_tasks, planning_tasks
from mjcfbuild.families import registry
from mjcfbuild.families.registry import (
    BY_NAME,
    CHECK_MODULES,
    COMPILES_MODEL,
    FAMILIES,
    REPORT_TASKS,
    STEP_FORMATS,
    STEP_TOOLS,
)
from mjcfbuild.graph.family import Family, file_task
from mjcfbuild.sharing.coordinator import SHARED_STEPS
from tests.conftest import EXAMPLES
from tests.families.toy_step import ToyPayload

# The tables engine/versions.py, engine/session.py, engine/workers.py and engine/freshness.py
# held before the registry. A format bump changes STEP_FORMATS here too, on purpose: it reruns
# that family's tasks in every folder built before.
BEFORE_FORMATS = {
    "expand": 5,
    "plan": 21,
    "mesh": 14,
    "decompose": 5,
    "assemble": 27,
    "scene": 3,
    "check": 26,
    "reference": 1,
    "previews": 6,
    "tuning": 1,
    "srdf": 3,
    "selfcollision": 5,
    "export_urdf": 4,
    "compose": 2,
    "mjcfpart": 2,
    "package": 4,
    "training": 7,
    "page": 3,
}
BEFORE_TOOLS = {
    "expand": ("xacro",),
    "plan": ("lxml",),
    "mesh": ("trimesh", "numpy", "lxml", "pillow", "fast-simplification", "scipy"),
    "decompose": ("coacd", "trimesh", "numpy", "scipy"),
    "assemble": ("mujoco", "numpy", "lxml"),
    "scene": ("lxml",),
    "srdf": ("xacro", "lxml"),
    "selfcollision": ("mujoco", "numpy"),
    "check": ("mujoco", "numpy"),
    "reference": ("yourdfpy", "numpy", "lxml"),
    "previews": ("mujoco", "numpy", "pillow"),
    "tuning": ("mujoco", "numpy", "pillow"),
    "export_urdf": ("mujoco", "numpy"),
    "compose": ("lxml",),
    "mjcfpart": ("mujoco", "lxml"),
    "package": ("mujoco", "numpy", "lxml"),
    "training": ("mujoco", "numpy", "scipy", "trimesh", "lxml"),
    "page": (),
}


def test_every_family_has_a_unique_name_a_format_and_a_step_that_exists():
    names = [family.name for family in FAMILIES]
    assert len(names) == len(set(names)) == len(BY_NAME)
    for family in FAMILIES:
        assert isinstance(family.format, int) and family.format >= 1, family.name
        assert all(isinstance(tool, str) and tool for tool in family.tools), family.name
        module_name, _, function = family.step.partition(":")
        assert module_name == family.module == f"mjcfbuild.steps.{family.name}"
        assert callable(getattr(importlib.import_module(module_name), function)), family.step
        assert family.stage in ("planning", "build")
    # The planning families come first: their tasks decide which build tasks exist.
    stages = [family.stage for family in FAMILIES]
    assert stages == sorted(stages, key=("planning", "build").index)


def test_the_derived_tables_are_the_ones_the_engine_kept_before():
    assert STEP_FORMATS == BEFORE_FORMATS
    assert STEP_TOOLS == BEFORE_TOOLS
    assert set(COMPILES_MODEL) == {
        f"mjcfbuild.steps.{name}:run"
        for name in ("selfcollision", "assemble", "check", "previews", "tuning", "training")
    }
    assert REPORT_TASKS == ("check", "previews", "tuning")
    assert CHECK_MODULES == (
        "mjcfbuild.steps.check",
        "mjcfbuild.steps.previews",
        "mjcfbuild.steps.tuning",
    )
    assert SHARED_STEPS == {
        "mjcfbuild.steps.mesh:run": "mesh",
        "mjcfbuild.steps.decompose:run": "decompose",
    }
    version = registry.step_versions("mesh")
    assert version["mjcfbuild-step"] == "mesh-14" and version["mjcfbuild"] == mjcfbuild.__version__
    assert list(version)[:6] == list(BEFORE_TOOLS["mesh"])


def _every_feature(tmp_path: Path) -> Path:
    """The example arm with every optional family on, built without its check (cheap); the
    graph is then made with the check on, which needs no output of the check."""
    arm = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    (arm / "arm.srdf").write_text(
        '<robot name="example_arm"><group name="all"/><group_state name="ready" group="all">'
        '<joint name="elbow" value="1.0"/></group_state></robot>'
    )
    manifest = arm / "robot.yaml"
    manifest.write_text(
        manifest.read_text()
        + "  package: true\n  page: true\n  urdf: exported.urdf\n  training: true\n"
        + "check:\n  tuning: true\n"
        + "collision:\n  default: decompose\n"
        + "self_collision:\n  srdf: arm.srdf\n  samples: 50\n"
    )
    mjcfbuild.build(manifest, jobs=1, check=False)
    return manifest


def _payloads(tasks: list[dict]) -> dict[str, list[dict]]:
    """Family name -> the payloads of its tasks, as sent to a worker."""
    by_step = {family.step: family.name for family in FAMILIES}
    found: dict[str, list[dict]] = {}
    for task in tasks:
        _, (_, _, step, payload, _) = task["actions"][0]
        found.setdefault(by_step[step], []).append(payload)
    return found


def test_every_family_makes_tasks_whose_payload_survives_the_trip_to_a_worker(tmp_path):
    manifest = _every_feature(tmp_path)
    payloads = _payloads(build_tasks(BuildContext.from_manifest_file(manifest, run_check=True)))
    for example in ("arm_gripper", "arm_mjcf_gripper"):  # the attach: part families
        folder = tmp_path / example
        shutil.copytree(EXAMPLES / example, folder, ignore=shutil.ignore_patterns("mjcf"))
        ctx = BuildContext.from_manifest_file(folder / "robot.yaml")
        for name, found in _payloads(planning_tasks(ctx)).items():
            payloads.setdefault(name, []).extend(found)
    assert set(payloads) == set(BY_NAME)
    for name, found in payloads.items():
        for payload in found:
            wire = json.loads(json.dumps(payload))  # as a worker receives it
            back = BY_NAME[name].payload.from_dict(wire).to_dict()
            assert json.loads(json.dumps(back)) == wire, name


def _toy_tasks(graph, family: Family) -> list[dict]:
    ctx = graph.ctx
    payload = ToyPayload(
        greeting=ctx.manifest.name, model=str(ctx.robot_path), output=str(ctx.state("toy.txt"))
    )
    task = file_task(
        ctx,
        family,
        f"{graph.prefix}toy",
        "toy",
        payload,
        in_worker=False,
        file_dep=[ctx.robot_path],
        targets=[ctx.state("toy.txt")],
        after=[f"{graph.prefix}assemble"],
    )
    return [task]


def _toy(format: int) -> Family:
    """A family of the test's own, as a module of mjcfbuild.families would declare it."""

    def tasks(graph) -> list[dict]:
        return _toy_tasks(graph, family)

    family = Family(
        name="toy",
        step="tests.families.toy_step:run",
        payload=ToyPayload,
        format=format,
        tools=("lxml",),
        tasks=tasks,
    )
    return family


TOY = _toy(1)


def test_a_family_added_to_the_registry_builds_reruns_on_a_format_bump_and_is_up_to_date(
    arm, monkeypatch
):
    # The family is not in the source files the no-op stamp watches: doit decides each time.
    monkeypatch.setenv(stamp.DISABLE_VARIABLE, "1")
    monkeypatch.setattr(registry, "FAMILIES", (*FAMILIES, TOY))
    manifest = arm / "robot.yaml"
    first = mjcfbuild.build(manifest, jobs=1, check=False)
    assert "toy" in first.ran
    toy = arm / "mjcf" / ".mjcfbuild" / "toy.txt"
    assert toy.read_text() == f"example_arm {(arm / 'mjcf' / 'example_arm.xml').stat().st_size}\n"
    assert mjcfbuild.build(manifest, jobs=1, check=False).ran == []
    monkeypatch.setattr(registry, "FAMILIES", (*FAMILIES, _toy(2)))
    assert mjcfbuild.build(manifest, jobs=1, check=False).ran == ["toy"]


def test_a_family_given_another_familys_payload_is_refused():
    with pytest.raises(AssertionError, match="toy is given"):
        file_task(
            None,  # type: ignore[arg-type]  # refused before the context is read
            TOY,
            "toy",
            "toy",
            BY_NAME["reference"].payload(urdf="u", kinematics="k", cache={}, output="o"),
            in_worker=False,
            file_dep=[],
            targets=[],
        )
