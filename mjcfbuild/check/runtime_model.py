"""The MJCF mujoco_ros2_control loads, against the model the check judges.

on_init reads the ``<hardware>`` param ``mujoco_model``: where there is one, the runtime loads
that file (its value trimmed of white space) and stops at start-up where no file of that name
is there; where there is none, it waits for an MJCF on the topic ``mujoco_model_topic``
(``/mujoco_robot_description``), which says nothing of a file. A path is compared with the
built model and scene where it can be related to them: the same file, or the same file of the
same ROS package (an install space's ``share/<package>/`` holds a copy of the source package's
files). A relative path, which the runtime resolves from the controller manager's working
folder, an absolute one in no package, and one in an install space where the built files are in
no package, are not said to be other files.
"""

from __future__ import annotations

from pathlib import Path, PurePath

from mjcfbuild.inputs.ros2_control import Ros2Control
from mjcfbuild.sources.packages import PACKAGE_PATTERN, find_enclosing_package

PARAM = "mujoco_model"


def model_param(
    control: Ros2Control, built: tuple[tuple[Path, str], ...], packages: dict[str, Path]
) -> tuple[list[str], list[str]]:
    """What the runtime makes of ``<param name="mujoco_model">``, given the ``built`` files
    (path and how messages name it; the last is the one to load) and the folders of the
    ``packages`` robot.yaml names (which $(find pkg) expanded to): a failure where it is empty
    (the runtime stops at start-up), a warning where it names a file other than the built
    ones. The failures and the warnings."""
    if PARAM not in control.hardware or not built:
        return [], []
    value, where = control.hardware[PARAM], control.at(PARAM)
    target, label = built[-1]
    place = _in_package(target, packages)
    hint = f" ($(find {place[0]})/{place[1]})" if place else ""
    if not value:
        return [
            f"{where}<hardware> param {PARAM} is empty: mujoco_ros2_control takes it for a file "
            f"name and stops at start-up (\"MuJoCo model file '' does not exist!\"); name the "
            f"built scene, {label}{hint}, or leave the param out to load the model from "
            "mujoco_model_topic"
        ], []
    path = PurePath(value)
    if not path.is_absolute() or any(_same(Path(value), file) for file, _ in built):
        return [], []
    named = _in_package(Path(value), packages)
    packaged = {_in_package(file, packages) for file, _ in built} - {None}
    if named is None or named in packaged:
        return [], []
    installed = _installed(Path(value), packages)
    if not packaged and installed:
        return [], []  # an install space's file of a package the built files are in no part of
    # A file of a package on this machine named as $(find) wrote it: the same words in every
    # checkout (its absolute path made the reports of two folders differ); an install space's
    # path as the description wrote it.
    shown = value if installed else f"$(find {named[0]})/{named[1]}"
    return [], [
        f"{where}<hardware> param {PARAM} names {shown}, which is neither the model checked "
        "here nor its scene: mujoco_ros2_control loads that file, so this check does not "
        f"judge what it runs; point the param at the built scene, {label}{hint} (or install "
        "the built files there)"
    ]


def _same(first: Path, second: Path) -> bool:
    return first.resolve() == second.resolve()


def _installed(path: Path, packages: dict[str, Path]) -> bool:
    """Whether ``path`` is known to be in a package only by an install space's
    ``share/<package>/`` in it."""
    return _in_folders(path, packages) is None and find_enclosing_package(path) is None


def _in_folders(path: Path, packages: dict[str, Path]) -> tuple[str, str] | None:
    """The innermost of ``packages`` whose folder holds ``path``, and its path there."""
    resolved = path.resolve()
    holding = [
        (name, folder.resolve())
        for name, folder in packages.items()
        if resolved.is_relative_to(folder.resolve())
    ]
    if not holding:
        return None
    name, folder = max(holding, key=lambda item: len(item[1].parts))
    return name, resolved.relative_to(folder).as_posix()


def _in_package(path: Path, packages: dict[str, Path]) -> tuple[str, str] | None:
    """The ROS package ``path`` is a file of, and its path there: one of ``packages`` whose
    folder holds it, else the package.xml above it, else an install space's
    ``share/<package>/`` in the path itself."""
    known = _in_folders(path, packages)
    if known is not None:
        return known
    enclosing = find_enclosing_package(path)
    if enclosing is not None:
        name, folder = enclosing
        return name, path.relative_to(folder).as_posix()
    parts = path.parts
    shares = [index for index, part in enumerate(parts[:-2]) if part == "share"]
    if shares and PACKAGE_PATTERN.match(parts[shares[-1] + 1]):
        index = shares[-1]
        return parts[index + 1], PurePath(*parts[index + 2 :]).as_posix()
    return None
