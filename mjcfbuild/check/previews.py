"""Preview pictures of a built model at home on its floor, rendered offscreen: a three-quarter
front view and a side view (visual and collision), a top view, and a close-up of the hand (the
end of an arm) or a foot (of a floating robot), where the robot has one.

The views are chosen from the robot's extent: the side view looks across the robot's longest
horizontal direction (a quadruped's body, an arm's reach), the three-quarter view half-way
between it and the front (+x), from higher up for a robot that is wide rather than tall. Each
view's camera is fitted to the robot's points as that view projects them, so the robot fills
the frame.

MuJoCo renders through OpenGL; on a machine without a display this needs EGL (set
``MUJOCO_GL=egl``, which mjcfbuild does when nothing else is set) and Mesa's EGL packages. The
background is a sky gradient, the same in every picture: each picture is drawn once without
the skybox, and the pixels that kept the cleared depth are the background.

Each picture comes with a digest of what it shows (its kind's content, :func:`_kind_digests`,
and its camera), and a picture whose digest is unchanged is not drawn again: a collision mesh
edited inside the robot's extent redraws the collision pictures, not the visual ones, which are
most of the drawing time (panda: 0.3 of 0.6 s); one that changes the extent moves the cameras
and redraws every picture.
"""

from __future__ import annotations

import hashlib
import io
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from mjcfbuild.check.drawn import drawn_model_xml
from mjcfbuild.check.loading import AssetSource, spec_reading_sources
from mjcfbuild.errors import ModelError
from mjcfbuild.failpoints import failpoint
from mjcfbuild.fsutil import atomic_write, md5_file

KINDS = ("visual", "collision")


class OffscreenUnavailable(Exception):
    """No OpenGL context to draw in: no EGL or GPU driver, or a ``MUJOCO_GL`` backend that is
    not installed. Any other failure while drawing is not this."""


SKY_TOP = (150, 190, 232)
SKY_BOTTOM = (236, 242, 250)
COLLISION_RGBA = (0.9, 0.45, 0.15, 1.0)
SHADOW_MAP_SIZE = 1024
# Each picture is drawn at twice its width and height and reduced, four samples a pixel.
SUPERSAMPLING = 2
MARGIN = 1.15  # the robot fills the frame, less this
# Everything above that decides how a picture looks; a change to the drawing code that
# changes the pictures changes this too (a new first element), so they are drawn again.
DRAWING = (4, SKY_TOP, SKY_BOTTOM, COLLISION_RGBA, SHADOW_MAP_SIZE, SUPERSAMPLING, MARGIN)


class PictureCache(Protocol):
    """Pictures drawn before, by the digest of what each shows (mjcfbuild.steps.previews
    keeps them in the shared product cache)."""

    def get(self, shows: str) -> bytes | None:
        """The PNG of a picture showing ``shows``, if one was kept."""

    def put(self, shows: str, png: bytes) -> None:
        """Keep the PNG of a picture showing ``shows``."""


@dataclass(frozen=True)
class View:
    """A camera: where it looks from (degrees), at what, from how far; the kinds it shows."""

    azimuth: float
    elevation: float
    lookat: tuple[float, float, float]
    distance: float
    kinds: tuple[str, ...]


