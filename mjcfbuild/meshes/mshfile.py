"""The binary copy of a mesh product that the build's own compiles read (MuJoCo's MSH format).

MuJoCo reads an OBJ file's numbers as text and a binary MSH file's as they are: the first
compile of a model in a process, where MuJoCo processes every mesh, takes about two thirds
of the time from MSH (g1: 0.45 s against 0.63, go1 0.58 against 0.87, panda 0.16 against
0.23; ``bench/msh_compile.py``); later ones, from MuJoCo's cache, take the same. A product
keeps its OBJ files, which the published model names and any tool reads, and beside each one
without texture coordinates an MSH copy of the same float32 vertices and triangles that the
build's compiles read instead. The model compiled from the copy is the one compiled from the
OBJ file, array for array, because every number of the OBJ file reads back as exactly its
float32 value (:func:`text_values`).
"""

from __future__ import annotations

from pathlib import PurePath

import numpy as np

SUFFIX = ".msh"


# Relative error of a number written with 9 significant digits (half a unit in the last one).
_NINE_DIGITS = 5e-9
# How much of half a float32 step a number's text may be from its float32 value: the rest is
# room for a parser whose digits are not exactly rounded (tinyobjloader, in MuJoCo: errors
# of about 1e-16 of the value, against a half step of at least 3e-8).
_WITHIN = 1 - 1e-5


def text_values(vertices: np.ndarray) -> np.ndarray:
    """The values to write in an OBJ file with 9 significant digits so that it reads back as
    exactly the float32 vertices of the binary copy, whichever parser reads it.

    A value goes as it is where its text lies within half a float32 step of its float32
    value (less room for the parser): MuJoCo's OBJ parser then reads the same float32, and
    the file keeps the numbers it always had (an STL file's float32 values; 0.265 from a
    text format stays 0.265). Elsewhere (a transformed COLLADA vertex, nearer the middle
    between two float32 values) the float32 value goes instead."""
    exact = np.asarray(vertices, dtype=np.float64)
    nearest = exact.astype(np.float32)
    within = 0.5 * _WITHIN * np.spacing(np.abs(nearest)).astype(np.float64)
    gap = np.abs(exact - nearest)
    safe = gap + _NINE_DIGITS * np.abs(exact) <= within  # whatever the text's last digit
    unsure = np.flatnonzero(~safe & (gap < within))
    if len(unsure):  # the text itself, read back exactly rounded
        texts = (("%.9g\n" * len(unsure)) % tuple(exact.flat[unsure].tolist())).split()
        read = np.array(texts, dtype=np.float64)
        safe.flat[unsure] = np.abs(read - nearest.flat[unsure]) <= within.flat[unsure]
    return np.where(safe, exact, nearest.astype(np.float64))


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
