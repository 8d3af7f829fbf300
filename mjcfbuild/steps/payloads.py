"""What each build step is given: one frozen dataclass per task, the contract between the
engine (which fills them in) and the steps (which read them).

A task is up to date when its file dependencies and its *parameters* are unchanged. The
parameters are derived from every field of the payload (:meth:`Payload.uptodate_params`), so an
option added to a payload counts the moment it is added; forgetting it is not possible. A field
that must not count says so in its type, with the reason (see the aliases below):

* :class:`NotCounted` - where a result is written, a label used in messages only, or a file
  whose content doit already compares as a file dependency;
* :class:`CountedIfGiven` - a file dependency that may be absent: its content is compared by
  doit, but whether it is given at all counts (doit does not notice a dependency dropped).

Payloads travel to worker processes and cluster workers as JSON (:meth:`Payload.to_dict`) and
are rebuilt there (:meth:`Payload.from_dict`). Standard library only: the engine imports this
on every build.
"""

from __future__ import annotations

import dataclasses
import typing
from dataclasses import dataclass
from typing import Annotated, Any

from mjcfbuild.records import Record


@dataclass(frozen=True)
class NotCounted:
    """Marks a payload field that does not make its task rerun, with the reason."""

    why: str


@dataclass(frozen=True)
class CountedIfGiven:
    """Marks a file-dependency field that counts only by being given or not."""

    why: str


OUTPUT = "where the result is written: a target of the task, checked by doit and outputs_intact"
FILE_DEPENDENCY = "a file dependency: doit compares its content"

# Where a result is written.
Output = Annotated[str, NotCounted(OUTPUT)]
# A file whose content doit compares.
FileDependency = Annotated[str, NotCounted(FILE_DEPENDENCY)]
# A file dependency that may be absent: doit does not notice a dependency dropped.
OptionalFileDependency = Annotated[str | None, CountedIfGiven(FILE_DEPENDENCY)]
# Mesh id -> a file dependency (products listed by the plan, which is a dependency too).
FileDependencies = Annotated[dict[str, str], NotCounted(FILE_DEPENDENCY)]
# Text used in messages only.
MessageLabel = Annotated[str, NotCounted("used in messages only")]
# The shared product cache: where products are cached does not change them.
CacheSettings = Annotated[
    dict[str, Any], NotCounted("where products are cached does not change them")
]


@dataclass(frozen=True)
class Payload(Record):
    """The base of every task payload."""

    def uptodate_params(self) -> dict[str, Any]:
        """Every field that counts, as JSON-ready data: the task's up-to-date parameters."""
        return _counted(self)

    @classmethod
    def uncounted_fields(cls) -> dict[str, str]:
        """Field name -> the reason it does not (fully) count."""
        return {name: marker.why for name, marker in _markers(cls).items()}


_MARKERS: dict[type, dict[str, NotCounted | CountedIfGiven]] = {}


def _markers(cls: type) -> dict[str, NotCounted | CountedIfGiven]:
    """The fields of payload class ``cls`` that carry a counting marker (read once per class)."""
    found = _MARKERS.get(cls)
    if found is None:
        found = {}
        for name, hint in typing.get_type_hints(cls, include_extras=True).items():
            for extra in getattr(hint, "__metadata__", ()):
                if isinstance(extra, NotCounted | CountedIfGiven):
                    found[name] = extra
        _MARKERS[cls] = found
    return found


def _counted(value: Any) -> Any:
    if isinstance(value, Payload):
        markers = _markers(type(value))
        result = {}
        for item in dataclasses.fields(value):
            marker = markers.get(item.name)
            inner = getattr(value, item.name)
            if isinstance(marker, NotCounted):
                continue
            result[item.name] = (inner is not None) if marker else _counted(inner)
        return result
    if isinstance(value, list | tuple):
        return [_counted(v) for v in value]
    if isinstance(value, dict):
        return {k: _counted(v) for k, v in value.items()}
    return value


# The tasks, in build order ---------------------------------------------------------------


@dataclass(frozen=True)
class ExpandPayload(Payload):
    """``expand``: a xacro expanded (or a URDF read) into the build's URDF."""

    kind: str  # urdf, xacro or description
    source: str
    args: dict[str, str]
    packages: dict[str, str]
    environment: dict[str, str]  # the ROS variables package lookup reads
    output: Output
    depfile: Output
    origins: Output  # where each expanded line's element was written (xacro)
    args_key: MessageLabel  # where args were given: a manifest key, the command line, or ""
    # An argument given an empty value (which xacro ignores) -> where robot.yaml gives it
    # ("robot.yaml:7: source.args.prefix"), for the warning; counted, so the line stays right.
    empty_args: dict[str, str] = dataclasses.field(default_factory=dict)
    # robot.yaml's folder: xacro's warnings name files relative to it, as the report does.
    base_dir: str = ""
    written: MessageLabel = ""  # the source's path as robot.yaml writes it ("": not known)
    # A digest of the packages ROS_PACKAGE_PATH and AMENT_PREFIX_PATH provide (name -> folder):
    # one that appears earlier on a path shadows the one read (sources.packages).
    package_index: str = ""


