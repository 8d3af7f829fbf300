"""The ``<ros2_control>`` transmissions under mujoco_ros2_control's rules (register_transmissions).

Read from the runtime's source (``mujoco_system_interface.cpp``, its 2026 releases).
"""

from __future__ import annotations

from mjcfbuild.check.runtime_actuators import actuator_of
from mjcfbuild.inputs.ros2_control import RUNTIME_PLUGINS, Ros2Control


def unmatched_transmissions(
    model, control: Ros2Control, fixed_joints: frozenset[str] = frozenset()
) -> tuple[list[str], list[str]]:
    """What ros2_control's parser refuses in every block's transmissions
    (:func:`parser_refusals`), and what stops register_transmissions at start-up, for each
    ``<ros2_control>``
    transmission: no ``<actuator>`` ("has no joints or actuators defined"); an actuator name
    that is neither a joint nor an actuator of the model ("Transmission actuator ... not
    found"); one that is an MJCF actuator's name, not its joint's (the handles are looked up by
    the joint an actuator drives: "Actuator ... not found in the MuJoCo actuator data"); a joint
    without an actuator ("... is passive and cannot be used"). And what it does wrong: a
    reduction between a joint and its own actuator drives the joint to reduction x command.
    Failures in a block written for mujoco_ros2_control (or naming no plugin); one warning
    per other block (a real robot's driver: the runtime would stop only once the plugin is
    swapped for its own). The failures and the warnings."""
    failures = parser_refusals(control, fixed_joints)
    elsewhere: dict[str, list[str]] = {}  # plugin -> what its transmissions get wrong
    for transmission in control.transmissions:
        if not transmission.in_ros2_control or transmission.joint in fixed_joints:
            continue  # a fixed joint's is refused before the runtime starts
        problems = _transmission_problems(model, transmission)
        if transmission.plugin and not transmission.plugin.startswith(RUNTIME_PLUGINS):
            elsewhere.setdefault(transmission.plugin, []).extend(
                f"transmission {transmission.element} of joint '{transmission.joint}' {problem}"
                for problem in problems
            )
            continue
        failures += [
            f"{transmission.origin}: transmission {transmission.element} of joint "
            f"'{transmission.joint}' {problem}"
            for problem in problems
        ]
    warnings = []
    for plugin, problems in elsewhere.items():
        if problems:
            problems = list(dict.fromkeys(problems))
            warnings.append(
                f"<ros2_control> transmissions for the hardware plugin {plugin} are not run by "
                "mujoco_ros2_control as written; with its plugin in their block, it would refuse "
                "or misdrive them: " + "; ".join(problems)
            )
    return list(dict.fromkeys(failures)), warnings


def parser_refusals(control: Ros2Control, fixed_joints: frozenset[str]) -> list[str]:
    """What ros2_control's parser refuses in a block's transmission, in every block, before any
    hardware starts: a <joint> or <actuator> without a role; a joint its block does not list
    (auto_fill_transmission_interfaces); a fixed joint, which no block may list."""
    listed = {(joint.block, joint.name) for joint in control.joints}
    refused = "ros2_control refuses the description at start-up"
    failures, said = [], set()
    for transmission in control.transmissions:
        if not transmission.in_ros2_control:
            continue
        head = f"{transmission.origin}: transmission {transmission.element}"
        if transmission.roleless and transmission.element not in said:
            said.add(transmission.element)
            missing = transmission.roleless
            failures.append(
                f"{head}: its {', '.join(missing)} {'has' if len(missing) == 1 else 'have'} "
                f'no role attribute: {refused} ("no attribute role in ... tag"); give each '
                '<joint> and <actuator> of the transmission one (role="joint1", '
                'role="actuator1")'
            )
        head += f" of joint '{transmission.joint}'"
        if transmission.joint in fixed_joints:
            failures.append(
                f'{head} names a fixed joint, which nothing moves: {refused} ("... declared '
                'joint ... is not available in component ..." where its block does not list '
                'the joint, "Fixed joints do not make sense in ros2_control" where it does); '
                "leave the transmission out"
            )
        elif (transmission.block, transmission.joint) not in listed:
            failures.append(
                f"{head} names a joint its <ros2_control> block does not list: {refused} "
                '("Transmission ... declared joint ... is not available in component ..."); '
                "list the joint in the block, or leave it out of the transmission"
            )
    return failures


def _transmission_problems(model, transmission) -> list[str]:
    """What register_transmissions refuses in one joint of a transmission, or gets wrong."""
    import mujoco

    if not transmission.actuators:
        return [
            'has no <actuator>: mujoco_ros2_control stops at start-up ("... has no joints or '
            "actuators defined\"); name the joint's actuator (the joint itself) in one"
        ]
    problems = []
    for name in transmission.actuators:
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        actuator = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        if joint >= 0 and actuator_of(model, name) < 0:
            problems.append(
                f"names actuator '{name}', a joint without an actuator: mujoco_ros2_control "
                'stops at start-up ("... is passive and cannot be used in a transmission"); '
                "drive the joint (actuators.rules) or name a driven one"
            )
        elif joint < 0 and actuator >= 0:
            driven = _driven_joint(model, actuator)
            problems.append(
                f"names actuator '{name}' by the MJCF actuator's name: mujoco_ros2_control finds "
                "a transmission's actuators by the joint they drive (\"Actuator ... not found "
                'in the MuJoCo actuator data") and stops at start-up; name '
                + (f"joint '{driven}'" if driven else "the joint it drives")
            )
        elif joint < 0:
            problems.append(
                f"names actuator '{name}', which is neither a joint nor an actuator of the "
                'model: mujoco_ros2_control stops at start-up ("Transmission actuator ... not '
                'found"); name the joint or its actuator'
            )
    if transmission.reduction and transmission.joint in transmission.actuators:
        problems.append(
            f"has a reduction of {transmission.reduction:g} to its own actuator: "
            "mujoco_ros2_control drives the joint to the command times the reduction and reports "
            "the position divided by it, as if a motor turned ahead of the joint; in the block "
            "the runtime runs, set the reduction to 1 (or leave the transmission out)"
        )
    return problems


def _driven_joint(model, actuator: int) -> str | None:
    """The joint an actuator drives directly, if it does."""
    import mujoco

    if model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_JOINT:
        return None
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, model.actuator_trnid[actuator, 0])
