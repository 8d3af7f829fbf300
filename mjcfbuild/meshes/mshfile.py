"""The binary copy of a mesh product that the build's own compiles read (MuJoCo's MSH format).

MuJoCo reads an OBJ file's numbers as text and a binary MSH file's as they are: the first
compile of a model in a process, where MuJoCo processes every mesh, takes about two thirds
of the time from MSH (g1: 0.45 s against 0.63, go1 0.58 against 0.87, panda 0.16 against
0.23; ``bench/msh_compile.py``); later ones, from MuJoCo's cache, take the same. A product
keeps its OBJ files, which the published model names and any tool reads, and beside each one
without texture coordinates an MSH copy of the same float32 vertices and triangles that the
build's compiles read instead. The model compiled from the copy is the one compiled from the
OBJ file, array for array, because the OBJ file is written from those float32 values
(:func:`float32_vertices`) with enough digits to read back as exactly them.
"""

from __future__ import annotations

from pathlib import PurePath

import numpy as np

SUFFIX = ".msh"


def float32_vertices(vertices: np.ndarray) -> np.ndarray:
    """``vertices`` rounded to the float32 values MuJoCo stores, as float64 (for the text)."""
    return np.asarray(vertices, dtype=np.float32).astype(np.float64)


def msh_bytes(vertices: np.ndarray, faces: np.ndarray) -> bytes:
    """MuJoCo's MSH file of the triangles ``faces`` over ``vertices``: four int32 counts
    (vertices, normals, texture coordinates, faces), then the float32 vertices and the int32
    corner indices, little-endian."""
    points = np.ascontiguousarray(vertices, dtype="<f4") + np.float32(0.0)  # -0.0 as in OBJ
    corners = np.ascontiguousarray(faces, dtype="<i4")
    header = np.array([len(points), 0, 0, len(corners)], dtype="<i4")
    return header.tobytes() + points.tobytes() + corners.tobytes()


def copy_name(name: str) -> str:
    """The file name of the binary copy of a product's OBJ file ``name``."""
    return str(PurePath(name).with_suffix(SUFFIX))


def read_file(name: str, files: dict[str, str]) -> str:
    """The file of a product (``files``: its file names) that compiles read for ``name``:
    the binary copy where the product has one, else ``name`` itself."""
    copy = copy_name(name)
    return copy if copy in files and copy != name else name