@dataclass(frozen=True)
class PartEntry(Payload):
    """One ``attach:`` part as the ``compose`` step joins it."""

    urdf: FileDependency
    label: str
    key: str  # the manifest key naming the part, for messages
    prefix: str
    to: str
    xyz: list[float]
    rpy: list[float]
    base_dir: str
    packages: dict[str, str]


@dataclass(frozen=True)
class ComposePayload(Payload):
    """``compose``: the expanded parts joined to the expanded main source."""

    main: FileDependency
    main_label: str
    base_dir: str
    parts: list[PartEntry]
    environment: dict[str, str]
    output: Output
    origins: Output  # where each line's element was written (through the inputs' own)
    # A digest of the packages ROS_PACKAGE_PATH and AMENT_PREFIX_PATH provide (name -> folder):
    # one that appears earlier on a path shadows the one read (sources.packages).
    package_index: str = ""


@dataclass(frozen=True)
class PlanPayload(Payload):
    """``plan``: the URDF parsed, its files resolved, its meshes and inputs listed."""

    urdf: FileDependency
    display: str
    expanded_from: str | None
    base_dir: str
    packages: dict[str, str]
    environment: dict[str, str]
    inputs_file: str | None
    inputs_file_label: str | None
    output: Output
    prebuilt_meshes: str | None = None  # convert -a: a folder of meshes converted before
    # The folders files may be read from without a warning; None: no warning (read_outside)
    roots: list[str] | None = None
    depfile: Output = ""  # the material textures it found and looked for in vain
    # A digest of the packages ROS_PACKAGE_PATH and AMENT_PREFIX_PATH provide (name -> folder):
    # one that appears earlier on a path shadows the one read (sources.packages).
    package_index: str = ""


@dataclass(frozen=True)
class MeshOptions(Payload):
    """How one mesh file is converted (also the product's cache parameters)."""

    roles: list[str]
    max_faces: int | None
    collada_up_axis: str  # ignore, apply, or auto (the mesh step decides from the evidence)
    collision_max_faces: int | None = None
    max_hull_vertices: int | None = None

    def cache_params(self) -> dict[str, Any]:
        """The options as the product key takes them: budgets only when set, so products of
        builds without them keep the keys they had before the budgets existed."""
        params = self.to_dict()
        for optional in ("collision_max_faces", "max_hull_vertices"):
            if params[optional] is None:
                del params[optional]
        return params


@dataclass(frozen=True)
class MeshPayload(Payload):
    """``mesh:<id>``: one mesh file converted into its product."""

    source: Annotated[str, NotCounted("a file dependency; the task's name follows it")]
    options: MeshOptions
    max_file_bytes: int
    product_dir: Output
    summary: Output
    depfile: Output
    cache: CacheSettings
    # A DAE file's up axis under ``auto``: what the links using it say (meshes.upaxis).
    evidence: list[dict[str, Any]] = dataclasses.field(default_factory=list)  # MeshUse
    label: MessageLabel = ""  # the mesh file as warnings name it (relative to robot.yaml)
    # The first URDF line naming the mesh, "file:line" as the plan's errors name it: where an
    # error about the whole file points ("" where no line is known).
    named_at: MessageLabel = ""
    # convert -a: the mesh file the pre-generated OBJ ``source`` stands for, whose look it
    # takes where it has none of its own (meshes.prebuilt)
    looks_from: OptionalFileDependency = None


@dataclass(frozen=True)
class DecomposePayload(Payload):
    """``decompose:<name>``: a mesh product's collision mesh split into convex parts."""

    params: dict[str, Any]  # CoACD's keyword arguments
    product_summary: FileDependency
    product_dir: Annotated[str, NotCounted("the product's folder, named by product_summary")]
    output_dir: Output
    summary: Output
    cache: CacheSettings


@dataclass(frozen=True)
class DecompositionFiles(Payload):
    """Where a decomposition's parts are, for the steps that read them."""

    mesh_id: str
    params: dict[str, Any]
    folder: Annotated[str, NotCounted("the parts, listed by the summary")]
    summary: FileDependency


