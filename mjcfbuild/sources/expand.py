"""Turning the declared source into URDF text, and recording every file that took part.

xacro runs in-process through the PyPI ``xacro`` package. Its ``$(find pkg)`` is answered by
mjcfbuild's :class:`PackageResolver`, so no ROS install is needed. Every file xacro opened
(includes, YAML), every optional include that did not exist, and every environment variable it
read are recorded, so the build reruns the expansion exactly when one of them changes.
"""

from __future__ import annotations

import io
import os
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from mjcfbuild.errors import InputError
from mjcfbuild.fsutil import normalise, unreadable_file
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.xmlguard import refuse_entities


@dataclass
class Expansion:
    """The URDF text of a source and what it was made from."""

    urdf: bytes
    files: list[str] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    environment: dict[str, str | None] = field(default_factory=dict)


def expand_source(
    source: Path,
    xacro: bool,
    args: Mapping[str, str],
    packages: Mapping[str, str],
    environment: Mapping[str, str],
) -> Expansion:
    """A source as URDF (or SRDF) text: expanded with xacro, or read as it is. ``packages`` maps
    package names to folders; ``environment`` holds the ROS variables that find the others."""
    if not xacro:
        return read_urdf_file(source)
    from mjcfbuild.sources.packages import PackageResolver

    resolver = PackageResolver({name: Path(f) for name, f in packages.items()}, environment)
    return expand_xacro(source, args, resolver)


def read_urdf_file(path: Path) -> Expansion:
    """A plain URDF source: its bytes, unchanged (it is parsed as bytes later)."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise InputError(
            "source file not found", file=path, hint="fix 'source' in robot.yaml"
        ) from None
    except IsADirectoryError:
        raise InputError("source is a folder, not a file", file=path) from None
    except OSError as exc:
        raise InputError(f"cannot read source: {exc.strerror}", file=path) from None
    return Expansion(urdf=data, files=[str(normalise(path))])


def expand_xacro(path: Path, mappings: Mapping[str, str], packages: PackageResolver) -> Expansion:
    """Expand a xacro file in-process; :class:`InputError` names the failing file."""
    problem = unreadable_file(path)
    if problem:
        raise InputError(
            f"xacro source {problem}", file=path, hint="fix 'source.xacro' in robot.yaml"
        )
    import xml.parsers.expat

    import xacro

    reads: dict[str, str | None] = {}
    raised: list[InputError] = []
    with _xacro_hooks(xacro, packages, reads, raised):
        try:
            document = xacro.process_file(str(path), mappings=dict(mappings))
        except xml.parsers.expat.ExpatError as exc:
            raise InputError(
                f"XML error: {xml.parsers.expat.errors.messages.get(exc.code, exc)}",
                file=_current_file(xacro, path),
                line=exc.lineno,
                column=exc.offset + 1 if exc.offset is not None else None,
            ) from None
        except Exception as exc:  # xacro raises many kinds; all mean "this input is wrong"
            if raised:  # our own $(find)/$(env) error, which xacro wraps in its own
                first = raised[0]
                raise InputError(
                    first.message,
                    file=_current_file(xacro, path),
                    line=first.location.line if first.location else None,
                    hint=first.hint,
                ) from None
            message = _xacro_message(exc)
            hint = "the same error appears with the 'xacro' command; fix the file or its args"
            if "substitution argument" in message:
                hint = (
                    "pass it under 'source.args' in robot.yaml, or give its <xacro:arg> a default"
                )
            raise InputError(
                f"xacro failed: {message}", file=_current_file(xacro, path), hint=hint
            ) from None
        included = list(xacro.all_includes)
    text = document.toprettyxml(indent="  ", encoding="utf-8")
    files = {str(normalise(path))}
    missing: set[str] = set()
    for name in included:
        resolved = str(normalise(name))
        (files if os.path.isfile(resolved) else missing).add(resolved)
    return Expansion(
        urdf=text,
        files=sorted(files),
        missing=sorted(missing),
        environment=dict(sorted(reads.items())),
    )


def _xacro_message(exc: Exception) -> str:
    text = str(exc).strip() or type(exc).__name__
    if type(exc).__name__ == "ArgException":
        return f"undefined substitution argument {text}"
    return text.splitlines()[0] if text else type(exc).__name__


def _current_file(xacro_module: Any, fallback: Path) -> str:  # the untyped xacro module
    stack = getattr(xacro_module, "filestack", None) or []
    for entry in reversed(stack):
        if entry:
            return str(entry)
    return str(fallback)


@contextmanager
def _xacro_hooks(
    xacro_module: Any,  # the untyped xacro module
    packages: PackageResolver,
    reads: dict[str, str | None],
    raised: list[InputError],
) -> Iterator[None]:
    """Answer $(find) from ``packages`` and record $(env)/$(optenv) reads, then restore.

    Errors these raise are also appended to ``raised``, because xacro re-raises them as its
    own exception type with the message mangled.
    """
    from xacro import substitution_args as subst

    def find(name: str) -> str:
        try:
            return str(packages.find(name))
        except InputError as exc:
            raised.append(exc)
            raise

    def env(name: str) -> str:
        value = os.environ.get(name)
        reads[name] = value
        if value is None:
            error = InputError(
                f"xacro reads environment variable {name}, which is not set",
                hint=f"set {name} or use $(optenv {name} default)",
            )
            raised.append(error)
            raise error
        return value

    def optenv(name: str, default: str = "") -> str:
        value = os.environ.get(name)
        reads[name] = value
        return default if value is None else value

    original_parse = xacro_module.parse

    def parse(inp: IO[bytes] | str | None, filename: str | None = None) -> Any:
        """xacro's parse, refusing entity declarations in every file it reads."""
        if inp is None and filename is not None:
            try:
                with open(os.path.join(xacro_module.root_dir, filename), "rb") as handle:
                    data = handle.read()
            except OSError:
                return original_parse(inp, filename)  # xacro reports it in its own words
            try:
                refuse_entities(data, filename)
            except InputError as exc:
                raised.append(exc)
                raise
            return original_parse(io.BytesIO(data), filename)
        return original_parse(inp, filename)

    replacements: dict[str, Callable] = {
        "_eval_find": find,
        "_eval_env": env,
        "_eval_optenv": optenv,
    }
    saved_functions = {name: getattr(subst, name) for name in replacements}
    saved_eval = {key: subst._eval_dict[key] for key in ("find", "env", "optenv")}
    xacro_module.all_includes.clear()
    xacro_module.parse = parse
    try:
        for name, function in replacements.items():
            setattr(subst, name, function)
        subst._eval_dict.update(find=find, env=env, optenv=optenv)
        yield
    finally:
        xacro_module.parse = original_parse
        for name, function in saved_functions.items():
            setattr(subst, name, function)
        subst._eval_dict.update(saved_eval)
