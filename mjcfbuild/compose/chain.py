"""Why parts attached to one another cannot be placed: the chain of ``to``s they make."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TypeVar

Part = TypeVar("Part")


def stuck_chain(
    first: Part, owner: Mapping[str, Part], target: Callable[[Part], str]
) -> tuple[Part, list[Part] | None]:
    """Follow ``first``'s target (``target(part)``: the name it is attached to) through
    ``owner`` (a name -> the waiting part that holds it): the last part of the chain, and
    None where its target is held by no waiting part (a name nothing has), or the parts of
    the cycle the chain runs into."""
    chain = [first]
    while target(chain[-1]) in owner and owner[target(chain[-1])] not in chain:
        chain.append(owner[target(chain[-1])])
    last = chain[-1]
    if target(last) not in owner:
        return last, None
    return last, chain[chain.index(owner[target(last)]) :]
