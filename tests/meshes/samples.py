"""Small mesh files of every supported format, written by the tests themselves."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh
from PIL import Image


def checker_png(path: Path) -> Path:
    """A small red (top) and blue (bottom) PNG."""
    checker_image().save(path)
    return path


def checker_image() -> Image.Image:
    """The red/blue image in memory."""
    pixels = np.zeros((8, 8, 3), dtype=np.uint8)
    pixels[:4, :, 0] = 255
    pixels[4:, :, 2] = 255
    return Image.fromarray(pixels)


def textured_box() -> trimesh.Trimesh:
    """A box with texture coordinates and a texture image."""
    box = trimesh.creation.box([0.1, 0.1, 0.1])
    box.unmerge_vertices()
    uv = np.random.default_rng(0).random((len(box.vertices), 2))
    box.visual = trimesh.visual.TextureVisuals(uv=uv, image=checker_image())
    return box


def obj_with_named_mtl_and_texture(folder: Path) -> Path:
    """An OBJ whose mtllib is not <stem>.mtl, with a coloured and a textured material."""
    folder.mkdir(parents=True, exist_ok=True)
    checker_png(folder / "skin.png")
    (folder / "looks.mtl").write_text(
        "newmtl plain\nKd 0.2 0.8 0.2\n\nnewmtl skin\nKd 1 1 1\nmap_Kd skin.png\n"
    )
    (folder / "part.obj").write_text(
        "mtllib looks.mtl\n"
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
        "vt 0 0\nvt 1 0\nvt 0 1\n"
        "usemtl plain\nf 1 3 2\nf 1 2 4\n"
        "usemtl skin\nf 1/1 4/2 3/3\nf 2/1 3/2 4/3\n"
    )
    return folder / "part.obj"


def ascii_stl(path: Path) -> Path:
    """A tetrahedron as ASCII STL."""
    mesh = trimesh.creation.icosphere(subdivisions=0, radius=0.05)
    data = mesh.export(file_type="stl_ascii")
    path.write_bytes(data.encode() if isinstance(data, str) else data)
    return path


def coloured_ply(path: Path) -> Path:
    """A PLY box whose faces have two colours."""
    mesh = trimesh.creation.box([0.1, 0.1, 0.1])
    colours = np.tile([255, 0, 0, 255], (len(mesh.faces), 1))
    colours[6:] = [0, 0, 255, 255]
    mesh.visual.face_colors = colours
    path.write_bytes(mesh.export(file_type="ply"))
    return path


def gltf(folder: Path, binary: bool) -> Path:
    """A textured box as GLB, or as glTF with its buffer and image beside it."""
    folder.mkdir(parents=True, exist_ok=True)
    scene = trimesh.Scene(textured_box())
    if binary:
        path = folder / "box.glb"
        path.write_bytes(scene.export(file_type="glb"))
        return path
    files = scene.export(file_type="gltf")
    for name, data in files.items():
        (folder / name).write_bytes(data)
    return folder / "model.gltf"
