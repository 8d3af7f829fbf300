"""Turning the declared source into URDF text, and recording every file that took part.

xacro runs in-process through the PyPI ``xacro`` package. Its ``$(find pkg)`` is answered by
mjcfbuild's :class:`PackageResolver`, so no ROS install is needed. Every file xacro opened
(includes, YAML), every optional include that did not exist, and every environment variable it
read are recorded, so the build reruns the expansion exactly when one of them changes.
"""

from __future__ import annotations

import io
import os
import re
import sys
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from mjcfbuild.errors import InputError, ManifestError, UsageError
from mjcfbuild.fsutil import case_match, case_suggestion, normalise, unreadable_file
from mjcfbuild.sources.kind import mesh_kind, xacro_evidence
from mjcfbuild.sources.packages import PackageResolver, did_you_mean, within_edits
from mjcfbuild.xmlguard import refuse_entities

# ``args_key`` of arguments given as NAME:=VALUE on the command line (``convert``).
COMMAND_LINE = "the command line"
# Carried by every element through xacro's expansion: where it was written ("file:line").
_ORIGIN = "mjcfbuild-origin"
_ARG_USE = re.compile(r"\$\(arg\s+([^\s)]+)\s*\)")
# An argument read in an expression: ${xacro.arg('name')} (the xacro command takes it too).
_ARG_READ = re.compile(r"""xacro\.arg\(\s*(['"])([^'"]+)\1\s*\)""")
# $(eval ...) reads arguments by their bare names: every name in one may be an argument. Its
# expression runs to the closing parenthesis (nested ones, and strings in either quote, allowed
# inside; an attribute's own quote ends it).
_EVAL = re.compile(r"""\$\(eval\s((?:'[^'<]*'|\((?:[^()"<]|\([^()"<]*\))*\)|[^()"<'])*)\)""")
_STRING = re.compile(r"'[^']*'|\"[^\"]*\"")
_NAME = re.compile(r"(?<![\w.])[A-Za-z_]\w*")


def _arguments_named(text: str) -> set[str]:
    """The argument names ``text`` uses: $(arg name), xacro.arg('name'), names in $(eval)
    (outside its strings; not attributes like ``.upper``)."""
    names = set(_ARG_USE.findall(text))
    names.update(name for _, name in _ARG_READ.findall(text))
    for expression in _EVAL.findall(text):
        names.update(_NAME.findall(_STRING.sub(" ", expression)))
    return names


@dataclass
class Expansion:
    """The URDF text of a source and what it was made from."""

    urdf: bytes
    files: list[str] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    environment: dict[str, str | None] = field(default_factory=dict)
    # xacro includes of a pattern (parts/*.xacro): pattern -> the files it matched
    globs: dict[str, list[str]] = field(default_factory=dict)
    # For xacro: line of the expanded URDF -> the file and line where its element was written.
    origins: dict[int, tuple[str, int]] = field(default_factory=dict)
    # Arguments given an empty value, which the xacro command ignores: name -> the non-empty
    # default that applies instead.
    ignored_args: dict[str, str] = field(default_factory=dict)
    # What xacro warned of (on its standard error, for the xacro command), each once.
    warnings: list[XacroWarning] = field(default_factory=list)


@dataclass(frozen=True)
class XacroWarning:
    """A warning xacro gave: its text, the file it was reading (the file of the macro it was
    instantiating, inside one) and the line there, where a search of the file finds it."""

    message: str
    file: str
    line: int | None = None
    macro: str | None = None


@dataclass
class _Reading:
    """What the expansion saw in the files xacro parsed."""

    track_lines: bool = True  # mark elements with where they were written
    files: list[str] = field(default_factory=list)  # origins name files by index in this
    declared: set[str] = field(default_factory=set)  # <xacro:arg> names and $(arg) uses
    globs: dict[str, list[str]] = field(default_factory=dict)  # include patterns, matches
    refused: InputError | None = None  # a YAML file xacro.load_yaml must not expand
    warnings: list[XacroWarning] = field(default_factory=list)  # what xacro warned of


def expand_source(
    source: Path,
    xacro: bool,
    args: Mapping[str, str],
    packages: Mapping[str, str],
    environment: Mapping[str, str],
    args_key: str | None = None,
    written: str = "",
) -> Expansion:
    """A source as URDF (or SRDF) text: expanded with xacro, or read as it is. ``packages`` maps
    package names to folders; ``environment`` holds the ROS variables that find the others;
    ``args_key`` says where ``args`` were given (see :func:`expand_xacro`); ``written`` is the
    source's path as robot.yaml writes it (see :func:`read_urdf_file`)."""
    if not xacro:
        return read_urdf_file(source, written)
    from mjcfbuild.sources.packages import PackageResolver

    resolver = PackageResolver({name: Path(f) for name, f in packages.items()}, environment)
    return expand_xacro(source, args, resolver, args_key)


