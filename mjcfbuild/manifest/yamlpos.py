"""YAML loading that remembers where every value came from.

PyYAML's ``safe_load`` forgets positions; validation errors need them to say
``robot.yaml:12:5``. This loader composes the node tree, builds plain Python values from it and
records the (line, column) of every mapping key and value, keyed by its path of keys and list
indices. It also refuses duplicate keys, which ``safe_load`` silently collapses, and (through
:mod:`mjcfbuild.yamlguard`) aliases that would expand without bound and nesting too deep.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import yaml

from mjcfbuild.yamlguard import YamlLimitError, compose_bounded

Path_ = tuple[str | int, ...]


@dataclass
class Positions:
    """Line and column (both 1-based) of every value, and of every key, by path."""

    values: dict[Path_, tuple[int, int]] = field(default_factory=dict)
    keys: dict[Path_, tuple[int, int]] = field(default_factory=dict)
    plain: dict[Path_, str] = field(default_factory=dict)  # unquoted scalars, as written

    def of(self, path: Path_) -> tuple[int, int] | None:
        """The best position for ``path``: the key if known, else the value, else a parent."""
        path = tuple(path)
        while True:
            if path in self.keys:
                return self.keys[path]
            if path in self.values:
                return self.values[path]
            if not path:
                return None
            path = path[:-1]


class YamlSyntaxError(Exception):
    """YAML that cannot be parsed, with the position of the problem."""

    def __init__(
        self, message: str, line: int | None, column: int | None, hint: str | None = None
    ) -> None:
        super().__init__(message)
        self.message = message
        self.line = line
        self.column = column
        self.hint = hint


def _mark(node: yaml.Node) -> tuple[int, int]:
    return node.start_mark.line + 1, node.start_mark.column + 1


# Contexts whose mark is where the mistake was made, when PyYAML only notices it lines later:
# a key without its ':', an unclosed quote or an unclosed [ or {.
_OPENED_CONTEXTS = ("while scanning a simple key", "while scanning a quoted scalar", "flow")


def _offending_mark(exc: yaml.MarkedYAMLError) -> yaml.Mark | None:
    """The position to report: where the problem was noticed, or the earlier line where it
    was made."""
    problem, context = exc.problem_mark, exc.context_mark
    if problem is None:
        return context
    opened = any(text in (exc.context or "") for text in _OPENED_CONTEXTS)
    if context is not None and opened and context.line < problem.line:
        return context
    return problem


def _syntax_hint(exc: yaml.MarkedYAMLError) -> str | None:
    """What to do about the usual YAML mistakes, from PyYAML's problem and context."""
    problem, context = exc.problem or "", exc.context or ""
    if "'\\t'" in problem or "\\t" in problem:
        return "indent with spaces: YAML does not allow tabs"
    if "could not find expected ':'" in problem:
        return "a key needs a ':' after it, or this line is indented too far"
    if "mapping values are not allowed" in problem:
        return "indented deeper than the keys beside it? A value with ': ' needs quotes"
    if "expected <block end>" in problem:
        return "this line's indentation matches no key above it: line it up with its siblings"
    if "quoted scalar" in context:
        return "close the quote opened here"
    if "flow mapping" in context:
        return "close the '{' opened here with '}', with ',' between its items"
    if "flow sequence" in context:
        return "close the '[' opened here with ']', with ',' between its items"
    if "block sequence" in context or "block collection" in problem:
        return "a list item ('- ') must be indented like the others of its list"
    if "undefined alias" in problem:
        return (
            "'*name' repeats what '&name' marks above it: mark that value, or quote this one "
            "if it is text that starts with '*'"
        )
    return None


def _unclosed_bracket(text: str, mark: yaml.Mark | None) -> tuple[str, int, int] | None:
    """The last '[' or '{' opened before ``mark`` and not closed by then, with its line and
    column (1-based), outside quotes and comments; None where every one closes."""
    if mark is None:
        return None
    opened: list[tuple[str, int, int]] = []
    for number, line in enumerate(text.splitlines()[: mark.line + 1]):
        end = mark.column if number == mark.line else len(line)
        quote, previous = "", " "
        for index, char in enumerate(line[:end]):
            if quote:
                quote = "" if char == quote else quote
            elif char == "#" and previous in " \t":
                break
            elif char in "\"'" and previous in " \t:[{,-":
                quote = char
            elif char in "[{":
                opened.append((char, number + 1, index + 1))
            elif char in "]}" and opened:
                opened.pop()
            previous = char
    return opened[-1] if opened else None


