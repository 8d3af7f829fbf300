"""The ``<ros2_control>`` transmissions under mujoco_ros2_control's rules (register_transmissions).

Read from the runtime's source (``mujoco_system_interface.cpp``, its 2026 releases).
"""

from __future__ import annotations

import math
from typing import NamedTuple

from mjcfbuild.check.runtime_actuators import actuator_of, registered, site_entry
from mjcfbuild.inputs.ros2_control import RUNTIME_PLUGINS, Ros2Control, Transmission

# The transmission types ros2_control's transmission_interface exports (its
# ros2_control_plugins.xml): register_transmissions finds no other of that package.
TRANSMISSION_TYPES = (
    "transmission_interface/SimpleTransmission",
    "transmission_interface/DifferentialTransmission",
    "transmission_interface/FourBarLinkageTransmission",
)
_PACKAGE = "transmission_interface"


class Problem(NamedTuple):
    """What the runtime does wrong with one joint of a transmission: ``stops`` where it stops
    at start-up, else it starts and misdrives or misreports the joint."""

    text: str  # after "transmission #N of joint 'x' "
    stops: bool = True


def unmatched_transmissions(
    model,
    control: Ros2Control,
    urdf_joints: dict[str, str | None] | None = None,
    fixed_joints: frozenset[str] = frozenset(),
) -> tuple[list[str], list[str]]:
    """What ros2_control's parser refuses in every block's transmissions
    (:func:`parser_refusals`), and what register_transmissions stops at or gets wrong in each
    of the others (:func:`_transmission_problems`). In a block written for mujoco_ros2_control
    (or naming no plugin) a stop is a failure and the rest a warning; one warning per other
    block (a real robot's driver: the runtime would stop only once the plugin is swapped for
    its own). ``urdf_joints`` maps each URDF joint to the joint it mimics (None for others).
    The failures and the warnings."""
    failures = parser_refusals(control, fixed_joints)
    warnings: list[str] = []
    elsewhere: dict[str, list[str]] = {}  # plugin -> what its transmissions get wrong
    said: set[tuple[str, str]] = set()  # an element's actuators are said at its first joint
    start = _start(model, control)
    # Only a joint started in position control holds its start by its command.
    positioned = {(j.block, j.name) for j in control.joints if "position" in j.commands}
    for transmission in control.transmissions:
        if not transmission.in_ros2_control or transmission.joint in fixed_joints:
            continue  # a fixed joint's is refused before the runtime starts
        problems = [
            problem
            for problem in _transmission_problems(
                model,
                transmission,
                urdf_joints or {},
                start if (transmission.block, transmission.joint) in positioned else None,
            )
            + _unequal_interfaces(control, transmission)
            if (transmission.element, problem.text) not in said
        ]
        said.update((transmission.element, problem.text) for problem in problems)
        head = f"transmission {transmission.element} of joint '{transmission.joint}'"
        if transmission.plugin and not transmission.plugin.startswith(RUNTIME_PLUGINS):
            elsewhere.setdefault(transmission.plugin, []).extend(
                f"{head} {problem.text}" for problem in problems
            )
            continue
        for problem in problems:
            found = failures if problem.stops else warnings
            found.append(f"{transmission.origin}: {head} {problem.text}")
    for element in control.jointless:
        # register_transmissions: a transmission whose joints are empty stops it.
        text = (
            f"transmission {element.element} has no <joint>: mujoco_ros2_control stops at "
            'start-up ("Transmission ... has no joints or actuators defined"); name the joint '
            'it drives in a <joint name="..." role="joint1">, or leave the transmission out'
        )
        if element.plugin and not element.plugin.startswith(RUNTIME_PLUGINS):
            elsewhere.setdefault(element.plugin, []).append(text)
        else:
            failures.append(f"{element.origin}: {text}")
    for plugin, texts in elsewhere.items():
        if texts:
            warnings.append(
                f"<ros2_control> transmissions for the hardware plugin {plugin} are not run by "
                "mujoco_ros2_control as written; with its plugin in their block, it would refuse "
                "or misdrive them: " + "; ".join(dict.fromkeys(texts))
            )
    return list(dict.fromkeys(failures)), list(dict.fromkeys(warnings))


