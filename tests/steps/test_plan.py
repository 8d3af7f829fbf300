"""The plan step: what it records of the files a URDF names, and when it reruns."""

from __future__ import annotations

import json

from tests.conftest import run_cli, simple_manifest, two_link_urdf, write

PAINTED = (
    '<material name="painted"><color rgba="1 0 0 1"/>\n'
    '<texture filename="textures/paint.png"/></material>'
)


def _textures(folder) -> list:
    """The texture of every material the plan records."""
    plan = json.loads((folder / "mjcf" / ".mjcfbuild" / "plan.json").read_text())
    shapes = [s for link in plan["robot"]["links"] for s in link["visuals"]]
    return [s["material"]["texture"] for s in shapes if s.get("material")]


def test_a_missing_texture_warns_and_is_used_once_it_appears(tmp_path):
    urdf = two_link_urdf().replace(
        '<material name="red"><color rgba="1 0 0 1"/></material>', PAINTED
    )
    write(tmp_path / "robot.urdf", urdf)
    line = next(n for n, text in enumerate(urdf.splitlines(), 1) if "<texture" in text)
    simple_manifest(tmp_path)
    warning = (
        f"robot.urdf:{line}: material 'painted': texture file 'textures/paint.png' not found; "
        "the model draws the material's colour, rgba 1 0 0 1"
    )
    first = run_cli("build", "--no-check", cwd=tmp_path)
    assert first.code == 0, first.stderr
    assert sum(warning in line for line in first.stderr.splitlines()) == 1, first.stderr
    assert _textures(tmp_path) == [None]

    texture = write(tmp_path / "textures" / "paint.png", "a texture")
    appeared = run_cli("build", "--no-check", cwd=tmp_path)
    assert appeared.code == 0, appeared.stderr
    assert "not found" not in appeared.stderr
    assert _textures(tmp_path) == [str(texture)]
    again = run_cli("build", "--no-check", cwd=tmp_path)
    assert " 0 run," in again.stdout, again.stdout  # a no-op once the plan saw it

    texture.unlink()
    removed = run_cli("build", "--no-check", cwd=tmp_path)
    assert removed.code == 0 and warning in removed.stderr, removed.stderr
    assert _textures(tmp_path) == [None]
