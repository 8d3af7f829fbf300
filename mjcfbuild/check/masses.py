"""Masses and inertias of the model's bodies against the URDF's links.

Each model body carries its own link and the links fused into it (those appearing as sites
of the body, or found only through the URDF's fixed joints). Their URDF masses and inertias
are combined here with the parallel axis theorem, independently of the assembly, and
compared with what MuJoCo compiled.
"""

from __future__ import annotations

import numpy as np

from mjcfbuild.check.findings import Problem
from mjcfbuild.urdf.kinematics import link_poses
from mjcfbuild.urdf.model import Robot
from mjcfbuild.urdf.transforms import Transform


def compare_masses(
    robot: Robot, model, repaired: set[str], tolerance: float = 1e-6
) -> tuple[list[Problem], float, float]:
    """(problems, URDF total mass, model total mass); ``repaired`` bodies are not compared.

    Numbers are compared relative to their size (``tolerance`` times the value; centres of
    mass times the larger of 1 m and their distance). A wrong mass is structural: it is
    another part, not a rounding of this one.
    """
    import mujoco

    poses = link_poses(robot)
    owner = owner_bodies(robot, model)
    groups: dict[int, list[str]] = {}
    for link, body in owner.items():
        groups.setdefault(body, []).append(link)
    problems = []
    for body, links in sorted(groups.items()):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or "world"
        if name in repaired or body == 0:
            continue
        mass, com, inertia = _combined(robot, links, poses, _body_pose(model, body, poses, links))
        model_mass = float(model.body_mass[body])
        if abs(mass - model_mass) > tolerance * max(abs(mass), 1e-12):
            problems.append(
                Problem(
                    f"body '{name}': mass {mass:.9g} in the URDF "
                    f"(links {', '.join(sorted(links))}), {model_mass:.9g} in the model",
                    structural=True,
                )
            )
            continue
        if mass <= 0:
            continue
        model_com = model.body_ipos[body]
        if np.linalg.norm(model_com - com) > tolerance * max(1.0, float(np.linalg.norm(com))):
            problems.append(
                Problem(
                    f"body '{name}': centre of mass {_vector(com)} in the URDF, "
                    f"{_vector(model_com)} in the model (body frame)"
                )
            )
            continue
        model_tensor = _model_tensor(model, body)
        if np.max(np.abs(model_tensor - inertia)) > tolerance * max(1e-9, np.max(np.abs(inertia))):
            problems.append(
                Problem(
                    f"body '{name}': inertia {_matrix(inertia)} in the URDF, "
                    f"{_matrix(model_tensor)} in the model (about the centre of mass, body frame)"
                )
            )
    model_total = float(np.sum(model.body_mass))
    return problems, urdf_mass(robot), model_total


def urdf_mass(robot: Robot) -> float:
    """The robot's total mass, as its links' ``<inertial>`` elements give it."""
    return sum(link.inertial.mass for link in robot.links if link.inertial is not None)


def placeholder_bodies(robot: Robot, model) -> list[str]:
    """The moving bodies with geometry none of whose URDF links has a mass (no ``<inertial>``,
    or mass 0): the build gave them a placeholder (``inertia.min_mass``), not the robot's."""
    import mujoco

    links_of: dict[int, list[str]] = {}
    for link, body in owner_bodies(robot, model).items():
        links_of.setdefault(body, []).append(link)
    drawn = {int(body) for body in model.geom_bodyid}
    found = []
    for body, links in sorted(links_of.items()):
        if body == 0 or int(model.body_weldid[body]) == 0 or body not in drawn:
            continue
        inertials = [robot.link(link).inertial for link in links]
        if all(inertial is None or inertial.mass <= 0 for inertial in inertials):
            found.append(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or f"#{body}")
    return found


def owner_bodies(robot: Robot, model) -> dict[str, int]:
    """The model body each URDF link belongs to: its own body, its site's, or its parent's."""
    import mujoco

    owner: dict[str, int] = {}
    parents = robot.parent_joint()
    for link in robot.links:
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link.name)
        if body < 0 and link.name != "world":
            site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, link.name)
            if site >= 0:
                body = int(model.site_bodyid[site])
        if body >= 0:
            owner[link.name] = body
        elif link.name == "world":
            owner[link.name] = 0
    # Links with no trace in the model follow their fixed joints to one that has one.
    for link in robot.links:
        name = link.name
        while name not in owner and name in parents and not parents[name].moves:
            name = parents[name].parent
        if name in owner and link.name not in owner:
            owner[link.name] = owner[name]
    return owner


def _body_pose(model, body, poses, links) -> Transform:
    """The body's frame in URDF coordinates: the pose of its own link, or of a site link."""
    import mujoco

    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body)
    if name in poses:
        return poses[name]
    # A body not named after a link: place it from one of its links' sites.
    link = links[0]
    site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, link)
    site_in_body = Transform.from_quat(tuple(model.site_pos[site]), tuple(model.site_quat[site]))
    return poses[link].compose(site_in_body.inverse())


def _combined(robot: Robot, links: list[str], poses, body_pose: Transform):
    to_body = body_pose.inverse()
    total = 0.0
    moment = np.zeros(3)
    parts = []
    for name in links:
        inertial = robot.link(name).inertial
        if inertial is None:
            continue
        frame = to_body.compose(poses[name]).compose(Transform.from_pose(inertial.origin))
        rotation = np.array(frame.rotation)
        ixx, ixy, ixz, iyy, iyz, izz = inertial.inertia
        local = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        parts.append((inertial.mass, np.array(frame.position), rotation @ local @ rotation.T))
        total += inertial.mass
        moment += inertial.mass * np.array(frame.position)
    if not parts:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    com = moment / total if total > 0 else parts[0][1]
    tensor = np.zeros((3, 3))
    for mass, position, rotated in parts:
        d = position - com
        tensor += rotated + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return total, com, tensor


def _model_tensor(model, body: int) -> np.ndarray:
    """The compiled inertia of a body as a tensor in the body frame, about its centre of mass."""
    import mujoco

    flat = np.zeros(9)
    mujoco.mju_quat2Mat(flat, model.body_iquat[body])
    rotation = flat.reshape(3, 3)
    return rotation @ np.diag(model.body_inertia[body]) @ rotation.T


def _vector(values) -> str:
    return "(" + ", ".join(f"{float(v):.6g}" for v in values) + ")"


def _matrix(tensor: np.ndarray) -> str:
    values = [tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1], tensor[0, 2], tensor[1, 2]]
    return "(" + ", ".join(f"{v:.6g}" for v in values) + ")"
