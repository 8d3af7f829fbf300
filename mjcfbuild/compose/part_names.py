"""Names an MJCF part's elements take in the model where the part gives none.

Imported by the check too, which may run without the build's dependencies (an exported model
folder measured on another machine): nothing here imports beyond the standard library.
"""

from __future__ import annotations


def joint_names(joints: list[tuple[str, str]]) -> list[str]:
    """The name each of a part's joints (name, body name; in the model's order) has in the
    model: its own, or for one without, its body's name with ``_joint`` (``_joint2``, ... for
    more in one body). Unnamed, robot.yaml's rules and home could not name a joint, the check
    took it for one without an actuator, and mujoco_ros2_control refuses to start. A joint of
    an unnamed body keeps no name."""
    taken = {name for name, _ in joints if name}
    result = []
    for name, body in joints:
        if not name and body:
            number, candidate = 1, f"{body}_joint"
            while candidate in taken:
                number += 1
                candidate = f"{body}_joint{number}"
            name = candidate
            taken.add(name)
        result.append(name)
    return result
