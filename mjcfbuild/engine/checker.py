"""The doit file checker: content hashes, read through the :class:`HashCache`."""

from __future__ import annotations

import os

from doit.dependency import FileChangedChecker

from mjcfbuild.graph.hashes import HashCache


def checker_class(hashes: HashCache) -> type[FileChangedChecker]:
    """A doit checker class bound to ``hashes`` (doit instantiates checkers itself)."""

    class ContentChecker(FileChangedChecker):
        """A dependency changed when its bytes did; mtime alone never counts."""

        def check_modified(self, file_path: str, file_stat: os.stat_result, state: object) -> bool:
            return state != hashes.md5(file_path, file_stat)

        def get_state(self, dep: str, current_state: object) -> str | None:
            digest = hashes.md5(dep)
            return None if digest == current_state else digest

    return ContentChecker
