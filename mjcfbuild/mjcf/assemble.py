"""Assembling the robot model on ``mujoco.MjSpec``.

The prepared URDF (see :mod:`mjcfbuild.mjcf.prepared`) is loaded into an MjSpec, then edited
through the API: Menagerie-style ``visual`` and ``collision`` classes, mesh and material
assets with stable names, a site for every link, an optional free joint, and an ``info`` string
on every element pointing at its line in the URDF so MuJoCo's compile errors do too. The model
is written with :func:`precise_xml` and the compiler settings it needs to load again.
"""

from __future__ import annotations

from copy import deepcopy
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lxml import etree

from mjcfbuild.actuators import ACTUATOR_TAGS, ActuatorRecord
from mjcfbuild.collision.policy import CollisionChoice, choose_collisions
from mjcfbuild.compose.attach import AttachedPart, attach_parts, part_frames, publish_part_files
from mjcfbuild.control.apply import Readiness
from mjcfbuild.control.stand_up import crouched_home, described_nothing, replace_tree, stands
from mjcfbuild.errors import ModelError
from mjcfbuild.inputs.gazebo import GazeboSensor
from mjcfbuild.inputs.model import Inputs
from mjcfbuild.inputs.processed import CameraInput
from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.manifest.simulation import ActuatorSettings
from mjcfbuild.meshes.product import MeshProduct
from mjcfbuild.mjcf.bodies import WORLD, Body, build_bodies, ground_notes, link_places
from mjcfbuild.mjcf.compile_errors import body_error, compile_error, spec_meshes, too_thin_mesh
from mjcfbuild.mjcf.depth import refuse_deep_bodies
from mjcfbuild.mjcf.geometry_mass import GeometryMass, with_geometry_masses
from mjcfbuild.mjcf.inertia import InertiaPolicy, Repair, validate_masses
from mjcfbuild.mjcf.precise import precise_xml
from mjcfbuild.mjcf.prepared import Decomposition, GeomRecord, Prepared, prepare
from mjcfbuild.mjsensors import without_sensors
from mjcfbuild.mjwarnings import capture_mujoco_warnings, take_mujoco_warnings
from mjcfbuild.sources.expand import COMMAND_LINE
from mjcfbuild.urdf.model import Robot

VISUAL_CLASS = "visual"
COLLISION_CLASS = "collision"
LINK_SITE_CLASS = "link_site"
OUTPUT_COMPILER = {
    "angle": "radian",
    "meshdir": "assets",
    "texturedir": "assets",
    "inertiafromgeom": "false",
}
# Attributes of a URDF's own <mujoco><compiler> that mjcfbuild decides itself.
_OWNED_COMPILER = {*OUTPUT_COMPILER, "discardvisual", "fusestatic", "strippath"}


@dataclass
class AssemblyOptions:
    """The manifest settings the assembly uses."""

    fuse_static: bool = True
    free_joint: bool = False  # robot.yaml's: a free joint on the root (and on what world holds)
    floating: bool = False  # the base floats: free_joint, or the URDF's own floating joint
    link_sites: str = "all"
    max_hull_vertices: int | None = None  # MuJoCo's maxhullvert on collision meshes
    inertia: InertiaPolicy = field(default_factory=InertiaPolicy)
    header: str = ""
    choices: list[CollisionChoice] | None = None  # default: the URDF's authored collisions
    decompositions: list[Decomposition] = field(default_factory=list)
    inputs: Inputs | None = None
    control: Ros2Control | None = None
    gazebo: list[GazeboSensor] = field(default_factory=list)  # the URDF's Gazebo sensors
    actuators: ActuatorSettings = field(default_factory=ActuatorSettings)
    motors: dict[str, dict] = field(default_factory=dict)  # rules' motors: name -> datasheet
    home: dict[str, float] = field(default_factory=dict)
    home_state: dict[str, float] | None = None  # an SRDF's group_state named 'home'
    home_from: str | None = None  # which SRDF group_state that is, for the report
    excludes: list[tuple[str, str]] = field(default_factory=list)
    manifest_label: str = "robot.yaml"
    # where robot.yaml writes each actuators rule's forcerange ("robot.yaml:5:
    # actuators.rules[0].forcerange"; "" for a rule without one), for the warnings naming it
    forcerange_at: list[str] = field(default_factory=list)
    parts: list[AttachedPart] = field(default_factory=list)  # MJCF parts, in attach order


