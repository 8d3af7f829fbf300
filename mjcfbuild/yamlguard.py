"""Refusing YAML whose aliases or nesting would blow up before any value is built.

An alias repeats the value its anchor names. A few lines of anchors that each repeat the one
before nine times (the "billion laughs") expand to billions of values: gigabytes and minutes
for a 700-byte file. PyYAML composes aliases as shared nodes, so the composed graph stays
small; this module measures what it would expand to and refuses it before anything walks it.
Ordinary reuse (a rule block used a few times, merge keys) is far below the limits.
"""

from __future__ import annotations

from typing import Any

import yaml

# Values that aliases may add to a document once expanded (a block of 50 values reused 2,000
# times); the document's own values are not counted, so large plain files are not refused.
MAX_ALIAS_VALUES = 100_000
# Mappings and lists nested in each other, aliases expanded. PyYAML composes nesting by
# recursion, and nothing a build reads nests more than a handful deep.
MAX_DEPTH = 100


class YamlLimitError(Exception):
    """YAML over one of the limits, with the (1-based) position of the alias or value."""

    hint = "write the repeated values out, or reuse fewer and smaller blocks"

    def __init__(self, message: str, line: int, column: int) -> None:
        super().__init__(message)
        self.message = message
        self.line = line
        self.column = column


class _BoundedLoader(yaml.SafeLoader):
    """SafeLoader that refuses deep nesting while composing and records every alias use."""

    def __init__(self, stream: str) -> None:
        super().__init__(stream)
        self.alias_uses: list[tuple[yaml.Node, yaml.Mark]] = []
        self.nesting = 0

    def compose_node(self, parent: Any, index: Any) -> Any:  # PyYAML's untyped signature
        event = self.peek_event()
        mark: Any = event.start_mark  # always set by PyYAML's parser
        if isinstance(event, yaml.AliasEvent):
            node = super().compose_node(parent, index)  # the anchor's node, never None
            assert node is not None
            self.alias_uses.append((node, mark))
            return node
        if isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
            if self.nesting >= MAX_DEPTH:
                raise _too_deep(mark)
            self.nesting += 1
            try:
                return super().compose_node(parent, index)
            finally:
                self.nesting -= 1
        return super().compose_node(parent, index)


def compose_bounded(text: str) -> yaml.Node | None:
    """The composed node of the single YAML document in ``text`` (None when empty).

    Raises :class:`YamlLimitError` where the document nests deeper than :data:`MAX_DEPTH`, an
    alias is used inside the value it names, or aliases add more than
    :data:`MAX_ALIAS_VALUES` values; PyYAML's own errors for YAML it cannot parse.
    """
    loader = _BoundedLoader(text)
    try:
        node = loader.get_single_node()
    finally:
        loader.dispose()
    if node is not None and loader.alias_uses:
        _check_expansion(node, loader.alias_uses)
    return node


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.MappingNode):
        return [item for pair in node.value for item in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def _check_expansion(root: yaml.Node, alias_uses: list[tuple[yaml.Node, yaml.Mark]]) -> None:
    """Measure, without recursion, each node's size and depth with aliases expanded."""
    size: dict[int, int] = {}
    depth: dict[int, int] = {}
    open_nodes: set[int] = set()
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    while stack:
        node, finished = stack.pop()
        key = id(node)
        if finished:
            children = _children(node)
            size[key] = 1 + sum(size[id(child)] for child in children)
            nested = isinstance(node, (yaml.MappingNode, yaml.SequenceNode))
            depth[key] = nested + max((depth[id(child)] for child in children), default=0)
            open_nodes.discard(key)
            continue
        if key in size:
            continue
        if key in open_nodes:  # an alias inside the value its anchor names
            mark = _alias_within(node, alias_uses)
            raise YamlLimitError(
                "this alias is used inside the value it names, which never ends",
                mark.line + 1,
                mark.column + 1,
            )
        open_nodes.add(key)
        stack.append((node, True))
        stack.extend((child, False) for child in reversed(_children(node)))
    distinct = len(size)
    if size[id(root)] - distinct > MAX_ALIAS_VALUES:
        node, mark = max(alias_uses, key=lambda use: size[id(use[0])])
        raise YamlLimitError(
            f"aliases add {size[id(root)] - distinct:,} values to this file (at most "
            f"{MAX_ALIAS_VALUES:,}); the alias here repeats {size[id(node)]:,}",
            mark.line + 1,
            mark.column + 1,
        )
    if depth[id(root)] > MAX_DEPTH:
        node, mark = max(alias_uses, key=lambda use: depth[id(use[0])])
        raise _too_deep(mark)


def _alias_within(node: yaml.Node, alias_uses: list[tuple[yaml.Node, yaml.Mark]]) -> yaml.Mark:
    """Where an alias to ``node`` is used inside ``node`` itself."""
    start, end = node.start_mark.index, node.end_mark.index
    marks = [mark for used, mark in alias_uses if used is node]
    return next((mark for mark in marks if start <= mark.index <= end), marks[0])


def _too_deep(mark: yaml.Mark) -> YamlLimitError:
    return YamlLimitError(
        f"values nested more than {MAX_DEPTH} deep (mappings and lists, aliases expanded)",
        mark.line + 1,
        mark.column + 1,
    )
