"""MJCF parts: a hand-tuned MuJoCo model read and compiled alone, then made ready to attach.

Attaching goes through ``MjSpec.attach``, which keeps the part's actuators, sensors, tendons,
equalities and defaults and prefixes every name. The written model has one ``<compiler>``
(mjcfbuild's: radians, no inertia from geoms, assets in ``assets/``), so before attaching,
everything the part's own compiler settings decided is made explicit: orientations become
quaternions, angles radians, inertias explicit (from the part compiled alone), and asset files
content-addressed copies. Keyframes are taken out; the part's ``home`` (or its qpos0) fills
its joints in the model's ``home`` keyframe.
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from lxml import etree

from mjcfbuild.compose.part_names import joint_names
from mjcfbuild.errors import InputError

HOME = "home"
# What MuJoCo's compiler converts from degrees when the part says angle="degree".
_ANGULAR_JOINTS = ("hinge", "ball")


@dataclass(frozen=True)
class PartJoint:
    """A joint of an MJCF part, named as in the part (without the prefix)."""

    name: str
    type: str  # free, ball, slide, hinge
    body: str
    range: tuple[float, float] | None  # None: unlimited
    actuated: bool  # an actuator of the part drives it (directly or through a tendon)


@dataclass
class PartSummary:
    """What the build needs to know about an MJCF part before and while attaching it."""

    label: str
    bodies: list[str]
    sites: list[str]
    joints: list[PartJoint]
    actuators: list[str]
    names: dict[str, list[str]]  # element kind -> names, for collisions with the model's
    home_qpos: dict[str, list[float]]  # joint -> its qpos in the part's home (or qpos0)
    home_ctrl: dict[str, float]  # actuator -> its ctrl in the part's home keyframe
    home_source: str  # "keyframe 'home'" or "qpos0"
    assets: dict[str, str] = field(default_factory=dict)  # content name -> stored copy
    files: list[str] = field(default_factory=list)  # every file the part was read from
    warnings: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-friendly form."""
        return asdict(self)

    @staticmethod
    def from_dict(data: dict[str, Any]) -> PartSummary:
        """The inverse of :meth:`to_dict`."""
        values = dict(data)
        values["joints"] = [
            PartJoint(**{**j, "range": tuple(j["range"]) if j["range"] else None})
            for j in data["joints"]
        ]
        return PartSummary(**values)


def load_part(path: Path, label: str):
    """The part's MjSpec and the MjModel it compiles to alone; a one-line error naming the
    part's file (and line, when MuJoCo gives one) if either fails."""
    import mujoco

    from mjcfbuild.mjcache import forget_earlier_builds

    forget_earlier_builds()  # the part's files are the user's
    try:
        spec = mujoco.MjSpec.from_file(str(path))
    except Exception as exc:
        raise part_error(exc, label, "MuJoCo could not read the part") from None
    try:
        model = spec.compile()
    except Exception as exc:
        raise part_error(exc, label, "the part does not compile on its own") from None
    for joint in range(model.njnt):
        if model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_FREE:
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, joint) or f"#{joint}"
            raise InputError(
                f"the part has a free joint ('{name}'); an attached part is held by its link",
                file=label,
                hint="remove the free joint from the part",
            )
    return spec, model


def part_error(exc: Exception, label: str, what: str) -> InputError:
    """A MuJoCo error about a part as one line, with the line MuJoCo names if it names one."""
    text = str(exc).strip().replace("XML Error: ", "").replace("Error: ", "")
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    message = lines[0].rstrip(":") if lines else type(exc).__name__
    parse_error = re.search(r"Error=XML_ERROR_(\w+)", text)
    if parse_error:  # tinyxml2's own words, e.g. XML_ERROR_PARSING_ELEMENT
        message = f"XML error: {parse_error.group(1).lower().replace('_', ' ')}"
    found = re.search(r"[Ll]ine(?: number=| )(\d+)", text)
    return InputError(
        f"{what}: {message}",
        file=label,
        line=int(found.group(1)) if found else None,
        hint="fix the part; MuJoCo's simulate shows it alone",
    )


