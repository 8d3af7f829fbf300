"""The pydantic models of ``robot.yaml``.

Every model forbids unknown keys, so a typo is an error that names the key and lists the allowed
ones instead of being silently ignored. Paths are kept as written; they are relative to the
manifest's folder and resolved by :class:`mjcfbuild.engine.context.BuildContext`.
"""

from __future__ import annotations

import re
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, computed_field, field_validator, model_validator

NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.-]*$"
PACKAGE_PATTERN = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")

RelPath = Annotated[str, Field(min_length=1, description="A path, relative to robot.yaml.")]
FileName = Annotated[
    str,
    Field(pattern=NAME_PATTERN, description="A plain file name (no folders)."),
]


class StrictModel(BaseModel):
    """Base of every manifest model: unknown keys are errors."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class Source(StrictModel):
    """Where the robot description comes from: one of ``urdf``, ``xacro``, ``description``."""

    urdf: RelPath | None = Field(None, description="A URDF file.")
    xacro: RelPath | None = Field(
        None, description="A xacro file, expanded in-process with the given args."
    )
    args: dict[str, str | int | float | bool] = Field(
        default_factory=dict,
        description="xacro arguments (name: value), as `name:=value` on the xacro command line.",
    )
    description: RelPath | None = Field(
        None,
        description=(
            "A robot description (URDF text) read from a file, or from standard input with '-'. "
            "Relative mesh paths in it are relative to robot.yaml's folder."
        ),
    )

    @model_validator(mode="after")
    def _exactly_one(self) -> Source:
        given = [key for key in ("urdf", "xacro", "description") if getattr(self, key)]
        if len(given) != 1:
            found = ", ".join(given) if given else "none"
            raise ValueError(f"give exactly one of urdf, xacro, description (found: {found})")
        if self.args and not self.xacro:
            raise ValueError("args are xacro arguments; they need a xacro source")
        return self

    @computed_field
    @property
    def xacro_args(self) -> dict[str, str]:
        """The xacro args as the strings xacro expects (YAML true becomes 'true')."""
        result = {}
        for name, value in sorted(self.args.items()):
            result[name] = str(value).lower() if isinstance(value, bool) else str(value)
        return result


class Options(StrictModel):
    """How the robot is turned into a MuJoCo model."""

    free_joint: bool = Field(
        False, description="Give the robot's root body a free joint (a floating base)."
    )
    fuse_static: bool = Field(
        True,
        description=(
            "Merge links attached by fixed joints into their parent body. Their names stay "
            "addressable as sites."
        ),
    )
    link_sites: Literal["all", "fused"] = Field(
        "all",
        description=(
            "Which URDF links get a site of their name: 'all' (as the mujoco_ros2_control "
            "converter does, so sensors and cameras can refer to any link) or only 'fused' "
            "links, which have no body of their own."
        ),
    )


class Scene(StrictModel):
    """The scene file written next to the robot: floor, light and sky around the robot."""

    file: RelPath | None = Field(
        None,
        description=(
            "Use this scene file verbatim instead of generating one. It should include the "
            "robot file by name."
        ),
    )


class Output(StrictModel):
    """Where the model is written."""

    folder: RelPath = Field("mjcf", description="Output folder, relative to robot.yaml.")
    robot: FileName | None = Field(
        None, description="File name of the robot model. Default: '<name>.xml'."
    )
    scene: FileName = Field("scene.xml", description="File name of the scene.")

    @model_validator(mode="after")
    def _distinct_files(self) -> Output:
        if self.robot is not None and self.robot == self.scene:
            raise ValueError("robot and scene must be different files")
        return self


class Manifest(StrictModel):
    """A robot build: its sources, how to convert them, and where the model goes."""

    name: str = Field(
        pattern=NAME_PATTERN,
        description="Name of the robot; the model is written to '<output.folder>/<name>.xml'.",
    )
    source: Source
    packages: dict[str, RelPath] = Field(
        default_factory=dict,
        description=(
            "ROS package name -> folder, for package:// URIs and xacro's $(find pkg). "
            "Packages not listed are looked up in ROS_PACKAGE_PATH and AMENT_PREFIX_PATH."
        ),
    )
    options: Options = Field(default_factory=Options)
    scene: Scene = Field(default_factory=Scene)
    output: Output = Field(default_factory=Output)

    @field_validator("packages")
    @classmethod
    def _package_names(cls, value: dict[str, str]) -> dict[str, str]:
        for name in value:
            if not PACKAGE_PATTERN.match(name):
                raise ValueError(f"'{name}' is not a valid ROS package name")
        return value

    @model_validator(mode="after")
    def _scene_not_robot(self) -> Manifest:
        if self.robot_file == self.output.scene:
            raise ValueError(
                f"the robot file and the scene file are both '{self.output.scene}'; "
                "set output.robot or output.scene"
            )
        return self

    @computed_field
    @property
    def robot_file(self) -> str:
        """File name of the robot model inside the output folder."""
        return self.output.robot or f"{self.name}.xml"