def parser_refusals(control: Ros2Control, fixed_joints: frozenset[str]) -> list[str]:
    """What ros2_control's parser refuses in a block's transmission, in every block, before any
    hardware starts: no <plugin> element, which parse_transmission_from_xml reads the type from
    unchecked (a crash); a <joint> or <actuator> without a role; a joint its block does not
    list (auto_fill_transmission_interfaces); a fixed joint, which no block may list."""
    listed = {(joint.block, joint.name) for joint in control.joints}
    refused = "ros2_control refuses the description at start-up"
    failures, said, typeless = [], set(), set()
    for transmission in control.transmissions:
        if not transmission.in_ros2_control:
            continue
        head = f"{transmission.origin}: transmission {transmission.element}"
        if transmission.plugin_missing and transmission.element not in typeless:
            typeless.add(transmission.element)
            failures.append(
                f"{head} has no <plugin>: ros2_control's parser (parse_transmission_from_xml) "
                "reads the transmission's type from that element without checking it is there, "
                "calling GetText() on a null pointer, so the controller manager crashes while "
                "parsing the robot description at start-up (undefined behaviour: a segmentation "
                f"fault in practice), before any hardware starts; give it <plugin>"
                f"{TRANSMISSION_TYPES[0]}</plugin>"
            )
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


def _start(model, control: Ros2Control) -> tuple[str, int] | None:
    """What register_mujoco_actuators starts the joints from where it takes their state from
    the simulation (override_mujoco_actuator_positions_), and that keyframe's index (-1 for a
    file): the override_start_position_file where that param is given (tried first), else
    the keyframe initial_keyframe names; None where it starts them at their initial_value."""
    import mujoco

    if control.hardware.get("override_start_position_file"):
        return "the override_start_position_file", -1
    name = control.hardware.get("initial_keyframe")
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, name) if name else -1
    return (f"keyframe '{name}'", key) if key >= 0 else None


def _transmission_problems(
    model,
    transmission: Transmission,
    urdf_joints: dict[str, str | None],
    start: tuple[str, int] | None,
) -> list[Problem]:
    """What register_transmissions stops at in one joint of a transmission, or gets wrong: no
    ``<actuator>`` ("has no joints or actuators defined"); an actuator name get_actuator_id
    does not find, neither a driven joint's nor an actuator's ("Transmission actuator ... not
    found in MuJoCo model"); one its actuator data has no entry for (an MJCF actuator's own
    name: "Actuator ... not found in the MuJoCo actuator data") or only an undriven joint's ("...
    is passive"). And the state it reports of a mimic follower, from another joint's actuator
    through the transmission (:func:`_follower_state`), and of a joint with a reduction to its own
    actuator: its commands pass as they are, its state through the transmission."""
    import mujoco

    kind = None if transmission.plugin_missing else _type_problem(transmission.kind)
    if not transmission.actuators:
        return [
            Problem(
                'has no <actuator>: mujoco_ros2_control stops at start-up ("... has no joints or '
                "actuators defined\"); name the joint's actuator (the joint itself) in one"
            )
        ]
    problems = [kind] if kind else []
    not_found = '("Transmission actuator ... not found in MuJoCo model")'
    for name in transmission.actuators:
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        actuator = actuator_of(model, name)
        leader = urdf_joints.get(name)
        if actuator < 0 and joint >= 0 and leader:
            fix = (
                f"leave the transmission out: the follower follows '{leader}'"
                if name == transmission.joint
                else f"name a driven joint ('{leader}' drives this one)"
            )
            problems.append(
                Problem(
                    f"names actuator '{name}', a mimic follower of '{leader}' that MuJoCo moves "
                    f"by an equality, not by an actuator: mujoco_ros2_control stops at start-up "
                    f"{not_found}; {fix}"
                )
            )
        elif actuator < 0 and joint >= 0:
            problems.append(
                Problem(
                    f"names actuator '{name}', a joint without an actuator: mujoco_ros2_control "
                    f"stops at start-up {not_found}; drive the joint (actuators.rules) or name "
                    "a driven one"
                )
            )
        elif actuator < 0:
            problems.append(
                Problem(
                    f"names actuator '{name}', which is neither a joint nor an actuator of the "
                    f"model: mujoco_ros2_control stops at start-up {not_found}; name the joint "
                    "or its actuator"
                )
            )
        elif (entry := registered(model, name)) != "actuator":
            driven = _driven_joint(model, actuator)
            why = (
                '"Actuator ... not found in the MuJoCo actuator data"'
                if entry is None
                else f"a joint '{name}' without an actuator: \"Actuator ... is passive and "
                'cannot be used in a transmission"'
            )
            problems.append(
                Problem(
                    f"names actuator '{name}' by the MJCF actuator's name: mujoco_ros2_control "
                    f"finds a transmission's actuators by the joint they drive ({why}) and stops "
                    "at start-up; name "
                    + (f"joint '{driven}'" if driven else "the joint it drives")
                )
            )
        elif site := site_entry(model, name):
            problems.append(Problem(_site_state(model, transmission.joint, name, *site), False))
    if any(problem.stops for problem in problems) or transmission.kind != TRANSMISSION_TYPES[0]:
        return problems  # what other kinds do with their reductions is theirs
    reduction, offset = transmission.joint_reduction, transmission.joint_offset
    if not reduction:
        # SimpleTransmissionLoader catches the constructor's throw and returns no transmission,
        # which register_transmissions goes on to configure.
        return [
            Problem(
                'has a mechanical_reduction of 0, which SimpleTransmission refuses ("Transmission '
                'reduction ratio cannot be zero"): its loader gives mujoco_ros2_control no '
                "transmission, and the runtime fails at start-up configuring it; give the gear "
                "ratio, or 1"
            )
        ]
    if transmission.joint in transmission.actuators and (reduction != 1 or offset):
        # joint_command_to_actuator_command copies a joint's command onto the actuator of its
        # own name after the transmission wrote it; actuator_state_to_joint_state has no such
        # step, so only the state goes through the transmission.
        gear = [f"reduction of {reduction:g}"] if reduction != 1 else []
        gear += [f"offset of {offset:g}"] if offset else []
        undo = "set the reduction to 1" + (" and the offset to 0" if offset else "")
        problems.append(
            Problem(
                f"has {_article(gear[0])} {' and an '.join(gear)} to its own actuator: "
                "mujoco_ros2_control passes the joint's commands to the actuator as they are "
                "(the joint's own command overwrites the transmission's) but reports its state "
                f"through the transmission, so a joint at 0.4 reads {0.4 / reduction + offset:g}"
                f"{_started(model, transmission.joint, start, reduction, offset)}; "
                f"in the block the runtime runs, {undo} (or leave the transmission out)",
                stops=False,
            )
        )
    follower = _follower_state(model, transmission, urdf_joints)
    return problems + ([Problem(follower, stops=False)] if follower else [])