def read_urdf_file(path: Path, written: str = "") -> Expansion:
    """A plain URDF source: its bytes, unchanged (it is parsed as bytes later). A xacro file
    is refused with a hint naming it as robot.yaml should: ``written``, the path as robot.yaml
    writes it (its folder kept), else the file's name."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise InputError(
            f"source file {unreadable_file(path) or 'not found'}",
            file=path,
            hint="fix 'source' in robot.yaml",
        ) from None
    except IsADirectoryError:
        raise InputError("source is a folder, not a file", file=path) from None
    except OSError as exc:
        raise InputError(f"cannot read source: {exc.strerror}", file=path) from None
    what = mesh_kind(path, data)
    if what is not None:
        raise InputError(
            f"this is {what}, not a URDF or xacro file",
            file=path,
            hint="name the robot's .urdf or .xacro file under 'source' in robot.yaml",
        )
    evidence = xacro_evidence(data)
    if evidence is not None:
        # Read as URDF, a xacro file loses every macro and include silently (a one-link model
        # that passes every check): it must be expanded.
        used, line = evidence
        raise InputError(
            f"this file is xacro ({used} at line {line}), not a URDF",
            file=path,
            line=line,
            hint=f"name it with source: {{xacro: {written or path.name}}} in robot.yaml",
        )
    return Expansion(urdf=data, files=[str(normalise(path))])


def expand_xacro(
    path: Path,
    mappings: Mapping[str, str],
    packages: PackageResolver,
    args_key: str | None = None,
) -> Expansion:
    """Expand a xacro file in-process; :class:`InputError` names the failing file.

    ``args_key`` is where ``mappings`` were given: a manifest key (``robot.yaml source.args``:
    an argument the files neither declare nor use is a :class:`ManifestError` at that key's
    line), :data:`COMMAND_LINE` (a :class:`UsageError`), or None (not checked).

    Where each element was written is tracked through the expansion (see
    :mod:`mjcfbuild.sources.origins`). If xacro fails with the tracking but expands the same
    files without it, the tracking was at fault, not the files: the expansion without it is
    used, and its lines stay untracked.
    """
    problem = unreadable_file(path)
    if problem:
        raise InputError(
            f"xacro source {problem}", file=path, hint="fix 'source.xacro' in robot.yaml"
        )
    mappings = as_the_command_takes(mappings)
    try:
        return _expand(path, mappings, packages, args_key, track_lines=True)
    except _XacroFailed:
        return _expand(path, mappings, packages, args_key, track_lines=False)


def as_the_command_takes(mappings: Mapping[str, str]) -> dict[str, str]:
    """The arguments as the ``xacro`` command takes ``name:=value`` words: each value stripped
    of the spaces around it (``load_mappings`` strips them). An empty value stays here, for
    the check of the names; :func:`_expand` passes xacro only the others."""
    return {name: value.strip() for name, value in mappings.items()}


class _XacroFailed(InputError):
    """xacro itself failed on the files (not a $(find), $(env) or XML error of ours)."""


def _expand(
    path: Path,
    mappings: Mapping[str, str],
    packages: PackageResolver,
    args_key: str | None,
    track_lines: bool,
) -> Expansion:
    """One run of xacro over ``path``, with or without the tracking of written lines."""
    import xml.parsers.expat

    import xacro

    reads: dict[str, str | None] = {}
    raised: list[InputError] = []
    reading = _Reading(track_lines=track_lines)
    # The xacro command ignores NAME:= with an empty value (load_mappings: "if src and dst"),
    # so the default applies. xacro adds each declared argument's default to this dict.
    passed = {name: value for name, value in mappings.items() if value}
    extra = _recursion_depth() - _COMMAND_DEPTH
    with (
        _xacro_hooks(xacro, packages, reads, raised, reading),
        _xacro_warnings(xacro, reading),
        _recursion_limit_raised(extra),
    ):
        try:
            document = xacro.process_file(str(path), mappings=passed)
        except xml.parsers.expat.ExpatError as exc:
            reason = xml.parsers.expat.errors.messages.get(exc.code, str(exc))
            current = _current_file(xacro, path)
            raise InputError(
                f"XML error: {reason}",
                file=current,
                line=exc.lineno,
                column=exc.offset + 1 if exc.offset is not None else None,
                hint=_unbound_prefix_hint(current, exc) if "unbound prefix" in reason else None,
            ) from None
        except Exception as exc:  # xacro raises many kinds; all mean "this input is wrong"
            if reading.refused is not None:  # names the YAML file itself, not the xacro file
                raise reading.refused from None
            current = _current_file(xacro, path)
            if raised:  # our own $(find)/$(env) error, which xacro wraps in its own
                first = raised[0]
                line = first.location.line if first.location else None
                package = re.match(r"unknown package '([^']+)'", first.message)
                variable = re.match(r"xacro reads environment variable (\S+),", first.message)
                if line is None and package:
                    line = _line_of(current, re.escape(f"$(find {package.group(1)})"))
                elif line is None and variable:
                    line = _line_of(current, rf"\$\(env\s+{re.escape(variable.group(1))}\s*\)")
                raise InputError(first.message, file=current, line=line, hint=first.hint) from None
            message = _xacro_message(exc)
            # Said only once xacro has failed without mjcfbuild's tracking too.
            hint = "xacro fails the same way on its own; fix the file or its args"
            line = None
            undefined = re.search(r"(?i)undefined substitution argument (\S+)", message)
            read = re.fullmatch(r"'([^']+)'", message.strip())  # xacro.arg's KeyError
            if read and read.group(1) not in passed:
                name = read.group(1)
                line = _line_of(current, rf"""xacro\.arg\(\s*['"]{re.escape(name)}['"]""")
                if line is not None:
                    raise InputError(
                        f"xacro failed: argument '{name}' is read with xacro.arg('{name}') "
                        "but given no value",
                        file=current,
                        line=line,
                        hint="pass it under 'source.args' in robot.yaml, or declare it with "
                        "<xacro:arg> and a default",
                    ) from None
            if undefined:
                name = undefined.group(1).strip("'\"")
                # Given under a misspelt name? (Only then: files not read yet may declare
                # the other unknown ones.)
                if did_you_mean(name, set(mappings) - reading.declared):
                    _check_args(mappings, reading, packages, path, args_key)
                line = _line_of(current, rf"\$\(arg\s+{re.escape(name)}\s*\)")
                message += did_you_mean(name, set(mappings) | (reading.declared - {name}))
                hint = (
                    "pass it under 'source.args' in robot.yaml, or give its <xacro:arg> a default"
                )
                declared = _line_of(
                    current, rf"""<[\w.-]+:arg\s[^>]*name\s*=\s*['"]{re.escape(name)}['"]"""
                )
                if declared is not None and line is not None and declared > line:
                    # ur_description's <robot name="$(arg name)"> before <xacro:arg name="name">:
                    # the default exists, but not yet where the argument is read.
                    hint = (
                        f"its <xacro:arg> (line {declared}) comes after this use, and xacro "
                        "reads the file in order, so its default does not apply here: pass it "
                        "under 'source.args' in robot.yaml (the xacro command needs "
                        f"{name}:=... too)"
                    )
            else:
                current, line, message, hint = _place_failure(exc, message, xacro, current, hint)
            failure = _XacroFailed if track_lines else InputError
            raise failure(f"xacro failed: {message}", file=current, line=line, hint=hint) from None
        included = list(xacro.all_includes)
    _check_args(mappings, reading, packages, path, args_key)
    with _recursion_limit_raised(extra):  # minidom walks the document recursively
        _refuse_values_not_text(document, reading, path)
        marks = _take_origins(document) if track_lines else []
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
        globs={pattern: sorted(found) for pattern, found in sorted(reading.globs.items())},
        origins=_origins(text, marks, reading.files) if track_lines else {},
        warnings=list(dict.fromkeys(reading.warnings)),
        ignored_args={
            name: str(passed[name])
            for name in sorted(mappings)
            if not mappings[name] and passed.get(name)
        },
    )


