"""Whether a cached product can be used: every file its summary names is there and matches.

A product's checksums (mjcfbuild.sharing.blob) prove it arrived as it was sent, not that it
makes sense: a summary may name a file (a mesh's collision file, a decomposition's part) that
the product does not contain, and the step that reads it would fail in every later build. The
store and the remote cache check a product here before they store or use it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from mjcfbuild.fsutil import md5_file

# The kinds of product with more to check than their list of files.
KINDS = ("mesh", "decompose", "selfcollision")


def product_problem(kind: str | None, summary: Any, folder: Path) -> str | None:
    """Why the product of ``kind`` (None: any) with ``summary`` in ``folder`` cannot be used,
    in a few words; None when it can."""
    try:
        files, named = _listed_files(kind, summary)
    except (AttributeError, KeyError, TypeError, ValueError) as exc:
        return f"its summary cannot be read ({type(exc).__name__})"
    for name in sorted(set(files) | named):
        if not _plain_name(name):
            return f"its summary names an unsafe file '{name[:40]}'"
    absent = sorted(named - set(files))
    if absent:
        return f"its summary names {absent[0]}, which it does not contain"
    for name, digest in sorted(files.items()):
        try:
            actual = md5_file(folder / name)
        except OSError:
            return f"{name} is missing"
        if actual != digest:
            return f"{name} does not match its digest"
    return None


def _listed_files(kind: str | None, summary: Any) -> tuple[dict[str, str], set[str]]:
    """The files a summary lists with their digests, and those its other fields name."""
    files = summary["files"]
    if not isinstance(files, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in files.items()
    ):
        raise TypeError("files is not a table of names and digests")
    named: set[str] = set()
    if kind == "mesh":
        from mjcfbuild.meshes.product import MeshProduct

        product = MeshProduct.from_dict(summary)
        for part in product.parts:
            named.add(part.file)
            if part.texture:
                named.add(part.texture)
        named.update(name for name in (product.collision, product.hull) if name)
    elif kind == "decompose":
        named.update(summary["parts"])
        if not named:
            raise ValueError("no parts")
    elif kind == "selfcollision":
        named.add("matrix.json")
    elif kind == "reference":
        named.add("reference.json")
    elif kind == "preview":
        named.add("picture.png")
    if not all(isinstance(name, str) for name in named):
        raise TypeError("a file name is not text")
    return files, named


def _plain_name(name: str) -> bool:
    return bool(name) and name not in (".", "..") and "/" not in name and "\\" not in name
