"""The MJCF mujoco_ros2_control loads (<param name="mujoco_model">) against the built model.

on_init (mujoco_system_interface.cpp) loads the file the param names, trimmed, and stops where
there is none ("MuJoCo model file '...' does not exist!"); without the param it waits for the
model on a topic. The check says where the param names another file than the one it judged.
"""

from __future__ import annotations

import json

import mjcfbuild
from mjcfbuild.errors import EXIT_CHECK, EXIT_OK
from tests.check.test_runtime import control_block
from tests.conftest import run_cli, two_link_urdf, write


def _build(folder, model: str, xacro: bool = False, package_xml: bool = True):
    """The two-link robot in package r_pkg (``folder``, which robot.yaml's packages name), its
    block's mujoco_model ``model``."""
    hardware = f'<param name="mujoco_model">{model}</param>'
    text = two_link_urdf(extra=control_block(["position"], hardware))
    if package_xml:
        write(folder / "package.xml", '<package format="3"><name>r_pkg</name></package>')
    name = "robot.urdf.xacro" if xacro else "robot.urdf"
    write(
        folder / name,
        text.replace("<robot ", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" '),
    )
    kind = "xacro" if xacro else "urdf"
    write(
        folder / "robot.yaml",
        f"name: r\nsource: {{{kind}: {name}}}\npackages: {{r_pkg: .}}\n",
    )
    return mjcfbuild.build(folder / "robot.yaml")


def _said(result) -> list[str]:
    return [w for w in result.warnings if "mujoco_model" in w]


def test_a_mujoco_model_naming_another_file_of_the_package_is_warned_at_its_line(tmp_path):
    """xacro's $(find r_pkg) is the package's folder: its mujoco/robot.xml is not the scene
    the build writes (mjcf/scene.xml), which the runtime would then not load."""
    other = _build(tmp_path / "other", "$(find r_pkg)/mujoco/robot.xml", xacro=True)
    (said,) = _said(other)
    # At the xacro file's line, with the expanded one the build read; the file as $(find)
    # names it, the same in every checkout (not the absolute path it expanded to).
    assert said.startswith(
        "robot.urdf.xacro:15: <hardware> param mujoco_model names $(find r_pkg)/mujoco/robot.xml, "
        "which is neither the model checked here nor its scene: mujoco_ros2_control loads that "
        "file, so this check does not judge what it runs; point the param at the built scene, "
        "mjcf/scene.xml ($(find r_pkg)/mjcf/scene.xml) (or install the built files there) "
        "[expanded: "
    ), said
    for model in ("$(find r_pkg)/mjcf/scene.xml", "$(find r_pkg)/mjcf/r.xml"):
        assert not _said(_build(tmp_path / "same", model, xacro=True))
    # A package robot.yaml names is one without a package.xml too.
    bare = _build(tmp_path / "bare", "$(find r_pkg)/mujoco/robot.xml", True, package_xml=False)
    (said,) = _said(bare)
    assert "point the param at the built scene, mjcf/scene.xml ($(find r_pkg)/mjcf/" in said


def test_a_mujoco_model_is_related_to_the_build_only_where_it_can_be(tmp_path):
    """An install space's share/r_pkg/ holds the package's files: its mjcf/scene.xml is the
    built scene, its mujoco/scene.xml another file. A relative path (the controller manager's
    working folder) and an absolute one in no package are not claimed to differ."""
    install = "/ws/install/r_pkg/share/r_pkg"
    assert not _said(_build(tmp_path / "installed", f"{install}/mjcf/scene.xml"))
    other = _said(_build(tmp_path / "elsewhere", f"{install}/mujoco/scene.xml"))
    assert len(other) == 1 and f"names {install}/mujoco/scene.xml, which is neither" in other[0]
    for model in ("mjcf/scene.xml", "/opt/models/scene.xml"):
        assert not _said(_build(tmp_path / "unrelated", model))


def test_an_empty_mujoco_model_stops_the_runtime(tmp_path):
    """A <param name="mujoco_model"/> (a xacro argument left empty, say) is a file name to the
    runtime: "MuJoCo model file '' does not exist!", and it stops."""
    write(tmp_path / "package.xml", '<package format="3"><name>r_pkg</name></package>')
    write(
        tmp_path / "robot.urdf",
        two_link_urdf(extra=control_block(["position"], '<param name="mujoco_model"> </param>')),
    )
    write(tmp_path / "robot.yaml", "name: r\nsource: {urdf: robot.urdf}\n")
    result = run_cli("build", str(tmp_path / "robot.yaml"))
    assert result.code == EXIT_CHECK, result.stderr
    failures = json.loads((tmp_path / "mjcf/.mjcfbuild/check.json").read_text())["failures"]
    assert failures == [
        "robot.urdf:15: <hardware> param mujoco_model is empty: mujoco_ros2_control takes it for "
        "a file name and stops at start-up (\"MuJoCo model file '' does not exist!\"); name the "
        "built scene, mjcf/scene.xml ($(find r_pkg)/mjcf/scene.xml), or leave the param out to "
        "load the model from mujoco_model_topic"
    ]


def test_check_urdf_compares_the_mujoco_model_with_the_mjcf_it_checks(tmp_path):
    """check --urdf --mjcf: the MJCF given is the model the runtime should load."""
    write(tmp_path / "package.xml", '<package format="3"><name>r_pkg</name></package>')
    assert _build(tmp_path, "unused").robot is not None
    mjcf = tmp_path / "mjcf" / "r.xml"
    for model, said in ((mjcf, False), (tmp_path / "mujoco" / "r.xml", True)):
        hardware = f'<param name="mujoco_model">{model}</param>'
        write(tmp_path / "p.urdf", two_link_urdf(extra=control_block(["position"], hardware)))
        result = run_cli("check", "--urdf", "p.urdf", "--mjcf", "mjcf/r.xml", cwd=tmp_path)
        assert result.code == EXIT_OK, result.stderr
        warned = "p.urdf:15: <hardware> param mujoco_model names" in result.stdout + result.stderr
        assert warned == said, result.stdout + result.stderr
        if said:
            assert "point the param at the built scene, mjcf/r.xml" in result.stdout + result.stderr