def summarise(spec, model, label: str) -> PartSummary:
    """The part's names, joints, actuators and home, from its spec and its model alone."""
    import mujoco

    def names(kind, count: int) -> list[str]:
        found = (mujoco.mj_id2name(model, kind, i) for i in range(count))
        return sorted(name for name in found if name)

    obj = mujoco.mjtObj
    actuated = _actuated_joints(model)
    given = joint_names(
        [
            (
                mujoco.mj_id2name(model, obj.mjOBJ_JOINT, j) or "",
                mujoco.mj_id2name(model, obj.mjOBJ_BODY, model.jnt_bodyid[j]) or "",
            )
            for j in range(model.njnt)
        ]
    )
    joints = []
    for j in range(model.njnt):
        kind = mujoco.mjtJoint(model.jnt_type[j]).name.removeprefix("mjJNT_").lower()
        limited = bool(model.jnt_limited[j])
        joints.append(
            PartJoint(
                name=given[j],
                type=kind,
                body=mujoco.mj_id2name(model, obj.mjOBJ_BODY, model.jnt_bodyid[j]) or "",
                range=(float(model.jnt_range[j][0]), float(model.jnt_range[j][1]))
                if limited
                else None,
                actuated=j in actuated,
            )
        )
    home = mujoco.mj_name2id(model, obj.mjOBJ_KEY, HOME)
    qpos = model.key_qpos[home] if home >= 0 else model.qpos0
    sizes = {int(mujoco.mjtJoint.mjJNT_FREE): 7, int(mujoco.mjtJoint.mjJNT_BALL): 4}
    home_qpos = {}
    for j, joint in enumerate(joints):
        address = model.jnt_qposadr[j]
        size = sizes.get(int(model.jnt_type[j]), 1)
        home_qpos[joint.name] = [float(v) for v in qpos[address : address + size]]
    home_ctrl = {}
    if home >= 0:
        for a in range(model.nu):
            name = mujoco.mj_id2name(model, obj.mjOBJ_ACTUATOR, a)
            if name:
                home_ctrl[name] = float(model.key_ctrl[home][a])
    warnings = []
    others = [spec.keys[i].name for i in range(len(spec.keys)) if spec.keys[i].name != HOME]
    if others:
        warnings.append(
            f"{label}: the part's keyframes {', '.join(repr(k) for k in others)} are left out "
            "(its 'home' keyframe fills its joints in the model's home)"
        )
    named_here = [
        given[j] for j in range(model.njnt) if not mujoco.mj_id2name(model, obj.mjOBJ_JOINT, j)
    ]
    if any(named_here):
        listed = ", ".join(f"'{name}'" for name in named_here if name)
        warnings.append(
            f"{label}: the part's joints without a name are named after their bodies ({listed}, "
            "prefixed in the model): robot.yaml rules and home name them so"
        )
    unnamed = [j for j in joints if not j.name] + [
        a for a in range(model.nu) if not mujoco.mj_id2name(model, obj.mjOBJ_ACTUATOR, a)
    ]
    if unnamed:
        warnings.append(
            f"{label}: the part has unnamed joints or actuators; robot.yaml rules and the "
            "home keyframe cannot name them"
        )
    warnings += _option_warnings(spec, label)
    bodies = [n for n in names(obj.mjOBJ_BODY, model.nbody) if n != "world"]
    return PartSummary(
        label=label,
        bodies=bodies,
        sites=names(obj.mjOBJ_SITE, model.nsite),
        joints=joints,
        actuators=names(obj.mjOBJ_ACTUATOR, model.nu),
        names={
            "body": bodies,
            "site": names(obj.mjOBJ_SITE, model.nsite),
            "joint": names(obj.mjOBJ_JOINT, model.njnt),
            "geom": names(obj.mjOBJ_GEOM, model.ngeom),
            "actuator": names(obj.mjOBJ_ACTUATOR, model.nu),
            "sensor": names(obj.mjOBJ_SENSOR, model.nsensor),
            "tendon": names(obj.mjOBJ_TENDON, model.ntendon),
            "camera": names(obj.mjOBJ_CAMERA, model.ncam),
        },
        home_qpos=home_qpos,
        home_ctrl=home_ctrl,
        home_source=f"keyframe '{HOME}'" if home >= 0 else "qpos0",
        warnings=warnings,
    )


