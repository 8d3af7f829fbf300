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
