"""Writing OBJ files MuJoCo reads, byte-for-byte reproducibly."""

from __future__ import annotations

import io

import numpy as np


def obj_bytes(vertices: np.ndarray, faces: np.ndarray, uv: np.ndarray | None = None) -> bytes:
    """An OBJ file with vertices, optional texture coordinates and triangles.

    Numbers are written with 9 significant digits, enough to round-trip the float32 values
    mesh files store, and in a fixed format so the same mesh always gives the same bytes.
    """
    buffer = io.BytesIO()
    # Adding 0.0 turns -0.0 into 0.0, so mirrored meshes do not print "-0".
    np.savetxt(buffer, np.asarray(vertices, dtype=np.float64) + 0.0, fmt="v %.9g %.9g %.9g")
    one_based = np.asarray(faces, dtype=np.int64) + 1
    if uv is not None:
        np.savetxt(buffer, np.asarray(uv, dtype=np.float64) + 0.0, fmt="vt %.9g %.9g")
        np.savetxt(
            buffer,
            np.repeat(one_based, 2, axis=1),
            fmt="f %d/%d %d/%d %d/%d",
        )
    else:
        np.savetxt(buffer, one_based, fmt="f %d %d %d")
    return buffer.getvalue()
