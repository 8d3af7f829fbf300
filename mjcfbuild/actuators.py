"""How an actuator is written into the model and read back from it: the one owner of that.

The build generates four kinds of actuator, each an MJCF element of its name:

- ``position``: a servo, kp (u - q) - kv q';
- ``velocity``: a servo on the joint's speed, kv (u - q');
- ``motor``: a torque (force) command, its control range the force limit;
- ``dcmotor``: a ``position`` servo whose drive has a torque-speed line (a motor's, or the
  one between a URDF joint's effort and velocity limits: :mod:`mjcfbuild.control.motors`),
  written as MuJoCo 4.0's ``<dcmotor input="pos">``: its controller computes the same
  kp (u - q) - kv q', drives the voltage that gives that torque and clamps it at the supply,
  so the torque falls along the line as speed rises; ``saturation`` is the force limit.

A robot.yaml actuator setting flows through here: :func:`resolve_choice` turns a joint's
rule (or the defaults) into an :class:`ActuatorChoice`, :func:`actuator_record` carries it
into the :class:`ActuatorRecord` that :mod:`mjcfbuild.control.apply` sizes the gains of, and
:func:`actuator_attributes` writes that record as MJCF. What reads a model back - the diff,
the URDF export, the checks, the home keyframe - reads it with :func:`read_actuator`,
:func:`actuator_kind`, :func:`servo_gains`, :func:`is_dcmotor` and :func:`dcmotor_of`; the
package formatter rounds and shares the attributes listed here; engines without ``<dcmotor>``
get the forms :func:`for_mujoco3` and :func:`as_position_servos` make.
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass
from typing import Any, Protocol

from mjcfbuild.numbers import output_list

POSITION = "position"
VELOCITY = "velocity"
MOTOR = "motor"
DCMOTOR = "dcmotor"
# Kinds whose control is a position target (their tuning steps a position).
POSITION_KINDS = (POSITION, DCMOTOR)
# A record's type where the build generates no actuator: a passive joint, or the user's own.
NONE, USER = "none", "user"

# Every MJCF actuator element MuJoCo 4.0 reads.
ACTUATOR_TAGS = (
    "general",
    "motor",
    "position",
    "velocity",
    "intvelocity",
    "damper",
    "cylinder",
    "muscle",
    "adhesion",
    "plugin",
    "dcmotor",  # MuJoCo 4.0's
    "pid",
)
# What the package formatter rounds and shares in default classes (package/format.py): the
# actuators it knows, their gain attributes (4 significant digits), their ranges (6), and what
# actuators of one class have in common (a <dcmotor>'s controller gains, torque-speed line and
# torque limit among them).
FORMATTED_TAGS = (
    "position",
    "velocity",
    "motor",
    "general",
    "intvelocity",
    "damper",
    "cylinder",
    "dcmotor",
)
GAIN_ATTRIBUTES = (
    "kp",
    "kv",
    "dampratio",
    "gainprm",
    "biasprm",
    "controller",
    "nominal",
    "saturation",
)
RANGE_ATTRIBUTES = ("ctrlrange", "forcerange")
CLASS_ATTRIBUTES = ("kp", "kv", "forcerange", "input", "nominal", "controller", "saturation")
# How a kind reads in words where it differs from its name (the package's README).
KIND_LABELS = {DCMOTOR: "dcmotor position servos"}


@dataclass(frozen=True)
class ActuatorChoice:
    """The actuator of one joint, before its gains are worked out from the compiled model:
    robot.yaml's settings for it (its rule's, else the defaults)."""

    joint: str
    type: str  # position, velocity, motor, none, or user (written by the user)
    source: str  # rule, ros2_control, transmission, default, user
    kp: float | None = None
    kv: float | None = None
    frequency: float = 10.0
    damping_ratio: float = 1.0
    forcerange: tuple[float, float] | None = None
    effort_limited: bool = False  # forcerange is the URDF's effort (no rule gave one)
    armature: float | None = None
    damping: float | None = None
    frictionloss: float | None = None
    gravcomp: bool = False
    rule: int | None = None  # index of the matching actuators.rules entry
    stiffen: bool = True  # default gains: stiffened where gravity at home would bend the joint
    wheel_candidate: bool = False  # continuous, default type: a wheel if its geometry says so
    rule_forcerange: bool = False  # forcerange from a rule: it also sets the joint's own limit
    motor: dict | None = None  # issue 33: the rule's drive at the output (control.motors.Drive)
    speed_limit: float | None = None  # the URDF velocity a position servo's speed line ends at
    # A <ros2_control> block commands it: mujoco_ros2_control accepts a position command only
    # on an affine-bias servo, so it never becomes a <dcmotor> (issue 42).
    runtime_commanded: bool = False

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return asdict(self)


class ActuatorDefaults(Protocol):
    """robot.yaml's ``actuators:`` as a choice reads it (manifest.simulation.ActuatorSettings,
    which sits above this module)."""

    @property
    def frequency(self) -> float: ...
    @property
    def damping_ratio(self) -> float: ...
    @property
    def speed_limits(self) -> bool: ...


class ActuatorRuleFields(Protocol):
    """One ``actuators.rules`` entry as a choice reads it (manifest.simulation.ActuatorRule)."""

    @property
    def kp(self) -> float | None: ...
    @property
    def kv(self) -> float | None: ...
    @property
    def frequency(self) -> float | None: ...
    @property
    def damping_ratio(self) -> float | None: ...
    @property
    def armature(self) -> float | None: ...
    @property
    def damping(self) -> float | None: ...
    @property
    def frictionloss(self) -> float | None: ...
    @property
    def forcerange(self) -> tuple[float, float] | None: ...
    @property
    def gravcomp(self) -> bool | None: ...


def resolve_choice(
    joint: str,
    kind: str,
    source: str,
    settings: ActuatorDefaults,
    index: int | None,
    rule: ActuatorRuleFields | None,
    effort_range: tuple[float, float] | None,
    speed: float | None,
) -> ActuatorChoice:
    """The choice for ``joint`` (``kind`` from ``source``): gains and dynamics from its rule
    (number ``index`` of ``settings.rules``), else the defaults. ``effort_range`` and ``speed``
    are the joint's URDF effort and velocity limits where they are limits."""
    speed_limit = speed if settings.speed_limits else None
    if rule is None:
        return ActuatorChoice(
            joint,
            kind,
            source,
            frequency=settings.frequency,
            damping_ratio=settings.damping_ratio,
            forcerange=effort_range,
            effort_limited=effort_range is not None,
            speed_limit=speed_limit,
        )
    return ActuatorChoice(
        joint,
        kind,
        source,
        kp=rule.kp,
        kv=rule.kv,
        frequency=rule.frequency or settings.frequency,
        damping_ratio=rule.damping_ratio or settings.damping_ratio,
        forcerange=rule.forcerange or effort_range,
        effort_limited=rule.forcerange is None and effort_range is not None,
        rule_forcerange=rule.forcerange is not None,
        armature=rule.armature,
        damping=rule.damping,
        frictionloss=rule.frictionloss,
        gravcomp=bool(rule.gravcomp),
        rule=index,
        stiffen=rule.kp is None and rule.frequency is None,
        speed_limit=speed_limit,
    )


