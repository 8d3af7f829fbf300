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
    """The pids_config_file a block's ``<hardware>`` names, where it names one by an absolute
    path (``$(find pkg)`` makes one): the check reads it, so it is a dependency (a missing
    one too: its appearing reruns the check)."""
    named = hardware.get("pids_config_file", "").strip()
    path = Path(named) if named else None
    return path if path is not None and path.is_absolute() else None


def read_pid_gains(path: Path) -> PidGains:
    """The gains of the file at ``path``, its values typed as ROS types them; OSError where it
    cannot be read, ValueError (naming the line) where ROS could not load it either."""
    import yaml

    text = path.read_text(encoding="utf-8", errors="replace")
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as exc:
        # Where the construct began (an unclosed bracket's line), else where YAML noticed.
        mark = getattr(exc, "context_mark", None) or getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}: " if mark is not None else ""
        raise ValueError(f"{where}{getattr(exc, 'problem', None) or exc}") from None
    document = _ros_value(node) if node is not None else {}
    if not isinstance(document, dict):
        raise ValueError("not a mapping of node names to parameters")
    parameters: dict[str, object] = {}
    for name, content in document.items():
        if not _names_the_node(str(name)) or not isinstance(content, dict):
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


# rcl_yaml_param_parser's booleans, among plain scalars (before integers and doubles).
_TRUE = {"y", "Y", "yes", "Yes", "YES", "true", "True", "TRUE", "on", "On", "ON"}
_FALSE = {"n", "N", "no", "No", "NO", "false", "False", "FALSE", "off", "Off", "OFF"}


def _ros_value(node) -> object:
    """A YAML node's value as ROS's parameter parser types it: a quoted scalar is a string; a
    plain one a boolean, else an integer where the whole of it is one, else a double where
    the whole of it is one (``1e-3`` too, a string to YAML 1.1), else a string."""
    import yaml

    if isinstance(node, yaml.MappingNode):
        return {str(_ros_value(key)): _ros_value(value) for key, value in node.value}
    if isinstance(node, yaml.SequenceNode):
        return [_ros_value(item) for item in node.value]
    text = node.value
    if node.style is not None:
        return text
    if text in _TRUE or text in _FALSE:
        return text in _TRUE
    if "_" in text:  # Python reads 1_000 as a number; strtol and strtod do not
        return text
    try:
        return int(text, 10)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


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
