"""The PID gains a ``pids_config_file`` gives mujoco_ros2_control, read as ROS reads them.

The runtime loads the file as its node's ROS parameters and, for a joint whose actuator does
not take a command interface directly, builds a PID from ``pid_gains.<interface>.<joint>.p``,
``.i`` and ``.d`` (control_toolbox's PidROS). A gain that is missing, or is not a double (ROS
types ``100`` as an integer, and PidROS then reads no gain: ``100.0`` is a double), leaves the
PID undefined, and the runtime stops at start-up for that interface.

The file is ROS's parameter YAML: node names at the top (``mujoco_ros2_control_node``, with a
namespace, or the ``/**`` wildcard), each with ``ros__parameters`` whose nested keys join with
dots.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

NODE = "mujoco_ros2_control_node"
GAINS = ("p", "i", "d")


@dataclass
class PidGains:
    """What a pids_config_file defines: the (interface, joint) pairs with every gain a double,
    and for the others named in it, what is wrong."""

    defined: set[tuple[str, str]] = field(default_factory=set)
    faults: dict[tuple[str, str], str] = field(default_factory=dict)

    def has(self, interface: str, joint: str) -> bool:
        """Whether the runtime finds a PID for ``interface`` of ``joint``."""
        return (interface, joint) in self.defined


def pids_file(hardware: dict[str, str]) -> Path | None:
    """The pids_config_file a block's ``<hardware>`` names, where it is a file here (a path
    ``$(find pkg)`` made absolute): the check reads it, so it is a dependency."""
    named = hardware.get("pids_config_file", "").strip()
    path = Path(named) if named else None
    return path if path is not None and path.is_absolute() and path.is_file() else None


def read_pid_gains(path: Path) -> PidGains:
    """The gains of the file at ``path``; OSError where it cannot be read, ValueError where it
    is no YAML mapping."""
    import yaml

    document = yaml.safe_load(path.read_text(encoding="utf-8"))
    if not isinstance(document, dict):
        raise ValueError("not a mapping of node names to parameters")
    parameters: dict[str, object] = {}
    for node, content in document.items():
        if not _names_the_node(str(node)) or not isinstance(content, dict):
            continue
        ros = content.get("ros__parameters")
        if isinstance(ros, dict):
            _flatten(ros, "", parameters)
    gains = PidGains()
    prefixes = {
        tuple(key.split(".")[1:3])
        for key in parameters
        if key.startswith("pid_gains.") and key.count(".") >= 3
    }
    for interface, joint in sorted(prefixes):
        values = {gain: parameters.get(f"pid_gains.{interface}.{joint}.{gain}") for gain in GAINS}
        fault = _fault(values)
        if fault is None:
            gains.defined.add((interface, joint))
        else:
            gains.faults[(interface, joint)] = fault
    return gains


def _names_the_node(node: str) -> bool:
    """Whether parameters under ``node`` reach the runtime's node: its name (with any
    namespace) or a wildcard."""
    last = node.rstrip("/").rsplit("/", 1)[-1]
    return last == NODE or "*" in node


def _flatten(tree: dict, prefix: str, into: dict[str, object]) -> None:
    for key, value in tree.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            _flatten(value, f"{name}.", into)
        else:
            into[name] = value


def _fault(values: dict[str, object]) -> str | None:
    """Why a PID with these gains is undefined to the runtime, or None where it is defined."""
    for gain, value in values.items():
        if value is None:
            return f"no {gain} gain"
        if isinstance(value, bool) or not isinstance(value, float):
            return f"its {gain} gain {value!r} is not a double (write {_as_double(value)})"
        if not math.isfinite(value):
            return f"its {gain} gain is {value}"
    return None


def _as_double(value: object) -> str:
    return f"{value}.0" if isinstance(value, int) and not isinstance(value, bool) else "a number"