@dataclass
class Assembly:
    """The assembled model and what must be published with it."""

    xml: bytes
    assets: dict[str, str]  # published name -> the product file published under it
    repairs: list[Repair]
    warnings: list[str]
    bodies: int
    geoms: int
    readiness: Readiness | None = None
    # published name -> (file, MD5) the build's compiles read for it (mjcfbuild.meshes.mshfile)
    reads: dict[str, tuple[str, str]] = field(default_factory=dict)
    # the links given the mass of their geometry (robot.yaml's inertia.missing: geometry)
    geometry_masses: list[GeometryMass] = field(default_factory=list)


def _from_geometry(options: AssemblyOptions) -> str:
    """How to give links without a mass that of their geometry, where it is not asked for."""
    if options.inertia.missing == "geometry":
        return ""
    as_mujoco = "to give each link the mass of its geometry, as MuJoCo's own URDF import does"
    if options.manifest_label == COMMAND_LINE:
        return f"build it from a robot.yaml with inertia: {{missing: geometry}} {as_mujoco}"
    return f"set inertia: {{missing: geometry}} in {options.manifest_label} {as_mujoco}"


def _free_joint(options: AssemblyOptions) -> tuple[str, str]:
    """Where the free joint was asked for (robot.yaml's setting, or convert's ``-f``) and how
    not to ask for it."""
    if options.manifest_label == COMMAND_LINE:
        return "the command line's -f", "leave out -f"
    return f"{options.manifest_label} options.free_joint", "set free_joint: false"


def assemble(
    robot: Robot,
    products: dict[str, MeshProduct],
    product_dirs: dict[str, Path],
    options: AssemblyOptions,
) -> Assembly:
    """Build the model of ``robot`` from its converted meshes."""
    import mujoco

    capture_mujoco_warnings()
    take_mujoco_warnings()

    given: list[GeometryMass] = []
    mass_warnings: list[str] = []
    if options.inertia.missing == "geometry":
        robot, given, mass_warnings = with_geometry_masses(
            robot,
            products,
            product_dirs,
            options.inertia.density,
            options.fuse_static,
            options.free_joint,
        )
    # A floating root moves too: a massless one gets the smallest repair, reported.
    bodies = build_bodies(robot, options.fuse_static, free_joint=options.free_joint)
    refuse_deep_bodies(robot, bodies)
    lines = {
        link.name: (link.inertial.line if link.inertial else link.line) for link in robot.links
    }
    repairs = validate_masses(
        bodies,
        options.inertia,
        robot.source,
        lines,
        _free_joint(options),
        _from_geometry(options),
    )
    choices = options.choices
    if choices is None:
        choices = choose_collisions(robot, "authored", [], {})
    prepared = prepare(
        robot.name,
        bodies,
        products,
        product_dirs,
        choices,
        options.decompositions,
        robot.mujoco_compiler,
        robot.source,
    )
    try:
        spec = mujoco.MjSpec.from_string(prepared.urdf)
    except Exception as exc:
        raise ModelError(
            f"MuJoCo could not import the prepared URDF: {_first_line(exc)}", file=robot.source
        ) from None
    _finish(spec, prepared, bodies, robot, options)
    published = attach_parts(spec, link_places(bodies), options.parts)
    root = _write_with_shell_retries(spec, prepared, robot.source)
    _finish_xml(root, prepared, robot, options)
    publish_part_files(root, published)
    prepared.files.update(published)  # published with the robot's, compiled from memory
    warnings, readiness = _apply_additions(root, prepared, bodies, robot, options)
    _layout(root)
    xml = etree.tostring(root, encoding="unicode")
    header = f"<!-- {options.header} -->\n" if options.header else ""
    return Assembly(
        xml=(header + xml + "\n").encode("utf-8"),
        assets=dict(prepared.files),
        repairs=repairs,
        warnings=[
            *robot.warnings,
            *(record.describe(robot.source) for record in given),
            *mass_warnings,
            *_nothing_floats(robot, bodies, options),
            *ground_notes(robot),
            *prepared.warnings,
            *warnings,
            *(f"MuJoCo: {text}" for text in take_mujoco_warnings()),
        ],
        bodies=len(bodies),
        geoms=len(prepared.geoms),
        readiness=readiness,
        reads=dict(prepared.reads),
        geometry_masses=given,
    )