@dataclass(frozen=True)
class MjcfPartPayload(Payload):
    """``part:<prefix>``: an ``attach:`` MJCF part compiled alone and normalised."""

    source: Annotated[str, NotCounted("a file dependency, with the files it includes")]
    label: str
    assets_dir: str  # counted: the normalised part names its assets in it
    xml: Output
    summary: Output
    depfile: Output


@dataclass(frozen=True)
class MjcfPartFiles(Payload):
    """An ``attach:`` MJCF part as the assemble and check steps take it."""

    key: MessageLabel  # its place in robot.yaml, e.g. "robot.yaml attach[1]"
    prefix: str
    to: str
    pos: list[float]
    quat: list[float]
    label: MessageLabel
    source: Annotated[str, NotCounted("the part task read it; its summary is a dependency")]
    xml: FileDependency  # the normalised part
    summary: FileDependency  # compose.mjcf.PartSummary


@dataclass(frozen=True)
class SrdfPayload(Payload):
    """``srdf``: the SRDF (or its xacro) read into disabled pairs and group states."""

    source: str
    label: str
    args: dict[str, str]
    packages: dict[str, str]
    environment: dict[str, str]
    output: Output
    depfile: Output  # what it read (its includes), for the next build to check
    discovered: bool = False  # found beside the description, not named in robot.yaml
    # self_collision.home_state where robot.yaml gives it, which the SRDF must then have.
    home_state: str | None = None
    manifest_label: str = "robot.yaml"
    # A digest of the packages ROS_PACKAGE_PATH and AMENT_PREFIX_PATH provide (name -> folder):
    # one that appears earlier on a path shadows the one read (sources.packages).
    package_index: str = ""


@dataclass(frozen=True)
class SelfCollisionPayload(Payload):
    """``selfcollision``: the collision matrix of the robot's links."""

    robot: dict[str, Any]  # the collision robot (see selfcollision.robot)
    choices: list[dict[str, Any]]  # collision.policy.CollisionChoice
    fuse_static: bool
    free_joint: bool
    decompositions: list[DecompositionFiles]
    initial: dict[str, float]  # ros2_control initial values
    home: dict[str, float]
    keep: list[list[str]]
    home_state: str
    settings: dict[str, Any]  # selfcollision.matrix.MatrixSettings
    srdf: OptionalFileDependency
    products: FileDependencies
    product_dirs: Annotated[dict[str, str], NotCounted("the folders of the products")]
    manifest_label: MessageLabel
    cache: CacheSettings
    output: Output
    # attach: MJCF parts, whose geoms the matrix covers against the rest of the model; their
    # files count through part_digests (selfcollision.parts), not as file dependencies.
    mjcf_parts: list[MjcfPartFiles] = dataclasses.field(default_factory=list)
    part_digests: list[str] = dataclasses.field(default_factory=list)


@dataclass(frozen=True)
class AssemblePayload(Payload):
    """``assemble``: the MJCF written from the plan, the products and the settings."""

    choices: list[dict[str, Any]]  # collision.policy.CollisionChoice, made once by the engine
    decompositions: list[DecompositionFiles]
    inputs: dict[str, Any]  # the MuJoCo inputs from the URDF, the inputs file and robot.yaml
    actuators: dict[str, Any]  # manifest.simulation.ActuatorSettings
    motors: dict[str, Any]  # the motors actuators.rules name: name -> datasheet values
    home: dict[str, float]
    floor: float | str
    srdf_home: str | None
    fuse_static: bool
    free_joint: bool
    link_sites: str
    max_hull_vertices: int | None
    inertia: dict[str, Any]  # mjcf.inertia.InertiaPolicy
    header: str
    assets_dir: str  # counted: the model names its assets relative to it
    self_collision: OptionalFileDependency
    srdf: OptionalFileDependency
    plan: FileDependency
    products: FileDependencies
    product_dirs: Annotated[dict[str, str], NotCounted("the folders of the products")]
    manifest_label: MessageLabel
    report: Output
    floor_record: Output
    output: Output
    mjcf_parts: list[MjcfPartFiles]  # attached after the URDF model is assembled
    # Where robot.yaml writes each actuators rule's forcerange ("robot.yaml:5:
    # actuators.rules[0].forcerange"; "" for a rule without one), for the warnings that name
    # it; counted, so the line stays right.
    forcerange_at: list[str] = dataclasses.field(default_factory=list)


@dataclass(frozen=True)
class WarmPayload(Payload):
    """``warm`` (not a task): the folders of the mesh products a model is assembled from, and
    the modules of the steps the warmed worker is prepared for (imported first)."""

    folders: list[str]
    modules: list[str] = dataclasses.field(default_factory=list)