def _actuated_joints(model) -> set[int]:
    """Joints an actuator drives: through a joint transmission or a tendon over joints."""
    import mujoco

    driven: set[int] = set()
    for a in range(model.nu):
        kind = model.actuator_trntype[a]
        target = int(model.actuator_trnid[a, 0])
        if kind in (mujoco.mjtTrn.mjTRN_JOINT, mujoco.mjtTrn.mjTRN_JOINTINPARENT):
            driven.add(target)
        elif kind == mujoco.mjtTrn.mjTRN_TENDON:
            start, count = model.tendon_adr[target], model.tendon_num[target]
            for w in range(start, start + count):
                if model.wrap_type[w] == mujoco.mjtWrap.mjWRAP_JOINT:
                    driven.add(int(model.wrap_objid[w]))
    return driven


def _changed_options(spec) -> list[str]:
    """The physics options (``<option>``) the part sets to other than MuJoCo's defaults."""
    import mujoco

    default = mujoco.MjSpec().option
    names = [name for name in dir(default) if not name.startswith("_")]
    return [
        name for name in names if str(getattr(spec.option, name)) != str(getattr(default, name))
    ]


def _option_warnings(spec, label: str) -> list[str]:
    changed = _changed_options(spec)
    if not changed:
        return []
    return [
        f"{label}: the part's <option> ({', '.join(changed)}) is not carried over; set it in "
        "robot.yaml's mujoco_inputs if the model needs it"
    ]


def asset_files(spec) -> list[tuple[Any, str, Path]]:
    """(element, attribute, absolute path) of every file the part's assets read.

    Relative paths are taken, as MuJoCo takes them, from the model's folder and the compiler's
    ``meshdir`` (meshes, heightfields, skins) or ``texturedir`` (textures).
    """
    base = Path(spec.modelfiledir or ".")
    found = []

    def resolve(name: str, folder: str) -> Path:
        path = Path(name)
        if spec.strippath:
            path = Path(path.name)
        if path.is_absolute():
            return path
        return (base / folder / path).resolve()

    for mesh in spec.meshes:
        if mesh.file:
            found.append((mesh, "file", resolve(mesh.file, spec.meshdir)))
    for hfield in spec.hfields:
        if hfield.file:
            found.append((hfield, "file", resolve(hfield.file, spec.meshdir)))
    for skin in spec.skins:
        if skin.file:
            found.append((skin, "file", resolve(skin.file, spec.meshdir)))
    for texture in spec.textures:
        if texture.file:
            found.append((texture, "file", resolve(texture.file, spec.texturedir)))
        for index, name in enumerate(texture.cubefiles):
            if name:
                found.append((texture, f"cubefiles.{index}", resolve(name, spec.texturedir)))
    return found


def content_name(data: bytes, suffix: str) -> str:
    """The published name of an asset file: its content's hash, so equal files are one file
    and the name is the same in every folder and on every machine."""
    return hashlib.sha256(data).hexdigest()[:20] + suffix.lower()