def _nothing_floats(robot: Robot, bodies: list[Body], options: AssemblyOptions) -> list[str]:
    """A warning where robot.yaml's ``free_joint`` floats nothing: the URDF's ``world`` link
    holds its robot only by moving joints (a rail, a turntable), none fixed or floating."""
    if not options.free_joint or any(body.floating for body in bodies):
        return []
    held = [joint for joint in robot.joints if joint.parent == WORLD]
    if not held or any(joint.kind == "floating" for joint in held):
        return []
    joint = held[0]
    where = f"{robot.source}:{joint.line}" if joint.line else robot.source
    return [
        f"{where}: options.free_joint floats nothing: the `world` link holds the robot by the "
        f"{joint.kind} joint '{joint.name}' and no fixed one, so the robot stays where that "
        "joint holds it (set free_joint: false, or make the joint `floating`)"
    ]


def _apply_additions(
    root, prepared: Prepared, bodies: list[Body], robot: Robot, options: AssemblyOptions
) -> tuple[list[str], Readiness]:
    """MuJoCo inputs, self-collision excludes, actuators and the home keyframe, then a compile
    of the finished model."""
    import mujoco

    from mjcfbuild.compose.control import with_parts
    from mjcfbuild.control.apply import make_ready, user_driven_joints
    from mjcfbuild.control.choose import choose_actuators
    from mjcfbuild.control.home import home_values
    from mjcfbuild.control.motors import apply_motors
    from mjcfbuild.inputs.apply import LinkPlace, apply_inputs
    from mjcfbuild.inputs.control_sensors import add_control_sensors
    from mjcfbuild.inputs.gazebo_sensors import add_gazebo_sensors
    from mjcfbuild.inputs.rays import unroll_lidar_rays
    from mjcfbuild.inputs.ros2_control import sensor_warnings
    from mjcfbuild.mjcf.arena import holds_contacts, size_arena
    from mjcfbuild.selfcollision.excludes import write_excludes

    links = {
        frame.link: LinkPlace(
            None if body.parent is None and body.name == WORLD else body.name, frame.pose
        )
        for body in bodies
        for frame in body.links
    }
    inputs = options.inputs or Inputs()
    result = apply_inputs(root, inputs, links, _mesh_aliases(prepared))
    warnings = list(result.warnings)
    control = options.control or Ros2Control()
    gazebo = add_gazebo_sensors(root, options.gazebo, control, links, robot)
    warnings += gazebo.warnings
    warnings += sensor_warnings(
        control,
        [c.name for c in inputs.of(CameraInput)] + gazebo.cameras,
        result.lidar_sensors + gazebo.lidars,
    )
    add_control_sensors(root, control, links)
    write_excludes(root, options.excludes)
    unroll_lidar_rays(root)  # MuJoCo compiles a replicated lidar's rays in quadratic time
    warnings += _ray_cost(root, result.lidar_sensors + gazebo.lidars)

    # The last model compiled from each whole tree (not a copy), by the tree's identity.
    compiled: dict[int, tuple[etree._Element, Any]] = {}

    def compile_tree(tree, drawing: bool = False) -> Any:
        copy = _reading_products(tree, prepared)
        if not drawing:
            _drop_drawing_meshes(copy)
        xml = etree.tostring(copy, encoding="unicode")
        try:
            model = without_sensors(mujoco.MjModel.from_xml_string(xml))  # trials read none
            compiled[id(tree)] = (tree, model)
            return model
        except Exception as exc:
            message = _first_line(exc).replace("Error: ", "")
            file, line = _raw_input_named(str(exc), inputs)
            from_urdf = body_error(message, str(exc), robot, bodies) if file is None else None
            if from_urdf is not None:
                raise from_urdf from None
            raise ModelError(
                f"MuJoCo rejected the model with its inputs: {message}",
                hint="check the mujoco_inputs and raw MJCF",
                file=file,
                line=line,
            ) from None

    parts = with_parts(robot, options.parts, options.actuators)
    choices = choose_actuators(
        parts.actuator_robot, control, options.actuators, user_driven_joints(root)
    )
    # issue 33: rules' motors (armature, force limits, torque-speed line); gear ratios from
    # the transmissions
    choices, motor_warnings = apply_motors(
        choices, options.actuators.rules, options.motors, control.transmissions
    )
    warnings += motor_warnings
    home = home_values(
        parts.home_robot,
        control,
        options.home,
        options.home_state,
        options.manifest_label,
        fallback=parts.fallback,
    )
    pristine = deepcopy(root)

    def ready(tree, home_values) -> Readiness:
        return make_ready(
            tree,
            parts.actuator_robot,
            choices,
            home_values,
            options.free_joint or options.floating,
            compile_tree,
            preset_qpos=parts.preset_qpos,
            preset_ctrl=parts.preset_ctrl,
            forcerange_at=options.forcerange_at,
        )

    # No compile of its own checks the inputs first: this one's failure, with the joints'
    # dynamics set, is MuJoCo's complaint about them (the same words).
    readiness = ready(root, home)
    floating = options.free_joint or options.floating
    if floating and described_nothing(home) and not stands(root, compile_tree):
        # The description gives no pose the robot stands in: try a computed crouch.
        crouched = crouched_home(root, compile_tree, home, readiness)
        if crouched is not None:
            trial = deepcopy(pristine)
            trial_readiness = ready(trial, crouched)
            if stands(trial, compile_tree):
                replace_tree(root, trial)
                compiled.pop(id(root), None)
                if id(trial) in compiled:
                    compiled[id(root)] = (root, compiled[id(trial)][1])
                readiness = trial_readiness
                readiness.home_from = (
                    "crouch mjcfbuild computed: no home pose was given (robot.yaml home:, "
                    "or an SRDF) and the robot falls from the zero pose; give home: to "
                    "choose your own"
                )
    if options.home_state:
        readiness.home_from = options.home_from
    chosen = {choice.joint for choice in choices}
    readiness.passive += [joint for joint in parts.undriven if joint not in chosen]
    readiness.actuators += _part_actuators(root, options.parts)
    warnings += readiness.notes
    # issue 40: a long chain's contacts outgrow the default arena. The last trial model of
    # the finished tree decides when it holds them: the published model differs from it only
    # by geoms that draw (more geoms, a larger arena). Otherwise, or where the inputs may
    # have changed what draws, the finished model is compiled as published.
    tree, trial_model = compiled.get(id(root), (None, None))
    if tree is not root or not inputs.is_empty() or not holds_contacts(trial_model):
        size_arena(root, compile_tree(root, drawing=True))
    return warnings, readiness


