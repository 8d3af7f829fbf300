"""One problem the check found, and whether it is about the model's structure.

Structural problems (a link, joint or body missing, a joint of another type, a wrong mass) say
the model is not the URDF's robot at all; numeric ones (an axis, a range, an inertia a little
off) say it is the robot, imprecisely. Reports list the structural ones first, so a real
finding is not buried under rounding differences.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """A check finding: its one-line text and whether it is structural."""

    text: str
    structural: bool = False


def structural_first(problems: list[Problem]) -> list[str]:
    """The texts, structural problems first, each group in its original order."""
    return [p.text for p in problems if p.structural] + [
        p.text for p in problems if not p.structural
    ]
