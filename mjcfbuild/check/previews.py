"""Preview pictures of a built model at home on its floor, rendered offscreen: front and side,
visual and collision.

MuJoCo renders through OpenGL; on a machine without a display this needs EGL (set
``MUJOCO_GL=egl``, which mjcfbuild does when nothing else is set) and Mesa's EGL packages. The
background is made light grey, so the pictures read on any page: each picture is drawn once
without the skybox, and the pixels that kept the cleared depth are the background.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

from mjcfbuild.check.loading import spec_reading_sources
from mjcfbuild.errors import ModelError

VIEWS = {"front": 180.0, "side": -90.0}
KINDS = ("visual", "collision")
BACKGROUND = (235, 235, 235)
COLLISION_RGBA = (0.9, 0.45, 0.15, 1.0)
SHADOW_MAP_SIZE = 1024
MULTISAMPLES = 2


def render_previews(
    model_path: Path,
    folder: Path,
    width: int = 480,
    height: int = 360,
    sources: dict[str, Path] | None = None,
) -> list[str]:
    """Write ``<view>_<kind>.png`` files into ``folder``; their names. ``sources``: the
    products a build published the assets from (see check.loading)."""
    from mjcfbuild.cachedir import user_cache_dir

    os.environ.setdefault("MUJOCO_GL", "egl")
    # Mesa keeps compiled shaders in ~/.cache unless told otherwise; mjcfbuild writes only in
    # its output folder and its own cache.
    os.environ.setdefault("MESA_SHADER_CACHE_DIR", str(user_cache_dir() / "mesa_shader_cache"))
    import mujoco
    import numpy as np
    from PIL import Image

    from mjcfbuild.mjwarnings import capture_mujoco_warnings

    capture_mujoco_warnings()

    try:
        model = _model_to_draw(model_path, sources or {})
    except ValueError as exc:  # the check reports why; there is nothing to draw
        raise ModelError(f"the model does not load: {str(exc).splitlines()[0]}") from None
    data = mujoco.MjData(model)
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if home >= 0:
        mujoco.mj_resetDataKeyframe(model, data, home)
    mujoco.mj_forward(model, data)
    planes = model.geom_type == mujoco.mjtGeom.mjGEOM_PLANE
    collides = ((model.geom_contype != 0) | (model.geom_conaffinity != 0)) & ~planes
    model.geom_group[:] = np.where(collides, 3, 2)
    model.geom_group[planes] = 0  # the floor shows in every picture
    model.geom_rgba[collides] = COLLISION_RGBA
    model.geom_matid[collides] = -1
    center, distance = _framing(model, data)
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    with _Offscreen(model, width, height) as offscreen:
        for view, azimuth in VIEWS.items():
            camera = mujoco.MjvCamera()
            camera.lookat[:] = center
            camera.distance = distance
            camera.azimuth = azimuth
            camera.elevation = -15.0
            for kind in KINDS:
                option = mujoco.MjvOption()
                option.geomgroup[:] = 0
                option.geomgroup[0] = 1
                option.geomgroup[2 if kind == "visual" else 3] = 1
                option.sitegroup[:] = 0
                pixels, background = offscreen.draw(data, camera, option)
                pixels[background] = BACKGROUND
                name = f"{view}_{kind}.png"
                Image.fromarray(pixels).save(folder / name, optimize=False)
                written.append(name)
    return written


def _model_to_draw(model_path: Path, sources: dict[str, Path]) -> Any:
    """The model as the pictures show it: without its skybox textures, which they do not
    draw and the renderer would otherwise upload (Menagerie's gradient: six 512 x 512 faces
    with their mipmaps, 0.06-0.09 s of panda's previews in software OpenGL)."""
    import mujoco

    spec = spec_reading_sources(model_path, sources)
    used = {name for material in spec.materials for name in material.textures if name}
    for texture in list(spec.textures):
        if texture.type == mujoco.mjtTexture.mjTEXTURE_SKYBOX and texture.name not in used:
            spec.delete(texture)
    return spec.compile()


class _Offscreen:
    """An offscreen OpenGL buffer that draws a model's scene into colour and depth at once."""

    def __init__(self, model, width: int, height: int) -> None:
        import mujoco

        self.model = model
        self.width, self.height = width, height
        # The offscreen buffer is sized from the model; the pictures must fit in it.
        model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
        model.vis.global_.offheight = max(model.vis.global_.offheight, height)
        # Software OpenGL (Mesa's llvmpipe) pays for every shadow-map texel and every sample:
        # at 480 x 360 a 1024 map and 2x multisampling look the same as MuJoCo's 4096 and 4x
        # and draw in two thirds of the time (go1: 1.3 -> 0.9 s for the four pictures).
        model.vis.quality.shadowsize = SHADOW_MAP_SIZE
        model.vis.quality.offsamples = MULTISAMPLES
        self.gl = mujoco.GLContext(width, height)
        self.gl.make_current()
        self.context = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_150)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self.context)
        self.context.readDepthMap = mujoco.mjtDepthMap.mjDEPTH_ZEROFAR  # the far plane reads 0
        self.scene = mujoco.MjvScene(model, maxgeom=10000)
        # Without the skybox nothing is drawn where no geom is: those pixels keep the cleared
        # depth, which marks the background in the same pass as the colours.
        self.scene.flags[mujoco.mjtRndFlag.mjRND_SKYBOX] = 0
        # A mirrored robot in the floor draws everything twice and reads as extra geometry in
        # the collision pictures.
        self.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = 0
        self.viewport = mujoco.MjrRect(0, 0, width, height)

    def draw(self, data: Any, camera: Any, option: Any) -> tuple[Any, Any]:
        """The picture (height x width x 3 bytes) and where it shows the background."""
        import mujoco
        import numpy as np

        mujoco.mjv_updateScene(
            self.model, data, option, None, camera, mujoco.mjtCatBit.mjCAT_ALL, self.scene
        )
        mujoco.mjr_render(self.viewport, self.scene, self.context)
        pixels = np.empty((self.height, self.width, 3), dtype=np.uint8)
        depth = np.empty((self.height, self.width), dtype=np.float32)
        mujoco.mjr_readPixels(pixels, depth, self.viewport, self.context)
        # OpenGL's rows run bottom to top; nothing drawn means the far plane, read as 0.
        return np.flipud(pixels).copy(), np.flipud(depth) <= 0.0

    def __enter__(self) -> _Offscreen:
        return self

    def __exit__(self, *exc: object) -> None:
        self.context.free()
        self.gl.free()


def _framing(model, data):
    """A point to look at and a distance that fits every geom's bounding box in the view."""
    import mujoco
    import numpy as np

    if model.ngeom == 0:
        return np.zeros(3), 1.0
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    corners = []
    for geom in range(model.ngeom):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue  # infinite: the robot is what the picture frames
        center, half = model.geom_aabb[geom][:3], model.geom_aabb[geom][3:]
        local = center + signs * half
        rotation = data.geom_xmat[geom].reshape(3, 3)
        corners.append(local @ rotation.T + data.geom_xpos[geom])
    if not corners:
        return np.zeros(3), 1.0
    points = np.concatenate(corners)
    low, high = points.min(axis=0), points.max(axis=0)
    center = (low + high) / 2
    radius = max(float(np.linalg.norm(high - low)) / 2, 0.05)
    fovy = math.radians(model.vis.global_.fovy)
    return center, radius / math.sin(fovy / 2) * 1.1
