"""Step ``selfcollision``: the collision matrix of the robot's collision geometry.

Its inputs are only what decides contacts: the links' collision geometry (with visuals and
inertias stripped by the task), the joints, the home pose and the settings. A visual mesh edit
leaves it up to date.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.collision.policy import CollisionChoice
from mjcfbuild.control.home import home_values
from mjcfbuild.errors import InputError, ManifestError
from mjcfbuild.inputs.ros2_control import ControlJoint, Ros2Control
from mjcfbuild.meshes.product import read_product
from mjcfbuild.mjcf.bodies import Body, build_bodies, floating_base, link_places
from mjcfbuild.mjcf.compile_errors import compile_error, spec_meshes
from mjcfbuild.mjcf.depth import refuse_deep_bodies
from mjcfbuild.mjcf.prepared import Decomposition, prepare
from mjcfbuild.selfcollision.matrix import (
    MatrixSettings,
    PairVerdict,
    collision_matrix,
    needs_exclude,
)
from mjcfbuild.selfcollision.srdf import Srdf
from mjcfbuild.selfcollision.srdf import home_state as home_state_of
from mjcfbuild.sources.packages import did_you_mean, listing
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import DecompositionFiles, SelfCollisionPayload
from mjcfbuild.urdf.model import robot_from_dict

MATRIX = "matrix.json"  # the cached product's one file

if TYPE_CHECKING:
    import mujoco  # untyped: its classes are Any to mypy, named here for the reader
    import numpy as np

    from mjcfbuild.compose.attach import AttachedPart


def run(payload: dict) -> dict:
    """Write the matrix (every pair with its reason) and the excludes the model needs."""
    request = SelfCollisionPayload.from_dict(payload)
    import mujoco

    robot = robot_from_dict(request.robot)
    bodies = build_bodies(robot, request.fuse_static, free_joint=request.free_joint)
    refuse_deep_bodies(robot, bodies)
    body_of = {frame.link: body.name for body in bodies for frame in body.links}
    choices = [CollisionChoice.from_dict(choice) for choice in request.choices]
    products = {m: read_product(Path(s)) for m, s in request.products.items()}
    decompositions = [_decomposition(entry) for entry in request.decompositions]
    prepared = prepare(
        robot.name,
        bodies,
        products,
        {m: Path(folder) for m, folder in request.product_dirs.items()},
        choices,
        decompositions,
        robot.mujoco_compiler,
        robot.source,
        visuals=False,
    )
    try:
        spec = mujoco.MjSpec.from_string(prepared.urdf)
    except Exception as exc:
        raise compile_error(exc, robot.source, prepared.meshes) from None
    for body in bodies:
        if body.floating:
            spec.body(body.name).add_freejoint()
    parts = _attach_parts(spec, bodies, request)
    try:
        model = _compile(spec)
    except Exception as exc:
        raise compile_error(exc, robot.source, spec_meshes(spec, prepared)) from None

    srdf = Srdf.from_dict(json.loads(Path(request.srdf).read_text())) if request.srdf else None
    control = Ros2Control(
        joints=[ControlJoint(name, [], value, "") for name, value in request.initial.items()]
    )
    joint_names = {joint.name for joint in robot.joints}
    _, home_state = (
        home_state_of(
            srdf, joint_names, request.home_state, floating_base(robot, request.free_joint)
        )
        if srdf
        else (None, None)
    )
    home = home_values(robot, control, request.home, home_state, request.manifest_label)
    qpos = model.qpos0.copy()
    for value in home:
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, value.joint)
        if index >= 0:
            qpos[model.jnt_qposadr[index]] = value.value
    for part in parts:  # a part's joints at the part's own home (or its qpos0)
        for joint, values in part.summary.home_qpos.items():
            index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, part.prefix + joint)
            if index >= 0:
                start = model.jnt_qposadr[index]
                qpos[start : start + len(values)] = values
    settings = MatrixSettings(**request.settings)
    verdicts, cached = _matrix(model, qpos, settings, request)
    # Pairs inside one MJCF part are the part's business: its author decided its contacts.
    part_bodies = [{part.prefix + b for b in part.summary.bodies} for part in parts]
    verdicts = [
        v
        for v in verdicts
        if not any(v["body1"] in inside and v["body2"] in inside for inside in part_bodies)
    ]

    by_pair = {frozenset((v["body1"], v["body2"])): v for v in verdicts}
    if srdf is not None and not srdf.discovered:
        for pair in srdf.pairs:
            bodies_of_pair = [
                _body(link, body_of, srdf, pair.line) for link in (pair.link1, pair.link2)
            ]
            key = frozenset(bodies_of_pair)
            if len(key) == 1:
                continue  # fused into one body: MuJoCo never collides a body with itself
            verdict = by_pair.get(key)
            if verdict is not None:
                verdict["reason"] = f"srdf: {pair.reason}"
                verdict["exclude"] = True
    for index, (link1, link2) in enumerate(request.keep):
        key = frozenset(
            _kept_body(link, body_of, request.manifest_label, index) for link in (link1, link2)
        )
        if key in by_pair:
            by_pair[key]["exclude"] = False
            by_pair[key]["reason"] += ", kept"

    excludes = [
        [v["body1"], v["body2"]]
        for v in verdicts
        if v["exclude"] and needs_exclude(model, PairVerdict(**v))
    ]
    result = {"pairs": verdicts, "excludes": excludes, "samples": settings.samples}
    outputs: dict[str, str] = {}
    write_output(
        Path(request.output),
        (json.dumps(result, indent=1, sort_keys=True) + "\n").encode(),
        outputs,
    )
    stored = not cached and bool(request.cache.get("enabled"))
    return {"outputs": outputs, "cached": cached, "stored": stored}


def _matrix(
    model: mujoco.MjModel, qpos: np.ndarray, settings: MatrixSettings, request: SelfCollisionPayload
) -> tuple[list[dict], bool]:
    """The verdicts of every pair, from the shared cache when this matrix was computed before
    (in any folder: the key holds no paths), else computed and stored; whether cached."""
    from mjcfbuild.products.store import open_store, product_key
    from mjcfbuild.steps.versions import SELFCOLLISION

    store = open_store(request.cache)
    robot = json.loads(json.dumps(request.robot))
    for link in robot["links"]:
        for shape in link["visuals"] + link["collisions"]:
            shape["geometry"]["path"] = None  # the mesh is identified by its product below
    params = {
        "robot": robot,
        "choices": request.choices,
        "fuse_static": request.fuse_static,
        "free_joint": request.free_joint,
        "home": [float(v) for v in qpos],
        "settings": request.settings,
        "versions": SELFCOLLISION.versions(),
        "parts": [[p.prefix, p.to, p.pos, p.quat] for p in request.mjcf_parts],
        "part_digests": request.part_digests,
    }
    inputs = [*request.products.values(), *(d.summary for d in request.decompositions)]
    key = product_key("selfcollision", params, sorted(inputs, key=lambda p: Path(p).name))
    kept = _verdicts(store.fetch_file(key, MATRIX, "selfcollision")) if store is not None else None
    if kept is not None:
        return kept, True
    verdicts = [v.to_dict() for v in collision_matrix(model, qpos, settings)]
    if store is not None:
        text = json.dumps(verdicts, sort_keys=True).encode()
        store.store_file(key, MATRIX, text, "selfcollision")
    return verdicts, False


def _verdicts(text: bytes | None) -> list[dict] | None:
    """The verdicts a cached matrix holds; None where it holds none (it is computed again)."""
    try:
        verdicts = json.loads(text) if text is not None else None
    except ValueError:
        return None
    return verdicts if isinstance(verdicts, list) else None


def _attach_parts(
    spec: mujoco.MjSpec, bodies: list[Body], request: SelfCollisionPayload
) -> list[AttachedPart]:
    """The ``attach:`` MJCF parts attached as the assembly attaches them, so the matrix covers
    their geoms against the rest of the model."""
    if not request.mjcf_parts:
        return []
    from mjcfbuild.compose.attach import AttachedPart, attach_parts

    parts: list[AttachedPart] = [
        AttachedPart.from_dict(entry.to_dict()) for entry in request.mjcf_parts
    ]
    attach_parts(spec, link_places(bodies), parts)
    return parts


def _compile(spec: mujoco.MjSpec) -> mujoco.MjModel:
    """Compile, giving meshes MuJoCo finds too thin for volume inertia shell inertia."""
    import mujoco

    from mjcfbuild.mjcf.compile_errors import too_thin_mesh

    for _ in range(len(spec.meshes) + 1):
        try:
            return spec.compile()
        except ValueError as exc:
            name = too_thin_mesh(str(exc))
            mesh = spec.mesh(name) if name else None
            if mesh is None or mesh.inertia == mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL:
                raise
            mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
    return spec.compile()


def _decomposition(entry: DecompositionFiles) -> Decomposition:
    summary = json.loads(Path(entry.summary).read_text())
    return Decomposition(
        entry.mesh_id, entry.params, Path(entry.folder), summary["parts"], summary["files"]
    )


def _body(link: str, body_of: dict[str, str], srdf: Srdf, line: int | None) -> str:
    if link not in body_of:
        raise InputError(
            f"link '{link}' is not a link of the robot{did_you_mean(link, set(body_of))}",
            file=srdf.label,
            line=line,
            hint=f"links: {listing(sorted(body_of))}",
        )
    return body_of[link]


def _kept_body(link: str, body_of: dict[str, str], label: str, index: int) -> str:
    if link not in body_of:
        raise ManifestError(
            f"link '{link}' is not a link of the robot{did_you_mean(link, set(body_of))}",
            file=f"{label} self_collision.keep[{index}]",
            hint=f"links: {listing(sorted(body_of))}",
        )
    return body_of[link]
