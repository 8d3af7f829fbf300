"""The ``attach:`` section of robot.yaml: parts attached to the main source.

A URDF or xacro part goes through the same pipeline as the main source; an MJCF part (a
hand-tuned MuJoCo model) is attached to the assembled model through ``MjSpec.attach`` with its
own actuators, sensors, tendons, equalities and defaults. Either way its names get a prefix and
its root is fixed to a link of the model built so far at an optional offset.
"""

from __future__ import annotations

import math
from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, computed_field, model_validator

PREFIX_PATTERN = r"^[A-Za-z_][A-Za-z0-9_.\-]*$"


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class PartSource(_Strict):
    """Where an attached part comes from: one of ``urdf``, ``xacro`` or ``mjcf``."""

    urdf: Annotated[str, Field(min_length=1)] | None = Field(
        None, description="A URDF file (relative to robot.yaml)."
    )
    xacro: Annotated[str, Field(min_length=1)] | None = Field(
        None, description="A xacro file (relative to robot.yaml), expanded with the given args."
    )
    mjcf: Annotated[str, Field(min_length=1)] | None = Field(
        None,
        description="A MuJoCo MJCF file (relative to robot.yaml), attached with its actuators, "
        "sensors, tendons, equalities, defaults and assets; its 'home' keyframe fills its joints.",
    )
    args: dict[str, str | int | float | bool] = Field(
        default_factory=dict, description="xacro arguments of the part."
    )

    @model_validator(mode="after")
    def _exactly_one(self) -> PartSource:
        given = [key for key in ("urdf", "xacro", "mjcf") if getattr(self, key)]
        if len(given) != 1:
            found = ", ".join(given) if given else "none"
            raise ValueError(f"give exactly one of urdf, xacro, mjcf (found: {found})")
        if self.args and not self.xacro:
            raise ValueError("args are xacro arguments; they need a xacro source")
        return self

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def kind(self) -> str:
        """``urdf``, ``xacro`` or ``mjcf``."""
        return "xacro" if self.xacro else "mjcf" if self.mjcf else "urdf"

    @computed_field  # type: ignore[prop-decorator]
    @property
    def file(self) -> str:
        """The part's file, as robot.yaml gives it."""
        return self.xacro or self.mjcf or self.urdf or ""

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def xacro_args(self) -> dict[str, str]:
        """The xacro args as the strings xacro expects (YAML true becomes 'true')."""
        return {
            name: str(value).lower() if isinstance(value, bool) else str(value)
            for name, value in sorted(self.args.items())
        }


class Attachment(_Strict):
    """A part attached to a link of the model built so far, its names prefixed."""

    source: PartSource
    to: str = Field(
        min_length=1,
        description="The link the part's root is fixed to: a link of the main source or of "
        "another part (with that part's prefix); an MJCF part may also name a body or site of "
        "an MJCF part attached before it.",
    )
    prefix: str = Field(
        pattern=PREFIX_PATTERN,
        description="Put before every name of the part (links, joints, materials; for an MJCF "
        "part also bodies, actuators, sensors, tendons, defaults, assets), e.g. 'hand_'.",
    )
    pos: tuple[float, float, float] = Field(
        (0.0, 0.0, 0.0), description="Position of the part's root in the 'to' link's frame (m)."
    )
    quat: tuple[float, float, float, float] | None = Field(
        None, description="Orientation of the part's root as a quaternion w, x, y, z."
    )
    euler: tuple[float, float, float] | None = Field(
        None,
        description="Orientation of the part's root as roll, pitch, yaw in radians (about fixed "
        "x, y, z axes, as a URDF origin's rpy).",
    )
    packages: dict[str, Annotated[str, Field(min_length=1)]] = Field(
        default_factory=dict,
        description="ROS package name -> folder (relative to robot.yaml) for the part's own "
        "package:// URIs and $(find pkg); over the top-level packages.",
    )

    @model_validator(mode="after")
    def _pose(self) -> Attachment:
        if self.quat is not None and self.euler is not None:
            raise ValueError("give quat or euler, not both")
        values = [*self.pos, *(self.quat or ()), *(self.euler or ())]
        if not all(math.isfinite(v) for v in values):
            raise ValueError("pos, quat and euler must be finite numbers")
        if self.quat is not None and math.sqrt(sum(q * q for q in self.quat)) < 1e-9:
            raise ValueError("quat must not be zero")
        if self.packages and self.source.kind == "mjcf":
            raise ValueError("packages are for URDF and xacro parts; an MJCF part names files")
        return self

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def rpy(self) -> tuple[float, float, float]:
        """The orientation as URDF roll, pitch, yaw."""
        if self.euler is not None:
            return self.euler
        if self.quat is None:
            return (0.0, 0.0, 0.0)
        from mjcfbuild.urdf.transforms import matrix_to_rpy, quat_to_matrix

        return matrix_to_rpy(quat_to_matrix(self.quat))

    @computed_field  # type: ignore[prop-decorator]
    @property
    def orientation(self) -> tuple[float, float, float, float]:
        """The orientation as a unit quaternion w, x, y, z (for an MJCF part's frame)."""
        from mjcfbuild.urdf.transforms import matrix_to_quat, rpy_to_matrix

        if self.quat is not None:
            norm = math.sqrt(sum(q * q for q in self.quat))
            w, x, y, z = (q / norm for q in self.quat)
            return (w, x, y, z)
        return matrix_to_quat(rpy_to_matrix(self.euler or (0.0, 0.0, 0.0)))


def check_prefixes(parts: list[Attachment]) -> list[Attachment]:
    """Refuse two parts with the same prefix (their names would collide)."""
    seen: dict[str, int] = {}
    for index, part in enumerate(parts):
        if part.prefix in seen:
            raise ValueError(
                f"attach[{index}] uses prefix '{part.prefix}' as attach[{seen[part.prefix]}] "
                "does; give each part its own"
            )
        seen[part.prefix] = index
    return parts
