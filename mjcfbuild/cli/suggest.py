"""One-line usage errors, with a suggestion where a word looks like a misspelled name.

Python 3.11's argparse prints its usage and then the error, and never suggests anything;
``mjcfbuild`` says it on one line, like every other error, and names the closest command,
option or choice (``mjcfbuild biuld`` -> "did you mean 'build'?").
"""

from __future__ import annotations

import argparse
import difflib
import re

# argparse's words for a bad choice: "argument COMMAND: invalid choice: 'biuld' (choose from
# 'build', 'check')"; the quotes around the choices are left out by some Python versions.
_INVALID_CHOICE = re.compile(
    r"^argument (?P<argument>[^:]+): invalid choice: (?P<value>.+?) "
    r"\(choose from (?P<choices>.*)\)$"
)


def closest(word: str, candidates: list[str]) -> str | None:
    """The candidate ``word`` most likely misspells, if one is close enough."""
    found = difflib.get_close_matches(word, candidates, n=1, cutoff=0.6)
    return found[0] if found else None


def did_you_mean(word: str, candidates: list[str]) -> str:
    """`` (did you mean 'x'?)`` for the candidate closest to ``word``, else ``""``."""
    match = closest(word, candidates)
    return f" (did you mean '{match}'?)" if match else ""


def usage_error_line(prog: str, message: str) -> str:
    """The line that reports an argparse error ``message`` of the parser ``prog``
    (``mjcfbuild``, or ``mjcfbuild build`` for a command)."""
    hint = f" (see {prog} --help)"
    choice = _INVALID_CHOICE.match(message)
    if choice is not None:
        value = choice.group("value").strip("'\"")
        choices = [word.strip("'\"") for word in choice.group("choices").split(", ")]
        suggestion = did_you_mean(value, choices)
        if choice.group("argument") == "COMMAND":
            message = f"no command '{value}'"
            hint = suggestion or f" (commands: {', '.join(choices)})"
        elif choice.group("argument").isidentifier():  # a positional word: cache's action
            message = f"no {choice.group('argument')} '{value}'"
            hint = suggestion or f" (choose from {', '.join(choices)})"
        else:
            message = f"argument {choice.group('argument')}: no choice '{value}'"
            hint = suggestion or f" (choose from {', '.join(choices)})"
    elif message.startswith("the following arguments are required: COMMAND"):
        message = "name a command"
        hint = f" (see {prog} --help for the list)"
    return _line(prog, message + hint)


def unknown_arguments_line(
    parser: argparse.ArgumentParser, command: str | None, words: list[str]
) -> str:
    """The line that reports ``words`` no parser took, naming the option of ``command`` (or
    of ``mjcfbuild`` itself) closest to the first of them."""
    commands: dict[str, argparse.ArgumentParser] = getattr(parser, "commands", {})
    owner = commands.get(command or "", parser)
    if len(words) > len(getattr(owner, "unrecognized", words)):
        owner = parser  # the command did not leave the first: it came before the command
        misplaced = misplaced_option(parser, getattr(parser, "words", []))
        if misplaced is not None:
            return misplaced
    word = words[0]
    hint = ""
    if word.startswith("-"):
        name = word.split("=", 1)[0]
        what = f"no option '{name}'"
        if name.startswith("--"):
            known = {*owner._option_string_actions, *parser._option_string_actions}
            hint = did_you_mean(name, sorted(o for o in known if o.startswith("--")))
    else:
        what = f"unexpected argument '{word}'"
    return _line(owner.prog, what + (hint or f" (see {owner.prog} --help)"))


def misplaced_option(parser: argparse.ArgumentParser, words: list[str]) -> str | None:
    """The line for an option of a command given before the command (``mjcfbuild -j 2
    build``, where argparse took the ``2`` for the command), else None: which command it
    belongs to and the command line with it after the command."""
    commands: dict[str, argparse.ArgumentParser] = getattr(parser, "commands", {})
    if not commands:
        return None
    for index, word in enumerate(words):
        if word == "--" or word in commands:
            return None  # options from here on are the command's
        if not word.startswith("-") or word.split("=", 1)[0] in parser._option_string_actions:
            continue
        found = _command_option(commands, word)
        if found is None:
            continue
        name, given = found
        owners = [c for c, sub in commands.items() if name in sub._option_string_actions]
        rest = words[index + 1 :]
        takes_value = commands[owners[0]]._option_string_actions[name].nargs != 0
        if takes_value and word == name and rest:
            given, rest = [*given, rest[0]], rest[1:]  # its value, taken for the command
        command = next((w for w in rest if w in commands), None)
        if command not in owners:
            command = None
        shown = " ".join(given)
        if command is not None:
            example = f"mjcfbuild {command} {shown} ..."
            return _line(parser.prog, f"{name} is an option of {command}: {example}")
        return _line(
            parser.prog,
            f"{name} is an option of {', '.join(owners)}, not of mjcfbuild: put it after the "
            f"command (mjcfbuild {owners[0]} {shown} ...)",
        )
    return None


def _command_option(
    commands: dict[str, argparse.ArgumentParser], word: str
) -> tuple[str, list[str]] | None:
    """The option of some command that ``word`` gives (``-j``, ``--jobs=2``, ``-j2``) and the
    words that give it, else None."""
    name = word.split("=", 1)[0]
    for candidate in (name, word[:2] if not word.startswith("--") else name):
        if any(candidate in sub._option_string_actions for sub in commands.values()):
            return candidate, [word]
    return None


def unknown_option(parser: argparse.ArgumentParser, words: list[str]) -> str | None:
    """The first of ``words`` that is a long option ``parser`` takes neither whole nor
    abbreviated, else None; for ``mjcfbuild`` itself, among the words before the command."""
    known = parser._option_string_actions
    for word in words:
        if word == "--":
            break
        if not word.startswith("-"):
            if getattr(parser, "commands", None):
                break  # the command's words are the command's
            continue
        name = word.split("=", 1)[0]
        if name.startswith("--") and not any(option.startswith(name) for option in known):
            return word
    return None


def _line(prog: str, text: str) -> str:
    """``mjcfbuild: error: [command: ]text``."""
    command = prog.removeprefix("mjcfbuild").strip()
    return f"mjcfbuild: error: {command + ': ' if command else ''}{text}"
