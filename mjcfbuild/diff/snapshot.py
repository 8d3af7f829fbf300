"""One build folder read into plain data: what ``diff`` compares.

The model file is compiled with MuJoCo (masses, inertias and poses are what the simulator sees,
not what the XML text says); the build's own records add the collision matrix's reasons, the
check's results and the preview pictures.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Any

from mjcfbuild.actuators import read_actuator
from mjcfbuild.errors import InputError, ModelError
from mjcfbuild.ownership import STATE_DIR

Snapshot = dict[str, Any]


def find_model(folder: Path) -> Path:
    """The robot model file of the build in ``folder``; :class:`InputError` when there is none."""
    report = folder / "report" / "report.json"
    if not (folder / STATE_DIR).is_dir() or not report.is_file():
        raise InputError(
            "no mjcfbuild build in this folder",
            file=str(folder),
            hint="give an output folder that mjcfbuild build wrote, with its .mjcfbuild folder",
        )
    try:
        name = json.loads(report.read_text())["model"]
    except (OSError, ValueError, KeyError, TypeError):
        raise InputError(
            "the build's report is unreadable", file=str(report), hint="build it again"
        ) from None
    model = folder / name
    if not model.is_file():
        raise InputError(
            f"the build's model {name} is missing", file=str(folder), hint="build it again"
        )
    return model


def read_snapshot(folder: Path) -> Snapshot:
    """Everything ``diff`` compares about the build in ``folder``."""
    model_path = find_model(folder)
    snapshot = model_snapshot(model_path)
    snapshot["collision_reasons"] = _collision_reasons(folder / STATE_DIR / "self_collision.json")
    snapshot["home_sources"] = _home_sources(folder / STATE_DIR / "assembly.json")
    snapshot["checks"] = _checks(folder / STATE_DIR / "check.json")
    snapshot["previews"] = _previews(folder / "report" / "previews")
    return snapshot


def model_snapshot(path: Path) -> Snapshot:
    """The model at ``path`` compiled: bodies, joints, actuators, geometry, excludes, home."""
    import mujoco

    try:
        model = mujoco.MjModel.from_xml_path(str(path))
    except ValueError as error:
        first = str(error).strip().splitlines()[0] if str(error).strip() else "compile error"
        raise ModelError(f"MuJoCo rejected the model: {first}", file=str(path)) from None
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return {
        "model": path.name,
        "bodies": _bodies(model, data),
        "frames": _frames(model, data),
        "joints": _joints(model),
        "actuators": _actuators(model),
        "geometry": _geometry(model),
        "excludes": _excludes(model),
        "home": _home(model),
    }


def _name(model, kind, index: int) -> str:
    import mujoco

    return mujoco.mj_id2name(model, kind, index) or f"#{index}"


def _floats(values) -> list[float]:
    return [float(v) for v in values]


def _bodies(model, data) -> dict[str, dict[str, Any]]:
    import mujoco

    bodies = {}
    for index in range(1, model.nbody):
        parent = int(model.body_parentid[index])
        bodies[_name(model, mujoco.mjtObj.mjOBJ_BODY, index)] = {
            "parent": _name(model, mujoco.mjtObj.mjOBJ_BODY, parent) if parent else "world",
            "pos": _floats(model.body_pos[index]),
            "quat": _floats(model.body_quat[index]),
            "world_pos": _floats(data.xpos[index]),
            "world_quat": _floats(data.xquat[index]),
            "mass": float(model.body_mass[index]),
            "inertia": _floats(model.body_inertia[index]),
            "com": _floats(model.body_ipos[index]),
        }
    return bodies


def _frames(model, data) -> dict[str, dict[str, Any]]:
    """Sites (the links that fixed joints fused away are sites) with their body and pose."""
    import mujoco

    frames = {}
    for index in range(model.nsite):
        body = int(model.site_bodyid[index])
        frames[_name(model, mujoco.mjtObj.mjOBJ_SITE, index)] = {
            "body": _name(model, mujoco.mjtObj.mjOBJ_BODY, body) if body else "world",
            "pos": _floats(model.site_pos[index]),
            "quat": _floats(model.site_quat[index]),
            "world_pos": _floats(data.site_xpos[index]),
        }
    return frames


_JOINT_TYPES = {0: "free", 1: "ball", 2: "slide", 3: "hinge"}


def _joints(model) -> dict[str, dict[str, Any]]:
    import mujoco

    joints = {}
    for index in range(model.njnt):
        dof = int(model.jnt_dofadr[index])
        joints[_name(model, mujoco.mjtObj.mjOBJ_JOINT, index)] = {
            "type": _JOINT_TYPES.get(int(model.jnt_type[index]), str(model.jnt_type[index])),
            "body": _name(model, mujoco.mjtObj.mjOBJ_BODY, int(model.jnt_bodyid[index])),
            "axis": _floats(model.jnt_axis[index]),
            "range": _floats(model.jnt_range[index]) if model.jnt_limited[index] else None,
            "force_range": _floats(model.jnt_actfrcrange[index])
            if model.jnt_actfrclimited[index]
            else None,
            "damping": float(model.dof_damping[dof]),
            "armature": float(model.dof_armature[dof]),
            "frictionloss": float(model.dof_frictionloss[dof]),
        }
    return joints


def _actuators(model) -> dict[str, dict[str, Any]]:
    import mujoco

    actuators = {}
    for index in range(model.nu):
        target = int(model.actuator_trnid[index][0])
        trn = int(model.actuator_trntype[index])
        kind = {0: mujoco.mjtObj.mjOBJ_JOINT, 4: mujoco.mjtObj.mjOBJ_SITE}.get(trn)
        actuators[_name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, index)] = {
            "target": _name(model, kind, target) if kind is not None else f"#{target}",
            **read_actuator(model, index).to_dict(),
        }
    return actuators


_GEOM_TYPES = {0: "plane", 2: "sphere", 3: "capsule", 4: "ellipsoid", 5: "cylinder", 6: "box"}


def _geometry(model) -> dict[str, dict[str, list[dict[str, Any]]]]:
    """Per body, its collision and visual geoms: type, size or mesh, pose."""
    import mujoco

    geometry: dict[str, dict[str, list[dict[str, Any]]]] = {}
    for index in range(model.ngeom):
        body = _name(model, mujoco.mjtObj.mjOBJ_BODY, int(model.geom_bodyid[index]))
        collides = bool(model.geom_contype[index] or model.geom_conaffinity[index])
        geom_type = int(model.geom_type[index])
        entry: dict[str, Any] = {
            "type": _GEOM_TYPES.get(geom_type, "mesh" if geom_type == 7 else str(geom_type)),
            "pos": _floats(model.geom_pos[index]),
        }
        mesh = int(model.geom_dataid[index])
        if geom_type == 7 and mesh >= 0:
            entry.update(_mesh(model, mesh))
        else:
            entry["size"] = _floats(model.geom_size[index])
        kind = "collision" if collides else "visual"
        geometry.setdefault(body, {"collision": [], "visual": []})[kind].append(entry)
    return geometry


def _mesh(model, index: int) -> dict[str, Any]:
    """A mesh's name, size and a digest of its vertices and faces as MuJoCo holds them."""
    import mujoco
    import numpy as np

    first, count = int(model.mesh_vertadr[index]), int(model.mesh_vertnum[index])
    vertices = model.mesh_vert[first : first + count]
    face_first, faces = int(model.mesh_faceadr[index]), int(model.mesh_facenum[index])
    digest = hashlib.md5(np.round(vertices, 9).astype("<f8").tobytes())
    digest.update(model.mesh_face[face_first : face_first + faces].astype("<i4").tobytes())
    # MuJoCo holds a mesh centred and turned to its principal axes of inertia (mesh_pos,
    # mesh_quat): its extent is taken in the mesh file's own axes, which an edit of a vertex
    # does not turn (there, 2 mm moved showed as 2 cm grown on two axes).
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, model.mesh_quat[index])
    in_file = vertices @ rotation.reshape(3, 3).T
    extent = (in_file.max(axis=0) - in_file.min(axis=0)) if count else np.zeros(3)
    return {
        "mesh": _name(model, mujoco.mjtObj.mjOBJ_MESH, index),
        "vertices": count,
        "faces": faces,
        "extent": _floats(extent),
        "digest": digest.hexdigest(),
    }


