"""Reading binary STL files without trimesh.

Most collision meshes in description repos are binary STL, and importing trimesh (with the
scipy and networkx it imports) costs a worker 0.6 s of CPU: more than converting the mesh. A
binary STL is a fixed layout that numpy reads directly; anything else (ASCII STL, or a file
whose length does not match its triangle count) is left to trimesh, which decides the same way.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

HEADER_BYTES = 80
# Each triangle: a normal and three corners as little-endian float32, then two attribute bytes.
TRIANGLE = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])


def read_binary_stl(path: Path) -> tuple[np.ndarray, np.ndarray] | None:
    """The corners (float64, one row per triangle corner, as the file repeats them) and the
    triangles of the binary STL file at ``path``; None when it is not one, that is when its
    length is not the 84 bytes of header and count plus 50 bytes per triangle it declares."""
    data = path.read_bytes()
    if len(data) < HEADER_BYTES + 4:
        return None
    count = int(np.frombuffer(data, dtype="<u4", count=1, offset=HEADER_BYTES)[0])
    if len(data) != HEADER_BYTES + 4 + count * TRIANGLE.itemsize:
        return None
    triangles = np.frombuffer(data, dtype=TRIANGLE, count=count, offset=HEADER_BYTES + 4)
    corners = triangles["corners"].reshape(-1, 3).astype(np.float64)
    return corners, np.arange(3 * count, dtype=np.int64).reshape(-1, 3)
