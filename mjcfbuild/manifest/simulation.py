"""The robot.yaml sections that make a model simulation-ready: actuators, home, self-collision,
placement.

They live apart from :mod:`mjcfbuild.manifest.models` because they describe control and contact,
not conversion; :class:`~mjcfbuild.manifest.models.Manifest` includes them.
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

ActuatorType = Literal["position", "velocity", "motor", "none"]

# The documented defaults: a 10 Hz, critically damped servo holds an arm within a few
# milliradians of its home pose against gravity (steady-state error = torque / kp).
DEFAULT_FREQUENCY = 10.0
DEFAULT_DAMPING_RATIO = 1.0
DEFAULT_SAMPLES = 1000


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class ActuatorRule(_Strict):
    """Actuation of the joints whose names match ``joints``; the first matching rule wins."""

    joints: list[str] = Field(
        min_length=1, description="Joint name patterns (* and ? wildcards), as in collision rules."
    )
    type: ActuatorType | None = Field(
        None,
        description=(
            "position, velocity, motor or none. Unset: the type <ros2_control> or a "
            "<transmission> gives the joint, else the default."
        ),
    )
    kp: float | None = Field(None, gt=0, description="Position gain (N m/rad or N/m).")
    kv: float | None = Field(
        None, gt=0, description="Velocity gain (damping of a position actuator, or velocity gain)."
    )
    frequency: float | None = Field(
        None,
        gt=0,
        description="Closed-loop natural frequency (Hz); kp and kv follow from the joint's "
        "effective inertia at home. Ignored where kp (position) or kv (velocity) is given.",
    )
    damping_ratio: float | None = Field(
        None, gt=0, description="Damping ratio with frequency (1 is critically damped)."
    )
    armature: float | None = Field(None, ge=0, description="Rotor inertia reflected at the joint.")
    damping: float | None = Field(
        None, ge=0, description="Joint damping; default the URDF <dynamics damping>."
    )
    frictionloss: float | None = Field(
        None, ge=0, description="Dry friction; default the URDF <dynamics friction>."
    )
    forcerange: tuple[float, float] | None = Field(
        None,
        description="Force limits; default plus and minus the URDF effort limit (on a floating "
        "robot whose efforts are all placeholders, the load that holds the robot).",
    )
    gravcomp: bool | None = Field(
        None, description="Compensate gravity on the bodies the joints move (body gravcomp)."
    )
    # issue 33: a real drive (mjcfbuild.control.motors)
    motor: str | None = Field(
        None,
        min_length=1,
        description="A motor (motors.define, motors.files or the shipped catalogue) that drives "
        "the joints: its armature, force limits, torque-speed line, friction and damping, "
        "unless this rule sets them.",
    )

    @model_validator(mode="after")
    def _ordered_range(self) -> ActuatorRule:
        if self.forcerange is not None and not self.forcerange[0] < self.forcerange[1]:
            raise ValueError("forcerange must be [lower, upper] with lower < upper")
        return self


class ActuatorSettings(_Strict):
    """Which actuator drives each moving joint, and how stiff it is."""

    default: ActuatorType = Field(
        "position",
        description=(
            "Actuator of every moving joint (mimic followers excepted) that no rule, "
            "<ros2_control> or <transmission> decides: position (continuous joints get "
            "velocity), velocity, motor or none (a passive model)."
        ),
    )
    frequency: float = Field(
        DEFAULT_FREQUENCY, gt=0, description="Default closed-loop natural frequency (Hz)."
    )
    damping_ratio: float = Field(
        DEFAULT_DAMPING_RATIO, gt=0, description="Default damping ratio (1: critically damped)."
    )
    speed_limits: bool = Field(
        True,
        description=(
            "Position servos of joints whose URDF gives an effort and a velocity limit get the "
            "torque-speed line through them (a <dcmotor>: full effort standing still, none at "
            "the velocity limit), so a joint moves no faster than the real one; false: plain "
            "<position> servos limited by effort alone."
        ),
    )
    rules: list[ActuatorRule] = Field(
        default_factory=list, description="Rules in order; the first whose pattern matches wins."
    )


class SelfCollisionSettings(_Strict):
    """Which pairs of robot bodies may collide (a collision matrix, as MoveIt computes it)."""

    samples: int = Field(
        DEFAULT_SAMPLES,
        gt=0,
        le=100_000,  # each is a collision pass over the robot: 1e9 asked for 45 GB
        description="Random joint configurations sampled (seeded).",
    )
    seed: int = Field(0, ge=0, description="Seed of the samples.")
    exclude_never: bool = Field(
        False, description="Also exclude pairs that collide in none of the samples."
    )
    keep: list[tuple[str, str]] = Field(
        default_factory=list, description="Link pairs that always keep colliding."
    )
    srdf: str | None = Field(
        None,
        min_length=1,
        description="An SRDF (or xacro of one) whose <disable_collisions> pairs are excluded.",
    )
    home_state: str = Field(
        "home",
        min_length=1,
        description="The SRDF <group_state> that supplies the home pose, where it names a joint "
        "robot.yaml's home: does not.",
    )


class Placement(_Strict):
    """Where the floor of the scene is, for a robot without a free joint."""

    floor: float | Literal["auto"] = Field(
        "auto",
        description=(
            "Height of the scene's floor (m), or 'auto': at z = 0, lowered under the robot's "
            "lowest collision geometry at home where that reaches below (its visual geometry "
            "where nothing collides). The model keeps the URDF's coordinates; only the scene's "
            "floor moves."
        ),
    )