# How deep the xacro command's process_file is called, as _recursion_depth counts from the
# function calling it (the script's module, main(), _process()), found by the test that holds
# both to the depth where a recursive macro first fails.
_COMMAND_DEPTH = 3


def _recursion_depth() -> int:
    """How deep the caller runs in the count Python's recursion limit bounds: found by
    recursing to the limit (about 0.1 ms), since the count includes calls through C that no
    frame shows."""

    def deeper(levels: int) -> int:
        try:
            return deeper(levels + 1)
        except RecursionError:
            return levels

    return sys.getrecursionlimit() - deeper(0)


@contextmanager
def _recursion_limit_raised(extra: int) -> Iterator[None]:
    """Python's recursion limit raised by ``extra`` levels, then restored: xacro given the
    headroom the xacro command gives it, though mjcfbuild's own calls (the build engine, a
    worker, a test runner) lie below it, so a macro recursing deep fails at the same depth."""
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(limit + max(extra, 0))
    try:
        yield
    finally:
        sys.setrecursionlimit(limit)


def _check_args(
    mappings: Mapping[str, str],
    reading: _Reading,
    packages: PackageResolver,
    source: Path,
    args_key: str | None,
) -> None:
    """Refuse an argument that no file of the expansion declares or uses: a misspelt name
    would otherwise be ignored, and the file's default used instead. A file included under
    a condition that was false declares its arguments too (xacro takes them either way)."""
    declared = reading.declared
    unknown = sorted(set(mappings) - declared)
    if args_key is None or not unknown:
        return
    skipped, unresolved = _declared_in_skipped_includes(reading.files, packages)
    declared = declared | skipped
    unknown = sorted(set(mappings) - declared)
    if unresolved:
        # A file included under a false condition by a name only xacro can evaluate may
        # declare any argument (the xacro command takes them all): only a typo's distance
        # from a declared name (two edits: 'use_gazeb', not 'use_gazebo_gui', which such a
        # file may well declare) is taken for a misspelling.
        unknown = [name for name in unknown if within_edits(name, declared, _TYPO_EDITS)]
    if not unknown:
        return
    name = unknown[0]
    listing = ", ".join(sorted(declared)) or "none"
    message = (
        f"xacro argument '{name}' is not declared in {source.name} or the files it includes"
        f"{did_you_mean(name, declared)} (declared: {listing})"
    )
    if args_key == COMMAND_LINE:
        raise UsageError(
            f"{name}:={mappings[name]}: {message}",
            hint="fix the argument's name, or declare it with <xacro:arg name=...>",
        )
    raise ManifestError(
        message,
        file=f"{args_key}.{name}",
        hint="fix its name, or declare it in the xacro file with <xacro:arg name=...>",
    )


# The most edits a misspelt argument name is taken to be from the name meant.
_TYPO_EDITS = 2

_INCLUDE = re.compile(r"""<xacro:include\b[^>]*?\bfilename\s*=\s*(['"])(.*?)\1""", re.DOTALL)
_FIND = re.compile(r"\$\(find\s+([^\s)]+)\s*\)")
_ARG_DECLARED = re.compile(r"""<xacro:arg\b[^>]*?\bname\s*=\s*(['"])(.*?)\1""", re.DOTALL)


