"""``get_package_share_directory``, looked up in the ament resource index."""

from __future__ import annotations

import os


class PackageNotFoundError(KeyError):
    """No prefix of AMENT_PREFIX_PATH has the package in its resource index."""


def get_package_share_directory(package_name: str) -> str:
    """The share folder of ``package_name``."""
    for prefix in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep):
        marker = os.path.join(prefix, "share", "ament_index", "resource_index", "packages")
        if prefix and os.path.isfile(os.path.join(marker, package_name)):
            return os.path.join(prefix, "share", package_name)
    raise PackageNotFoundError(f"package '{package_name}' not found")
