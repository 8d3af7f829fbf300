"""Validated manifests remembered by content, so a no-op build never imports pydantic.

Validating ``robot.yaml`` is a pure function of its text; importing pydantic to do it costs
about 0.1 s, half of a no-op build. The validated manifest is stored in the user cache folder
under a key made of the manifest's bytes, the mjcfbuild version and the models' source, and read
back as a :class:`FrozenManifest`: a read-only view with the same attributes.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from mjcfbuild import __version__
from mjcfbuild.cachedir import user_cache_dir
from mjcfbuild.fsutil import atomic_write

# Every module that defines manifest models: a change to any of them changes the cache key.
_MODELS = tuple(
    Path(__file__).with_name(name) for name in ("models.py", "simulation.py", "composition.py")
)
_MODEL_TAG = "__model__"
# Entries written before keys kept the manifest's order were sorted; they are not read.
_FORMAT = b"ordered-keys"


class FrozenManifest:
    """A read-only view of a validated manifest (or one of its parts), by attribute."""

    __slots__ = ("_data",)

    def __init__(self, data: dict) -> None:
        object.__setattr__(self, "_data", data)

    def __getattr__(self, name: str):
        try:
            return _thaw(self._data[name])
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name: str, value) -> None:
        raise AttributeError("a manifest is read-only")

    def __repr__(self) -> str:
        return f"FrozenManifest({self._data!r})"


def _thaw(value):
    if isinstance(value, dict) and value.get(_MODEL_TAG):
        return FrozenManifest(value)
    if isinstance(value, list):  # lists of models (rules, cameras, ...) read by attribute too
        return [_thaw(item) for item in value]
    return value


def _freeze(value):
    """Plain JSON data of a pydantic model, computed fields included, sub-models tagged."""
    from pydantic import BaseModel

    if isinstance(value, BaseModel):
        data = {_MODEL_TAG: True}
        names = list(type(value).model_fields) + list(type(value).model_computed_fields)
        for name in names:
            data[name] = _freeze(getattr(value, name))
        return data
    if isinstance(value, dict):
        return {str(k): _freeze(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_freeze(v) for v in value]
    return value


def cache_key(text: bytes) -> str:
    """The key of a manifest text: its bytes, mjcfbuild's version and the models' source."""
    digest = hashlib.sha256(text)
    digest.update(_FORMAT)
    digest.update(__version__.encode())
    for models in _MODELS:
        digest.update(models.read_bytes())
    return digest.hexdigest()


def _entry(key: str) -> Path:
    return user_cache_dir() / "manifests" / f"{key}.json"


def read_cached(text: bytes) -> FrozenManifest | None:
    """The validated manifest for ``text``, if it was validated before."""
    try:
        data = json.loads(_entry(cache_key(text)).read_text())
    except (OSError, ValueError):
        return None
    return FrozenManifest(data) if isinstance(data, dict) else None


def remember(text: bytes, manifest) -> None:
    """Store a freshly validated manifest; a cache that cannot be written is skipped."""
    path = _entry(cache_key(text))
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        # Keys keep the manifest's order: a cached manifest must read exactly like a fresh one
        # (sorted keys reordered the attributes a `modify` sets, between cold and warm builds).
        atomic_write(path, json.dumps(_freeze(manifest)).encode())
    except OSError:
        pass


def plain(value):
    """A manifest part (validated model or cached view) as plain JSON data."""
    if hasattr(value, "model_dump"):
        return value.model_dump(mode="json")
    if isinstance(value, FrozenManifest):
        value = value._data
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items() if k != _MODEL_TAG}
    if isinstance(value, list):
        return [plain(v) for v in value]
    return value