def render_previews(
    model_path: Path,
    folder: Path,
    width: int = 480,
    height: int = 360,
    sources: dict[str, AssetSource] | None = None,
    drawn: Mapping[str, str] | None = None,
    cache: PictureCache | None = None,
) -> dict[str, str | None]:
    """Write the pictures ``<view>_<kind>.png`` into ``folder``; each picture's name and the
    digest of what it shows (None where that cannot be told). ``drawn``: pictures already in
    ``folder`` with the digest each was drawn for; one whose digest is unchanged is kept.
    ``cache``: pictures drawn before, in any folder; one found there is copied, not drawn.
    ``sources``: the products a build published the assets from (see check.loading)."""
    from mjcfbuild.cachedir import user_cache_dir
    from mjcfbuild.check.shadercache import choose_shader_cache

    os.environ.setdefault("MUJOCO_GL", "egl")
    choose_shader_cache(os.environ, user_cache_dir() / "mesa_shader_cache")
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
    views = choose_views(model, data, width / height)
    pictures = {
        f"{name}_{kind}.png": (name, kind) for name, view in views.items() for kind in view.kinds
    }
    digests = _kind_digests(model_path, spec, model, collides, (width, height))
    shown = {
        name: _picture_digest(digests[kind], views[view]) if digests else None
        for name, (view, kind) in pictures.items()
    }
    to_draw = [
        name for name in pictures if shown[name] is None or (drawn or {}).get(name) != shown[name]
    ]
    if cache is not None:
        to_draw = [name for name in to_draw if not _copied(cache, shown[name], folder / name)]
    if not to_draw:
        return shown
    model.geom_group[:] = np.where(collides, 3, 2)
    model.geom_group[planes] = 0  # the floor shows in every picture
    model.geom_rgba[collides] = COLLISION_RGBA
    model.geom_matid[collides] = -1
    folder.mkdir(parents=True, exist_ok=True)
    sky = _sky(height * SUPERSAMPLING, width * SUPERSAMPLING)
    with _Offscreen(model, width * SUPERSAMPLING, height * SUPERSAMPLING) as offscreen:
        for name in to_draw:
            failpoint("previews-draw")  # the tests fail a drawing here, as a bug would
            view_name, kind = pictures[name]
            view = views[view_name]
            camera = mujoco.MjvCamera()
            camera.lookat[:] = view.lookat
            camera.distance = view.distance
            camera.azimuth = view.azimuth
            camera.elevation = view.elevation
            option = mujoco.MjvOption()
            option.geomgroup[:] = 0
            option.geomgroup[0] = 1
            option.geomgroup[2 if kind == "visual" else 3] = 1
            option.sitegroup[:] = 0
            pixels, background = offscreen.draw(data, camera, option)
            pixels[background] = sky[background]
            picture = Image.fromarray(pixels).reduce(SUPERSAMPLING)  # the mean of each square
            png = io.BytesIO()
            picture.save(png, format="PNG", optimize=False)
            atomic_write(folder / name, png.getvalue())  # a full disk names the picture
            shows = shown[name]
            if cache is not None and shows is not None:
                cache.put(shows, png.getvalue())
    return shown


def _copied(cache: PictureCache, shows: str | None, path: Path) -> bool:
    """Whether the picture showing ``shows`` was found in ``cache`` and written to ``path``."""
    png = cache.get(shows) if shows is not None else None
    if png is None:
        return False
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, png)
    return True


def _model_to_draw(model_path: Path, sources: dict[str, AssetSource]) -> tuple[Any, Any]:
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
    model_path: Path, spec: Any, model: Any, collides: Any, size: tuple[int, int]
) -> dict[str, str] | None:
    """Per kind of picture, the digest of what it shows; None if that cannot be told.

    Both kinds show the model's XML as drawn (check.drawn), the textures and height fields,
    at the picture ``size``; each picture adds its view's camera (:func:`_picture_digest`). The
    kind itself differs (which geoms show, and the collision colour), and so do the mesh files:
    a visual picture shows the meshes of the geoms that do not collide, a collision picture
    those of the geoms that do.
    """
    import mujoco

    xml = drawn_model_xml(model_path)
    if xml is None or model.nskin or model.nflex:
        return None  # skins and flexes read files this does not follow: always draw
    common = hashlib.sha256(repr((DRAWING, mujoco.__version__, size)).encode())
    common.update(xml)
    for array in (model.tex_data, model.tex_height, model.tex_width):
        common.update(array.tobytes())
    common.update(model.hfield_data.tobytes())
    kinds: list[set[str]] = [set() for _ in range(model.nmesh)]
    for geom in range(model.ngeom):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_MESH:
            kinds[model.geom_dataid[geom]].add("collision" if collides[geom] else "visual")
    digests = {kind: common.copy() for kind in KINDS}
    for kind, digest in digests.items():
        # The kind itself: which geoms show and in what colour. Where every mesh is both seen
        # and colliding (the Trossen arms' STL files) nothing else tells the two apart.
        digest.update(f"\0{kind}".encode())
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
        try:
            self.gl = _gl_context(width, height)
            self.gl.make_current()
            self.context = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_150)
        except Exception as exc:  # mujoco's backends raise ImportError, RuntimeError, ...
            message = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
            raise OffscreenUnavailable(message or type(exc).__name__) from exc
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

        # The scene keeps the last picture's camera, and mjv_updateScene places an infinite
        # plane (the floor) around that camera before it moves the scene's to this one: a
        # picture's floor would depend on the picture drawn before it (edge pixels differ,
        # so an incremental build's pictures differ from a clean build's). The scene's camera
        # is set to this picture's first.
        mujoco.mjv_updateCamera(self.model, data, camera, self.scene)
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