def _type_problem(kind: str) -> Problem | None:
    """register_transmissions stops where the transmission loader has no class of the type
    ("Transmission ... of type ... not available"): one of transmission_interface's package
    that it does not export, or an empty <plugin> (ros2_control's parser logs "text not
    specified in the plugin tag" and reads the type as ''). A type of another package is
    loaded only where one installed beside the runtime exports it, which the check cannot
    know: a warning. (A transmission without a <plugin> element never gets here: the parser
    crashes on it, :func:`parser_refusals`.)"""
    if kind in TRANSMISSION_TYPES:
        return None
    refused = f"mujoco_ros2_control stops at start-up (\"... of type '{kind}' not available\")"
    if not kind:
        return Problem(
            "has an empty <plugin> (ros2_control's parser logs \"text not specified in the "
            f"plugin tag\" and reads the type as ''): {refused}; give it <plugin>"
            f"{TRANSMISSION_TYPES[0]}</plugin>"
        )
    # The package's own plugins are "transmission_interface/Name"; a C++ class name
    # "transmission_interface::Name" is a common mistake. Another package whose name begins
    # the same ("transmission_interface_extras/X") is another package.
    if kind == _PACKAGE or kind.startswith((f"{_PACKAGE}/", f"{_PACKAGE}::")):
        from mjcfbuild.sources.packages import did_you_mean

        plugin_name = kind.replace("::", "/")  # the C++ class name for the plugin's
        hint = (
            f"; did you mean '{plugin_name}'?"
            if plugin_name in TRANSMISSION_TYPES
            else did_you_mean(kind, set(TRANSMISSION_TYPES))
        )
        return Problem(
            f"is of type '{kind}', which transmission_interface does not export: {refused}; "
            f"use one of {', '.join(TRANSMISSION_TYPES)}{hint}"
        )
    return Problem(
        f"is of type '{kind}', a plugin of another package than transmission_interface: "
        f"{refused.replace('stops', 'would stop')} where no package installed beside it exports "
        "that plugin, and what the plugin does with the joint's commands and state is not "
        f"judged here; install its package, or use {TRANSMISSION_TYPES[0]}",
        stops=False,
    )


def _site_state(model, joint: str, name: str, site: str, index: int) -> str:
    """What the runtime reports of a transmission's joint from a site actuator: the state of
    the joint whose index is the site's (register_mujoco_actuators reads ``jnt_qposadr[site]``)."""
    import mujoco

    read = (
        f"joint '{mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, index) or f'#{index}'}'"
        if index < model.njnt
        else "past the model's joints (an undefined read)"
    )
    return (
        f"names actuator '{name}', which acts at site '{site}': mujoco_ros2_control registers a "
        "site actuator with the state of the joint whose index is the site's, so it reports "
        f"joint '{joint}' from {read} (site #{index} read as joint #{index}); name a joint "
        "actuator (the joint it drives) in the transmission"
    )