# Rays past which a model's lidars are most of a simulation step: MuJoCo casts each one against
# the geoms at every step (TIAGo Pro's 1,639 took 9 ms a step, its other work 0.07 ms).
_MANY_RAYS = 256


def _ray_cost(root: etree._Element, lidars: list[str]) -> list[str]:
    """A warning where the model's rangefinders are so many that casting them is most of
    every step of a simulation (whether or not anything reads them)."""
    rays = sum(1 for _ in root.iter("rangefinder"))
    if rays <= _MANY_RAYS:
        return []
    names = sorted(set(lidars))
    shown = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
    return [
        f"the model's {rays} rangefinders ({shown or 'lidar rays'}) are cast at every "
        "simulation step, whether or not anything reads them: with this many, most of each "
        "step's time; fewer samples in a lidar (Gazebo's <horizontal><samples>, or the lidars "
        "input's) make the model simulate faster"
    ]


def _raw_input_named(error: str, inputs: Inputs) -> tuple[str | None, int | None]:
    """Where the raw input is that MuJoCo's ``error`` is about: the first raw element holding
    an element of the tag MuJoCo names (``Element 'option', line 3``), if one does; (None,
    None) otherwise (the element came from the URDF or mjcfbuild, or MuJoCo named none)."""
    import re

    from mjcfbuild.inputs.model import origin_location

    named = re.search(r"Element '(\w+)'", error)
    # MuJoCo names a keyframe by its index ("keyframe 0: invalid ctrl size"), not its element.
    tag = named.group(1) if named else "key" if re.match(r"(Error: )?keyframe \d", error) else None
    if tag is None:
        return None, None
    for item in inputs.raw:
        try:
            element = etree.fromstring(item.xml)
        except etree.XMLSyntaxError:
            continue
        if next(element.iter(tag), None) is not None:
            return origin_location(item.origin)
    return None, None