@dataclass
class ActuatorRecord:
    """An actuator of the finished model, as it is written and reported."""

    name: str
    joint: str
    type: str
    source: str
    kp: float | None = None
    kv: float | None = None
    ctrlrange: list[float] | None = None
    forcerange: list[float] | None = None
    placeholder_effort: float | None = None  # the URDF effort the forcerange replaced
    weight_bearing: bool = False  # kp raised to hold the standing robot (control.standing)
    armature: float | None = None  # added to the joint so the stiff servo stays stable
    motor: dict | None = None  # issue 33: the drive (control.motors.Drive) behind the actuator
    rule: int | None = None  # issue 33: the actuators.rules entry it came from (tuning groups)


def actuator_record(choice: ActuatorChoice, name: str) -> ActuatorRecord:
    """The record of ``choice``'s actuator, named ``name``, before its gains are sized."""
    forcerange = list(choice.forcerange) if choice.forcerange else None
    return ActuatorRecord(
        name,
        choice.joint,
        choice.type,
        choice.source,
        forcerange=forcerange,
        motor=choice.motor,
        rule=choice.rule,
    )


def has_speed_line(motor: dict | None) -> bool:
    """Whether a drive (:meth:`mjcfbuild.control.motors.Drive.to_dict`) has a torque-speed
    line."""
    return bool(motor) and motor.get("no_load_speed") is not None  # type: ignore[union-attr]


def without_speed_line(motor: dict | None) -> dict | None:
    """A drive's record without its torque-speed line (its rotor and force limit stay)."""
    if not motor:
        return motor
    return {**motor, "no_load_speed": None, "stall_torque": None}


def settle_kind(record: ActuatorRecord, runtime_commanded: bool) -> None:
    """Make a position servo whose drive has a torque-speed line a ``<dcmotor>`` (issue 33) -
    except where ros2_control commands the joint: mujoco_ros2_control takes a ``<dcmotor>``
    (its DCMOTOR bias) for a custom actuator and refuses a position command on it (issue 42),
    so there the line goes and the servo stays a ``<position>``."""
    if record.type == POSITION and has_speed_line(record.motor):
        if runtime_commanded:
            record.motor = without_speed_line(record.motor)
        else:
            record.type = DCMOTOR