def _declared_in_skipped_includes(
    files: list[str], packages: PackageResolver
) -> tuple[set[str], bool]:
    """The arguments declared or used in the files the ``files`` xacro read include but xacro
    did not read (an include inside an ``xacro:if`` that was false), and in theirs: found in
    the text, where an include's file name resolves without evaluating anything but
    ``$(find)``; and whether an include's file name did not (an expression)."""
    read = {str(normalise(file)) for file in files}
    seen = set(read)
    pending = sorted(read)
    declared: set[str] = set()
    unresolved = False
    while pending:
        current = pending.pop()
        try:
            text = Path(current).read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue
        if current not in read:
            declared.update(_arguments_named(text))
            declared.update(name for _, name in _ARG_DECLARED.findall(text))
        for _, name in _INCLUDE.findall(text):
            try:
                name = _FIND.sub(lambda found: str(packages.find(found.group(1))), name)
            except InputError:
                unresolved = True
                continue
            if "$" in name:
                unresolved = True  # an expression: only xacro can evaluate it
                continue
            resolved = str(normalise(Path(current).parent / name))
            if resolved not in seen and os.path.isfile(resolved):
                seen.add(resolved)
                pending.append(resolved)
    return declared, unresolved


def _line_of(file: str, pattern: str, after: str | None = None) -> int | None:
    """The first line of ``file`` matching ``pattern``, if any; with ``after``, the first from
    the line matching ``after`` on."""
    return _first_line(file, after, lambda line: re.search(pattern, line) is not None)


def _lines_matching(file: str, pattern: str, after: str | None = None) -> list[int]:
    """Every line of ``file`` matching ``pattern`` (from the line matching ``after`` on)."""
    return [number for number, line in _numbered_lines(file, after) if re.search(pattern, line)]


def _first_line(file: str, after: str | None, test: Callable[[str], bool]) -> int | None:
    """The first line of ``file`` that passes ``test``, from the line matching ``after`` on."""
    return next((number for number, line in _numbered_lines(file, after) if test(line)), None)


def _numbered_lines(file: str, after: str | None) -> list[tuple[int, str]]:
    """The lines of ``file`` with their numbers, from the first matching ``after`` on (all
    without it); none where it cannot be read."""
    try:
        with open(file, encoding="utf-8", errors="replace") as handle:
            lines = list(enumerate(handle, 1))
    except OSError:
        return []
    if after is not None:
        start = next((i for i, (_, line) in enumerate(lines) if re.search(after, line)), None)
        lines = lines[start:] if start is not None else []
    return lines


def _refuse_other_encodings(data: bytes, filename: str) -> None:
    """An :class:`InputError` at its line for a file that is not UTF-8: the xacro command
    reads every file as UTF-8 and refuses one in ISO-8859-1 (whatever its XML declaration
    says), which a build from bytes would otherwise have accepted."""
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(
            f"byte 0x{data[exc.start]:02x} is not UTF-8; xacro reads every file as UTF-8",
            file=filename,
            line=data.count(b"\n", 0, exc.start) + 1,
            hint="save the file as UTF-8",
        ) from None


def _mark_origins(document: Any, data: bytes, file: str, reading: _Reading) -> None:
    """Record the arguments a freshly parsed file (a minidom document) declares or uses, and
    when tracking lines, give each of its non-xacro elements an attribute saying where it is
    written, which xacro copies along wherever the element ends up."""
    from lxml import etree

    text = data.decode("utf-8", "replace")
    reading.declared.update(_arguments_named(text))
    nodes = document.getElementsByTagName("*")
    for node in nodes:
        if node.tagName == "xacro:arg" and node.getAttribute("name"):
            reading.declared.add(node.getAttribute("name"))
    if not reading.track_lines:
        return
    try:
        parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True)
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:
        return  # xacro reports it, or reads what lxml refuses (an unbound prefix): no lines
    elements = [element for element in root.iter() if isinstance(element.tag, str)]
    if len(elements) != len(nodes) or any(
        _qualified_name(element) != node.tagName
        for element, node in zip(elements, nodes, strict=True)
    ):
        return  # never seen; without the same elements, no origin is better than a wrong one
    index = len(reading.files)
    reading.files.append(file)
    for element, node in zip(elements, nodes, strict=True):
        # An attribute on a xacro element would reach a macro call as a parameter it does not
        # declare ("Invalid parameter").
        if not is_xacro_element(node.tagName):
            node.setAttribute(_ORIGIN, f"{index}:{element.sourceline}")


def is_xacro_element(tag: str) -> bool:
    """Whether xacro processes an element with the tag name ``tag`` as written: xacro's own
    rule is the prefix ``xacro:``, whatever namespace URI it is bound to (descriptions use
    http://www.ros.org/wiki/xacro, http://ros.org/wiki/xacro and http://wiki.ros.org/xacro)."""
    return tag.startswith("xacro:")


def _qualified_name(element: Any) -> str:
    """An lxml element's tag as written (``prefix:local``), as minidom names it."""
    from lxml import etree

    local = etree.QName(element).localname
    return f"{element.prefix}:{local}" if element.prefix else local


def _refuse_values_not_text(document: Any, reading: _Reading, source: Path) -> None:
    """An :class:`InputError` at the element for an attribute whose value xacro left a number
    (``<xacro:attribute value="${2*pi}"/>``): the xacro command fails writing it, with a
    traceback; here it was an internal error."""
    for node in document.getElementsByTagName("*"):
        for name, value in node.attributes.items():
            if isinstance(value, str):
                continue
            file, line = str(source), None
            origin = node.getAttribute(_ORIGIN)
            if origin:
                index, _, number = origin.partition(":")
                file, line = reading.files[int(index)], int(number)
            raise InputError(
                f"xacro failed: attribute '{name}' of <{node.tagName}> is the "
                f"{type(value).__name__} {value!r}, not text (the xacro command fails writing "
                "it too)",
                file=file,
                line=line,
                hint='make the value text where it is computed: value="${str(2*pi)}"',
            )


