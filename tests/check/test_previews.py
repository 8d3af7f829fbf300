"""Preview pictures are drawn from the model as published, less what they never show, and
only when what they show changed."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import mujoco
import pytest
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


def _render(
    scene: Path, drawn: dict | None = None, cache: Path | None = None
) -> dict[str, str | None]:
    """render_previews in a process of its own: MuJoCo picks its OpenGL platform when it is
    imported, and this one may have imported it without MUJOCO_GL, as a worker never does.
    ``cache``: a folder that keeps the pictures by what they show, as the shared cache does."""
    code = (
        "import json, sys; from pathlib import Path; "
        "from mjcfbuild.check.previews import render_previews; "
        "scene = Path(sys.argv[1]); drawn = json.loads(sys.argv[2]); "
        "kept = Path(sys.argv[3]) if sys.argv[3] else None\n"
        "class Kept:\n"
        "    def get(self, shows):\n"
        "        path = kept / shows\n"
        "        return path.read_bytes() if path.exists() else None\n"
        "    def put(self, shows, png):\n"
        "        kept.mkdir(exist_ok=True); (kept / shows).write_bytes(png)\n"
        "cache = Kept() if kept else None\n"
        "print(json.dumps(render_previews(scene, scene.parent / 'previews', 160, 120, None, "
        "drawn, cache)))"
    )
    environment = {**os.environ, "MUJOCO_GL": "egl"}
    done = subprocess.run(
        [sys.executable, "-c", code, str(scene), json.dumps(drawn or {}), str(cache or "")],
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
    assert len(names) == 5  # three-quarter and side, each kind; top; a box has no hand
    for name in names:
        drawn = (tmp_path / "sky" / "previews" / name).read_bytes()
        assert drawn == (tmp_path / "plain" / "previews" / name).read_bytes()


def test_a_skybox_texture_a_material_uses_is_kept(tmp_path):
    named = SKYBOX.replace('type="skybox"', 'name="sky" type="skybox"')
    scene = _scene(tmp_path, named, material_texture="sky")
    assert _model_to_draw(scene, {})[1].ntex == 2


def _two_meshes(folder: Path) -> Path:
    """A scene with a robot of two mesh geoms, one only seen and one that collides, inside a
    box that collides: the box decides how the views are framed, until a mesh grows out of it."""
    folder.mkdir(parents=True, exist_ok=True)
    _tetrahedron(folder / "shell.obj", 0.2)
    _tetrahedron(folder / "hull.obj", 0.1)
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
      <geom type="mesh" mesh="hull" pos="0.02 0.02 0.02"/>
      <geom type="box" size="0.16 0.16 0.16" pos="0.05 0.05 0.1"/>
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
    with Image.open(tmp_path / "previews" / "three_quarter_visual.png") as picture:
        assert picture.size == (160, 120)  # drawn larger, reduced to the size asked for
    assert len(set(first.values())) == len(first)  # each picture shows its own view and kind

    _forget_pictures(tmp_path)  # a picture not drawn again is not written again
    assert _render(scene, first) == first
    assert _pictures(tmp_path) == set()

    _tetrahedron(tmp_path / "hull.obj", 0.1, tip=0.9)  # lower, inside the box
    hull_changed = _render(scene, first)
    assert _pictures(tmp_path) == {"three_quarter_collision.png", "side_collision.png"}
    assert hull_changed["three_quarter_visual.png"] == first["three_quarter_visual.png"]
    assert hull_changed["three_quarter_collision.png"] != first["three_quarter_collision.png"]

    _forget_pictures(tmp_path)
    _tetrahedron(tmp_path / "shell.obj", 0.2, lean=0.05)  # inside the box too
    shell_changed = _render(scene, hull_changed)
    shown_by_the_shell = {"three_quarter_visual.png", "side_visual.png", "top_visual.png"}
    assert _pictures(tmp_path) == shown_by_the_shell
    assert (
        shell_changed["three_quarter_collision.png"] == hull_changed["three_quarter_collision.png"]
    )


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
            _tetrahedron(tmp_path / "hull.obj", 0.1, tip=4.0)  # out of the box
        else:
            path = scene if change == "the floor" else robot
            path.write_text(path.read_text().replace(*edit))
        redrawn = _render(scene, first)
        assert len(_pictures(tmp_path)) == 5, change
        assert not set(redrawn.values()) & set(first.values()), change
        first = redrawn

    _forget_pictures(tmp_path)  # damping does not show
    robot.write_text(robot.read_text().replace('damping="1"', 'damping="2"'))
    assert _render(scene, first) == first
    assert _pictures(tmp_path) == set()


def test_a_mesh_both_seen_and_colliding_gives_each_kind_its_own_picture(tmp_path):
    """Where every mesh is both a visual and a collision geom (the Trossen arms' STL files),
    the collision pictures show the same meshes as the visual ones, in their own colour: a
    picture taken from the cache must be of its own kind."""
    first = tmp_path / "first"
    scene = _two_meshes(first)
    robot = first / "robot.xml"
    robot.write_text(robot.read_text().replace('mesh="hull"', 'mesh="shell"'))
    cache = tmp_path / "cache"
    shown = _render(scene, cache=cache)
    assert len(set(shown.values())) == len(shown)  # each picture shows its own view and kind
    visual = (first / "previews" / "side_visual.png").read_bytes()
    collision = (first / "previews" / "side_collision.png").read_bytes()
    assert visual != collision

    second = tmp_path / "second"  # the same robot in another folder: its pictures are copied
    second.mkdir()
    for name in ("scene.xml", "robot.xml", "shell.obj", "hull.obj"):
        (second / name).write_bytes((first / name).read_bytes())
    assert _render(second / "scene.xml", cache=cache) == shown
    assert (second / "previews" / "side_visual.png").read_bytes() == visual
    assert (second / "previews" / "side_collision.png").read_bytes() == collision


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
    assert len(pictures) == 5
    for picture in pictures:
        assert picture.read_bytes() == (tmp_path / "two" / "again" / picture.name).read_bytes()


def test_a_picture_drawn_alone_is_the_picture_drawn_with_the_others(tmp_path):
    """An incremental build draws only the pictures whose content changed: each must come out
    as the clean build drew it after the others (MuJoCo placed the floor, an infinite plane,
    around the camera of the picture drawn before)."""
    scene = _scene(tmp_path, "")
    shown = _render(scene)
    assert len(shown) == 5
    code = (
        "import json, sys; from pathlib import Path; "
        "from mjcfbuild.check.previews import render_previews; "
        "scene = Path(sys.argv[1]); shown = json.loads(sys.argv[2]); "
        "[render_previews(scene, scene.parent / name, 160, 120, None, "
        "{n: d for n, d in shown.items() if n != name}) for name in shown]"
    )
    environment = {**os.environ, "MUJOCO_GL": "egl"}
    done = subprocess.run(
        [sys.executable, "-c", code, str(scene), json.dumps(shown)],
        env=environment,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    for name in shown:
        assert [path.name for path in (tmp_path / name).iterdir()] == [name]  # drawn alone
        alone = (tmp_path / name / name).read_bytes()
        assert alone == (tmp_path / "previews" / name).read_bytes(), name


def _compiled(body_xml: str):
    """A model of ``body_xml`` in the world, at its zero pose, with its data."""
    model = mujoco.MjModel.from_xml_string(f"<mujoco><worldbody>{body_xml}</worldbody></mujoco>")
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


ARM = """<body name="base"><geom size="0.05"/>
  <body name="link" pos="0 0 0.1"><joint/><geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.03"/>
    <body name="hand" pos="0.5 0 0"><joint/><geom size="0.04"/>
      <body name="left" pos="0.05 0.02 0"><joint type="slide" axis="0 1 0"/><geom type="box" size="0.03 0.005 0.01"/></body>
      <body name="right" pos="0.05 -0.02 0"><joint type="slide" axis="0 1 0"/><geom type="box" size="0.03 0.005 0.01"/></body>
    </body>
  </body>
</body>"""

FLOATING = """<body name="trunk" pos="0 0 0.5"><freejoint/><geom type="box" size="0.3 0.1 0.05"/>
  <body name="front" pos="0.25 0 -0.05"><joint/><geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.02"/></body>
  <body name="rear" pos="-0.25 0 -0.05"><joint/><geom type="capsule" fromto="0 0 0 0 0 -0.42" size="0.02"/></body>
</body>"""


def test_the_closeup_is_the_arms_hand_or_the_lowest_foot():
    from mjcfbuild.check.previews import closeup_bodies

    model, data = _compiled(ARM)
    names = {model.body(b).name for b in closeup_bodies(model, data)}
    assert names == {"hand", "left", "right"}
    model, data = _compiled(FLOATING)
    assert {model.body(b).name for b in closeup_bodies(model, data)} == {"rear"}  # the lowest
    model, data = _compiled('<body name="box"><freejoint/><geom size="0.1"/></body>')
    assert closeup_bodies(model, data) == set()  # no hand, no foot: the robot itself


def test_the_side_view_looks_across_the_robots_long_direction():
    from mjcfbuild.check.previews import choose_views

    model, data = _compiled(ARM)  # reaches along +x
    views = choose_views(model, data, 4 / 3)
    assert views["side"].azimuth == -90.0 and views["three_quarter"].azimuth == -135.0
    assert set(views) == {"three_quarter", "side", "top", "closeup"}
    turned = ARM.replace('<body name="base">', '<body name="base" euler="0 0 90">')
    model, data = _compiled(turned)  # the same arm reaching along +y
    assert choose_views(model, data, 4 / 3)["side"].azimuth in (0.0, 180.0, -180.0)


def test_the_view_fits_the_robot_in_the_frame():
    import math

    import numpy as np

    from mjcfbuild.check.previews import MARGIN, choose_views, geom_points

    model, data = _compiled(FLOATING)
    points, _ = geom_points(model, data)
    for name, view in choose_views(model, data, 4 / 3).items():
        if name == "closeup":
            continue
        a, e = math.radians(view.azimuth), math.radians(view.elevation)
        forward = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
        right = np.cross(forward, [0, 0, 1])
        right /= np.linalg.norm(right)
        up = np.cross(right, forward)
        relative = points - (np.array(view.lookat) - view.distance * forward)
        depth = relative @ forward
        tangent = math.tan(math.radians(model.vis.global_.fovy) / 2)
        across = relative @ right / depth / (tangent * 4 / 3)
        upward = relative @ up / depth / tangent
        assert max(np.abs(across).max(), np.abs(upward).max()) == pytest.approx(
            1 / MARGIN, rel=1e-3
        )
        # centred: as much room on either side of the binding direction
        for values in (across, upward):
            if np.abs(values).max() > 0.99 / MARGIN:
                assert values.max() == pytest.approx(-values.min(), rel=1e-3), name


def test_the_background_is_a_sky_gradient(tmp_path):
    from mjcfbuild.check.previews import SKY_BOTTOM, SKY_TOP

    scene = _two_meshes(tmp_path)
    _render(scene)
    with Image.open(tmp_path / "previews" / "side_visual.png") as picture:
        top = picture.getpixel((2, 0))
        lower = picture.getpixel((2, 20))
    assert all(abs(a - b) <= 2 for a, b in zip(top, SKY_TOP, strict=True))
    assert top != lower and all(
        min(a, b) <= c <= max(a, b) for a, b, c in zip(SKY_TOP, SKY_BOTTOM, lower, strict=True)
    )


def test_a_closeup_of_two_arms_on_the_world_ends_and_draws_no_closeup():
    """Two arms fixed to the world share no ancestor but the world: the search for the hand's
    common ancestor must end there (it once looped for ever on a dual-arm robot)."""
    import mujoco

    from mjcfbuild.check.previews import closeup_bodies

    arm = (
        '<body name="{n}0" pos="{y} 0 0"><joint axis="0 1 0"/><geom size="0.02 0.2" pos="0 0 0.2" type="capsule"/>'
        '<body name="{n}1" pos="0 0 0.4"><joint axis="0 1 0"/><geom size="0.02 0.1" pos="0 0 0.1" type="capsule"/></body></body>'
    )
    model = mujoco.MjModel.from_xml_string(
        f"<mujoco><worldbody>{arm.format(n='left', y=0.3)}{arm.format(n='right', y=-0.3)}</worldbody></mujoco>"
    )
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert closeup_bodies(model, data) == set()
