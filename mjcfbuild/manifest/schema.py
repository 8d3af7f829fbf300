"""The JSON Schema of ``robot.yaml``, generated from the pydantic models."""

from __future__ import annotations

import json

from mjcfbuild.manifest.models import Manifest


def manifest_schema() -> dict:
    """The JSON Schema (draft 2020-12) of the manifest."""
    schema = Manifest.model_json_schema(mode="validation")
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "mjcfbuild robot.yaml"
    return schema


def manifest_schema_text() -> str:
    """The schema as the exact text stored in ``schemas/robot.schema.json``."""
    return json.dumps(manifest_schema(), indent=2, sort_keys=True) + "\n"
