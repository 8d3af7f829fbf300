"""Real robot descriptions from the ``example-robot-data`` wheel, downloaded into a cache.

The wheel (about 130 MB, from PyPI) carries some 39 robot descriptions with their meshes; their
licences are their own, so they are never copied into this repository. The wheel is fetched
once with ``pip download`` into ``$XDG_CACHE_HOME/mjcfbuild-dev`` (or ``MJCFBUILD_ROBOT_CACHE``)
and robots are unpacked from it on demand.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from dataclasses import dataclass
from pathlib import Path

VERSION = "6.0.0"
PACKAGE = "example-robot-data"
_PREFIX = "cmeel.prefix/share/example-robot-data/"


@dataclass(frozen=True)
class Robot:
    """One description in the wheel: its URDF, and whether it has a floating base."""

    name: str
    urdf: str
    floating: bool


ROBOTS = {
    robot.name: robot
    for robot in [
        Robot("panda", "robots/panda_description/urdf/panda.urdf", False),
        Robot("ur5", "robots/ur_description/urdf/ur5_robot.urdf", False),
        Robot("go1", "robots/go1_description/urdf/go1.urdf", True),
        Robot("go2", "robots/go2_description/urdf/go2.urdf", True),
        Robot("g1", "robots/g1_description/urdf/g1_29dof_rev_1_0.urdf", True),
        Robot("a1", "robots/a1_description/urdf/a1.urdf", True),
        Robot("z1", "robots/z1_description/urdf/z1.urdf", False),
        Robot("anymal_c", "robots/anymal_c_simple_description/urdf/anymal.urdf", True),
        Robot("allegro", "robots/allegro_hand_description/urdf/allegro_right_hand.urdf", False),
        Robot("so101", "robots/so_arm_description/urdf/so101.urdf", False),
        Robot("xarm7", "robots/xarm_description/urdf/xarm7.urdf", False),
        Robot("tiago", "robots/tiago_description/robots/tiago.urdf", True),
        Robot("talos", "robots/talos_data/robots/talos_full_v2.urdf", True),
        Robot("solo12", "robots/solo_description/robots/solo12.urdf", True),
    ]
}


# The rest of the wheel's robot descriptions (one URDF each), for bench/robot_suite.py: every
# robot the wheel carries, built from a bare robot.yaml. ``floating`` is what `mjcfbuild init`
# decides from the kinematics (mjcfbuild.urdf.base), checked by hand: legs, wheels, rotors.
# The test suite builds ROBOTS only (CI time); the bench builds them all. cassie_description
# ships SDF files only, which are not URDF.
MORE_ROBOTS = {
    robot.name: robot
    for robot in [
        Robot("alex", "robots/alex_description/urdf/alex_nub_hands.urdf", False),
        Robot(
            "alexander", "robots/alexander_description/urdf/alexander_v1.lowerBodyOnly.urdf", True
        ),
        Robot("anymal_b", "robots/anymal_b_simple_description/robots/anymal.urdf", True),
        Robot("asr_twodof", "robots/asr_twodof_description/urdf/TwoDofs.urdf", False),
        Robot("b1", "robots/b1_description/urdf/b1.urdf", True),
        Robot("baxter", "robots/baxter_description/urdf/baxter.urdf", False),
        Robot("bolt", "robots/bolt_description/robots/bolt.urdf", True),
        Robot("borinot", "robots/borinot_description/urdf/borinot_flying_arm_2.urdf", True),
        Robot("centauro", "robots/centauro_description/urdf/centauro.urdf", True),
        Robot(
            "double_pendulum", "robots/double_pendulum_description/urdf/double_pendulum.urdf", False
        ),
        Robot("finger_edu", "robots/finger_edu_description/robots/finger_edu.urdf", False),
        Robot("hector", "robots/hector_description/robots/quadrotor_base.urdf", True),
        Robot("hextilt", "robots/hextilt_description/urdf/hextilt_flying_arm_5.urdf", True),
        Robot("human", "robots/human_description/robots/human.urdf", True),
        Robot("hyq", "robots/hyq_description/robots/hyq_no_sensors.urdf", True),
        Robot("icub", "robots/icub_description/robots/icub_reduced.urdf", True),
        Robot("iris", "robots/iris_description/robots/iris.urdf", True),
        Robot("kinova", "robots/kinova_description/robots/kinova.urdf", False),
        Robot("laikago", "robots/laikago_description/urdf/laikago.urdf", True),
        Robot("pr2", "robots/pr2_description/urdf/pr2.urdf", True),
        Robot("quadruped", "robots/quadruped_description/urdf/quadruped.urdf", True),
        Robot("romeo", "robots/romeo_description/urdf/romeo_small.urdf", True),
        Robot(
            "simple_humanoid", "robots/simple_humanoid_description/urdf/simple_humanoid.urdf", True
        ),
        Robot("solo8", "robots/solo_description/robots/solo.urdf", True),
        Robot("tiago_pro", "robots/tiago_pro_description/robots/tiago_pro.urdf", True),
    ]
}
ALL_ROBOTS = {**ROBOTS, **MORE_ROBOTS}


def cache_dir() -> Path:
    """Where the wheel and unpacked robots are kept."""
    explicit = os.environ.get("MJCFBUILD_ROBOT_CACHE")
    if explicit:
        return Path(explicit)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache")
    return Path(base) / "mjcfbuild-dev"


def download_wheel(name: str, version: str, stem: str, pip_options: tuple[str, ...] = ()) -> Path:
    """The wheel of ``name`` ``version`` (file names start ``stem``), downloaded into the cache
    with ``pip download`` on first use (``pip_options`` added: ``--python-version`` and
    ``--platform`` for a wheel built only for another Python, whose data is all we read)."""
    folder = cache_dir()
    pattern = f"{stem}-{version}-*.whl"
    found = sorted(folder.glob(pattern))
    if found:
        return found[0]
    folder.mkdir(parents=True, exist_ok=True)
    command = [sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:"]
    command += [*pip_options, "--quiet", f"{name}=={version}", "-d", str(folder)]
    subprocess.run(command, check=True)
    return sorted(folder.glob(pattern))[0]


def wheel() -> Path:
    """The example-robot-data wheel, downloaded on first use."""
    return download_wheel(PACKAGE, VERSION, "example_robot_data")


def package_root() -> Path:
    """The unpacked ``example-robot-data`` package folder (package:// root)."""
    return cache_dir() / f"example-robot-data-{VERSION}"


def unpack(robot: Robot) -> Path:
    """Unpack the robot's description folder (once); the path of its URDF."""
    _unpack_folder("/".join(robot.urdf.split("/")[:2]) + "/")
    return package_root() / robot.urdf


def unpack_all() -> Path:
    """Unpack every description folder of the wheel (once each); the ``robots`` folder."""
    with zipfile.ZipFile(wheel()) as archive:
        names = [m[len(_PREFIX) :] for m in archive.namelist() if m.startswith(_PREFIX)]
    for top in sorted({"/".join(n.split("/")[:2]) + "/" for n in names if n.count("/") >= 2}):
        _unpack_folder(top)
    return package_root() / "robots"


def _unpack_folder(top: str) -> None:
    """Unpack the wheel's folder ``top`` (``robots/<name>/``) under :func:`package_root`."""
    root = package_root()
    marker = root / top / ".unpacked"
    if marker.exists():
        return
    with zipfile.ZipFile(wheel()) as archive:
        for member in archive.namelist():
            if member.startswith(_PREFIX + top) and not member.endswith("/"):
                target = root / member[len(_PREFIX) :]
                target.parent.mkdir(parents=True, exist_ok=True)
                with archive.open(member) as source, open(target, "wb") as out:
                    shutil.copyfileobj(source, out)
    marker.parent.mkdir(parents=True, exist_ok=True)
    marker.write_text("")


def copy_robot(robot: Robot, destination: Path) -> tuple[Path, Path]:
    """A private copy of the robot's package folder (for edits); (URDF, package root)."""
    unpack(robot)
    top = "/".join(robot.urdf.split("/")[:2])
    target_root = destination / "example-robot-data"
    shutil.copytree(package_root() / top, target_root / top)
    return target_root / robot.urdf, target_root


def manifest(
    robot: Robot,
    folder: Path,
    urdf: Path,
    packages_root: Path,
    extra: str = "",
    fuse_static: bool = True,
) -> Path:
    """Write a manifest building ``urdf`` into ``folder/mjcf``; its path."""
    path = folder / "robot.yaml"
    folder.mkdir(parents=True, exist_ok=True)
    path.write_text(
        f"name: {robot.name}\n"
        f"source:\n  urdf: {urdf}\n"
        f"packages:\n  example-robot-data: {packages_root}\n"
        f"options:\n  free_joint: {'true' if robot.floating else 'false'}\n"
        f"  fuse_static: {'true' if fuse_static else 'false'}\n"
        f"{extra}"
    )
    return path