def _reading_products(root: etree._Element, prepared: Prepared) -> etree._Element:
    """A copy of the model that reads each asset from the file it is published from, or from
    that product's binary copy (mjcfbuild.meshes.mshfile).

    The same meshes as the published assets, under the names the first compile (of the
    prepared URDF) read them by: MuJoCo caches processed meshes by file name, so every later
    compile of this build skips processing them again (seconds for a detailed robot).
    """
    copy = deepcopy(root)
    for compiler in copy.iter("compiler"):
        compiler.attrib.pop("meshdir", None)
        compiler.attrib.pop("texturedir", None)
    for element in (*copy.iter("mesh"), *copy.iter("texture")):
        name = element.get("file") or ""
        source = prepared.reads[name][0] if name in prepared.reads else prepared.files.get(name)
        if source is not None:
            element.set("file", str(source))
    return copy


def _drop_drawing_meshes(root: etree._Element) -> None:
    """Remove from ``root`` the mesh geoms that only draw the model, and the mesh assets only
    they use, where that changes nothing the compiles before the last one read (joints,
    masses, collisions, actuators): geoms of the ``visual`` class (no contacts, no mass) that
    nothing can name. Processing the meshes is most of a compile (go1's 13 MB trunk: 0.1 s
    each time, even from MuJoCo's cache); the last compile and the published model keep them.
    """
    visual = root.find("default/default[@class='visual']/geom")
    if visual is None or (visual.get("density"), visual.get("contype")) != ("0", "0"):
        return  # the inputs changed what a visual geom is
    if visual.get("conaffinity") != "0":
        return
    dropped = False
    for geom in list(root.iter("geom")):
        if geom.get("class") != "visual" or geom.get("type") != "mesh":
            continue
        if {"name", "mass", "density"} & set(geom.attrib):
            continue
        parent = geom.getparent()
        if parent is not None and parent.tag in ("body", "worldbody"):
            parent.remove(geom)
            dropped = True
    if not dropped:
        return
    used = {element.get("mesh") for element in root.iter() if element.get("mesh")}
    for asset in root.findall("asset"):
        for mesh in asset.findall("mesh"):
            if mesh.get("name") and mesh.get("name") not in used:  # unnamed: by its file
                asset.remove(mesh)


def _part_actuators(root: etree._Element, parts: list[AttachedPart]) -> list[ActuatorRecord]:
    """The MJCF parts' own actuators, for the report: the part wrote them, not mjcfbuild."""
    names = {part.prefix + name for part in parts for name in part.summary.actuators}
    section = root.find("actuator")
    records = []
    for element in section if section is not None else []:
        if element.tag in ACTUATOR_TAGS and element.get("name") in names:
            target = element.get("joint") or element.get("tendon") or element.get("site") or ""
            records.append(ActuatorRecord(element.get("name") or "", target, element.tag, "part"))
    return records


def _mesh_aliases(prepared: Prepared) -> dict[str, set[str]]:
    """Names a modify_element may use for each mesh asset: its own, the file's, the id's."""
    aliases = {}
    for asset in prepared.meshes:
        names = {asset.name, asset.mesh_id, asset.file[:-4]}
        if asset.uri:
            names |= {Path(asset.uri).stem, Path(asset.uri).name}
        aliases[asset.name] = {n for n in names if n}
    return aliases


