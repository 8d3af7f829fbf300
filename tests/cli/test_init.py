"""``mjcfbuild init`` writes a manifest that builds."""

from __future__ import annotations

from mjcfbuild.errors import EXIT_OK, EXIT_USAGE
from tests.conftest import EXAMPLES


def test_init_then_build(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    result = cli("init", str(source), "-o", "robot.yaml", cwd=tmp_path)
    assert result.code == EXIT_OK, result.stderr
    assert "mjcfbuild build robot.yaml" in result.stdout
    built = cli("build", "-q", cwd=tmp_path)
    assert built.code == EXIT_OK, built.stderr
    assert (tmp_path / "mjcf" / "example_arm.xml").exists()


def test_init_does_not_overwrite_without_force(cli, tmp_path):
    source = EXAMPLES / "arm" / "urdf" / "arm.urdf.xacro"
    (tmp_path / "robot.yaml").write_text("mine")
    result = cli("init", str(source), cwd=tmp_path)
    assert result.code == EXIT_USAGE and (tmp_path / "robot.yaml").read_text() == "mine"
    assert cli("init", str(source), "--force", cwd=tmp_path).code == EXIT_OK
