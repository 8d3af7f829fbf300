"""How deep a model's bodies nest, against the deepest nesting MuJoCo can read back.

MJCF nests each body inside its parent, so a chain of links (a snake, a rope, a conveyor) is as
deep as it is long. MuJoCo reads MJCF with tinyxml2, which refuses elements nested 500 deep:
``<mujoco>``, ``<worldbody>``, the bodies, then their joints and geoms leave room for 496 nested
bodies (measured with MuJoCo 4.0.0, by ``MjModel.from_xml_string`` and ``MjSpec.from_string``
alike; its compiler stops at 1,023 bodies deep, "depth limit exceeded in signature
computation"). A deeper model could be compiled but never loaded from the file written, so it
is refused before any work is spent on it, as MuJoCo's limit rather than a fault in the file.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mjcfbuild.errors import ModelError
from mjcfbuild.mjcf.bodies import WORLD, ground_link

if TYPE_CHECKING:
    from mjcfbuild.mjcf.bodies import Body
    from mjcfbuild.urdf.model import Joint, Robot

MAX_BODY_DEPTH = 496


def refuse_deep_chains(robot: Robot) -> None:
    """Raise :class:`ModelError` where moving joints alone nest bodies deeper than
    :data:`MAX_BODY_DEPTH` (fixed joints may be fused away; moving ones always make a body)."""
    children = robot.child_joints()
    depth = {robot.root: 0 if ground_link(robot) is not None else 1}
    joint_to: dict[str, Joint] = {}
    pending = [robot.root]
    while pending:
        parent = pending.pop()
        for joint in children[parent]:
            depth[joint.child] = depth[parent] + joint.moves
            joint_to[joint.child] = joint
            pending.append(joint.child)
    deepest = max(depth, key=lambda link: depth[link])
    if depth[deepest] <= MAX_BODY_DEPTH:
        return
    link = deepest
    while not (joint_to[link].moves and depth[link] == MAX_BODY_DEPTH + 1):
        link = joint_to[link].parent
    raise _too_deep(robot, joint_to[link], depth[deepest])


def refuse_deep_bodies(robot: Robot, bodies: list[Body]) -> None:
    """Raise :class:`ModelError` where ``bodies`` (parents first) nest deeper than
    :data:`MAX_BODY_DEPTH`."""
    depth: dict[str, int] = {}
    by_name = {body.name: body for body in bodies}
    for body in bodies:
        if body.parent is None:
            depth[body.name] = 0 if body.name == WORLD else 1
        else:
            depth[body.name] = depth[body.parent] + 1
    deepest = max(depth, key=lambda name: depth[name])
    if depth[deepest] <= MAX_BODY_DEPTH:
        return
    body = by_name[deepest]
    while depth[body.name] > MAX_BODY_DEPTH + 1:
        body = by_name[str(body.parent)]
    assert body.joint is not None, "every body but the root hangs from a joint"
    raise _too_deep(robot, body.joint, depth[deepest])


def _too_deep(robot: Robot, joint: Joint, deepest: int) -> ModelError:
    return ModelError(
        f"the kinematic tree nests bodies {deepest} deep and MuJoCo reads at most "
        f"{MAX_BODY_DEPTH} from an MJCF file (its XML reader stops at 500 nested elements); "
        f"joint '{joint.name}' starts body {MAX_BODY_DEPTH + 1}",
        file=robot.source,
        line=joint.line,
        hint="this is MuJoCo's limit, not a fault in the file: build the chain as shorter "
        "models, or fuse fixed joints (options.fuse_static)",
    )
