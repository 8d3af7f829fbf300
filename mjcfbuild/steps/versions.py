"""What a step's output depends on besides its inputs: the versions of its tools, read without
importing them, and its format.

Each family (:mod:`mjcfbuild.families`) declares its step's format and tools. The steps whose
products the machine-wide cache keeps (mesh, decompose, selfcollision) key them by those
versions, and the steps sit below the families, so their formats are declared here, where the
step and its family both read them.
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass
from functools import cache

from mjcfbuild.version import __version__


@cache
def tool_version(distribution: str) -> str:
    """The installed version of a distribution, or 'missing'."""
    found = _installed_versions().get(_normalised(distribution))
    if found is not None:
        return found
    # Not installed from a wheel (an egg, a source tree on the path): ask importlib, which
    # reads the metadata, and costs every build's start 0.02 s of email-parsing imports.
    from importlib import metadata

    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return "missing"


@cache
def _installed_versions() -> dict[str, str]:
    """Each distribution's version as its ``<name>-<version>.dist-info`` folder names it (what
    installers write, and what importlib.metadata would read), the first on ``sys.path``
    winning as it does there."""
    versions: dict[str, str] = {}
    for folder in sys.path:
        try:
            names = os.listdir(folder or ".")
        except OSError:
            continue
        for name in names:
            if name.endswith(".dist-info"):
                distribution, _, version = name.removesuffix(".dist-info").rpartition("-")
                if distribution and version:
                    versions.setdefault(_normalised(distribution), version)
    return versions


def _normalised(name: str) -> str:
    """A distribution name as PEP 503 compares them."""
    return re.sub(r"[-_.]+", "-", name).lower()


@dataclass(frozen=True)
class StepFormat:
    """A step's name, its format (bumped when its output for the same inputs changes) and the
    distributions whose versions make its output what it is."""

    name: str
    format: int
    tools: tuple[str, ...]

    def versions(self) -> dict[str, str]:
        """Tool versions and the format (in a task's up-to-date parameters and in product
        cache keys)."""
        versions = {name: tool_version(name) for name in self.tools}
        versions["mjcfbuild-step"] = f"{self.name}-{self.format}"
        versions["mjcfbuild"] = __version__
        return versions


# mesh 8: COLLADA lookat/skew placements and nonsense units refused, not ignored; 9: a mesh
# whose every triangle is degenerate refused at its file, not passed to MuJoCo; 10: COLLADA's
# X_UP turned as the spec's table says, concave polygons ear-clipped, accessor offsets and
# unnamed params, TEXCOORDs of <vertices>, the common profile's colour, a missing scene refused;
# 11: a textured material keeps its texture where a primitive has no texture coordinates; 12:
# the COLLADA spec's opacity, a texture that is no image left out with a warning; 13: COLLADA
# texture coordinate sets as bound, vertex colours, emission, skins, files without a scene;
# the look of an -a OBJ's original; mesh material warnings quoted, none for collision-only; 14:
# a mesh of fewer than 4 vertices gets a spare corner (MuJoCo reads none smaller)
MESH = StepFormat(
    "mesh", 14, ("trimesh", "numpy", "lxml", "pillow", "fast-simplification", "scipy")
)
# decompose 4: a mesh without a COLLADA scene decomposes to nothing ("method": "none"); 5: a
# flat mesh CoACD makes nothing of is its own flat part
DECOMPOSE = StepFormat("decompose", 5, ("coacd", "trimesh", "numpy", "scipy"))
# selfcollision 4: a URDF floating joint from `world` floats the robot (its standing home);
# 5: free_joint on a URDF rooted at `world` floats what the world holds as one whole; a root
# holding the robot by a floating joint is the world body
SELFCOLLISION = StepFormat("selfcollision", 5, ("mujoco", "numpy"))
REFERENCE = StepFormat("reference", 1, ("yourdfpy", "numpy", "lxml"))
# previews 6: each picture's floor placed around its own camera, its kind in its digest
PREVIEWS = StepFormat("previews", 6, ("mujoco", "numpy", "pillow"))
