"""The decompose step of a mesh that shows nothing (a DAE without a scene): no parts, no
CoACD, and the build goes on without the mesh."""

from __future__ import annotations

import json

from mjcfbuild.errors import EXIT_OK
from tests.conftest import run_cli, write
from tests.meshes.test_collada import MATERIAL, QUAD, dae


def test_a_mesh_without_a_scene_decomposes_into_nothing(tmp_path):
    write(tmp_path / "loose.dae", dae(QUAD + MATERIAL.format(diffuse="<color>1 0 0 1</color>")))
    box = '<geometry><box size="0.1 0.1 0.1"/></geometry>'
    mesh = '<geometry><mesh filename="loose.dae"/></geometry>'
    write(
        tmp_path / "robot.urdf",
        f'<robot name="r"><link name="base"><visual>{box}</visual><collision>{box}</collision>'
        f"<visual>{mesh}</visual><collision>{mesh}</collision></link></robot>",
    )
    write(
        tmp_path / "robot.yaml",
        "name: r\nsource:\n  urdf: robot.urdf\ncollision:\n  default: decompose\n",
    )
    result = run_cli("build", "--no-check", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    assert "nothing to decompose: the mesh shows nothing" in result.stdout
    warnings = json.loads((tmp_path / "mjcf" / "report" / "report.json").read_text())["warnings"]
    assert any(w.startswith("loose.dae: it has no <scene>") for w in warnings), warnings