def _picture_digest(kind_digest: str, view: View) -> str:
    """What one picture shows: its kind's content and its camera."""
    return hashlib.sha256(f"{kind_digest}\0{view!r}".encode()).hexdigest()


def _sky(height: int, width: int) -> Any:
    """The background: a vertical gradient from :data:`SKY_TOP` to :data:`SKY_BOTTOM`."""
    import numpy as np

    rows = np.linspace(0.0, 1.0, height)[:, None]
    colours = (1 - rows) * np.array(SKY_TOP) + rows * np.array(SKY_BOTTOM)
    line = np.round(colours).astype(np.uint8)
    return np.repeat(line[:, None, :], width, axis=1)


def geom_points(model, data) -> tuple[Any, Any]:
    """Points that bound every geom but the floor, in the world (each mesh by its vertices,
    each other geom by its bounding box's corners), and the body of each point. Vertices and
    not a mesh's box, which MuJoCo aligns with the mesh's axes of inertia: any edit of the
    mesh turns those axes and would move the camera, and redraw every picture."""
    import mujoco
    import numpy as np

    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    points, bodies = [], []
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
        points.append(local @ rotation.T + data.geom_xpos[geom])
        bodies.append(np.full(len(local), model.geom_bodyid[geom]))
    if not points:
        return np.zeros((1, 3)), np.zeros(1, dtype=int)
    return np.concatenate(points), np.concatenate(bodies)


def choose_views(model, data, aspect: float) -> dict[str, View]:
    """The views of the robot, each fitted to fill the frame: ``three_quarter`` and ``side``
    (visual and collision), ``top`` (visual) and ``closeup`` (of a hand or a foot, both kinds)
    where the robot has one."""
    import numpy as np

    points, bodies = geom_points(model, data)
    fovy = float(model.vis.global_.fovy)
    along = _long_axis(points)
    left = np.array([-along[1], along[0]])  # the side view's camera is on the robot's left
    side = math.degrees(math.atan2(-left[1], -left[0]))
    quarter_from = along + left
    three_quarter = math.degrees(math.atan2(-quarter_from[1], -quarter_from[0]))
    extent = points.max(axis=0) - points.min(axis=0)
    wide = extent[2] < 0.8 * max(extent[0], extent[1])
    views = {
        "three_quarter": _fit(points, three_quarter, -30.0 if wide else -20.0, fovy, aspect, KINDS),
        "side": _fit(points, side, -12.0, fovy, aspect, KINDS),
        # From above, the long direction across the picture, which is wider than high.
        "top": _fit(points, side, -89.0, fovy, aspect, ("visual",)),
    }
    end = closeup_bodies(model, data)
    if end:
        near = np.isin(bodies, sorted(end))
        if near.any():
            views["closeup"] = _fit(points[near], three_quarter, -25.0, fovy, aspect, KINDS)
    return views


