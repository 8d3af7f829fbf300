"""Preview pictures are drawn from the model as published, less what they never show."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import mujoco

from mjcfbuild.check.previews import _model_to_draw

SKYBOX = (
    '<texture type="skybox" builtin="gradient" rgb1="0.3 0.5 0.7" rgb2="0 0 0" '
    'width="64" height="384"/>'
)


def _scene(folder: Path, sky: str, material_texture: str = "ground") -> Path:
    """A box on a checkered floor under a light; ``sky`` is the skybox texture element."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "scene.xml"
    path.write_text(f"""<mujoco>
  <asset>
    {sky}
    <texture type="2d" name="ground" builtin="checker" rgb1="0.2 0.3 0.4" rgb2="0.1 0.2 0.3"
      width="64" height="64"/>
    <material name="ground" texture="{material_texture}" texrepeat="4 4"/>
  </asset>
  <worldbody>
    <light pos="0 0 1.5" dir="0 0 -1" directional="true"/>
    <geom name="floor" type="plane" size="0 0 0.05" material="ground"/>
    <body pos="0 0 0.2">
      <freejoint/>
      <geom type="box" size="0.1 0.15 0.2" rgba="0.8 0.3 0.3 1"/>
      <geom type="sphere" size="0.05" pos="0 0 0.3" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>""")
    return path


def _render(scene: Path) -> list[str]:
    """render_previews in a process of its own: MuJoCo picks its OpenGL platform when it is
    imported, and this one may have imported it without MUJOCO_GL, as a worker never does."""
    code = (
        "import json, sys; from pathlib import Path; "
        "from mjcfbuild.check.previews import render_previews; "
        "scene = Path(sys.argv[1]); "
        "print(json.dumps(render_previews(scene, scene.parent / 'previews', 160, 120)))"
    )
    environment = {**os.environ, "MUJOCO_GL": "egl"}
    done = subprocess.run(
        [sys.executable, "-c", code, str(scene)], env=environment, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_the_skybox_is_left_out_and_the_pictures_stay_the_same(tmp_path):
    with_sky = _scene(tmp_path / "sky", SKYBOX)
    without = _scene(tmp_path / "plain", "")
    assert mujoco.MjModel.from_xml_path(str(with_sky)).ntex == 2
    assert _model_to_draw(with_sky, {}).ntex == 1  # the floor's checker only

    names = _render(with_sky)
    assert names == _render(without)
    assert len(names) == 4
    for name in names:
        drawn = (tmp_path / "sky" / "previews" / name).read_bytes()
        assert drawn == (tmp_path / "plain" / "previews" / name).read_bytes()


def test_a_skybox_texture_a_material_uses_is_kept(tmp_path):
    named = SKYBOX.replace('type="skybox"', 'name="sky" type="skybox"')
    scene = _scene(tmp_path, named, material_texture="sky")
    assert _model_to_draw(scene, {}).ntex == 2
