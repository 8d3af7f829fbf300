"""Bounds on YAML aliases and nesting, checked on the composed graph before any value is built."""

from __future__ import annotations

import pytest

from mjcfbuild import yamlguard
from mjcfbuild.yamlguard import YamlLimitError, compose_bounded


def laughs(levels: int) -> str:
    """The "billion laughs": each anchor's list repeats the one before nine times."""
    lines = ['l0: &l0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for level in range(1, levels + 1):
        lines.append(f"l{level}: &l{level} [{', '.join([f'*l{level - 1}'] * 9)}]")
    return "\n".join(lines) + "\n"


def test_billion_laughs_is_refused_at_the_alias_that_repeats_most():
    with pytest.raises(YamlLimitError) as caught:
        compose_bounded(laughs(9))  # 9**10 values: gigabytes if it were ever built
    assert caught.value.line == 10  # l9's line: its aliases repeat l8, the largest block
    assert caught.value.column == 10
    assert "aliases add" in caught.value.message
    assert "at most 100,000" in caught.value.message


def test_small_aliases_and_merge_keys_pass():
    text = (
        "shared: &rule {joints: ['*finger*'], frequency: 5}\n"
        "rules: [*rule, *rule]\n"
        "base: &b {x: 1}\n"
        "other: {<<: *b, y: 2}\n"
    )
    assert compose_bounded(text) is not None
    assert compose_bounded(laughs(3)) is not None  # 9**4 = 6,561 values


def test_only_values_added_by_aliases_count(monkeypatch):
    monkeypatch.setattr(yamlguard, "MAX_ALIAS_VALUES", 10)
    plain = "values: [" + ", ".join(str(n) for n in range(50)) + "]\n"
    assert compose_bounded(plain) is not None
    assert compose_bounded("a: &a [1, 2, 3, 4]\nb: [*a, *a]\n") is not None  # adds 10
    with pytest.raises(YamlLimitError) as caught:
        compose_bounded("a: &a [1, 2, 3, 4]\nb: [*a, *a]\nc: *a\n")  # adds 15
    assert (caught.value.line, caught.value.column) == (2, 5)


def test_an_alias_inside_its_own_value_is_refused():
    with pytest.raises(YamlLimitError) as caught:
        compose_bounded("top:\n  loop: &a\n    - 1\n    - *a\n")
    assert (caught.value.line, caught.value.column) == (4, 7)
    assert "inside the value it names" in caught.value.message


def test_deep_nesting_is_refused_where_it_passes_the_limit_without_recursion_error():
    text = "[" * 5000 + "]" * 5000  # PyYAML's composer would recurse 5,000 deep
    with pytest.raises(YamlLimitError) as caught:
        compose_bounded(text)
    assert (caught.value.line, caught.value.column) == (1, yamlguard.MAX_DEPTH + 1)
    assert compose_bounded("[" * yamlguard.MAX_DEPTH + "]" * yamlguard.MAX_DEPTH) is not None


def test_nesting_made_deep_by_aliases_is_refused():
    lines = ["d0: &d0 [[[[[[[[[[1]]]]]]]]]]"]
    for level in range(1, 12):
        lines.append(f"d{level}: &d{level} [[[[[[[[[[*d{level - 1}]]]]]]]]]]")
    with pytest.raises(YamlLimitError) as caught:
        compose_bounded("\n".join(lines) + "\n")
    assert caught.value.line == 12
    assert "nested more than 100 deep" in caught.value.message


def test_empty_text_is_none_and_syntax_errors_stay_pyyaml_errors():
    import yaml

    assert compose_bounded("") is None
    with pytest.raises(yaml.YAMLError):
        compose_bounded("a: [1\n")