@dataclass(frozen=True)
class ScenePayload(Payload):
    """``scene``: the scene file around the robot model."""

    scene_file: str | None
    scene_block: dict[str, str] | None  # {"xml", "origin"}
    model: str  # the model's name
    robot_file: str
    floor: float | str
    floor_record: FileDependency
    output: Output


@dataclass(frozen=True)
class CheckPayload(Payload):
    """``check``: the built model proven against its source."""

    options: dict[str, Any]  # check.model_check.CheckOptions
    plan: FileDependency
    assembly_report: FileDependency
    model: FileDependency
    model_label: MessageLabel
    scene: FileDependency
    reference: FileDependency  # what the independent reader read from the URDF
    output: Output
    mjcf_parts: list[MjcfPartFiles]  # each compared with the part compiled alone
    depfile: Output = ""  # the files it read besides these (the pids_config_file), or looked for
    # robot.yaml's packages (name -> folder): where $(find pkg) put a mujoco_model param's file
    packages: dict[str, str] = dataclasses.field(default_factory=dict)


@dataclass(frozen=True)
class ReferencePayload(Payload):
    """``reference``: the URDF's kinematics as the check's independent reader reads them."""

    urdf: Annotated[str, NotCounted("read for its kinematics alone, which `kinematics` digests")]
    kinematics: str  # check.reference.kinematic_digest of the URDF text
    cache: CacheSettings
    output: Output


@dataclass(frozen=True)
class PreviewsPayload(Payload):
    """``previews``: pictures of the scene at home."""

    folder: str
    model: Annotated[str, NotCounted("the scene: what the pictures show is compared by digest")]
    assembly_report: Annotated[
        str, NotCounted("names the products the assets were published from: speed, not content")
    ]
    record: Output  # each picture in ``folder`` with what it shows, to keep those unchanged
    cache: CacheSettings


@dataclass(frozen=True)
class TuningPayload(Payload):
    """``tuning``: each actuator group's step and sine response in the built model."""

    folder: str  # the plots (counted: the record names them relative to the report)
    rules: list[dict[str, Any]]  # actuators.rules: the groups' labels
    model: FileDependency
    assembly_report: FileDependency  # the actuators (with their rules) and the asset sources
    record: Output


@dataclass(frozen=True)
class ExportUrdfPayload(Payload):
    """``export_urdf``: the built model written back as URDF."""

    options: dict[str, Any]
    model: FileDependency
    plan: FileDependency  # the source URDF's velocity limits
    assembly_report: FileDependency  # the drives behind the actuators
    urdf: Output
    mesh_dir: Annotated[str, NotCounted("named by options.mesh_folder")]
    record: Output


@dataclass(frozen=True)
class PackagePayload(Payload):
    """``package``: a Menagerie-grade folder of the model (``output.package: true``)."""

    name: str
    provenance: dict[str, str]  # source, robot.yaml's text, versions, the license's name
    # The git revision and remote the README names: as of the package's last change, since a
    # commit alone (of the package itself, say) changes nothing the model is built from.
    git: Annotated[dict[str, str], NotCounted("no input of the model: a commit changes it")]
    model: FileDependency
    scene: FileDependency
    assembly_report: FileDependency  # lists each asset with its MD5: the assets count through it
    assets: Annotated[str, NotCounted("the assets' bytes count through the assembly report")]
    check: OptionalFileDependency
    picture: OptionalFileDependency
    license: OptionalFileDependency
    folder: Output
    record: Output  # the packaged model's snapshot: what the next CHANGELOG entry compares with


@dataclass(frozen=True)
class PagePayload(Payload):
    """``page``: the interactive report page (``output.page: true``)."""

    name: str
    mujoco_js: str  # the pinned @mujoco/mujoco version and its integrity: the page embeds it
    model: FileDependency
    scene: FileDependency
    assembly_report: FileDependency  # lists each asset with its MD5: the assets count through it
    assets: Annotated[str, NotCounted("the assets' bytes count through the assembly report")]
    hold_tolerance: float  # what the page's hold and stand tests allow
    folder: Output  # the report folder: index.html and page/


@dataclass(frozen=True)
class TrainingPayload(Payload):
    """``training``: the training variant for batched simulation, and its scene."""

    settings: dict[str, Any]  # training.variant.VariantSettings
    header: str
    model: FileDependency  # the full model, which the variant is made from
    self_collision: OptionalFileDependency  # the collision matrix, for the self pairs
    robot_file: str  # the full model's file name, which a user's scene file includes
    scene: ScenePayload  # the variant's scene (robot_file: the variant's)
    output: Output
    record: Output
