"""The ``motors:`` section of robot.yaml: drives described by their datasheet values.

A motor names a real drive - its rotor, its gearbox and its torque-speed limits - so that the
joint it moves gets the drive's reflected inertia (armature), its force limits and its
torque-speed line (see :mod:`mjcfbuild.control.motors`). Actuator rules refer to motors by name;
names are looked up in ``motors.define``, then in ``motors.files`` (in order), then in the
catalogue shipped with mjcfbuild (``mjcfbuild/control/catalogue.yaml``).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, RootModel, model_validator

MotorName = str
MotorFile = Annotated[str, Field(min_length=1, description="A path, relative to robot.yaml.")]


class Motor(BaseModel):
    """One drive: rotor, gearbox and limits. Torques in N m and speeds in rad/s, given at the
    output (the joint) or at the rotor, as ``at`` says; the rotor inertia is always the rotor's."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    rotor_inertia: float = Field(
        gt=0, description="Moment of inertia of the rotor about its axis (kg m^2), at the rotor."
    )
    ratio: float | None = Field(
        None,
        gt=0,
        description="Gear ratio (rotor turns per output turn). Unset: the mechanicalReduction "
        "of the joint's <transmission>, else 1. A <transmission> reduction wins over it.",
    )
    at: Literal["output", "rotor"] = Field(
        "output",
        description="Where the torques, speed and torque constant below are given: at the "
        "output (the joint) or at the rotor (before the gearbox).",
    )
    peak_torque: float = Field(gt=0, description="Peak torque (N m): the actuator's force limit.")
    continuous_torque: float | None = Field(
        None, gt=0, description="Continuous (rated) torque (N m); at most the peak torque."
    )
    no_load_speed: float | None = Field(
        None, gt=0, description="No-load speed (rad/s) at the supply voltage."
    )
    stall_torque: float | None = Field(
        None,
        gt=0,
        description="Stall torque (N m) at the supply voltage: the torque-speed line's torque "
        "at zero speed. Default: torque_constant * voltage / resistance, else the peak torque.",
    )
    torque_constant: float | None = Field(
        None, gt=0, description="Torque constant (N m/A); with resistance and voltage."
    )
    resistance: float | None = Field(
        None, gt=0, description="Terminal resistance (ohm); with torque_constant and voltage."
    )
    voltage: float | None = Field(
        None, gt=0, description="Supply voltage (V); with torque_constant and resistance."
    )
    friction: float | None = Field(
        None, ge=0, description="Dry friction torque at the output (N m): joint frictionloss."
    )
    damping: float | None = Field(
        None, ge=0, description="Viscous friction at the output (N m s/rad): joint damping."
    )
    source: str | None = Field(None, description="Where the values come from (a datasheet).")

    @model_validator(mode="after")
    def _consistent(self) -> Motor:
        if self.continuous_torque is not None and self.peak_torque < self.continuous_torque:
            raise ValueError(
                f"peak_torque {self.peak_torque:g} is below continuous_torque "
                f"{self.continuous_torque:g}; the peak torque must be at least the continuous one"
            )
        electrical = (self.torque_constant, self.resistance, self.voltage)
        if any(v is not None for v in electrical) and any(v is None for v in electrical):
            raise ValueError(
                "torque_constant, resistance and voltage go together: give all three, or "
                "no_load_speed (and stall_torque) instead"
            )
        return self


class MotorCatalogue(RootModel[dict[MotorName, Motor]]):
    """A motor file: motor name -> datasheet values (the format of the shipped catalogue)."""


class MotorSettings(BaseModel):
    """Drives that actuator rules name with ``motor:``."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    files: list[MotorFile] = Field(
        default_factory=list,
        description="YAML files of more motors (name -> datasheet values, as in "
        "mjcfbuild/control/catalogue.yaml), relative to robot.yaml; earlier files win.",
    )
    define: dict[MotorName, Motor] = Field(
        default_factory=dict,
        description="Motors defined here: name -> datasheet values. They win over the files "
        "and the shipped catalogue.",
    )