def _long_axis(points) -> Any:
    """The robot's longest horizontal direction, pointing forward (+x); +x for a round one."""
    import numpy as np

    flat = points[:, :2] - points[:, :2].mean(axis=0)
    values, vectors = np.linalg.eigh(flat.T @ flat)
    if values[1] < 1.5 * values[0] or values[1] <= 0:
        return np.array([1.0, 0.0])
    axis = vectors[:, 1]
    axis = axis if axis[0] >= 0 else -axis
    # Rounded, so that a change at the far end of a mesh does not turn every view.
    return np.round(axis / np.linalg.norm(axis), 3)


def closeup_bodies(model, data) -> set[int]:
    """The bodies of a hand or a foot: for a floating robot, the end body that reaches lowest
    (a foot, or a quadruped's shank); for a fixed one, every body under the deepest end bodies'
    nearest common ancestor (a gripper). End bodies: bodies with geometry and none below them.
    Empty when that would be the whole robot."""
    import mujoco
    import numpy as np

    points, owners = geom_points(model, data)
    drawn = {int(b) for b in np.unique(owners)} - {0}
    ends = [
        body
        for body in sorted(drawn)
        if not any(_under(model, other, body) for other in drawn if other != body)
    ]
    if not ends:
        return set()

    def depth(body: int) -> int:
        count = 0
        while body:
            body, count = int(model.body_parentid[body]), count + 1
        return count

    floating = any(model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE for j in range(model.njnt))
    if floating:
        lowest = {body: round(float(points[owners == body][:, 2].min()), 6) for body in ends}
        chosen = {min(ends, key=lambda body: (lowest[body], body))}
    else:
        deepest = max(depth(body) for body in ends)
        tips = [body for body in ends if depth(body) == deepest]
        ancestor = tips[0]
        while not all(_under(model, tip, ancestor) for tip in tips):
            ancestor = int(model.body_parentid[ancestor])
        chosen = {b for b in range(1, model.nbody) if _under(model, b, ancestor)}
    roots = {b for b in range(1, model.nbody) if model.body_parentid[b] == 0}
    return set() if chosen & roots else chosen


def _under(model, body: int, ancestor: int) -> bool:
    if ancestor == 0:  # the world holds every body (two arms on it share no other ancestor)
        return True
    while body:
        if body == ancestor:
            return True
        body = int(model.body_parentid[body])
    return False


def _fit(points, azimuth: float, elevation: float, fovy: float, aspect: float, kinds) -> View:
    """The camera at ``azimuth`` and ``elevation`` (degrees) that sees every point, the nearest
    edge of the robot's picture :data:`MARGIN` from the frame's edge."""
    import numpy as np

    a, e = math.radians(azimuth), math.radians(elevation)
    forward = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    across, upward, depth = points @ right, points @ up, points @ forward
    tan_v = math.tan(math.radians(fovy) / 2) / MARGIN
    tan_h = tan_v * aspect
    # The camera at depth s along ``forward`` and (c_r, c_u) across sees point i when
    # |across_i - c_r| <= tan_h (depth_i - s), and likewise upward. Across, that holds for
    # max(across - tan_h depth) + tan_h s <= c_r <= min(across + tan_h depth) - tan_h s: the
    # nearest camera is in the middle of the two bounds, where they meet.
    position = []
    nearest = []
    for values, tangent in ((across, tan_h), (upward, tan_v)):
        low = float(np.max(values - tangent * depth))
        high = float(np.min(values + tangent * depth))
        position.append((low + high) / 2)
        nearest.append((high - low) / (2 * tangent))
    camera_depth = min(*nearest, float(depth.min()) - 0.05)  # and out of the robot
    distance = max((float(depth.min()) + float(depth.max())) / 2 - camera_depth, 0.05)
    camera = position[0] * right + position[1] * up + camera_depth * forward
    lookat = camera + distance * forward
    # To the micrometre: MuJoCo stores a mesh about its centre of mass, so a vertex that did
    # not move can come back a rounding error away after an edit elsewhere in the mesh.
    return View(
        round(azimuth, 3),
        elevation,
        tuple(round(float(x), 6) for x in lookat),  # type: ignore[arg-type]
        round(distance, 6),
        tuple(kinds),
    )
