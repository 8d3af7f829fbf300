"""Versions of the tools each step uses, read without importing them."""

from __future__ import annotations

from functools import cache
from importlib import metadata

from mjcfbuild.version import __version__

# Bump a step's number when its output for the same inputs changes.
STEP_FORMATS = {
    "expand": 2,  # 2: the origins of the expanded lines
    "plan": 7,  # 5: ros2_control <hardware>; 6: chains deeper than MuJoCo reads; 7: Gazebo sensors
    "mesh": 5,
    "decompose": 3,
    "assemble": 12,  # 12: the Gazebo sensors' MJCF counterparts
    "scene": 3,
    "check": 9,  # 9: the Gazebo sensors table; torque-motor and wheel stand verdicts
    "reference": 1,
    "previews": 5,
    "tuning": 1,
    "srdf": 2,
    "selfcollision": 3,
    "export_urdf": 2,  # 2: mimic offsets with ref; speed limits from drives and the URDF
    "compose": 2,  # 2: the origins of the composed lines
    "mjcfpart": 1,
    "package": 2,  # 2: <dcmotor> gains rounded and shared in classes
    "training": 7,  # 7: solver per device (output.training.device); <position> servos for MJX
    "page": 2,  # 2: bold, pictures and quotes in the tables; the diff's changes section
}

STEP_TOOLS = {
    "expand": ("xacro",),
    "plan": ("lxml",),
    "mesh": ("trimesh", "numpy", "lxml", "pillow", "fast-simplification", "scipy"),
    "decompose": ("coacd", "trimesh", "numpy", "scipy"),
    "assemble": ("mujoco", "numpy", "lxml"),
    "scene": ("lxml",),
    "srdf": ("xacro", "lxml"),
    "selfcollision": ("mujoco", "numpy"),
    "check": ("mujoco", "numpy"),
    "reference": ("yourdfpy", "numpy", "lxml"),
    "previews": ("mujoco", "numpy", "pillow"),
    "tuning": ("mujoco", "numpy", "pillow"),
    "export_urdf": ("mujoco", "numpy"),
    "compose": ("lxml",),
    "mjcfpart": ("mujoco", "lxml"),
    "package": ("mujoco", "numpy", "lxml"),
    "training": ("mujoco", "numpy", "scipy", "trimesh", "lxml"),
    "page": (),
}


@cache
def tool_version(distribution: str) -> str:
    """The installed version of a distribution, or 'missing'."""
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return "missing"


def step_versions(step: str) -> dict[str, str]:
    """What a step's output depends on besides its inputs: tool versions and its format."""
    versions = {name: tool_version(name) for name in STEP_TOOLS[step]}
    versions["mjcfbuild-step"] = f"{step}-{STEP_FORMATS[step]}"
    versions["mjcfbuild"] = __version__
    return versions