def _write_with_shell_retries(spec, prepared: Prepared, source: str):
    """Compile and write; a mesh MuJoCo finds too thin for volume inertia gets shell inertia.

    The product summaries already flag meshes whose volume is near zero; MuJoCo's own test
    differs slightly (it measures from the mesh centre), so its verdict is followed too.
    """
    import mujoco

    for _ in range(len(prepared.meshes) + 1):
        try:
            return precise_xml(spec)
        except Exception as exc:
            text = str(exc)
            name = too_thin_mesh(text)
            mesh = spec.mesh(name) if name else None
            if mesh is None or mesh.inertia == mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL:
                named = prepared.meshes + spec_meshes(spec, prepared)
                raise compile_error(exc, source, named) from None
            mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
            prepared.warnings.append(f"mesh '{name}' encloses no volume; it uses shell inertia")
    raise ModelError("MuJoCo: too many meshes without volume")


def _first_line(exc: Exception) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def _finish(
    spec, prepared: Prepared, bodies: list[Body], robot: Robot, options: AssemblyOptions
) -> None:
    import mujoco

    spec.modelname = robot.name
    visual = spec.add_default(VISUAL_CLASS, spec.default)
    visual.geom.group = 2
    visual.geom.contype = 0
    visual.geom.conaffinity = 0
    visual.geom.density = 0
    collision = spec.add_default(COLLISION_CLASS, spec.default)
    collision.geom.group = 3
    link_site = spec.add_default(LINK_SITE_CLASS, spec.default)
    link_site.site.group = 5
    link_site.site.size = [0.005, 0.005, 0.005]

    for name, file in sorted(prepared.textures.items()):
        # Compiled from the product file; _finish_xml writes the published name.
        spec.add_texture(name=name, type=mujoco.mjtTexture.mjTEXTURE_2D, file=prepared.files[file])
    for material in prepared.materials:
        added = spec.add_material(name=material.name)
        if material.rgba is not None:
            added.rgba = list(material.rgba)
        if material.texture is not None:
            added.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = material.texture
        if material.emission is not None:
            added.emission = material.emission

    by_file = {(asset.read_file, tuple(asset.scale)): asset for asset in prepared.meshes}
    for mesh in spec.meshes:
        asset = by_file[(mesh.file, tuple(float(s) for s in mesh.scale))]
        old, mesh.name = mesh.name, asset.name
        mesh.info = _origin(robot.source, asset.line, f"mesh '{asset.uri}'")
        if asset.shell:
            mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
        for geom in spec.geoms:
            if geom.meshname == old:
                geom.meshname = asset.name

    if options.max_hull_vertices is not None:
        colliding = {r.mesh for r in prepared.geoms.values() if r.role == "collision" and r.mesh}
        for mesh in spec.meshes:
            if mesh.name in colliding:
                mesh.maxhullvert = options.max_hull_vertices

    authored = _unique_authored_names(prepared.geoms.values())
    for geom in spec.geoms:
        record = prepared.geoms[geom.name]
        _style_geom(geom, record, visual if record.role == "visual" else collision, mujoco)
        geom.info = _origin(robot.source, record.line, f"link '{record.link}' {record.role}")
        geom.name = record.authored_name if record.authored_name in authored else ""

    links = {link.name: link for link in robot.links}
    joints = {joint.name: joint for joint in robot.joints}
    for body in bodies:
        target = (
            spec.worldbody if body.parent is None and body.name == WORLD else spec.body(body.name)
        )
        if body.mass is not None and target is not spec.worldbody and target.mass > 0:
            _set_principal_inertia(target, body)
        if body.name != WORLD or body.parent is not None:
            target.info = _origin(robot.source, links[body.name].line, f"link '{body.name}'")
        for frame in body.links:
            if options.link_sites == "all" or frame.fused:
                site = target.add_site(
                    name=frame.link, pos=list(frame.pose.position), quat=list(frame.pose.quat)
                )
                site.classname = link_site
                site.group = 5
                site.size = [0.005, 0.005, 0.005]
                site.info = _origin(robot.source, links[frame.link].line, f"link '{frame.link}'")
        if body.joint is not None and body.joint.moves:
            joint = spec.joint(body.joint.name)
            if joint is not None:
                joint.info = _origin(
                    robot.source, joints[body.joint.name].line, f"joint '{body.joint.name}'"
                )
        if body.floating:
            target.add_freejoint(name=f"{body.name}_freejoint")


