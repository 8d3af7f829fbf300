"""The ``robot.yaml`` manifest: models, loading with positioned errors, and its JSON Schema."""

from mjcfbuild.manifest.loading import load_manifest, parse_manifest
from mjcfbuild.manifest.models import Manifest

__all__ = ["Manifest", "load_manifest", "parse_manifest"]