def actuator_attributes(record: ActuatorRecord) -> dict[str, str]:
    """The MJCF attributes of a generated actuator; its element's tag is ``record.type``."""
    if record.type == DCMOTOR and record.motor is not None:  # issue 33
        assert record.kp is not None and record.kv is not None
        return _dcmotor_attributes(record, record.kp, record.kv, record.motor)
    written = {"name": record.name, "joint": record.joint}
    if record.kp is not None:
        written["kp"] = output_list([record.kp])
    if record.kv is not None:
        written["kv"] = output_list([record.kv])
    if record.ctrlrange is not None:
        written["ctrlrange"] = output_list(record.ctrlrange)
    if record.forcerange is not None:
        written["forcerange"] = output_list(record.forcerange)
    return written


def _dcmotor_attributes(
    record: ActuatorRecord, kp: float, kv: float, motor: dict
) -> dict[str, str]:
    """A ``<dcmotor input="pos">`` position servo: gains in torque space, the line as MuJoCo's
    ``nominal`` operating point (voltage, stall torque, no-load speed), the controller's
    voltage clamp at the supply, and the force limit as ``saturation``."""
    voltage = float(motor["voltage"])
    forcerange = record.forcerange
    peak = max(abs(v) for v in forcerange) if forcerange else float(motor["peak_torque"])
    written = {
        "name": record.name,
        "joint": record.joint,
        "input": "pos",
        "nominal": output_list([voltage, motor["stall_torque"], motor["no_load_speed"]]),
        "controller": output_list([kp, 0, kv, 0, 0, voltage]),
        "saturation": output_list([peak, 0, 0]),
    }
    if record.ctrlrange is not None:
        written["ctrlrange"] = output_list(record.ctrlrange)
    return written


# Reading back: a compiled model (MjModel) or an MjSpec. A <dcmotor>'s gainprm, as MuJoCo 4.0
# compiles it: resistance, motor constant, -, -, then its controller's kp, ki, kd and voltage
# clamp.
_DC_RESISTANCE, _DC_CONSTANT, _DC_KP, _DC_KI, _DC_KD, _DC_CLAMP = 0, 1, 4, 5, 6, 7


@dataclass(frozen=True)
class DcMotor:
    """A compiled ``<dcmotor>``'s motor and controller."""

    resistance: float
    constant: float  # motor constant: torque per ampere, back-EMF per unit speed
    kp: float
    ki: float
    kd: float
    voltage_clamp: float  # 0: none
    top_voltage: float | None  # the clamp, else a voltage input's control range; None: unbounded

    @property
    def stall_torque(self) -> float | None:
        """The torque standing still at the top voltage (None: unbounded)."""
        if self.resistance > 0 and self.top_voltage is not None:
            return self.constant * self.top_voltage / self.resistance
        return None

    @property
    def no_load_speed(self) -> float | None:
        """The speed where the back-EMF reaches the top voltage and the torque is gone."""
        if self.constant > 0 and self.top_voltage is not None:
            return self.top_voltage / self.constant
        return None


def is_dcmotor(model: Any, index: int) -> bool:
    """Whether actuator ``index`` of a compiled model is a ``<dcmotor>``."""
    import mujoco

    return int(model.actuator_gaintype[index]) == int(mujoco.mjtGain.mjGAIN_DCMOTOR)


def dcmotor_of(model: Any, index: int) -> DcMotor | None:
    """Actuator ``index``'s motor and controller where it is a ``<dcmotor>``, else None."""
    import mujoco

    if not is_dcmotor(model, index):
        return None
    gain = model.actuator_gainprm[index]
    clamp = float(gain[_DC_CLAMP])
    top: float | None = clamp if clamp > 0 else None
    voltage_input = model.actuator_ctrlspec[index] & mujoco.mjtCtrlInput.mjINPUT_VOLTAGE
    if top is None and voltage_input and model.actuator_ctrllimited[index]:
        top = max(abs(float(v)) for v in model.actuator_ctrlrange[index]) or None
    return DcMotor(
        resistance=float(gain[_DC_RESISTANCE]),
        constant=float(gain[_DC_CONSTANT]),
        kp=float(gain[_DC_KP]),
        ki=float(gain[_DC_KI]),
        kd=float(gain[_DC_KD]),
        voltage_clamp=clamp,
        top_voltage=top,
    )


def actuator_kind(model: Any, index: int) -> str:
    """position, velocity, motor or dcmotor as the build writes them, read from a compiled
    model's gain and bias (as MuJoCo's shortcuts set them); general for anything else."""
    if is_dcmotor(model, index):
        return DCMOTOR
    if int(model.actuator_gaintype[index]) != 0:  # not a fixed gain
        return "general"
    bias = model.actuator_biasprm[index]
    if int(model.actuator_biastype[index]) == 0:
        return MOTOR
    if bias[1] != 0:
        return POSITION
    return VELOCITY if bias[2] != 0 else "general"