def included_files(path: Path, label: str) -> list[Path]:
    """The files ``<include>``d by the part, recursively (relative to the part's folder, as
    MuJoCo resolves them)."""
    base = path.parent
    seen: list[Path] = []
    pending = [path]
    while pending:
        current = pending.pop()
        try:
            root = etree.parse(str(current), etree.XMLParser(huge_tree=True)).getroot()
        except (OSError, etree.XMLSyntaxError):
            continue  # MuJoCo already read (or refused) it; nothing more to find
        for element in root.iter("include"):
            name = element.get("file")
            if not name:
                continue
            included = (base / name).resolve()
            if included not in seen and included != path.resolve():
                seen.append(included)
                pending.append(included)
    return seen


def normalise(spec, model, stored: dict[str, Path]) -> None:
    """Make everything the part's compiler decided explicit, name its unnamed joints
    (:func:`joint_names`), and point its assets at the stored copies (``stored``: absolute
    source path -> stored copy)."""
    import mujoco

    ordered = [joint for body in spec.bodies for joint in body.joints]
    names = joint_names([(joint.name, joint.parent.name) for joint in ordered])
    for joint, name in zip(ordered, names, strict=True):
        joint.name = name

    for key in list(spec.keys):
        spec.delete(key)
    default_option = mujoco.MjSpec().option
    for name in _changed_options(spec):  # the model's options win; summarise() warned
        setattr(spec.option, name, getattr(default_option, name))
    degree = bool(spec.compiler.degree)
    sequence = spec.compiler.eulerseq
    for kind in ("bodies", "geoms", "sites", "cameras", "frames", "lights"):
        for element in getattr(spec, kind):
            alt = getattr(element, "alt", None)
            if alt is not None and alt.type != mujoco.mjtOrientation.mjORIENTATION_QUAT:
                element.quat = spec.resolve_orientation(degree, sequence, alt)
                alt.type = mujoco.mjtOrientation.mjORIENTATION_QUAT
    if degree:
        scale = math.pi / 180
        for joint in spec.joints:
            if joint.type.name.removeprefix("mjJNT_").lower() in _ANGULAR_JOINTS:
                joint.range = [v * scale for v in joint.range]
                joint.ref *= scale
                joint.springref *= scale
        spec.compiler.degree = False
    for body in spec.bodies:
        if body.name == "world" or body is spec.worldbody:
            continue
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body.name)
        if index < 0 or model.body_mass[index] <= 0:
            continue
        body.mass = float(model.body_mass[index])
        body.ipos = [float(v) for v in model.body_ipos[index]]
        body.iquat = [float(v) for v in model.body_iquat[index]]
        body.ialt.type = mujoco.mjtOrientation.mjORIENTATION_QUAT
        body.inertia = [float(v) for v in model.body_inertia[index]]
        body.fullinertia = [float("nan")] * 6
        body.explicitinertial = True
    for element, attribute, path in asset_files(spec):
        copy = str(stored[str(path)])
        if attribute.startswith("cubefiles."):
            files = list(element.cubefiles)
            files[int(attribute.split(".")[1])] = copy
            element.cubefiles = files
        else:
            setattr(element, attribute, copy)
    spec.meshdir = ""
    spec.texturedir = ""
    spec.strippath = False


def part_joints_as_urdf(summary: PartSummary, prefix: str) -> list:
    """The part's hinge and slide joints as URDF joints (prefixed), for the home pose and
    actuator rules; a limited hinge is revolute, an unlimited one continuous."""
    from mjcfbuild.urdf.model import Joint, Limit

    result = []
    for joint in summary.joints:
        if joint.type not in ("hinge", "slide") or not joint.name:
            continue
        kind = "prismatic" if joint.type == "slide" else "revolute"
        limit = None
        if joint.range is not None:
            limit = Limit(lower=joint.range[0], upper=joint.range[1])
        elif kind == "revolute":
            kind = "continuous"
        result.append(
            Joint(
                name=prefix + joint.name,
                kind=kind,
                parent=prefix + joint.body,
                child=prefix + joint.body,
                limit=limit,
            )
        )
    return result
