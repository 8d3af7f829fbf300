"""The pydantic models of ``robot.yaml``.

Every model forbids unknown keys, so a typo is an error that names the key and lists the allowed
ones instead of being silently ignored. Paths are kept as written; they are relative to the
manifest's folder and resolved by :class:`mjcfbuild.graph.context.GraphContext`.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Annotated, Any, Literal

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    computed_field,
    field_validator,
    model_validator,
)

from mjcfbuild.collision.policy import POLICIES, POLICY_NAMES, policies_described
from mjcfbuild.inputs.model import RAW_SECTIONS
from mjcfbuild.inputs.processed import CameraInput, DecomposeInput, LidarInput, ModifyInput
from mjcfbuild.manifest.composition import Attachment, check_prefixes
from mjcfbuild.manifest.motors import MotorSettings
from mjcfbuild.manifest.simulation import (
    ActuatorSettings,
    Placement,
    SelfCollisionSettings,
)
from mjcfbuild.sources.packages import PACKAGE_PATTERN

NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.-]*$"

RelPath = Annotated[str, Field(min_length=1, description="A path, relative to robot.yaml.")]
FileName = Annotated[
    str,
    Field(pattern=NAME_PATTERN, description="A plain file name (no folders)."),
]


class StrictModel(BaseModel):
    """Base of every manifest model: unknown keys are errors."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class Source(StrictModel):
    """Where the robot description comes from: one of ``urdf``, ``xacro``, ``description``."""

    urdf: RelPath | None = Field(None, description="A URDF file.")
    xacro: RelPath | None = Field(
        None, description="A xacro file, expanded in-process with the given args."
    )
    args: dict[str, str | int | float | bool] = Field(
        default_factory=dict,
        description=(
            "xacro arguments (name: value), as `name:=value` on the xacro command line: values "
            "stripped of surrounding spaces, an empty value ignored (the default applies)."
        ),
    )
    description: RelPath | None = Field(
        None,
        description=(
            "A robot description (URDF text) read from a file, or from standard input with '-'. "
            "Relative mesh paths in it are relative to robot.yaml's folder."
        ),
    )
    read_outside: bool = Field(
        False,
        description=(
            "The description reads meshes or textures from outside every package folder and "
            "robot.yaml's folder on purpose: do not warn about them."
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

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
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
        False,
        description=(
            "Give the robot's root body a free joint (a floating base). For a URDF rooted at "
            "a `world` link, what the world holds floats as one whole: the heaviest link fixed "
            "to it gets the free joint and carries the rest."
        ),
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


class MeshSettings(StrictModel):
    """How mesh files are converted."""

    max_faces: int | None = Field(
        None,
        gt=3,
        description=(
            "Face budget of the visual meshes of each mesh file: heavier ones are simplified "
            "(quadric decimation), with a warning. Default: no budget (meshes are written as "
            "OBJ, which MuJoCo reads at any size)."
        ),
    )
    collision_max_faces: int | None = Field(
        None,
        gt=3,
        description=(
            "Face budget of a mesh used as collision geometry (authored or visual policy), "
            "apart from the visual budget. Default: no budget."
        ),
    )
    max_hull_vertices: int | None = Field(
        None,
        gt=3,
        description=(
            "Most vertices of any convex hull the model collides with: hulls of the hull and "
            "primitive policies, CoACD parts (max_ch_vertex), and MuJoCo's own hulls of "
            "collision meshes (maxhullvert). Fewer vertices make contacts cheaper. Default: "
            "no limit."
        ),
    )
    max_file_mb: float = Field(
        500,
        gt=0,
        description=(
            "Largest mesh file to read, in megabytes (10^6 bytes). Bigger files are refused "
            "before they are loaded, since loading one can exhaust the memory of a CI machine."
        ),
    )
    collada_up_axis: Literal["auto", "ignore", "apply"] = Field(
        "auto",
        description=(
            "What to do with a DAE file's <up_axis> when it says Y_UP or X_UP: 'auto' decides "
            "per file from the links that use it (their collision primitives, centre of mass "
            "and joint origins fit the mesh better turned or as written; the report says which "
            "files were turned and why); 'ignore' uses the coordinates as they are, as ROS "
            "tools draw them; 'apply' rotates them to Z up."
        ),
    )
    collada_up_axis_files: dict[str, Literal["ignore", "apply"]] = Field(
        default_factory=dict,
        description=(
            "Per-file choices that win over collada_up_axis: a file name or glob (matched "
            "against the end of the mesh file's path, e.g. 'torso.dae' or 'meshes/arm_*.dae') "
            "-> 'ignore' or 'apply'."
        ),
    )


class CoacdParams(StrictModel):
    """Convex decomposition parameters: when to keep the hull, and CoACD's own (the names of
    ``coacd.run_coacd``)."""

    threshold: float = Field(
        0.05, gt=0, le=1, description="Concavity threshold: lower gives more, tighter parts."
    )
    hull_tolerance: float | None = Field(
        None,
        ge=0,
        le=1,
        allow_inf_nan=False,
        description=(
            "Keep a mesh's convex hull (one part, no CoACD) when the hull stands off the mesh "
            "by at most this, in the threshold's units (relative to half the mesh's largest "
            "extent). Default (null): the threshold. 0 runs CoACD on every mesh."
        ),
    )
    scale_to_mesh: bool = Field(
        True,
        description=(
            "Scale CoACD's remeshing resolution and tree search to what the threshold can "
            "resolve on each mesh (much faster on detailed meshes); false passes the "
            "parameters below to CoACD unchanged."
        ),
    )
    max_convex_hull: int = Field(-1, description="Most parts to keep; -1 for no limit.")
    preprocess_mode: Literal["auto", "on", "off"] = "auto"
    preprocess_resolution: int = Field(50, gt=0)
    resolution: int = Field(2000, gt=0)
    mcts_nodes: int = Field(20, gt=0)
    mcts_iterations: int = Field(150, gt=0)
    mcts_max_depth: int = Field(3, gt=0)
    pca: bool = False
    merge: bool = True
    decimate: bool = False
    max_ch_vertex: int = Field(256, gt=3)
    extrude: bool = False
    extrude_margin: float = Field(0.01, ge=0)
    approximate_mode: Literal["ch", "box"] = "ch"
    seed: int = Field(0, ge=0, description="Random seed; fixed so results are reproducible.")

    @field_validator("hull_tolerance", mode="before")
    @classmethod
    def _tolerance_is_a_number(cls, value: object) -> object:
        if isinstance(value, bool):  # YAML's yes/no would otherwise read as 1.0 and 0.0
            raise ValueError("use a number between 0 and 1 (0 runs CoACD on every mesh)")
        return value


# The names of collision.policy.POLICIES (mypy sees a str; the schema, their enum).
if TYPE_CHECKING:
    Policy = str
else:
    Policy = Literal[POLICY_NAMES]
DECOMPOSING = [name for name, policy in POLICIES.items() if policy.coacd]


class CollisionRule(StrictModel):
    """Use ``policy`` for the links and/or meshes whose names match the patterns."""

    links: list[str] = Field(
        default_factory=list, description="Link name patterns (* and ? wildcards)."
    )
    meshes: list[str] = Field(
        default_factory=list,
        description="Mesh patterns, matched against the file name, its stem, the URI and "
        "mjcfbuild's mesh name.",
    )
    policy: Policy = Field(
        description=f"The geometry the matched shapes collide with: {policies_described()}."
    )
    decompose: dict[str, float | int | bool | str] = Field(
        default_factory=dict,
        description="CoACD parameters for this rule, over those of collision.decompose.",
    )

    @model_validator(mode="after")
    def _has_patterns(self) -> CollisionRule:
        if not self.links and not self.meshes:
            raise ValueError("a rule needs 'links' or 'meshes' patterns")
        if self.decompose and self.policy not in DECOMPOSING:
            raise ValueError(
                f"decompose parameters only apply to policy: {' or '.join(DECOMPOSING)}"
            )
        unknown = sorted(set(self.decompose) - set(CoacdParams.model_fields))
        if unknown:
            raise ValueError(
                f"unknown CoACD parameter(s) {', '.join(unknown)}; "
                f"allowed: {', '.join(sorted(CoacdParams.model_fields))}"
            )
        try:  # here, so a bad value is reported at its rule, not as an internal error
            CoacdParams.model_validate(self.decompose)
        except ValidationError as error:
            first = error.errors()[0]
            where = ".".join(str(part) for part in first["loc"])
            raise ValueError(f"decompose.{where}: {first['msg']}") from None
        return self


class CollisionSettings(StrictModel):
    """Which geometry each link collides with."""

    default: Policy = Field(
        "authored",
        description=(f"Policy for every link and mesh no rule matches: {policies_described()}."),
    )
    decompose: CoacdParams = Field(
        default_factory=CoacdParams, description="Default CoACD parameters."
    )
    rules: list[CollisionRule] = Field(
        default_factory=list, description="Rules in order; the first that matches wins."
    )

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def decompose_defaults(self) -> dict:
        """The default CoACD parameters as a plain mapping."""
        return self.decompose.model_dump()

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def effective_rules(self) -> list[dict]:
        """The rules with their complete, validated CoACD parameters."""
        result = []
        for rule in self.rules:
            params = CoacdParams(**{**self.decompose.model_dump(), **rule.decompose})
            result.append(
                {
                    "links": list(rule.links),
                    "meshes": list(rule.meshes),
                    "policy": rule.policy,
                    "decompose": params.model_dump() if rule.policy in DECOMPOSING else {},
                }
            )
        return result


class InertiaSettings(StrictModel):
    """What to do with masses and inertias MuJoCo would refuse."""

    policy: Literal["repair", "fail"] = Field(
        "repair",
        description="'repair' fixes them minimally and lists every change; 'fail' stops the build.",
    )
    min_mass: float = Field(1e-4, gt=0, description="Smallest mass of a moving body (kg).")
    min_inertia: float = Field(
        1e-8, gt=0, description="Smallest principal inertia of a moving body (kg m^2)."
    )
    missing: Literal["placeholder", "geometry"] = Field(
        "placeholder",
        description="A link with geometry but no <inertial> (or mass 0): 'placeholder' gives a "
        "moving one min_mass and says so (a robot with no mass at all is refused); 'geometry' "
        "gives it the mass, centre of mass and inertia of its collision geometry (its visual "
        "geometry where it has none) at `density`, as MuJoCo's own URDF import does.",
    )
    density: float = Field(
        1000.0,
        gt=0,
        description="Density (kg/m^3) of the geometry that gives links their mass with "
        "missing: geometry. Default: 1000, MuJoCo's.",
    )

    @model_validator(mode="after")
    def _density_needs_geometry(self) -> InertiaSettings:
        if "density" in self.model_fields_set and self.missing != "geometry":
            raise ValueError(
                "density is the density of the geometry that gives links without <inertial> "
                "their mass; it needs missing: geometry"
            )
        return self


class CacheSettings(StrictModel):
    """The cache of converted meshes and decompositions, shared by every build."""

    enabled: bool = True
    folder: RelPath | None = Field(
        None,
        description="Cache folder (relative to robot.yaml). Default: $MJCFBUILD_CACHE_DIR, "
        "else $XDG_CACHE_HOME/mjcfbuild, else ~/.cache/mjcfbuild.",
    )
    max_size: str | None = Field(
        None,
        pattern=r"^\s*[0-9.]+\s*[KkMmGgTt]?[iI]?[bB]?\s*$",
        description="Size cap, for example '2G'; least recently used entries go first. "
        "Default: $MJCFBUILD_CACHE_MAX, else 5G.",
    )
    remote: str | None = Field(
        None,
        description="A remote cache shared by machines: s3://bucket/prefix, gs://bucket/prefix, "
        "https://host/prefix (read-only) or a shared folder. $MJCFBUILD_CACHE_REMOTE wins; "
        "build --no-remote turns it off.",
    )

    @field_validator("remote")
    @classmethod
    def _remote_address(cls, value: str | None) -> str | None:
        from mjcfbuild.sharing_settings import AddressError, parse_remote

        if value is not None:
            try:
                parse_remote(value)
            except AddressError as exc:
                raise ValueError(str(exc)) from None
        return value


class MujocoInputs(StrictModel):
    """What the model gets beyond the URDF, as the reference converter's inputs can say it.

    The same can come from <mujoco_inputs> in the URDF and from a separate inputs file; when
    two places say the same thing, robot.yaml wins over the inputs file, which wins over the
    URDF, and the build warns.
    """

    file: RelPath | None = Field(
        None, description="An inputs file in the reference converter's <mujoco_inputs> format."
    )
    raw: str | None = Field(
        None,
        description=f"Raw MJCF copied into the model: {', '.join(RAW_SECTIONS)} sections.",
    )
    # One list per processed tag (inputs.processed.PROCESSED_INPUTS), named by its manifest_key.
    cameras: list[CameraInput] = Field(default_factory=list)
    lidars: list[LidarInput] = Field(default_factory=list)
    modify: list[ModifyInput] = Field(default_factory=list)
    decompose: list[DecomposeInput] = Field(default_factory=list)


# More link-pose configurations than this is no more evidence, only minutes of waiting.
MOST_CONFIGURATIONS = 10_000


class CheckSettings(StrictModel):
    """The check that ends every build (also ``mjcfbuild check``)."""

    enabled: bool = Field(True, description="Check the model against the URDF after building.")
    previews: bool = Field(True, description="Render preview pictures for the report.")
    tuning: bool = Field(
        True,
        description="Measure each actuator group's step and sine response for the report "
        "(docs/simulation.md, the tuning report).",
    )
    configurations: int = Field(
        20,
        ge=1,
        le=MOST_CONFIGURATIONS,
        description="Random joint configurations for the kinematics check.",
    )
    position_tolerance: float = Field(1e-6, gt=0, description="Largest link position error (m).")
    rotation_tolerance: float = Field(1e-6, gt=0, description="Largest link rotation error (rad).")
    steps: int = Field(2000, ge=1, le=1_000_000, description="Zero-control simulation steps.")
    hold_tolerance: float = Field(
        0.05,
        gt=0,
        description="Largest joint deviation (rad or m) of a fixed-base robot holding its home "
        "pose for 1 s.",
    )


class Scene(StrictModel):
    """The scene file written next to the robot: floor, light and sky around the robot.

    Without ``file`` or ``mjcf`` (and without a <scene> in the inputs), a default scene.
    """

    file: RelPath | None = Field(
        None,
        description=(
            "Use this scene file verbatim instead of generating one. It should include the "
            "robot file by name."
        ),
    )
    mjcf: str | None = Field(
        None,
        description="MJCF the scene holds besides the robot (statistic, visual, asset, "
        "worldbody, option), like the inputs' <scene> block.",
    )

    @model_validator(mode="after")
    def _one(self) -> Scene:
        if self.file and self.mjcf:
            raise ValueError("give scene.file or scene.mjcf, not both")
        return self


RESERVED_OUTPUT_NAMES = {"assets", "report", ".mjcfbuild"}


def urdf_file_name(value: object) -> object:
    """``value``, an output URDF's file name; a ValueError that says what is expected where it
    is none (``true``, a path with folders: "is not a valid name" said neither)."""
    expected = (
        "a file name such as 'my_robot.urdf', written in the output folder "
        "(or a mapping with file, meshes, asset_prefix and sites)"
    )
    if value is True:
        raise ValueError(f"expected {expected}, got true")
    if value is False:
        raise ValueError(f"expected {expected}, got false; leave the key out for no URDF")
    if isinstance(value, str) and re.search(r"[/\\]", value):
        name = re.split(r"[/\\]", value)[-1] or "my_robot.urdf"
        raise ValueError(
            f"{value!r} names a folder; expected a file name such as '{name}', written in "
            "the output folder (output.folder chooses that folder)"
        )
    return value


class UrdfExport(StrictModel):
    """A URDF of the built model, for RViz, MoveIt and other ROS tools."""

    file: FileName = Field(description="File name of the URDF, in the output folder.")

    @field_validator("file", mode="before")
    @classmethod
    def _file_name(cls, value: object) -> object:
        return urdf_file_name(value)

    meshes: FileName | None = Field(
        None,
        description=(
            "Folder (in the output folder) for the URDF's OBJ and MTL files. "
            "Default: '<file stem>_meshes'."
        ),
    )
    asset_prefix: str | None = Field(
        None,
        description=(
            "How the URDF names its mesh files, e.g. 'package://my_robot_description/mjcf/"
            "robot_meshes/'. Default: the mesh folder relative to the URDF."
        ),
    )
    sites: bool = Field(True, description="Export sites (link frames, sensors) as frame links.")

    @model_validator(mode="after")
    def _names(self) -> UrdfExport:
        if self.mesh_folder in RESERVED_OUTPUT_NAMES:
            raise ValueError(f"'{self.mesh_folder}' is used by the build; choose another 'meshes'")
        return self

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def mesh_folder(self) -> str:
        """The mesh folder's name."""
        return self.meshes or f"{self.file.rsplit('.', 1)[0]}_meshes"


class FloorContacts(StrictModel):
    """Which links of the training variant touch the floor, beyond the default."""

    add: list[str] = Field(
        default_factory=list, description="Links that also collide with the floor."
    )
    remove: list[str] = Field(
        default_factory=list, description="Links that do not collide with the floor."
    )


class TrainingVariant(StrictModel):
    """The training variant for batched simulation (MuJoCo Warp, MJX): primitive collision
    geometry, contacts limited to the floor and the self pairs that matter, bounded solver work.
    See docs/simulation.md."""

    file: FileName | None = Field(
        None, description="File name of the variant. Default: '<name>_mjx.xml'."
    )
    scene: FileName = Field("scene_mjx.xml", description="File name of the variant's scene.")
    floor_contacts: FloorContacts = Field(
        default_factory=FloorContacts,
        description=(
            "Links added to or removed from the default floor contacts (links touching the "
            "floor at home, and end effectors)."
        ),
    )
    self_contacts: bool = Field(
        False,
        description=(
            "Keep the self-collision pairs the matrix finds touching sometimes (off by "
            "default: the floor contacts alone, as trainers' feet-only set-ups have)."
        ),
    )
    max_hull_vertices: int = Field(
        16, ge=4, le=256, description="Most vertices of a hull, where no primitive fits a link."
    )
    primitive_fit: float = Field(
        2.0,
        ge=1.0,
        le=100.0,
        description=(
            "A primitive replaces a link's collision geometry when its volume is at most this "
            "many times the geometry's convex hull; otherwise a capped hull does."
        ),
    )
    device: Literal["gpu", "cpu"] = Field(
        "gpu",
        description=(
            "Where the variant will run: gpu (MuJoCo Warp or MJX on a GPU) or cpu (MuJoCo Warp "
            "on a CPU). Picks the solver: newton on a gpu (MuJoCo Menagerie's and Playground's "
            "training settings), cg on a cpu (measured fastest there)."
        ),
    )
    iterations: int | None = Field(
        None,
        ge=1,
        le=1000,
        description="Constraint solver iterations. Default: the solver's (newton 1, cg 2).",
    )
    ls_iterations: int | None = Field(
        None,
        ge=1,
        le=1000,
        description="Line search iterations. Default: the solver's (newton 5, cg 4).",
    )
    solver: Literal["cg", "newton"] | None = Field(
        None,
        description=(
            "Constraint solver: cg (no Hessian to factorize at each iteration) or newton "
            "(fewer iterations to converge). Default: the device's."
        ),
    )
    timestep: float | None = Field(
        None, gt=0, le=1, description="Simulation timestep (s). Default: the model's."
    )
    frictionloss: bool = Field(
        False,
        description=(
            "Keep the joints' dry friction (frictionloss): one solver constraint per joint "
            "at every step, about as costly as the rest of a quadruped's step in MuJoCo Warp."
        ),
    )
    dcmotor: bool = Field(
        False,
        description=(
            "Keep <dcmotor> servos (the torque-speed lines of motors and URDF limits), which "
            "only MuJoCo Warp runs; by default they become <position> servos with the same "
            "gains and force limits, which MJX runs too."
        ),
    )


def _also_boolean(schema: dict[str, Any]) -> None:
    """A setting that also takes true or false (turned into its settings before validation)."""
    schema["anyOf"] = [*schema.get("anyOf", []), {"type": "boolean"}]


class Output(StrictModel):
    """Where the model is written."""

    folder: RelPath = Field("mjcf", description="Output folder, relative to robot.yaml.")
    allow_outside: bool = Field(
        False,
        description=(
            "Let 'folder' leave the folder tree of robot.yaml (an absolute path, '..', or a "
            "link pointing elsewhere); otherwise such a folder is refused."
        ),
    )
    robot: FileName | None = Field(
        None, description="File name of the robot model. Default: '<name>.xml'."
    )
    scene: FileName = Field("scene.xml", description="File name of the scene.")
    package: bool = Field(
        False,
        description=(
            "Also write a MuJoCo Menagerie-grade folder of the model in '<folder>/package': "
            "the model formatted the Menagerie way, scene, assets, README, the description's "
            "LICENSE, a CHANGELOG kept across builds and '<name>.png'."
        ),
    )
    page: bool = Field(
        False,
        description=(
            "Also write the interactive report page, '<folder>/report/index.html': the robot in "
            "3D with joint sliders and the checks played in MuJoCo's WebAssembly build, which "
            "the first build downloads from npm (about 5.5 MB, cached); it opens from file:// "
            "with no server or network. docs/review.md says more."
        ),
    )
    urdf: UrdfExport | FileName | None = Field(
        None,
        description=(
            "Also write a URDF of the built model: a file name, or a mapping with file, "
            "meshes, asset_prefix and sites."
        ),
    )
    training: TrainingVariant | None = Field(
        None,
        description=(
            "Also write a training variant for MuJoCo Warp / MJX ('<name>_mjx.xml' and "
            "'scene_mjx.xml'): true, or a mapping of its settings."
        ),
        json_schema_extra=_also_boolean,
    )

    @field_validator("training", mode="before")
    @classmethod
    def _training_switch(cls, value: object) -> object:
        # true: the defaults; false: no variant (a mapping's errors keep their key path)
        if value is True:
            return {}
        return None if value is False else value

    @field_validator("urdf", mode="before")
    @classmethod
    def _urdf_switch(cls, value: object) -> object:
        # true and false name no file ("expected a non-empty string, got True")
        if isinstance(value, (bool, str)):
            return urdf_file_name(value)
        return value

    @field_validator("urdf")
    @classmethod
    def _urdf_file_alone(cls, value: UrdfExport | str | None) -> UrdfExport | None:
        return UrdfExport(file=value) if isinstance(value, str) else value

    @model_validator(mode="after")
    def _distinct_files(self) -> Output:
        if self.robot is not None and self.robot == self.scene:
            raise ValueError("robot and scene must be different files")
        # _urdf_file_alone has made a file name a UrdfExport; the field's type still admits str
        if isinstance(self.urdf, UrdfExport) and self.urdf.file in (self.robot, self.scene):
            raise ValueError("the URDF must be a file of its own")
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
    attach: list[Attachment] = Field(
        default_factory=list,
        description="Parts attached to the main source (a gripper on an arm, an arm on a base), "
        "each built like the main source, its names prefixed; see docs/composition.md.",
    )
    options: Options = Field(default_factory=Options)
    meshes: MeshSettings = Field(default_factory=MeshSettings)
    collision: CollisionSettings = Field(default_factory=CollisionSettings)
    inertia: InertiaSettings = Field(default_factory=InertiaSettings)
    cache: CacheSettings = Field(default_factory=CacheSettings)
    mujoco_inputs: MujocoInputs = Field(default_factory=MujocoInputs)
    actuators: ActuatorSettings = Field(default_factory=ActuatorSettings)
    motors: MotorSettings = Field(default_factory=MotorSettings)
    home: dict[str, float] = Field(
        default_factory=dict,
        description=(
            "The home pose: joint name pattern -> position (rad or m); the first matching "
            "pattern wins. Joints not named take their ros2_control initial_value, else 0 "
            "(clipped into their range)."
        ),
    )
    self_collision: SelfCollisionSettings | Literal["none"] = Field(
        default_factory=SelfCollisionSettings,
        description="Which robot body pairs may collide; 'none' writes no contact excludes.",
    )
    placement: Placement = Field(default_factory=Placement)
    check: CheckSettings = Field(default_factory=CheckSettings)
    scene: Scene = Field(default_factory=Scene)
    output: Output = Field(default_factory=Output)
    executor: str | None = Field(
        None,
        description="Where mesh conversions and decompositions run: 'local' (default) or "
        "dask://host:port. --executor and $MJCFBUILD_EXECUTOR win.",
    )

    @field_validator("executor")
    @classmethod
    def _executor_address(cls, value: str | None) -> str | None:
        from mjcfbuild.sharing_settings import AddressError, parse_executor

        if value is not None:
            try:
                parse_executor(value)
            except AddressError as exc:
                raise ValueError(str(exc)) from None
        return value

    @field_validator("attach")
    @classmethod
    def _distinct_prefixes(cls, value: list[Attachment]) -> list[Attachment]:
        return check_prefixes(value)

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
        files = self.training_files
        if files and (len(set(files)) < 2 or set(files) & {self.robot_file, self.output.scene}):
            raise ValueError(
                "the training variant and its scene need file names of their own; "
                "set output.training.file and output.training.scene"
            )
        return self

    # pydantic's documented form; mypy rejects any decorator above @property
    @computed_field  # type: ignore[prop-decorator]
    @property
    def robot_file(self) -> str:
        """File name of the robot model inside the output folder."""
        return self.output.robot or f"{self.name}.xml"

    @property
    def training(self) -> TrainingVariant | None:
        """The training variant's settings, when one is written."""
        return self.output.training

    @property
    def training_files(self) -> tuple[str, str] | None:
        """File names of the training variant and its scene, when one is written."""
        variant = self.training
        if variant is None:
            return None
        return variant.file or f"{self.name}_mjx.xml", variant.scene