def _excludes(model) -> list[list[str]]:
    """The model's ``<contact><exclude>`` body pairs, each pair sorted, the list sorted."""
    import mujoco

    pairs = []
    for signature in model.exclude_signature:
        first, second = int(signature) >> 16, int(signature) & 0xFFFF
        names = sorted(
            _name(model, mujoco.mjtObj.mjOBJ_BODY, body) if body else "world"
            for body in (first, second)
        )
        pairs.append(names)
    return sorted(pairs)


def _home(model) -> dict[str, Any] | None:
    """The ``home`` keyframe: each joint's position (free and ball joints as lists), each
    actuator's control; None without one."""
    import mujoco

    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if key < 0:
        return None
    qpos = model.key_qpos[key]
    widths = {0: 7, 1: 4, 2: 1, 3: 1}
    joints: dict[str, Any] = {}
    for index in range(model.njnt):
        start = int(model.jnt_qposadr[index])
        width = widths[int(model.jnt_type[index])]
        values = _floats(qpos[start : start + width])
        joints[_name(model, mujoco.mjtObj.mjOBJ_JOINT, index)] = values[0] if width == 1 else values
    ctrl = {
        _name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, i): float(model.key_ctrl[key][i])
        for i in range(model.nu)
    }
    return {"qpos": joints, "ctrl": ctrl}


