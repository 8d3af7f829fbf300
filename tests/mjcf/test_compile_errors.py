"""MuJoCo's compile errors as one line naming the description's file, line and mesh."""

from __future__ import annotations

import mujoco
import pytest

from mjcfbuild.mjcf.compile_errors import compile_error
from mjcfbuild.mjcf.prepared import MeshAsset


def test_a_mesh_too_small_is_named_by_its_file_where_mujoco_names_its_import_name(tmp_path):
    # The self-collision step compiles the URDF through MuJoCo's import, which names a mesh
    # after its file stem ('mesh' for every product): the error named neither file nor line.
    tiny = tmp_path / "mesh.obj"
    tiny.write_text(
        "v 0 0 0\nv 1e-9 0 0\nv 0 1e-9 0\nv 0 0 1e-9\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    )
    with pytest.raises(ValueError) as refused:
        mujoco.MjModel.from_xml_string(
            f'<mujoco><asset><mesh file="{tiny}"/></asset><worldbody><geom type="mesh" '
            'mesh="mesh"/></worldbody></mujoco>'
        )
    asset = MeshAsset("mesh", "tiny.obj", str(tiny), (1.0, 1.0, 1.0), line=11, uri="tiny.obj")
    error = compile_error(refused.value, "r.urdf", [asset])
    assert error.one_line().startswith(
        "r.urdf:11: MuJoCo: mesh surface area is too small: mesh 'tiny.obj' (MuJoCo "
    )


def test_an_error_about_a_joint_named_like_a_link_is_not_blamed_on_the_link():
    # MuJoCo names the failing element by its name only; a URDF joint may share a link's name,
    # so only a mass or inertia error is taken for a body's.
    from mjcfbuild.mjcf.bodies import build_bodies
    from mjcfbuild.mjcf.compile_errors import body_error
    from mjcfbuild.urdf.parse import parse_urdf
    from tests.conftest import two_link_urdf

    robot = parse_urdf(two_link_urdf().encode(), "r.urdf")
    bodies = build_bodies(robot, fuse_static=True)
    with pytest.raises(ValueError) as refused:
        mujoco.MjModel.from_xml_string(
            '<mujoco><worldbody><body name="arm"><joint name="arm" limited="true" range="1 0"/>'
            '<geom size="0.1"/></body></worldbody></mujoco>'
        )
    message = str(refused.value).splitlines()[0].removeprefix("Error: ")
    assert "Element name 'arm'" in str(refused.value)
    assert body_error(message, str(refused.value), robot, bodies) is None
    inertia = "inertia must satisfy A + B >= C\nElement name 'arm', id 2"
    blamed = body_error("inertia must satisfy A + B >= C", inertia, robot, bodies)
    assert blamed is not None and blamed.location.file == "r.urdf"
