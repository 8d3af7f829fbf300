"""mjcfbuild: declarative, incremental builds of MuJoCo models from URDF and xacro.

The command line (``mjcfbuild build robot.yaml``) is the main interface; scripts and notebooks
can use :func:`build` and :func:`load_manifest`. Importing this package is cheap: MuJoCo,
trimesh and numpy are only imported by the build steps that need them.
"""

from __future__ import annotations

from mjcfbuild.version import __version__

__all__ = ["__version__", "build", "load_manifest"]


def load_manifest(path):
    """Read and validate a ``robot.yaml``; raises :class:`mjcfbuild.errors.ManifestError`."""
    from mjcfbuild.manifest.loading import load_manifest as _load

    return _load(path)


def build(manifest, jobs: int | None = None, quiet: bool = True, base_dir=None, check: bool = True):
    """Build a robot; see :func:`mjcfbuild.api.build`."""
    from mjcfbuild.api import build as _build

    return _build(manifest, jobs=jobs, quiet=quiet, base_dir=base_dir, check=check)