def _take_origins(document: Any) -> list[str]:
    """Remove the origin attributes from the expanded document: each element's, in order."""
    marks = []
    for node in document.getElementsByTagName("*"):
        marks.append(node.getAttribute(_ORIGIN))
        if node.hasAttribute(_ORIGIN):
            node.removeAttribute(_ORIGIN)
    return marks


def _origins(text: bytes, marks: list[str], files: list[str]) -> dict[int, tuple[str, int]]:
    """Line of the expanded text -> (file, line) where the element starting there was
    written."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True)
    root = etree.fromstring(text, parser)
    lines = [element.sourceline for element in root.iter() if isinstance(element.tag, str)]
    if len(lines) != len(marks):
        return {}
    origins: dict[int, tuple[str, int]] = {}
    for line, mark in zip(lines, marks, strict=True):
        if mark:
            index, _, written = mark.partition(":")
            origins.setdefault(line, (str(normalise(files[int(index)])), int(written)))
    return origins


def _place_failure(
    exc: Exception, message: str, xacro_module: Any, current: str, hint: str
) -> tuple[str, int | None, str, str]:
    """The file and line a xacro failure is about, with its message and hint, from what xacro
    leaves behind: the macros being instantiated and the files being read. xacro's DOM has no
    line numbers, so the line is found by searching the file for what the message names."""
    cause = getattr(exc, "exc", None)
    if isinstance(cause, OSError) and cause.filename:
        # A missing include: xacro names it twice, with the file that includes it nowhere.
        missing = str(cause.filename)
        stack = [str(f) for f in getattr(xacro_module, "filestack", None) or [] if f]
        including = next((f for f in reversed(stack) if f != missing), current)
        shown = os.path.relpath(missing, os.path.dirname(including))
        if shown.startswith(".."):
            shown = missing
        base = re.escape(os.path.basename(missing))
        line = _line_of(including, rf"<xacro:include\b.*{base}") or _line_of(including, base)
        reason = "not found" if isinstance(cause, FileNotFoundError) else cause.strerror
        match = case_match(missing) if isinstance(cause, FileNotFoundError) else None
        if match is not None:
            return (
                including,
                line,
                f"included file {shown} not found; did you mean "
                f"'{case_suggestion(missing, match)}'?",
                "write the name as the file is spelt: letter case matters here",
            )
        return (
            including,
            line,
            f"included file {shown} {reason}",
            "fix the include's filename (relative to this file, or $(find package)/...) "
            'or add optional="true"',
        )
    stack = [str(f) for f in getattr(xacro_module, "filestack", None) or [] if f]
    cycle = _include_cycle(stack)
    if cycle and "maximum recursion depth" in message:
        including, included = cycle[-2], cycle[-1]
        base = re.escape(os.path.basename(included))
        names = " includes ".join(os.path.basename(file) for file in cycle)
        return (
            including,
            _line_of(including, rf"<xacro:include\b.*{base}") or _line_of(including, base),
            f"include cycle: {names}",
            "remove the include that closes the cycle",
        )
    macros = list(getattr(xacro_module, "macrostack", None) or [])
    # Where to look, innermost first: the body of the macro being instantiated, then where it
    # was called (the body of the macro around it, or the file being read).
    places: list[tuple[str, str | None]] = []
    if macros:
        name = macros[-1].body.getAttribute("name")
        message = f"in macro '{name}': {message}"
        defined_in = str(macros[-1].history[-1][-1] or current)
        places.append((defined_in, rf"<xacro:macro\s[^>]*name=[\"']{re.escape(name)}[\"']"))
        if len(macros) > 1:
            outer = macros[-2]
            places.append(
                (
                    str(outer.history[-1][-1] or current),
                    rf"<xacro:macro\s[^>]*name=[\"']{re.escape(outer.body.getAttribute('name'))}",
                )
            )
        else:
            places.append((current, None))
    else:
        places.append((current, None))
    failure = _extension_failure(exc)
    if failure is not None:  # a $(...): found by its own text, in the macro or the file
        hint = _substitution_hint(failure, hint)
        for file, start in places:
            line = _substitution_line(file, failure, start)
            if line is not None:
                return file, line, message, hint
        return places[0][0], None, message, hint
    undefined = re.search(r"name '([^']+)' is not defined", message)
    unknown = re.search(r"unknown macro name: (xacro:\S+)", message)
    conditional = re.search(r'Xacro conditional "(.*?)" evaluated to', message)
    if undefined:
        pattern = rf"\$\{{[^}}]*\b{re.escape(undefined.group(1))}\b"
        hint = "define it with <xacro:property>, or as a macro parameter, before it is used"
        message = message.rstrip() + did_you_mean(
            undefined.group(1), _names_in_scope(macros, stack, current)
        )
    elif unknown:
        pattern = rf"<{re.escape(unknown.group(1))}\b"
        hint = "define the macro, or include the file that does, before this call"
        called = unknown.group(1).removeprefix("xacro:")
        files = [*(getattr(xacro_module, "all_includes", None) or []), *stack, current]
        message = message.rstrip() + did_you_mean(called, _macros_defined(files))
    elif conditional:
        # Found where it is written: in the macro's body (the call site only after that)
        value = re.escape(conditional.group(1))
        pattern = rf"<xacro:(?:if|unless)\s[^>]*value=[\"']{value}[\"']"
        hint = "give value= a boolean: true, false, 1, 0, or a ${...} expression of one"
    elif macros:  # a bad call (an undeclared or missing parameter), or its body failed
        macro = macros[-1]
        name = macro.body.getAttribute("name")
        # An expression that failed is found where it is written: in the macro's body, or in
        # the one call that passes it (xacro evaluates a call's parameters as it calls).
        expression = re.search(r"when evaluating expression '(.*)'", str(exc))
        if expression is not None:
            for file, start in places:
                line = _line_of(file, _expression_token(expression.group(1)), after=start)
                if line is not None:
                    return file, line, message, hint
        # A call of a macro from an include's namespace is written <xacro:ns.name ...>.
        pattern = rf"<xacro:(?:[\w.]+\.)?{re.escape(name)}\b"
        places = places[1:]
        declared = [param.lstrip("*") for param in macro.params]
        invalid = re.search(r'Invalid parameter "([^"]+)"', message)
        lacking = re.search(r"Undefined parameters \[([^\]]*)\]", message)
        if invalid:
            given = invalid.group(1)
            message = (
                f"macro '{name}' is called with parameter '{given}', which it does not declare"
                f"{did_you_mean(given, declared)} (declared: {', '.join(declared) or 'none'})"
            )
            hint = "fix the parameter's name in the call"
        elif lacking:
            message = f"macro '{name}' is called without parameter {lacking.group(1)}"
            hint = "give it in the call, or a default in the macro's params as name:=value"
    else:
        # Outside macros xacro names only the expression (in its message's later lines):
        # found where it is written, as ${...} or $(...) text.
        expression = re.search(r"when evaluating expression '(.*)'", str(exc))
        missing_default = "xacro:arg: missing attribute 'default'" in message
        block = re.search(r'Undefined block "([^"]+)"', message)
        # $(...) inside $(...): xacro reads the inner one's text up to its first ')'.
        nested = re.search(r"invalid expression: (\$\(.+)", message)
        circular = re.search(r"circular variable definition: (\S+) ->", message)
        if circular is not None:  # before the expressions, which name only a property
            pattern = rf"<xacro:property\s[^>]*name=[\"']{re.escape(circular.group(1))}[\"']"
            hint = "define the property from values that do not lead back to it"
        elif expression is not None:
            pattern = _expression_token(expression.group(1))
        elif missing_default:
            pattern = r"<xacro:arg\b(?![^>]*\bdefault=)"
        elif nested is not None:
            pattern = re.escape(nested.group(1).strip())
            hint = "xacro does not read $(...) inside $(...): set a property or ${...} first"
        elif block is not None:
            pattern = rf"<xacro:insert_block\s[^>]*name=[\"']{re.escape(block.group(1))}[\"']"
            hint = "insert a block the macro declares as a *param, or a property's lazy block"
        else:
            return current, None, message, hint
    for file, start in places:
        line = _line_of(file, pattern, after=start)
        if line is not None:
            return file, line, message, hint
    return places[0][0] if places else current, None, message, hint


def _expression_token(expression: str) -> str:
    """A pattern of ``expression`` as written: the whole of a ``${...}`` (xacro names what is
    between the braces), so a short one ('e') is not found inside other text."""
    return rf"\$\{{\s*{re.escape(expression.strip())}\s*\}}"


def _macros_defined(files: list[str]) -> set[str]:
    """The names of the macros ``files`` define (by their text: xacro's own table is not left
    behind)."""
    names: set[str] = set()
    for file in dict.fromkeys(files):
        try:
            text = Path(file).read_text(errors="replace")
        except OSError:
            continue
        names.update(re.findall(r"<xacro:macro\s[^>]*\bname=[\"']([^\"']+)[\"']", text))
    return names


def _names_in_scope(macros: list[Any], stack: list[str], current: str) -> set[str]:
    """Names an expression may have meant: the parameters of the macros being instantiated
    and the properties the files being read define (by their text: xacro's own table is not
    left behind)."""
    names = {
        param.lstrip("*").split(":=")[0].split("=")[0] for macro in macros for param in macro.params
    }
    for file in {*stack, current}:
        try:
            text = Path(file).read_text(errors="replace")
        except OSError:
            continue
        names.update(re.findall(r"<xacro:property\s[^>]*\bname=[\"']([^\"']+)[\"']", text))
    return {name for name in names if name}


def _include_cycle(stack: list[str]) -> list[str]:
    """The files of the first include cycle in xacro's file stack (the first file again at
    its end), or [] where no file includes itself."""
    seen: dict[str, int] = {}
    for index, file in enumerate(stack):
        key = os.path.realpath(file)
        if key in seen:
            return stack[seen[key] : index + 1]
        seen[key] = index
    return []


def _xacro_message(exc: Exception) -> str:
    """xacro's error as one line of text."""
    failure = _extension_failure(exc)
    if failure is not None:
        return _substitution_message(failure)
    text = str(exc).strip() or type(exc).__name__
    if type(exc).__name__ == "ArgException":
        return f"undefined substitution argument {text}"
    return text.splitlines()[0] if text else type(exc).__name__