def _collision_reasons(path: Path) -> dict[str, str]:
    """``"a|b" -> reason`` from the build's collision matrix (adjacent, never, sometimes...),
    with ``, excluded`` where the pair is excluded."""
    try:
        pairs = json.loads(path.read_text()).get("pairs", [])
    except (OSError, ValueError, AttributeError):
        return {}
    reasons = {}
    for pair in pairs:
        key = "|".join(sorted((str(pair.get("body1")), str(pair.get("body2")))))
        reason = str(pair.get("reason", ""))
        reasons[key] = reason + (", excluded" if pair.get("exclude") else "")
    return reasons


def _home_sources(path: Path) -> dict[str, str]:
    """Where each joint's home value came from (robot.yaml, an SRDF state, zero, mimic...), as
    the assembly recorded it."""
    try:
        readiness = json.loads(path.read_text()).get("readiness") or {}
        return {str(h["joint"]): str(h["source"]) for h in readiness.get("home") or []}
    except (OSError, ValueError, AttributeError, KeyError, TypeError):
        return {}


def _checks(path: Path) -> dict[str, Any] | None:
    """What the check found: passed or not, its failures, the hold, stand and Menagerie tests;
    None when the build did not check."""
    from mjcfbuild.check.results import CheckResults

    results = CheckResults.read(path)
    if results is None:
        return None
    stand = results.stand
    menagerie = results.menagerie_test
    return {
        "passes": results.passes,
        "failures": [str(f) for f in results.failures],
        "stand": {
            "verdict": results.stand_verdict(),
            "max_tilt": stand.max_tilt,
            "max_sink": stand.max_sink,
        }
        if stand
        else None,
        "hold_deviation": results.hold.max_deviation if results.hold else None,
        "menagerie_finite": menagerie.finite if menagerie else None,
        "menagerie_warnings": len(menagerie.warnings) if menagerie else None,
    }


def _previews(folder: Path) -> dict[str, str]:
    """Each preview picture's file name and the MD5 of its bytes."""
    if not folder.is_dir():
        return {}
    return {
        path.name: hashlib.md5(path.read_bytes()).hexdigest()
        for path in sorted(folder.glob("*.png"))
    }
