"""Preview pictures of a built model at home on its floor, rendered offscreen: front and side,
visual and collision.

MuJoCo renders through OpenGL; on a machine without a display this needs EGL (set
``MUJOCO_GL=egl``, which mjcfbuild does when nothing else is set) and Mesa's EGL packages. The
background is made light grey, so the pictures read on any page: each picture is drawn once
without the skybox, and the pixels that kept the cleared depth are the background.

Each picture comes with a digest of what it shows (:func:`_kind_digests`), and a picture whose
digest is unchanged is not drawn again: a collision mesh edited redraws the two collision
pictures, not the visual ones, which are most of the drawing time (panda: 0.3 of 0.6 s).
"""

from __future__ import annotations

import hashlib
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from mjcfbuild.check.drawn import drawn_model_xml
from mjcfbuild.check.loading import spec_reading_sources
from mjcfbuild.errors import ModelError
from mjcfbuild.fsutil import md5_file

VIEWS = {"front": 180.0, "side": -90.0}
ELEVATION = -15.0
KINDS = ("visual", "collision")
BACKGROUND = (235, 235, 235)
COLLISION_RGBA = (0.9, 0.45, 0.15, 1.0)
SHADOW_MAP_SIZE = 1024
# Each picture is drawn at twice its width and height and reduced, four samples a pixel.
SUPERSAMPLING = 2
# Everything above that decides how a picture looks; a change to the drawing code that
# changes the pictures changes this too (a new first element), so they are drawn again.
DRAWING = (2, VIEWS, ELEVATION, BACKGROUND, COLLISION_RGBA, SHADOW_MAP_SIZE, SUPERSAMPLING)
# File name -> the view's azimuth and the kind of geometry shown, in the order drawn.
PICTURES = {
    f"{view}_{kind}.png": (azimuth, kind) for view, azimuth in VIEWS.items() for kind in KINDS
}


def render_previews(
    model_path: Path,
    folder: Path,
    width: int = 480,
    height: int = 360,
    sources: dict[str, Path] | None = None,
    drawn: Mapping[str, str] | None = None,
) -> dict[str, str | None]:
    """Write the pictures ``<view>_<kind>.png`` into ``folder``; each picture's name and the
    digest of what it shows (None where that cannot be told). ``drawn``: pictures already in
    ``folder`` with the digest each was drawn for; one whose digest is unchanged is kept.
    ``sources``: the products a build published the assets from (see check.loading)."""
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
        spec, model = _model_to_draw(model_path, sources or {})
    except ValueError as exc:  # the check reports why; there is nothing to draw
        raise ModelError(f"the model does not load: {str(exc).splitlines()[0]}") from None
    data = mujoco.MjData(model)
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if home >= 0:
        mujoco.mj_resetDataKeyframe(model, data, home)
    mujoco.mj_forward(model, data)
    planes = model.geom_type == mujoco.mjtGeom.mjGEOM_PLANE
    collides = ((model.geom_contype != 0) | (model.geom_conaffinity != 0)) & ~planes
    center, distance = _framing(model, data)
    framing = (tuple(float(x) for x in center), float(distance), width, height)
    digests = _kind_digests(model_path, spec, model, collides, framing)
    shown = {name: digests[kind] if digests else None for name, (_, kind) in PICTURES.items()}
    to_draw = [
        name for name in PICTURES if shown[name] is None or (drawn or {}).get(name) != shown[name]
    ]
    if not to_draw:
        return shown
    model.geom_group[:] = np.where(collides, 3, 2)
    model.geom_group[planes] = 0  # the floor shows in every picture
    model.geom_rgba[collides] = COLLISION_RGBA
    model.geom_matid[collides] = -1
    folder.mkdir(parents=True, exist_ok=True)
    with _Offscreen(model, width * SUPERSAMPLING, height * SUPERSAMPLING) as offscreen:
        for name in to_draw:
            azimuth, kind = PICTURES[name]
            camera = mujoco.MjvCamera()
            camera.lookat[:] = center
            camera.distance = distance
            camera.azimuth = azimuth
            camera.elevation = ELEVATION
            option = mujoco.MjvOption()
            option.geomgroup[:] = 0
            option.geomgroup[0] = 1
            option.geomgroup[2 if kind == "visual" else 3] = 1
            option.sitegroup[:] = 0
            pixels, background = offscreen.draw(data, camera, option)
            pixels[background] = BACKGROUND
            picture = Image.fromarray(pixels).reduce(SUPERSAMPLING)  # the mean of each square
            picture.save(folder / name, optimize=False)
    return shown