def _unclosed_quote(text: str, before: int | None) -> tuple[int, int] | None:
    """The line and column of the first quote that opens a value and is not closed on its
    line, above line ``before`` (1-based; None: anywhere); None where every quote closes."""
    for number, line in enumerate(text.splitlines(), start=1):
        if before is not None and number >= before:
            return None
        quote, opened_at, previous = "", 0, " "
        index = 0
        while index < len(line):
            char = line[index]
            if quote == '"':
                if char == "\\":
                    index += 1  # an escaped character
                elif char == '"':
                    quote = ""
            elif quote == "'":
                if char == "'" and line[index + 1 : index + 2] == "'":
                    index += 1  # '' is a quote inside the value
                elif char == "'":
                    quote = ""
            elif char == "#" and previous in " \t":
                break  # a comment
            elif char in "\"'" and previous in " \t:[{,-":
                quote, opened_at = char, index
            previous = char
            index += 1
        if quote:
            return number, opened_at + 1
    return None


def load_with_positions(text: str) -> tuple[object, Positions]:
    """Parse one YAML document into plain values and the positions of every value."""
    try:
        node = compose_bounded(text)
    except YamlLimitError as exc:
        raise YamlSyntaxError(exc.message, exc.line, exc.column, exc.hint) from None
    except yaml.MarkedYAMLError as exc:
        mark = _offending_mark(exc)
        line = mark.line + 1 if mark else None
        column = mark.column + 1 if mark else None
        bracket = _unclosed_bracket(text, mark) if "flow node" in (exc.context or "") else None
        if bracket is not None:
            # A block item or key inside a '[' or '{' left open: the bracket is the mistake.
            char, bracket_line, bracket_column = bracket
            closing = "]" if char == "[" else "}"
            raise YamlSyntaxError(
                f"YAML syntax error: this '{char}' is not closed before line {line}",
                bracket_line,
                bracket_column,
                f"close it with '{closing}' on its line, or drop it and write the items as "
                "'- ' lines (a list) or 'key: value' lines (a mapping) below",
            ) from None
        opened = _unclosed_quote(text, line)
        if opened is not None:
            # The scanner read on to the next quote and failed lines later: the quote is
            # the mistake.
            raise YamlSyntaxError(
                "YAML syntax error: this quote is not closed on its line",
                *opened,
                "close the quote opened here: a value quoted here ends on its line",
            ) from None
        problem = exc.problem or exc.context or "invalid YAML"
        raise YamlSyntaxError(
            f"YAML syntax error: {problem}", line, column, _syntax_hint(exc)
        ) from None
    except yaml.YAMLError as exc:
        raise YamlSyntaxError(f"YAML syntax error: {exc}", None, None) from None
    except ValueError as exc:  # PyYAML's scanner on an escape beyond Unicode, like "\U00110000"
        raise YamlSyntaxError(f"YAML syntax error: invalid character ({exc})", None, None) from None
    positions = Positions()
    if node is None:
        return None, positions
    constructor = yaml.SafeLoader("")
    value = _build(node, (), positions, constructor)
    return value, positions


def _build(node: yaml.Node, path: Path_, positions: Positions, constructor: yaml.SafeLoader) -> Any:
    positions.values[path] = _mark(node)
    if isinstance(node, yaml.MappingNode):
        constructor.flatten_mapping(node)
        result: dict = {}
        for key_node, value_node in node.value:
            key = constructor.construct_object(key_node, deep=True)
            if isinstance(key, (list, dict)):
                line, column = _mark(key_node)
                raise YamlSyntaxError("a mapping key must be a plain value", line, column)
            if not isinstance(key, str):
                # As written: YAML 1.1 reads the key `on:` (or `yes:`, `1.10:`) as a value.
                plain = isinstance(key_node, yaml.ScalarNode) and key_node.style is None
                key = key_node.value if plain else str(key)
            if key in result:
                line, column = _mark(key_node)
                first, _ = positions.keys.get((*path, key), (None, None))
                where = f" (first at line {first})" if first else ""
                raise YamlSyntaxError(
                    f"duplicate key '{key}'{where}", line, column, "remove one of them"
                )
            child = (*path, key)
            positions.keys[child] = _mark(key_node)
            result[key] = _build(value_node, child, positions, constructor)
        return result
    if isinstance(node, yaml.SequenceNode):
        return [
            _build(item, (*path, index), positions, constructor)
            for index, item in enumerate(node.value)
        ]
    if isinstance(node, yaml.ScalarNode) and node.style is None:
        positions.plain[path] = node.value
    try:
        return constructor.construct_object(node, deep=True)
    except yaml.constructor.ConstructorError as exc:
        line, column = _mark(node)
        raise YamlSyntaxError(f"YAML error: {exc.problem}", line, column) from None
