"""Reading any MJCF into :class:`ModelOut` through MuJoCo: compiled numbers, spec class names.

The compiled model gives every number after defaults, ``fromto``, mesh centring and scaling
are resolved, so hand-written models read like generated ones. Class names, which the compiled
model drops, come from the spec the model was compiled from.
"""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.actuators import dcmotor_of
from mjcfbuild.errors import InputError, ModelError
from mjcfbuild.export.model import BodyOut, GeomOut, JointOut, MeshOut, MimicOut, ModelOut
from mjcfbuild.fsutil import unreadable_file
from mjcfbuild.mjerrors import load_error
from mjcfbuild.urdf.model import WORLD
from mjcfbuild.urdf.transforms import Transform, matmul, matrix3, quat_to_matrix, transpose

DEFAULT_GEOM_RGBA = (0.5, 0.5, 0.5, 1.0)
# Actuator dynamics whose activation settles at the control (none, filter, filterexact).
_STEADY_DYNAMICS = (0, 2, 3)
JOINT_KINDS = {0: "free", 1: "ball", 2: "slide", 3: "hinge"}
GEOM_KINDS = {0: "plane", 1: "hfield", 2: "sphere", 3: "capsule", 4: "ellipsoid", 5: "cylinder"}
GEOM_KINDS.update({6: "box", 7: "mesh", 8: "sdf"})


def read_mjcf(path: Path, speeds: dict[str, float] | None = None) -> ModelOut:
    """Load and compile the MJCF at ``path``; :class:`ModelError` if MuJoCo refuses it.

    ``speeds`` (joint name -> top speed) are what is known beyond the model, such as a build's
    drives and its source URDF's velocity limits: they fill in the joints whose speed the
    model's own actuators do not give (:func:`joint_speed`)."""
    import mujoco

    from mjcfbuild.mjwarnings import capture_mujoco_warnings

    capture_mujoco_warnings()
    problem = unreadable_file(path)
    if problem:
        raise InputError(f"model file {problem}", file=path)
    try:
        spec = mujoco.MjSpec.from_file(str(path))
        model = spec.compile()
    except Exception as exc:
        raise ModelError(f"MuJoCo cannot load the model: {load_error(exc)}", file=path) from None
    classes = {geom.id: (geom.classname.name if geom.classname else "") for geom in spec.geoms}
    names = _body_names(model)
    bodies = [_body(model, index, names) for index in range(model.nbody)]
    for geom in range(model.ngeom):
        if GEOM_KINDS[int(model.geom_type[geom])] not in ("plane", "hfield", "sdf"):
            bodies[model.geom_bodyid[geom]].geoms.append(_geom(model, geom, classes.get(geom, "")))
    for site in range(model.nsite):
        body = model.site_bodyid[site]
        name = model.site(site).name or f"{names[body]}_site{site}"
        pose = Transform.from_quat(_vec(model.site_pos[site]), _quat(model.site_quat[site]))
        bodies[body].sites.append((name, pose))
    meshes = {index: _mesh(model, index) for index in sorted(_meshes_used(bodies))}
    warnings = _skipped_geoms(model, names)
    mimics = _mimics(model)
    _fill_speeds(bodies, mimics, speeds or {})
    return ModelOut(
        name=spec.modelname or path.stem,
        bodies=bodies,
        meshes=meshes,
        mimics=mimics,
        warnings=warnings,
    )


def _body_names(model) -> list[str]:
    names = []
    for index in range(model.nbody):
        name = model.body(index).name
        names.append(WORLD if index == 0 else (name or f"body{index}"))
    return names


def _body(model, index: int, names: list[str]) -> BodyOut:
    parent = None if index == 0 else names[model.body_parentid[index]]
    body = BodyOut(
        name=names[index],
        parent=parent,
        pose=Transform.from_quat(_vec(model.body_pos[index]), _quat(model.body_quat[index])),
    )
    if index > 0:
        body.mass = float(model.body_mass[index])
        body.com = _vec(model.body_ipos[index])
        axes = quat_to_matrix(_quat(model.body_iquat[index]))
        moments = _vec(model.body_inertia[index])
        diagonal = matrix3((moments[i] if i == j else 0.0 for j in range(3)) for i in range(3))
        body.inertia = matmul(matmul(axes, diagonal), transpose(axes))
    first = model.body_jntadr[index]
    for joint in range(first, first + model.body_jntnum[index]) if first >= 0 else ():
        body.joints.append(_joint(model, joint))
    return body


