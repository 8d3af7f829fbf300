"""The XML side of the COLLADA reader: elements by id as pycollada finds them, and numbers.

:mod:`mjcfbuild.meshes.collada` reads geometry and scenes with it, and
:mod:`mjcfbuild.meshes.collada_looks` materials.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
from lxml import etree

from mjcfbuild.errors import InputError


class Reader:
    """A parsed DAE file: its elements by id, and errors naming its lines."""

    def __init__(self, path: Path) -> None:
        self.path = path
        try:
            parser = etree.XMLParser(
                resolve_entities=False, no_network=True, load_dtd=False, huge_tree=True
            )
            self.root = etree.parse(str(path), parser).getroot()
        except (etree.XMLSyntaxError, OSError) as exc:
            raise InputError(f"cannot read COLLADA file: {exc}", file=path) from None
        self.ns = self.root.nsmap.get(None)
        # Every element by id, in document order. Exporters reuse ids (every geometry's
        # positions called "verts"), so one id may name several elements: lookups choose by
        # scope and kind (see `by_url`), never by whichever came last.
        self.ids: dict[str, list] = {}
        for element in self.root.iter(etree.Element):
            element_id = element.get("id")
            if element_id:
                self.ids.setdefault(element_id, []).append(element)

    def tag(self, name: str) -> str:
        """The qualified tag of the COLLADA element ``name`` in this file's namespace."""
        return f"{{{self.ns}}}{name}" if self.ns else name

    def find(self, element, path: str):
        """The first element at ``path`` (local names) under ``element``, in any namespace."""
        return element.find(_any_namespace(path))

    def findall(self, element, path: str):
        """Every element at ``path`` (local names) under ``element``, in any namespace."""
        return element.findall(_any_namespace(path))

    def by_url(self, url: str | None, kinds: tuple[str, ...], referrer=None, scope=None):
        """The element of one of ``kinds`` (local names) that ``url`` ("#id") names.

        Ids are looked up as pycollada does: first among ``scope`` (the children of a
        ``<mesh>``, where sources and vertices live), then in the whole document among
        elements of the right kind. An id that still names two different elements is an
        error naming both lines: the readings would disagree, and guessing could hand over
        another geometry's vertices."""
        if not url:
            return None
        element_id = url[1:] if url.startswith("#") else url
        for candidates in (
            [e for e in scope if e.get("id") == element_id] if scope is not None else [],
            self.ids.get(element_id, []),
        ):
            found = [e for e in candidates if etree.QName(e).localname in kinds]
            if not found:
                continue
            first = found[0]
            if any(_differs(first, other) for other in found[1:]):
                lines = " and ".join(str(e.sourceline) for e in found)
                kind = etree.QName(first).localname
                raise InputError(
                    f"id '{element_id}' names {len(found)} different <{kind}> "
                    f"elements (lines {lines}); the reference cannot tell which one it means",
                    file=self.path,
                    line=referrer.sourceline if referrer is not None else None,
                    hint="give each element its own id (re-export the mesh), or convert it to OBJ",
                )
            return first
        return None

    def error(self, message: str, element=None) -> InputError:
        """An input error of this file, at ``element``'s line where one is given."""
        return InputError(
            message,
            file=self.path,
            line=element.sourceline if element is not None else None,
            hint="re-export the mesh, or convert it to OBJ",
        )


def _differs(one, other) -> bool:
    """Whether two elements with the same id say different things. Copies are harmless, except
    <vertices> in different meshes: their inputs name sources of their own mesh."""
    if etree.QName(one).localname == "vertices" and one.getparent() is not other.getparent():
        return True
    return etree.tostring(one, with_tail=False) != etree.tostring(other, with_tail=False)


def _any_namespace(path: str) -> str:
    return "/".join(f"{{*}}{part}" for part in path.split("/"))


def floats(reader: Reader, element) -> np.ndarray:
    """The numbers of ``element``'s text (none for no element); anything else in it is an
    error at its line (``0,2``: a decimal comma)."""
    return _numbers(reader, element, np.float64, "numbers")


def ints(reader: Reader, element) -> np.ndarray:
    """The whole numbers of ``element``'s text, as :func:`_floats`."""
    return _numbers(reader, element, np.int64, "whole numbers")


def _numbers(reader: Reader, element, dtype, what: str) -> np.ndarray:
    text = element.text if element is not None else None
    if not text or not text.strip():
        return np.zeros(0, dtype=dtype)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        try:
            return np.fromstring(text, dtype=dtype, sep=" ")
        except ValueError:
            pass
    words = text.split()
    kind = float if dtype is np.float64 else int
    bad = next((word for word in words if not _parses(kind, word)), words[0])
    raise reader.error(
        f"<{etree.QName(element).localname}> holds '{bad[:20]}' among its {what}", element
    )


def _parses(kind: type, word: str) -> bool:
    try:
        kind(word)
    except ValueError:
        return False
    return True
