"""The ``robot.yaml`` manifest: models, loading with positioned errors, and its JSON Schema.

Imports are lazy: a no-op build is decided from its stamp (:mod:`mjcfbuild.engine.stamp`) and
never imports pydantic.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Manifest", "load_manifest", "parse_manifest"]


def __getattr__(name: str) -> Any:
    if name == "Manifest":
        from mjcfbuild.manifest.models import Manifest

        return Manifest
    if name in ("load_manifest", "parse_manifest"):
        from mjcfbuild.manifest import loading

        return getattr(loading, name)
    raise AttributeError(name)
