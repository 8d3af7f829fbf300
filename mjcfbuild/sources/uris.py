"""Resolving the file references a URDF makes (meshes, textures) to real paths."""

from __future__ import annotations

from pathlib import Path
from urllib.parse import unquote

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import normalise
from mjcfbuild.sources.packages import PackageResolver

_PACKAGE_SCHEMES = ("package://", "model://")
_REMOTE_SCHEMES = ("http://", "https://", "ftp://")


def resolve_uri(uri: str, base_dir: Path, packages: PackageResolver) -> Path:
    """The absolute path ``uri`` names.

    ``package://pkg/rest`` (and Gazebo's ``model://``) resolve through ``packages``;
    ``file://`` URIs and plain paths are absolute or relative to ``base_dir``, the folder of
    the URDF (or xacro) file that mentions them.
    """
    text = uri.strip()
    if not text:
        raise InputError("empty file name")
    named = _package_part(text)
    if named is not None:
        package, inner = named
        if not package:
            raise InputError(f"'{uri}' names no package")
        if not inner.strip("/"):
            # package:///base.stl (onshape-to-robot's, for a file beside the URDF): the
            # package part is empty, and the one name is a file's.
            empty = text.split("://", 1)[1].startswith("/")
            raise InputError(
                f"'{uri}' names no package, only a file"
                if empty
                else f"'{uri}' names package '{package}' but no file in it",
                hint=_no_file_hint(package, base_dir),
            )
        return normalise(packages.find(package) / unquote(inner))
    if text.startswith(_REMOTE_SCHEMES):
        raise InputError(
            f"'{uri}' is a remote file; mjcfbuild does not download files",
            hint="download it into the description and refer to it by a relative path",
        )
    if text.startswith("file://"):
        text = unquote(text[len("file://") :])
    path = Path(text)
    if not path.is_absolute():
        path = base_dir / path
    return normalise(path)


def uri_package_folder(uri: str, packages: PackageResolver) -> Path | None:
    """The folder of the package a ``package://`` (or ``model://``) URI names; None for other
    URIs. Call it after :func:`resolve_uri` succeeded (the package is found)."""
    named = _package_part(uri.strip())
    return normalise(packages.find(named[0])) if named and named[0] else None


def _no_file_hint(package: str, base_dir: Path) -> str:
    """What to write instead of ``package://<package>``: pybullet (and Genesis) read
    ``package://name.obj`` as the file ``name.obj`` beside the URDF; MuJoCo's import does not."""
    if (base_dir / unquote(package)).is_file():
        return f"'{package}' is a file beside the URDF: write filename=\"{package}\""
    return f"write package://{package}/<the file's path inside it>"


def _package_part(text: str) -> tuple[str, str] | None:
    """(package, the rest) of a package URI, else None."""
    for scheme in _PACKAGE_SCHEMES:
        if text.startswith(scheme):
            # "package:///pkg/..." (an extra slash, seen in real descriptions) means the same.
            package, _, inner = text[len(scheme) :].lstrip("/").partition("/")
            return package, inner
    return None