def _extension_failure(exc: BaseException | None) -> BaseException | None:
    """The error a $(...) substitution raised, where xacro wrapped it as "<class '...'>: text"
    (which prints its text twice, and no line), else None."""
    while exc is not None:
        inner = getattr(exc, "exc", None)
        if not isinstance(inner, BaseException):
            return None
        if exc.args and exc.args[0] == f"{type(inner)}: {inner}":
            return inner
        exc = inner
    return None


def _substitution_message(failure: BaseException) -> str:
    """What a failed $(...) substitution means, in one line."""
    text = " ".join(str(failure).split())
    unknown = re.search(r"Unknown substitution command \[([^\]]*)\]", text)
    if isinstance(failure, SyntaxError):
        return f"$(eval ...) is not a Python expression: {failure.msg}"
    if "Cannot substitute $(dirname)" in text:
        return (
            "$(dirname) cannot be substituted: xacro 2.1.1 does not know the file's name there "
            "(the xacro command fails on it too)"
        )
    if unknown is not None:
        return (
            f"unknown substitution $({unknown.group(1)}): xacro knows find, env, optenv, arg, eval"
        )
    if type(failure).__name__ == "SubstitutionException":
        return text
    return f"$(eval ...) failed: {text or type(failure).__name__}"


def _substitution_hint(failure: BaseException, hint: str) -> str:
    """What to do about a failed $(...) substitution (``hint`` where nothing better is known)."""
    if "Cannot substitute $(dirname)" in str(failure):
        return "write ${xacro.abs_filename('.')} for this file's folder, or $(find package)"
    if isinstance(failure, SyntaxError):
        return "fix the expression: $(eval) takes one Python expression of the arguments"
    if isinstance(failure, NameError):
        return "$(eval) reads arguments by name: pass it under 'source.args' in robot.yaml"
    return hint


