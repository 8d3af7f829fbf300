"""The task payloads: what counts toward a task being up to date is derived, not listed."""

from __future__ import annotations

import dataclasses
import json

import pytest

import mjcfbuild
from mjcfbuild.families import scene
from mjcfbuild.steps import payloads
from mjcfbuild.steps.payloads import (
    AssemblePayload,
    DecompositionFiles,
    MeshOptions,
    MeshPayload,
    Payload,
    ScenePayload,
)
from tests.conftest import simple_manifest, two_link_urdf, write

PAYLOAD_CLASSES = [
    cls
    for cls in vars(payloads).values()
    if isinstance(cls, type) and issubclass(cls, Payload) and cls is not Payload
]


def _mesh_payload(**changes) -> MeshPayload:
    options = MeshOptions(roles=["visual", "collision"], max_faces=None, collada_up_axis="apply")
    fields = {
        "source": "/robot/meshes/link.stl",
        "options": options,
        "max_file_bytes": 1000,
        "product_dir": "/out/products/link",
        "summary": "/out/products/link.json",
        "depfile": "/out/products/link.deps.json",
        "cache": {"enabled": True, "folder": "/cache", "max_bytes": 10},
    }
    return MeshPayload(**{**fields, **changes})


@pytest.mark.parametrize("cls", PAYLOAD_CLASSES, ids=lambda cls: cls.__name__)
def test_every_field_that_does_not_count_says_why(cls):
    for name, why in cls.uncounted_fields().items():
        assert name in {f.name for f in dataclasses.fields(cls)}
        assert len(why) > 10, f"{cls.__name__}.{name} needs a reason"


def test_a_counted_field_changes_the_parameters_and_an_uncounted_one_does_not():
    payload = _mesh_payload()
    base = payload.uptodate_params()
    assert _mesh_payload(max_file_bytes=2000).uptodate_params() != base
    options = dataclasses.replace(payload.options, max_hull_vertices=32)
    assert _mesh_payload(options=options).uptodate_params() != base
    assert _mesh_payload(product_dir="/elsewhere").uptodate_params() == base
    assert _mesh_payload(cache={"enabled": False}).uptodate_params() == base


def test_an_optional_file_dependency_counts_by_being_given():
    def assemble(self_collision):
        return AssemblePayload(
            choices=[],
            decompositions=[DecompositionFiles("m", {"threshold": 0.05}, "/d/m", "/d/m.json")],
            inputs={},
            actuators={},
            motors={},
            home={},
            floor="auto",
            srdf_home=None,
            fuse_static=True,
            free_joint=False,
            link_sites="fused",
            max_hull_vertices=None,
            inertia={},
            header="",
            assets_dir="/out/assets",
            self_collision=self_collision,
            srdf=None,
            plan="/out/plan.json",
            products={},
            product_dirs={},
            manifest_label="robot.yaml",
            report="/out/report.json",
            floor_record="/out/floor.json",
            output="/out/robot.xml",
            mjcf_parts=[],
        )

    given = assemble("/out/self_collision.json").uptodate_params()
    assert given["self_collision"] is True
    assert assemble(None).uptodate_params()["self_collision"] is False
    assert assemble("/other/self_collision.json").uptodate_params() == given
    # Nested payloads follow their own markers: a decomposition's folder does not count.
    assert given["decompositions"] == [{"mesh_id": "m", "params": {"threshold": 0.05}}]


def test_a_payload_survives_the_trip_to_a_worker():
    payload = _mesh_payload()
    assert MeshPayload.from_dict(json.loads(json.dumps(payload.to_dict()))) == payload


def test_a_field_added_to_a_payload_reruns_its_task(tmp_path, monkeypatch):
    write(tmp_path / "robot.urdf", two_link_urdf())
    manifest = simple_manifest(tmp_path)
    mjcfbuild.build(manifest, jobs=1, check=False)
    assert not mjcfbuild.build(manifest, jobs=1, check=False).ran

    @dataclasses.dataclass(frozen=True)
    class SceneWithNewOption(ScenePayload):
        lighting: str = "studio"

    monkeypatch.setattr(scene, "ScenePayload", SceneWithNewOption)
    assert mjcfbuild.build(manifest, jobs=1, check=False).ran == ["scene"]
