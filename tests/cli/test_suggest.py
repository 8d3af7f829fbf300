"""Usage errors are one line with exit code 2, naming the closest command, option or choice
to a misspelled one (mjcfbuild/cli/suggest.py)."""

from __future__ import annotations

import pytest

from mjcfbuild.cli.suggest import closest, usage_error_line
from mjcfbuild.errors import EXIT_USAGE
from tests.conftest import run_cli


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        (["biuld"], "mjcfbuild: error: no command 'biuld' (did you mean 'build'?)"),
        (["expalin"], "mjcfbuild: error: no command 'expalin' (did you mean 'explain'?)"),
        (
            ["build", "--qiuet"],
            "mjcfbuild: error: build: no option '--qiuet' (did you mean '--quiet'?)",
        ),
        (
            ["check", "--manfest=robot.yaml"],
            "mjcfbuild: error: check: no option '--manfest' (did you mean '--manifest'?)",
        ),
        (
            ["convert", "-u", "r.urdf", "--mujoco-inputs", "x.xml"],
            "mjcfbuild: error: convert: no option '--mujoco-inputs' (did you mean '--mujoco_inputs'?)",
        ),
        (
            ["cache", "prnue"],
            "mjcfbuild: error: cache: no action 'prnue' (did you mean 'prune'?)",
        ),
        (
            ["diff", "--format", "txt"],
            "mjcfbuild: error: diff: argument --format: no choice 'txt' (did you mean 'text'?)",
        ),
        (
            ["graph", "a.yaml", "b.yaml"],
            "mjcfbuild: error: graph: unexpected argument 'b.yaml' (see mjcfbuild graph --help)",
        ),
        (
            ["build", "-j", "0"],
            "mjcfbuild: error: build: argument -j/--jobs: must be at least 1 "
            "(see mjcfbuild build --help)",
        ),
        ([], "mjcfbuild: error: name a command (see mjcfbuild --help for the list)"),
        # An unknown option is named before the error it led to:
        # Before: "name a command", as if nothing had been given.
        (["--verison"], "mjcfbuild: error: no option '--verison' (did you mean '--version'?)"),
        # Before: "argument action: no choice 'x'", the option's value taken for the action.
        (
            ["cache", "--foldr", "x"],
            "mjcfbuild: error: cache: no option '--foldr' (did you mean '--folder'?)",
        ),
        # Before: "the following arguments are required: -o/--output".
        (
            ["export-urdf", "--outptu", "x.urdf", "m.xml"],
            "mjcfbuild: error: export-urdf: no option '--outptu' (did you mean '--output'?)",
        ),
        # Before: "build: no option", though it came before the command.
        (["--qiet", "build"], "mjcfbuild: error: no option '--qiet' (did you mean '--quiet'?)"),
        # A command's option before the command. Before: "no command '2'", the value of -j
        # taken for the command, or "no option '-n'".
        (
            ["-j", "2", "build"],
            "mjcfbuild: error: -j is an option of build: mjcfbuild build -j 2 ...",
        ),
        (
            ["-q", "--jobs=2", "watch"],
            "mjcfbuild: error: --jobs is an option of watch: mjcfbuild watch --jobs=2 ...",
        ),
        (["-n", "clean"], "mjcfbuild: error: -n is an option of clean: mjcfbuild clean -n ..."),
        (
            ["--timeout", "5", "check", "robot.yaml"],
            "mjcfbuild: error: --timeout is an option of check: mjcfbuild check --timeout 5 ...",
        ),
        (
            ["-j", "2"],
            "mjcfbuild: error: -j is an option of build, watch, convert, diff, not of mjcfbuild: "
            "put it after the command (mjcfbuild build -j 2 ...)",
        ),
    ],
)
def test_a_usage_error_is_one_line_with_a_suggestion(argv, line, tmp_path):
    result = run_cli(*argv, cwd=tmp_path)
    assert result.code == EXIT_USAGE
    assert result.stderr == line + "\n"
    assert result.stdout == ""


def test_a_word_like_no_command_lists_the_commands(tmp_path):
    result = run_cli("zzzz", cwd=tmp_path)
    assert result.code == EXIT_USAGE
    assert result.stderr.startswith("mjcfbuild: error: no command 'zzzz' (commands: build, ")
    assert result.stderr.count("\n") == 1


def test_choices_are_read_with_or_without_quotes():
    quoted = "argument COMMAND: invalid choice: 'grpah' (choose from 'build', 'graph')"
    bare = "argument COMMAND: invalid choice: 'grpah' (choose from build, graph)"
    for message in (quoted, bare):
        assert usage_error_line("mjcfbuild", message) == (
            "mjcfbuild: error: no command 'grpah' (did you mean 'graph'?)"
        )


def test_nothing_close_is_no_suggestion():
    assert closest("build", ["build", "check"]) == "build"
    assert closest("--verbose", ["--jobs", "--timeout"]) is None


def test_an_abbreviated_option_is_not_taken_for_an_unknown_one(tmp_path):
    result = run_cli("export-urdf", "--mesh", "meshes", "m.xml", cwd=tmp_path)
    assert result.code == EXIT_USAGE
    assert "the following arguments are required: -o/--output" in result.stderr