def _substitution_line(file: str, failure: BaseException, after: str | None) -> int | None:
    """The line of ``file`` (from the line matching ``after`` on) with the $(...) that failed:
    found by its text, or for an $(eval) that does not parse, as the first that does not."""
    text = str(failure)
    unknown = re.search(r"Unknown substitution command \[([^\]]*)\]", text)
    named = re.search(r"name '([^']+)' is not defined", text)
    bracketed = re.search(r"\[([^\]]*)\]\s*$", text)
    if "Cannot substitute $(dirname)" in text:
        return _line_of(file, r"\$\(dirname\)", after=after)
    if unknown is not None:
        return _line_of(file, rf"\$\(\s*{re.escape(unknown.group(1))}\s*\)", after=after)
    if isinstance(failure, SyntaxError):
        return _first_line(
            file,
            after,
            lambda line: any(not _compiles(found.group(1)) for found in _EVAL.finditer(line)),
        )
    if named is not None:
        return _line_of(file, rf"\$\(eval\s[^)]*\b{re.escape(named.group(1))}\b", after=after)
    if type(failure).__name__ == "SubstitutionException":
        token = rf"\$\({re.escape(bracketed.group(1))}\)" if bracketed else None
        return _line_of(file, token, after=after) if token else None
    # Any other error of an $(eval): placed only where the file has one $(eval).
    lines = _lines_matching(file, r"\$\(eval\s", after)
    return lines[0] if len(lines) == 1 else None


def _compiles(expression: str) -> bool:
    """Whether ``expression`` is one Python expression."""
    try:
        compile(expression.strip(), "<eval>", "eval")
    except (SyntaxError, ValueError):
        return False
    return True


def _unbound_prefix_hint(file: str, exc: Any) -> str:
    """What to declare for the prefix an expat "unbound prefix" error is about (``exc``: its
    line and offset point at the element that uses it)."""
    lines = _numbered_lines(file, None)
    text = lines[exc.lineno - 1][1] if 0 < exc.lineno <= len(lines) else ""
    used = re.search(r"([A-Za-z_][\w.-]*):[A-Za-z_]", text[exc.offset or 0 :])
    prefix = used.group(1) if used else "xacro"
    if prefix == "xacro":
        return 'declare xacro\'s namespace on the root element: xmlns:xacro="http://www.ros.org/wiki/xacro"'
    return f'declare the prefix on the root element: xmlns:{prefix}="<its namespace URI>"'


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
    reading: _Reading,
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
                _refuse_other_encodings(data, filename)
            except InputError as exc:
                raised.append(exc)
                raise
            # As text, as the xacro command opens it: the file's bytes are UTF-8 whatever
            # its XML declaration says (given bytes, the parser obeyed encoding="ISO-8859-1").
            document = original_parse(io.StringIO(data.decode("utf-8")), filename)
            _mark_origins(document, data, os.path.join(xacro_module.root_dir, filename), reading)
            return document
        return original_parse(inp, filename)

    original_includes = xacro_module.get_include_files

    def include_files(spec: str, symbols: Any) -> Iterator[str]:
        """xacro's files of an include; a pattern's matches are recorded (a file added to
        the folder later changes the expansion)."""
        found = list(original_includes(spec, symbols))
        pattern = xacro_module.abs_filename_spec(xacro_module.eval_text(spec, symbols))
        if re.search(r"[*[?]", pattern):  # kept as xacro globbed it, to glob it alike again
            reading.globs[pattern] = list(found)
        yield from found

    def guarded(load_yaml: Callable) -> Callable:
        def load_bounded(filename: str) -> Any:
            """xacro's load_yaml, first refusing aliases that expand without bound."""
            _refuse_yaml_bombs(xacro_module.abs_filename_spec(filename), reading)
            return load_yaml(filename)

        return load_bounded

    replacements: dict[str, Callable] = {
        "_eval_find": find,
        "_eval_env": env,
        "_eval_optenv": optenv,
    }
    saved_functions = {name: getattr(subst, name) for name in replacements}
    saved_eval = {key: subst._eval_dict[key] for key in ("find", "env", "optenv")}
    # Expressions call load_yaml through the symbol table: as xacro.load_yaml, and (deprecated)
    # as a plain load_yaml whose wrapper holds the original.
    symbols = xacro_module._global_symbols
    saved_symbols = {"load_yaml": symbols.get("load_yaml")}
    saved_namespaced = symbols["xacro"]["load_yaml"]
    xacro_module.all_includes.clear()
    xacro_module.parse = parse
    xacro_module.get_include_files = include_files
    try:
        symbols["xacro"]["load_yaml"] = guarded(saved_namespaced)
        if saved_symbols["load_yaml"] is not None:
            symbols["load_yaml"] = guarded(saved_symbols["load_yaml"])
        for name, function in replacements.items():
            setattr(subst, name, function)
        subst._eval_dict.update(find=find, env=env, optenv=optenv)
        yield
    finally:
        xacro_module.parse = original_parse
        xacro_module.get_include_files = original_includes
        symbols["xacro"]["load_yaml"] = saved_namespaced
        if saved_symbols["load_yaml"] is not None:
            symbols["load_yaml"] = saved_symbols["load_yaml"]
        for name, function in saved_functions.items():
            setattr(subst, name, function)
        subst._eval_dict.update(saved_eval)


