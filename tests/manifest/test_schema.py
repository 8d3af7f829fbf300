"""The committed JSON Schema is generated from the models and must not go stale."""

from __future__ import annotations

import json

from mjcfbuild.manifest.schema import manifest_schema, manifest_schema_text
from tests.conftest import ROOT


def test_committed_schema_is_current():
    committed = (ROOT / "schemas" / "robot.schema.json").read_text()
    assert committed == manifest_schema_text(), (
        "schemas/robot.schema.json is stale: run `doit schema` (or "
        "`mjcfbuild schema > schemas/robot.schema.json`) and commit it"
    )


def test_schema_forbids_unknown_keys_everywhere():
    schema = manifest_schema()
    assert schema["additionalProperties"] is False
    for definition in schema["$defs"].values():
        assert definition.get("additionalProperties") is False


def test_schema_is_valid_json_schema_document():
    schema = json.loads(manifest_schema_text())
    assert schema["$schema"].startswith("https://json-schema.org/")
    assert set(schema["required"]) == {"name", "source"}


def test_the_raw_key_names_the_sections_the_inputs_reader_accepts():
    from mjcfbuild.inputs.model import RAW_SECTIONS

    raw = manifest_schema()["$defs"]["MujocoInputs"]["properties"]["raw"]["description"]
    named = raw.split(": ", 1)[1].removesuffix(" sections.").split(", ")
    assert named == list(RAW_SECTIONS)
