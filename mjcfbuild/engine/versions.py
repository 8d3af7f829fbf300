"""Versions of the tools the steps use, read without importing them (each family names its
tools and format in its module: mjcfbuild.families)."""

from __future__ import annotations

from functools import cache
from importlib import metadata


@cache
def tool_version(distribution: str) -> str:
    """The installed version of a distribution, or 'missing'."""
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return "missing"