@contextmanager
def _xacro_warnings(xacro_module: Any, reading: _Reading) -> Iterator[None]:
    """Keep xacro's warnings in ``reading`` instead of letting them print to standard error,
    where a build's worker left them in the expand step's log: its own (a redefined global
    symbol, a deprecated name, ...) and those an expression asks for with xacro.warning()."""

    def warning(*args: Any, **_: Any) -> str:
        message = " ".join(" ".join(str(arg) for arg in args).split())
        reading.warnings.append(_placed_warning(xacro_module, message))
        return ""  # what xacro.warning() gives an expression

    def print_location(*_: Any, **__: Any) -> str:
        return ""  # xacro's trace after a warning: the warning records where it is

    namespace = xacro_module._global_symbols["xacro"]
    saved = (xacro_module.warning, xacro_module.print_location, namespace["warning"])
    xacro_module.warning, xacro_module.print_location = warning, print_location
    namespace["warning"] = warning
    try:
        yield
    finally:
        xacro_module.warning, xacro_module.print_location, namespace["warning"] = saved


def _placed_warning(xacro_module: Any, message: str) -> XacroWarning:
    """``message`` at the file xacro is reading (the body of the macro it is instantiating,
    inside one) and, where the file's text shows what it is about, that line."""
    macros = list(getattr(xacro_module, "macrostack", None) or [])
    current = _current_file(xacro_module, Path("?"))
    start = None
    macro = None
    if macros:
        macro = macros[-1].body.getAttribute("name")
        current = str(macros[-1].history[-1][-1] or current)
        start = rf"<xacro:macro\s[^>]*name=[\"']{re.escape(macro)}[\"']"
    redefined = re.fullmatch(r"redefining global symbol: (\S+)", message)
    deprecated = re.match(r"Using (\w+)\(\) directly is deprecated", message)
    attributes = re.match(r"(\S+): unknown attribute\(s\): ([^,\s]+)", message)
    pattern = None
    if redefined:
        pattern = rf"<xacro:property\s[^>]*name=[\"']{re.escape(redefined.group(1))}[\"']"
    elif deprecated:
        pattern = rf"\$\{{[^}}]*(?<![\w.]){re.escape(deprecated.group(1))}\s*\("
    elif attributes:
        pattern = rf"<{re.escape(attributes.group(1))}\s[^>]*\b{re.escape(attributes.group(2))}="
    line = _line_of(current, pattern, after=start) if pattern else None
    return XacroWarning(message, current, line, macro)


def _refuse_yaml_bombs(path: str, reading: _Reading) -> None:
    """Raise :class:`InputError` (kept in ``reading``) where the YAML file at ``path`` nests too
    deep or its aliases expand without bound; anything else is left to xacro, so ordinary files
    load exactly as xacro loads them."""
    import yaml

    from mjcfbuild.yamlguard import YamlLimitError, compose_bounded

    try:
        with open(path, encoding="utf-8") as handle:
            text = handle.read()
        compose_bounded(text)
    except YamlLimitError as exc:
        reading.refused = InputError(
            exc.message,
            file=str(normalise(path)),
            line=exc.line,
            column=exc.column,
            hint=exc.hint,
        )
        raise reading.refused from None
    except yaml.MarkedYAMLError as exc:  # xacro fails alike, naming neither file nor line
        mark = exc.problem_mark
        reading.refused = InputError(
            f"YAML syntax error: {exc.problem}" + (f" ({exc.context})" if exc.context else ""),
            file=str(normalise(path)),
            line=mark.line + 1 if mark is not None else None,
            column=mark.column + 1 if mark is not None else None,
            hint="xacro's load_yaml reads it; fix the YAML",
        )
        raise reading.refused from None
    except (OSError, ValueError, yaml.YAMLError):  # ValueError: UnicodeDecodeError too
        return  # xacro reports these in its own words