def _started(
    model, joint: str, start: tuple[str, int] | None, reduction: float, offset: float
) -> str:
    """What a position-commanded joint with a reduction to its own actuator does at start-up
    where the runtime starts from the simulation's state (``start``: how it is named, the
    keyframe's index or -1): initialize_initial_positions copies the joint's state, read
    through the transmission, into its command, which the first write passes to the actuator
    as it is, so the joint leaves where it was put before any controller acts. (Started at its
    initial_value instead, the joint's command is that value: it stays.)"""
    import mujoco

    if start is None:
        return ""
    named, key = start
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
    at = ""
    if index >= 0 and key >= 0:
        value = float(model.key_qpos[key, model.jnt_qposadr[index]])
        at = f" (from {value:g} to {value / reduction + offset:g})"
    return (
        f"; and started from {named}, it takes that reading for the joint's position command, "
        f"so the joint leaves its start at once{at}, before any controller acts"
    )


def _unequal_interfaces(control: Ros2Control, transmission: Transmission) -> list[Problem]:
    """register_transmissions stops where the joints of one transmission (said at its first)
    have different command interfaces in their block, in any order."""
    rows = [row for row in control.transmissions if row.element == transmission.element]
    if rows[0] is not transmission:
        return []
    commands = {(joint.block, joint.name): joint.commands for joint in control.joints}
    first = commands.get((transmission.block, transmission.joint), [])
    for row in rows[1:]:
        other = commands.get((row.block, row.joint), [])
        if len(other) != len(first) or any(name not in first for name in other):
            return [
                Problem(
                    f"and joint '{row.joint}' have different command interfaces in their block "
                    f"({', '.join(first) or 'none'}; {', '.join(other) or 'none'}): "
                    'mujoco_ros2_control stops at start-up ("All joints of transmission ... '
                    'must have the same command interfaces"); give them the same ones'
                )
            ]
    return []


def _follower_state(
    model, transmission: Transmission, urdf_joints: dict[str, str | None]
) -> str | None:
    """A mimic follower's transmission from another joint's actuator: the runtime registers it
    and reports the follower's state through it (SimpleTransmission: the actuator's position
    / reduction + offset), while MuJoCo moves the follower by the equality its <mimic> became;
    the commands are the leader's own (its joint's command overwrites the transmission's). What
    it reports wrong, where the two differ."""
    follower, (name, *more) = transmission.joint, transmission.actuators
    if not urdf_joints.get(follower) or more or name == follower:
        return None
    poly = _coupling(model, follower, name)
    if poly is None:
        return None  # no equality of the follower on that joint: what moves it is not shown
    reduction, offset = transmission.joint_reduction, transmission.joint_offset
    if (
        not any(poly[2:])
        and math.isclose(poly[1], 1 / reduction, rel_tol=1e-9)
        and math.isclose(poly[0], offset, abs_tol=1e-12)
    ):
        return None
    reported = _through(reduction, offset, name)
    moved = f"a polynomial of {name}" if any(poly[2:]) else f"{poly[1]:g} x {name}"
    moved += f" + {poly[0]:g}" if poly[0] and not any(poly[2:]) else ""
    return (
        f"reads the mimic follower's state from actuator '{name}': mujoco_ros2_control reports "
        f"the follower at {reported}, where MuJoCo moves it at {moved} by its <mimic>; in the "
        "block the runtime runs, leave the follower out of the transmission (the runtime then "
        "reports the follower's own joint)"
    )


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"


def _through(reduction: float, offset: float, what: str) -> str:
    """``what`` as SimpleTransmission turns an actuator's position into its joint's."""
    return (f"{what} / {reduction:g}" if reduction != 1 else what) + (
        f" + {offset:g}" if offset else ""
    )


def _coupling(model, follower: str, leader: str) -> tuple[float, ...] | None:
    """The polynomial coefficients of an active joint equality moving ``follower`` by
    ``leader`` (joint1 = c0 + c1 joint2 + ...), if the model has one."""
    import mujoco

    first = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, follower)
    second = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, leader)
    for index in range(model.neq):
        if (
            model.eq_type[index] == mujoco.mjtEq.mjEQ_JOINT
            and model.eq_active0[index]
            and (model.eq_obj1id[index], model.eq_obj2id[index]) == (first, second)
        ):
            return tuple(float(value) for value in model.eq_data[index, :5])
    return None


def _driven_joint(model, actuator: int) -> str | None:
    """The joint an actuator drives directly, if it does."""
    import mujoco

    if model.actuator_trntype[actuator] != mujoco.mjtTrn.mjTRN_JOINT:
        return None
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, model.actuator_trnid[actuator, 0])