def joint_name(model, index: int) -> str:
    """The joint's name, or a stable one for an unnamed joint."""
    return model.joint(index).name or f"joint{index}"


def _joint(model, index: int) -> JointOut:
    kind = JOINT_KINDS[int(model.jnt_type[index])]
    reference = 0.0
    if kind in ("hinge", "slide"):
        reference = float(model.qpos0[model.jnt_qposadr[index]])
    limited = bool(model.jnt_limited[index])
    lower, upper = (float(v) for v in model.jnt_range[index])
    dof = model.jnt_dofadr[index]
    return JointOut(
        name=joint_name(model, index),
        kind=kind,
        position=_vec(model.jnt_pos[index]),
        axis=_vec(model.jnt_axis[index]),
        limited=limited,
        lower=lower - reference,
        upper=upper - reference,
        effort=_effort(model, index),
        damping=float(model.dof_damping[dof]),
        friction=float(model.dof_frictionloss[dof]),
        velocity=joint_speed(model, index) if kind in ("hinge", "slide") else None,
    )


def _effort(model, joint: int) -> float:
    """The joint's force limit: its actuatorfrcrange, else what an actuator on it can apply:
    its force range, a ``<dcmotor>``'s stall torque at its top voltage (the smaller of the two
    where it has both), or a motor's gain times its control range; all times the gear, since
    the joint feels the actuator's force times the gear."""
    if model.jnt_actfrclimited[joint]:
        return max(abs(float(v)) for v in model.jnt_actfrcrange[joint])
    for actuator in range(model.nu):
        if model.actuator_trntype[actuator] != 0 or model.actuator_trnid[actuator][0] != joint:
            continue
        gear = abs(float(model.actuator_gear[actuator][0]))
        limits = []
        if model.actuator_forcelimited[actuator]:
            limits.append(max(abs(float(v)) for v in model.actuator_forcerange[actuator]))
        motor = dcmotor_of(model, actuator)
        if motor is not None and motor.stall_torque is not None:
            limits.append(motor.stall_torque)
        if limits:
            return min(limits) * gear
        if model.actuator_ctrllimited[actuator] and model.actuator_biastype[actuator] == 0:
            gain = abs(float(model.actuator_gainprm[actuator][0]) * gear)
            return gain * max(abs(float(v)) for v in model.actuator_ctrlrange[actuator])
    return 0.0


def joint_speed(model, joint: int) -> float | None:
    """The top speed the first actuator on the joint that bounds it allows (None: none does):

    - a ``<dcmotor>``'s no-load speed: its torque falls to zero where the back-EMF reaches the
      top voltage (the controller's voltage clamp, else a voltage input's control range), at
      actuator speed voltage / motor constant;
    - a velocity servo's (fixed gain, affine bias with a velocity term only) fastest target in
      its control range, the speed at which its force falls to zero.

    Actuator speeds are the joint's times the gear, so both are divided by it."""
    import mujoco

    for actuator in range(model.nu):
        if model.actuator_trntype[actuator] not in (0, 1):  # joint, jointinparent
            continue
        gear = abs(float(model.actuator_gear[actuator][0]))
        if model.actuator_trnid[actuator][0] != joint or gear == 0:
            continue
        gain, bias = model.actuator_gainprm[actuator], model.actuator_biasprm[actuator]
        controls = (
            model.actuator_ctrlrange[actuator] if model.actuator_ctrllimited[actuator] else None
        )
        motor = dcmotor_of(model, actuator)
        if motor is not None:
            if motor.no_load_speed is not None:
                return motor.no_load_speed / gear
        elif (
            model.actuator_gaintype[actuator] == mujoco.mjtGain.mjGAIN_FIXED
            and model.actuator_biastype[actuator] == mujoco.mjtBias.mjBIAS_AFFINE
            and model.actuator_dyntype[actuator] in _STEADY_DYNAMICS
            and float(bias[1]) == 0.0
            and float(bias[2]) < 0.0
            and controls is not None
        ):
            top = max(abs(float(gain[0]) * float(c) + float(bias[0])) for c in controls)
            return top / -float(bias[2]) / gear
    return None


def _fill_speeds(bodies: list[BodyOut], mimics: list[MimicOut], speeds: dict[str, float]) -> None:
    """Joints the model's actuators leave without a speed take one from ``speeds``; then a
    coupled joint still without one moves as fast as its leader allows (|multiplier| times)."""
    joints = {joint.name: joint for body in bodies for joint in body.joints}
    for name, joint in joints.items():
        if joint.velocity is None and joint.kind in ("hinge", "slide"):
            known = speeds.get(name)
            joint.velocity = known if known is not None and known > 0 else None
    for mimic in mimics:
        follower, leader = joints.get(mimic.follower), joints.get(mimic.leader)
        if follower is None or leader is None or follower.velocity is not None:
            continue
        if leader.velocity is not None and mimic.multiplier != 0:
            follower.velocity = abs(mimic.multiplier) * leader.velocity