def _set_principal_inertia(spec_body, body: Body) -> None:
    """Write the body's inertia as principal moments and axes computed here, at full precision.

    MuJoCo's import stores the URDF tensor and diagonalises it only when compiling, so the
    written axes would be rounded values from the compiled model.
    """
    import numpy as np

    from mjcfbuild.urdf.transforms import matrix3, matrix_to_quat

    assert body.mass is not None, "called only for a body with mass properties"
    tensor = np.array(body.mass.inertia, dtype=float)
    moments, axes = np.linalg.eigh(0.5 * (tensor + tensor.T))
    # Order and orient the principal axes like the body's own axes where they nearly are,
    # so a diagonal URDF tensor stays diagonal with an identity orientation.
    nearest = np.argmax(np.abs(axes), axis=0)
    if sorted(nearest) == [0, 1, 2]:
        order = np.argsort(nearest)
        moments, axes = moments[order], axes[:, order]
        axes = axes * np.sign(np.diag(axes))
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    rotation = matrix3((float(v) for v in row) for row in axes)
    spec_body.ipos = list(body.mass.com)
    spec_body.iquat = list(matrix_to_quat(rotation))
    spec_body.inertia = [max(float(m), 0.0) for m in moments]
    spec_body.fullinertia = [float("nan")] * 6
    spec_body.explicitinertial = True


def _style_geom(geom, record: GeomRecord, default, mujoco) -> None:
    """Put a geom in its class and give it only the attributes the class does not."""
    geom.classname = default
    geom.group = default.geom.group
    geom.contype = default.geom.contype
    geom.conaffinity = default.geom.conaffinity
    geom.density = default.geom.density
    geom.rgba = list(default.geom.rgba)
    if record.kind == "capsule":
        geom.type = mujoco.mjtGeom.mjGEOM_CAPSULE
    if record.material is not None:
        geom.material = record.material
    elif record.rgba is not None:
        geom.rgba = list(record.rgba)


def _unique_authored_names(records) -> set[str]:
    counts: dict[str, int] = {}
    for record in records:
        if record.authored_name:
            counts[record.authored_name] = counts.get(record.authored_name, 0) + 1
    return {name for name, count in counts.items() if count == 1}


def _origin(source: str, line: int | None, what: str) -> str:
    return f"{source}:{line} {what}" if line else f"{source} {what}"


def _finish_xml(
    root: etree._Element, prepared: Prepared, robot: Robot, options: AssemblyOptions
) -> None:
    """Compiler settings, relative mesh and texture files, explicit geom types."""
    for compiler in root.findall("compiler"):
        root.remove(compiler)
    settings = {k: v for k, v in robot.mujoco_compiler.items() if k not in _OWNED_COMPILER}
    settings.update(OUTPUT_COMPILER)
    compiler = etree.Element("compiler", {k: settings[k] for k in sorted(settings)})
    root.insert(0, compiler)
    files = {asset.name: asset.file for asset in prepared.meshes}
    for mesh in root.iter("mesh"):
        name = mesh.get("name")
        if name in files:
            mesh.set("file", files[name])
        mesh.attrib.pop("content_type", None)
    for texture in root.iter("texture"):
        name = texture.get("name")
        if name in prepared.textures:
            texture.set("file", prepared.textures[name])
            # Compiling resolved MuJoCo's default "auto" for this file; keep the default.
            texture.attrib.pop("colorspace", None)
        texture.attrib.pop("content_type", None)
    # MuJoCo omits type="sphere" (its default); written out, no input default can change it.
    # An MJCF part's geoms keep their classes' types.
    parted = {geom for frame in part_frames(root, options.parts) for geom in frame.iter("geom")}
    for geom in root.find("worldbody").iter("geom"):
        if geom.get("type") is None and geom not in parted:
            geom.set("type", "sphere")


def _layout(root: etree._Element) -> None:
    """Menagerie-style layout: two-space indent, a blank line between top-level sections."""
    etree.indent(root, space="  ")
    children = list(root)
    root.text = "\n  "
    for index, child in enumerate(children):
        child.tail = "\n" if index == len(children) - 1 else "\n\n  "