def _model_to_draw(model_path: Path, sources: dict[str, Path]) -> tuple[Any, Any]:
    """The model as the pictures show it (its MjSpec and MjModel): without its skybox
    textures, which they do not draw and the renderer would otherwise upload (Menagerie's
    gradient: six 512 x 512 faces with their mipmaps, 0.06-0.09 s of panda's previews in
    software OpenGL)."""
    import mujoco

    spec = spec_reading_sources(model_path, sources)
    used = {name for material in spec.materials for name in material.textures if name}
    for texture in list(spec.textures):
        if texture.type == mujoco.mjtTexture.mjTEXTURE_SKYBOX and texture.name not in used:
            spec.delete(texture)
    return spec, spec.compile()


def _kind_digests(
    model_path: Path, spec: Any, model: Any, collides: Any, framing: tuple
) -> dict[str, str] | None:
    """Per kind of picture, the digest of what it shows; None if that cannot be told.

    Both kinds show the model's XML as drawn (check.drawn), the textures and height fields,
    and are framed to fit every geom (``framing``: centre, distance and picture size). The
    mesh files are the difference: a visual picture shows the meshes of the geoms that do
    not collide, a collision picture those of the geoms that do.
    """
    import mujoco

    xml = drawn_model_xml(model_path)
    if xml is None or model.nskin or model.nflex:
        return None  # skins and flexes read files this does not follow: always draw
    common = hashlib.sha256(repr((DRAWING, mujoco.__version__, framing)).encode())
    common.update(xml)
    for array in (model.tex_data, model.tex_height, model.tex_width):
        common.update(array.tobytes())
    common.update(model.hfield_data.tobytes())
    kinds: list[set[str]] = [set() for _ in range(model.nmesh)]
    for geom in range(model.ngeom):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_MESH:
            kinds[model.geom_dataid[geom]].add("collision" if collides[geom] else "visual")
    digests = {kind: common.copy() for kind in KINDS}
    base = Path(spec.modelfiledir)
    for index, mesh in enumerate(spec.meshes):
        if not mesh.file or not kinds[index]:
            continue
        try:
            content = md5_file(base / spec.meshdir / mesh.file)
        except OSError:
            return None
        for kind in kinds[index]:
            digests[kind].update(f"\0{index}\0{content}".encode())
    return {kind: digest.hexdigest() for kind, digest in digests.items()}


class _Offscreen:
    """An offscreen OpenGL buffer that draws a model's scene into colour and depth at once."""

    def __init__(self, model, width: int, height: int) -> None:
        import mujoco

        self.model = model
        self.width, self.height = width, height
        # The offscreen buffer is sized from the model; the pictures must fit in it.
        model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
        model.vis.global_.offheight = max(model.vis.global_.offheight, height)
        # Software OpenGL (Mesa's llvmpipe) pays for every shadow-map texel: at these sizes a
        # 1024 map looks the same as MuJoCo's 4096 (go1: 1.3 -> 0.9 s for four pictures).
        # No multisampling: the pictures are supersampled instead, which llvmpipe draws in
        # about the same time (the robots' meshes, not the pixels, take it) and reads back
        # without resolving samples, a step whose first use costs 0.04 s in every process.
        model.vis.quality.shadowsize = SHADOW_MAP_SIZE
        model.vis.quality.offsamples = 0
        self.gl = _gl_context(width, height)
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


# The OpenGL context of this process, made once: a worker that draws previews again (in a
# later build, as a resident worker) finds the shaders Mesa compiled for the last pictures.
_contexts: dict[tuple[int, int], Any] = {}


def _gl_context(width: int, height: int) -> Any:
    import mujoco

    if (width, height) not in _contexts:
        _contexts[(width, height)] = mujoco.GLContext(width, height)
    return _contexts[(width, height)]


def _framing(model, data):
    """A point to look at and a distance that fits every geom in the view: each mesh by its
    vertices, each other geom by its bounding box. Vertices and not a mesh's box, which
    MuJoCo aligns with the mesh's axes of inertia: any edit of the mesh turns those axes
    and would move the camera, and redraw every picture, however small the edit."""
    import mujoco
    import numpy as np

    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    corners = []
    for geom in range(model.ngeom):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue  # infinite: the robot is what the picture frames
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_MESH:
            mesh = model.geom_dataid[geom]
            start = model.mesh_vertadr[mesh]
            local = model.mesh_vert[start : start + model.mesh_vertnum[mesh]]
        else:
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
    # To the micrometre: MuJoCo stores a mesh about its centre of mass, so a vertex that did
    # not move can come back a rounding error away after an edit elsewhere in the mesh.
    return np.round(center, 6), round(radius / math.sin(fovy / 2) * 1.1, 6)