def _geom(model, index: int, class_name: str) -> GeomOut:
    kind = GEOM_KINDS[int(model.geom_type[index])]
    rgba = tuple(float(v) for v in model.geom_rgba[index])
    material = model.geom_matid[index]
    # MuJoCo draws a geom in its material's colour unless the geom's own rgba was changed.
    if material >= 0 and _close(rgba, DEFAULT_GEOM_RGBA):
        rgba = tuple(float(v) for v in model.mat_rgba[material])
    return GeomOut(
        kind=kind,
        size=tuple(float(v) for v in model.geom_size[index]),
        pose=Transform.from_quat(_vec(model.geom_pos[index]), _quat(model.geom_quat[index])),
        rgba=rgba,  # type: ignore[arg-type]
        roles=_roles(model, index, class_name),
        mesh=int(model.geom_dataid[index]) if kind == "mesh" else None,
    )


def _roles(model, index: int, class_name: str) -> tuple[str, ...]:
    """Visual, collision or both: by class name first, then contype/conaffinity and group."""
    name = class_name.lower()
    if "collision" in name and "visual" not in name:
        return ("collision",)
    if "visual" in name and "collision" not in name:
        return ("visual",)
    if not (model.geom_contype[index] or model.geom_conaffinity[index]):
        return ("visual",)
    if model.geom_group[index] >= 3:  # groups 0-2 are drawn by default; 3 and up are not
        return ("collision",)
    return ("visual", "collision")


def _meshes_used(bodies: list[BodyOut]) -> set[int]:
    return {geom.mesh for body in bodies for geom in body.geoms if geom.mesh is not None}


def _mesh(model, index: int) -> MeshOut:
    start, count = model.mesh_vertadr[index], model.mesh_vertnum[index]
    first, faces = model.mesh_faceadr[index], model.mesh_facenum[index]
    return MeshOut(
        name=model.mesh(index).name or f"mesh{index}",
        vertices=model.mesh_vert[start : start + count].astype(float),
        faces=model.mesh_face[first : first + faces].astype(int),
    )


def _skipped_geoms(model, names: list[str]) -> list[str]:
    warnings = []
    for geom in range(model.ngeom):
        kind = GEOM_KINDS[int(model.geom_type[geom])]
        if kind in ("plane", "hfield", "sdf"):
            label = model.geom(geom).name or f"geom {geom}"
            body = names[model.geom_bodyid[geom]]
            warnings.append(f"{label} in body '{body}' is a {kind}, which URDF cannot describe")
    return warnings


def _mimics(model) -> list[MimicOut]:
    """Active joint couplings ``q1 = c0 + c1 q2`` (higher terms zero) between hinge and slide
    joints, in URDF coordinates (measured from each joint's reference position).

    MuJoCo's joint equality already measures both joints from their reference positions: it
    holds ``q1 - ref1 = c0 + c1 (q2 - ref2)``, and an exported joint's zero is its ``ref`` (the
    pose its body is written in), so ``c0`` and ``c1`` are the mimic's offset and multiplier as
    they are."""
    result = []
    for index in range(model.neq):
        if model.eq_type[index] != 2 or not model.eq_active0[index]:  # 2: mjEQ_JOINT
            continue
        follower, leader = int(model.eq_obj1id[index]), int(model.eq_obj2id[index])
        if leader < 0 or any(abs(float(c)) > 0 for c in model.eq_data[index][2:5]):
            continue
        if any(model.jnt_type[j] not in (2, 3) for j in (follower, leader)):
            continue
        result.append(
            MimicOut(
                follower=joint_name(model, follower),
                leader=joint_name(model, leader),
                multiplier=float(model.eq_data[index][1]),
                offset=float(model.eq_data[index][0]),
            )
        )
    return result


def _vec(values) -> tuple[float, float, float]:
    return (float(values[0]), float(values[1]), float(values[2]))


def _quat(values) -> tuple[float, float, float, float]:
    return (float(values[0]), float(values[1]), float(values[2]), float(values[3]))


def _close(a, b) -> bool:
    return all(abs(x - y) < 1e-6 for x, y in zip(a, b, strict=True))