@dataclass(frozen=True)
class ActuatorReading:
    """What the diff compares of an actuator, read from a compiled model; a field added here
    is snapshotted and compared (mjcfbuild.diff) without more."""

    kind: str  # actuator_kind
    kp: float
    kv: float
    gear: float
    ctrlrange: list[float] | None  # None: not limited
    forcerange: list[float] | None

    def to_dict(self) -> dict[str, Any]:
        """A JSON-friendly form."""
        return asdict(self)


READING_FIELDS = tuple(ActuatorReading.__dataclass_fields__)


def read_actuator(model: Any, index: int) -> ActuatorReading:
    """Actuator ``index`` of a compiled model as :class:`ActuatorReading`."""
    kp, kv = servo_gains(model, index)
    return ActuatorReading(
        kind=actuator_kind(model, index),
        kp=kp,
        kv=kv,
        gear=float(model.actuator_gear[index][0]),
        ctrlrange=[float(v) for v in model.actuator_ctrlrange[index]]
        if model.actuator_ctrllimited[index]
        else None,
        forcerange=[float(v) for v in model.actuator_forcerange[index]]
        if model.actuator_forcelimited[index]
        else None,
    )


def servo_gains(model: Any, index: int) -> tuple[float, float]:
    """Actuator ``index``'s kp and kv: a ``<dcmotor>``'s controller gains, else the gain and
    the bias's velocity term of a shortcut servo."""
    gain, bias = model.actuator_gainprm[index], model.actuator_biasprm[index]
    if is_dcmotor(model, index):
        return float(gain[_DC_KP]), float(gain[_DC_KD])
    return float(gain[0]), float(-bias[2])


# Compat: engines older than the MuJoCo that builds the model (4.0). The report page's
# WebAssembly build (npm's newest is 3.14) and MJX's JAX engine (mujoco-mjx 3.17) read 3.x MJCF.
# MuJoCo 4.0 writes input="pos" on the actuators its <position> shortcut makes (an MJCF part's
# servo, the training variant's servos); 3.14 allows input only on so3, pid and dcmotor
# actuators and has no other meaning for it. Those actuators' gains and biases are written out
# in full, so without the attribute 3.x simulates the same servo.
_INPUT_REFUSED = re.compile(
    rb"<(?:general|position|velocity|intvelocity|motor|damper|cylinder|muscle|adhesion)\b[^>]*>"
)
_INPUT = re.compile(rb"\s+input=\"[^\"]*\"")


def for_mujoco3(xml: bytes) -> bytes:
    """``xml`` with what MuJoCo 3.x refuses taken out; the same bytes otherwise. A
    ``<general>`` with DC motor dynamics (how MjSpec writes a ``<dcmotor>``) keeps its input:
    there it means what it does on ``<dcmotor>``."""

    def without_input(tag: re.Match[bytes]) -> bytes:
        text = tag.group(0)
        return text if b'"dcmotor"' in text else _INPUT.sub(b"", text)

    return _INPUT_REFUSED.sub(without_input, xml)


def as_position_servos(spec: Any) -> tuple[int, list[str]]:
    """Turn an MjSpec's ``<dcmotor input="pos">`` servos without an integral term into
    ``<position>`` servos with the same gains, force limit and control range (MJX's JAX engine
    refuses ``<dcmotor>``: NotImplementedError in ``mjx.put_model``). The torque-speed line
    goes; the rotor inertia that came with it stays on the joint. Returns how many were turned
    and the names of the ``<dcmotor>`` actuators kept (voltage or velocity input, or an
    integral term: no position servo is the same drive)."""
    import mujoco

    motors = [a for a in spec.actuators if a.gaintype == mujoco.mjtGain.mjGAIN_DCMOTOR]
    servos = [
        a
        for a in motors
        if a.ctrlspec == mujoco.mjtCtrlInput.mjINPUT_POS and float(a.gainprm[_DC_KI]) == 0.0
    ]
    for actuator in servos:
        kp, kv = float(actuator.gainprm[_DC_KP]), float(actuator.gainprm[_DC_KD])
        actuator.type = mujoco.mjtActuator.mjACTUATOR_POSITION
        actuator.dyntype = mujoco.mjtDyn.mjDYN_NONE
        actuator.dynprm = [1.0] + [0.0] * (len(actuator.dynprm) - 1)  # MuJoCo's default
        actuator.gainprm = [0.0] * len(actuator.gainprm)
        actuator.biasprm = [0.0] * len(actuator.biasprm)
        actuator.actearly = False
        actuator.set_to_position(kp=kp, kv=kv)
    kept = [a.name or f"actuator {a.id}" for a in motors if a not in servos]
    return len(servos), kept
