"""Preview pictures are drawn from the model as published, less what they never show, and
only when what they show changed."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import mujoco
from PIL import Image

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


def _render(scene: Path, drawn: dict | None = None) -> dict[str, str | None]:
    """render_previews in a process of its own: MuJoCo picks its OpenGL platform when it is
    imported, and this one may have imported it without MUJOCO_GL, as a worker never does."""
    code = (
        "import json, sys; from pathlib import Path; "
        "from mjcfbuild.check.previews import render_previews; "
        "scene = Path(sys.argv[1]); drawn = json.loads(sys.argv[2]); "
        "print(json.dumps(render_previews(scene, scene.parent / 'previews', 160, 120, None, drawn)))"
    )
    environment = {**os.environ, "MUJOCO_GL": "egl"}
    done = subprocess.run(
        [sys.executable, "-c", code, str(scene), json.dumps(drawn or {})],
        env=environment,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_the_skybox_is_left_out_and_the_pictures_stay_the_same(tmp_path):
    with_sky = _scene(tmp_path / "sky", SKYBOX)
    without = _scene(tmp_path / "plain", "")
    assert mujoco.MjModel.from_xml_path(str(with_sky)).ntex == 2
    assert _model_to_draw(with_sky, {})[1].ntex == 1  # the floor's checker only

    names = sorted(_render(with_sky))
    assert names == sorted(_render(without))
    assert len(names) == 4
    for name in names:
        drawn = (tmp_path / "sky" / "previews" / name).read_bytes()
        assert drawn == (tmp_path / "plain" / "previews" / name).read_bytes()


def test_a_skybox_texture_a_material_uses_is_kept(tmp_path):
    named = SKYBOX.replace('type="skybox"', 'name="sky" type="skybox"')
    scene = _scene(tmp_path, named, material_texture="sky")
    assert _model_to_draw(scene, {})[1].ntex == 2


def _two_meshes(folder: Path) -> Path:
    """A scene with a robot of two mesh geoms, one only seen and one that collides."""
    folder.mkdir(parents=True, exist_ok=True)
    _tetrahedron(folder / "shell.obj", 0.2)
    _tetrahedron(folder / "hull.obj", 0.15)
    scene = folder / "scene.xml"
    scene.write_text("""<mujoco>
  <include file="robot.xml"/>
  <worldbody>
    <light pos="0 0 1.5" dir="0 0 -1" directional="true"/>
    <geom name="floor" type="plane" size="0 0 0.05" rgba="0.3 0.4 0.5 1"/>
  </worldbody>
</mujoco>""")
    (folder / "robot.xml").write_text("""<mujoco model="robot">
  <asset>
    <mesh name="shell" file="shell.obj"/>
    <mesh name="hull" file="hull.obj"/>
  </asset>
  <worldbody>
    <body name="link" pos="0 0 0.3">
      <joint name="hinge" damping="1"/>
      <geom type="mesh" mesh="shell" contype="0" conaffinity="0" rgba="0.2 0.6 0.9 1"/>
      <geom type="mesh" mesh="hull" pos="0.1 0 0"/>
    </body>
  </worldbody>
</mujoco>""")
    return scene


def _tetrahedron(path: Path, size: float, tip: float = 1.0, lean: float = 0.0) -> None:
    path.write_text(
        f"v 0 0 0\nv {size} 0 0\nv 0 {size} 0\nv {lean} 0 {size * tip}\n"
        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    )


def _pictures(folder: Path) -> set[str]:
    return {path.name for path in (folder / "previews").glob("*.png")}


def _forget_pictures(folder: Path) -> None:
    for path in (folder / "previews").glob("*.png"):
        path.unlink()


def test_only_the_pictures_of_what_changed_are_drawn_again(tmp_path):
    scene = _two_meshes(tmp_path)
    first = _render(scene)
    assert _pictures(tmp_path) == set(first) and None not in first.values()
    with Image.open(tmp_path / "previews" / "front_visual.png") as picture:
        assert picture.size == (160, 120)  # drawn larger, reduced to the size asked for
    assert first["front_visual.png"] == first["side_visual.png"] != first["front_collision.png"]

    _forget_pictures(tmp_path)  # a picture not drawn again is not written again
    assert _render(scene, first) == first
    assert _pictures(tmp_path) == set()

    _tetrahedron(tmp_path / "hull.obj", 0.15, tip=0.9)  # lower, inside the frame
    hull_changed = _render(scene, first)
    assert _pictures(tmp_path) == {"front_collision.png", "side_collision.png"}
    assert hull_changed["front_visual.png"] == first["front_visual.png"]
    assert hull_changed["front_collision.png"] != first["front_collision.png"]

    _forget_pictures(tmp_path)
    _tetrahedron(tmp_path / "shell.obj", 0.2, lean=0.05)  # inside the frame too
    shell_changed = _render(scene, hull_changed)
    assert _pictures(tmp_path) == {"front_visual.png", "side_visual.png"}
    assert shell_changed["front_collision.png"] == hull_changed["front_collision.png"]


def test_what_both_kinds_show_draws_both_again(tmp_path):
    scene = _two_meshes(tmp_path)
    first = _render(scene)
    robot = tmp_path / "robot.xml"
    changes = {
        "the pose": ('pos="0 0 0.3"', 'pos="0 0 0.4"'),
        "the frame (a mesh grew)": None,
        "the floor": ('rgba="0.3 0.4 0.5 1"', 'rgba="0.3 0.4 0.6 1"'),
    }
    for change, edit in changes.items():
        _forget_pictures(tmp_path)
        if edit is None:
            _tetrahedron(tmp_path / "hull.obj", 0.15, tip=3.0)
        else:
            path = scene if change == "the floor" else robot
            path.write_text(path.read_text().replace(*edit))
        redrawn = _render(scene, first)
        assert len(_pictures(tmp_path)) == 4, change
        assert not set(redrawn.values()) & set(first.values()), change
        first = redrawn

    _forget_pictures(tmp_path)  # damping does not show
    robot.write_text(robot.read_text().replace('damping="1"', 'damping="2"'))
    assert _render(scene, first) == first
    assert _pictures(tmp_path) == set()


def test_a_process_that_draws_twice_draws_what_a_new_process_draws(tmp_path):
    """A worker keeps its OpenGL context from one model's previews to the next (a resident
    worker, from one build to the next): nothing of the first drawing shows in the second."""
    first, second = _two_meshes(tmp_path / "one"), _scene(tmp_path / "two", SKYBOX)
    code = (
        "import sys; from pathlib import Path; "
        "from mjcfbuild.check.previews import render_previews; "
        "[render_previews(Path(a), Path(a).parent / 'again', 160, 120) for a in sys.argv[1:]]"
    )
    environment = {**os.environ, "MUJOCO_GL": "egl"}
    done = subprocess.run(
        [sys.executable, "-c", code, str(first), str(second)],
        env=environment,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    _render(second)  # alone, in a process of its own
    pictures = sorted((tmp_path / "two" / "previews").glob("*.png"))
    assert len(pictures) == 4
    for picture in pictures:
        assert picture.read_bytes() == (tmp_path / "two" / "again" / picture.name).read_bytes()
