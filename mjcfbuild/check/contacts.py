"""Geoms already touching at rest: listed, with the contact excludes that would silence them."""

from __future__ import annotations

import json
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol


class PartFiles(Protocol):
    """An ``attach:`` MJCF part as the check step passes it (steps.payloads.MjcfPartFiles):
    the check sits below the steps, so it names only what it reads."""

    @property
    def prefix(self) -> str: ...

    @property
    def label(self) -> str: ...

    @property
    def summary(self) -> str: ...


@dataclass
class RestingContact:
    """Two bodies whose collision geoms touch at the home (or zero) configuration."""

    body1: str
    body2: str
    depth: float
    pose: str


def resting_contacts(model) -> list[RestingContact]:
    """Robot body pairs in contact at the 'home' keyframe (at qpos0 if there is none)."""
    import mujoco

    found: dict[tuple[str, str], RestingContact] = {}
    data = mujoco.MjData(model)
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    poses = [("home", home)] if home >= 0 else [("zero", None)]
    for label, key in poses:
        mujoco.mj_resetData(model, data)
        if key is not None:
            mujoco.mj_resetDataKeyframe(model, data, key)
        mujoco.mj_forward(model, data)
        for contact in data.contact[: data.ncon]:
            if contact.dist > 0:
                continue  # within a margin, not touching
            if mujoco.mjtGeom.mjGEOM_PLANE in (
                model.geom_type[contact.geom1],
                model.geom_type[contact.geom2],
            ):
                continue  # the scene's floor, not the robot
            bodies = sorted(
                mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[g]) or "world"
                for g in (contact.geom1, contact.geom2)
            )
            pair = (bodies[0], bodies[1])
            if pair[0] == pair[1] or pair in found:
                continue
            found[pair] = RestingContact(pair[0], pair[1], float(-contact.dist), label)
    return sorted(found.values(), key=lambda c: (c.body1, c.body2))


def exclude_suggestion(contacts: list[RestingContact]) -> str:
    """A ``<contact>`` block excluding the pairs, ready for raw inputs."""
    if not contacts:
        return ""
    lines = ["<contact>"]
    lines += [f'  <exclude body1="{c.body1}" body2="{c.body2}"/>' for c in contacts]
    lines.append("</contact>")
    return "\n".join(lines)


def split_by_part(
    contacts: list[RestingContact], part_bodies: dict[str, set[str]]
) -> tuple[list[RestingContact], list[tuple[str, RestingContact]]]:
    """The contacts between bodies of the model, and those inside one MJCF part (with the
    part's name): a hand-tuned part's own contacts at rest are the part's business, as
    MuJoCo Menagerie's tests accept a gripper whose fingers touch when closed."""
    model_pairs: list[RestingContact] = []
    inside: list[tuple[str, RestingContact]] = []
    for contact in contacts:
        part = next(
            (
                name
                for name, bodies in sorted(part_bodies.items())
                if contact.body1 in bodies and contact.body2 in bodies
            ),
            None,
        )
        if part is None:
            model_pairs.append(contact)
        else:
            inside.append((part, contact))
    return model_pairs, inside


def part_bodies(parts: Iterable[PartFiles]) -> dict[str, set[str]]:
    """Each MJCF part's bodies as the model names them, by the part's prefix and file."""
    from mjcfbuild.compose.mjcf import PartSummary

    found = {}
    for entry in parts:
        try:
            summary = PartSummary.from_dict(json.loads(Path(entry.summary).read_text()))
        except (OSError, ValueError, KeyError):
            continue  # the part check reports an unreadable part
        found[f"{entry.prefix} ({entry.label})"] = {entry.prefix + b for b in summary.bodies}
    return found
