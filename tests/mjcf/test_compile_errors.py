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
