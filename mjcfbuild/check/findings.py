"""One problem the check found, and whether it is about the model's structure.

Structural problems (a link, joint or body missing, a joint of another type, a wrong mass) say
the model is not the URDF's robot at all; numeric ones (an axis, a range, an inertia a little
off) say it is the robot, imprecisely. Reports list the structural ones first, so a real
finding is not buried under rounding differences. A :class:`BodyFinding` is what the
plausibility test says of one body (or link, or the robot as a whole), with its likely cause.
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


@dataclass
class BodyFinding:
    """One body that failed the plausibility test (check.plausibility), and why it likely did."""

    body: str
    problems: list[str]
    cause: str  # "units in mm", "up axis", "wrong origin", "mass units", "impossible inertia"
    detail: str
    fails: bool  # a failure of the check; else a warning
    where: str = ""  # "file:line" of the URDF link to fix, when known
    subject: str = "body"  # what ``body`` names: a body, a link, the robot

    def text(self) -> str:
        """The one-line message."""
        place = f"{self.where}: " if self.where else ""
        return (
            f"{place}{self.subject} '{self.body}': {'; '.join(self.problems)}; likely cause: "
            f"{self.detail}"
        )
