"""What a URDF joint's ``<limit>`` means for its range: one definition for the build and the check.

A revolute or prismatic joint is limited when its ``<limit>`` gives ``lower`` or ``upper`` (a
missing one of the two is 0, as the URDF specification says). A ``<limit>`` with neither, only
``effort`` and ``velocity``, is how wheeled robots describe wheels and casters: such a joint is
unlimited, as MuJoCo's own URDF import leaves it. Continuous and floating joints are unlimited.
"""

from __future__ import annotations

from mjcfbuild.urdf.model import Joint

LIMITED_KINDS = ("revolute", "prismatic")


def joint_range(joint: Joint) -> tuple[float, float] | None:
    """The joint's (lower, upper) range, or None when the joint is unlimited."""
    limit = joint.limit
    if joint.kind not in LIMITED_KINDS or limit is None:
        return None
    if limit.lower is None and limit.upper is None:
        return None
    return (limit.lower or 0.0, limit.upper or 0.0)


def unbounded_warning(joint: Joint, where: str) -> str | None:
    """A warning for a revolute/prismatic joint left unlimited because no bound is given."""
    if joint.kind not in LIMITED_KINDS or joint_range(joint) is not None:
        return None
    if joint.limit is None:
        return None  # no <limit> at all is a malformed URDF joint, but not ambiguous
    return (
        f"{where}: {joint.kind} joint '{joint.name}' has a <limit> without lower or upper; "
        'left it unlimited, as MuJoCo\'s URDF import does (say type="continuous" for a wheel, '
        "or give lower and upper to limit it)"
    )
