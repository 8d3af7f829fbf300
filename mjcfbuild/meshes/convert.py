"""Converting one mesh file into the files a model uses (a mesh *product*).

A product is a folder of files and a summary:

* ``mesh.obj`` - the whole mesh, when it has a single look: it serves every purpose;
* ``part<k>.obj`` - one OBJ per look (colour and texture), for drawing, when there are several;
* ``texture<j>.png`` - the textures those parts use, as PNG;
* ``collision.obj`` - all triangles in one file, when a multi-look mesh is also collision
  geometry (MuJoCo collides with its convex hull);
* ``hull.obj`` - the convex hull, when a collision policy asks for it (hull, primitive).

A file that shows nothing (a DAE without a scene, of which viewers draw nothing) is an empty
product: no parts, no collision mesh, no hull; the model leaves out the geoms that name it.

File names inside a product do not depend on what the mesh is called in a robot, so the same
input gives the same product wherever it is used; the assembly names the published files.
Meshes over the manifest's face budget are simplified, with a warning. (MuJoCo's limit of
200,000 faces applies to STL files only; products are OBJ, which it reads at any size.)
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from mjcfbuild.fsutil import write_if_changed
from mjcfbuild.meshes.load import MeshPart, at_least_min_vertices, load_parts
from mjcfbuild.meshes.mshfile import copy_name, msh_bytes, text_values
from mjcfbuild.meshes.objfile import obj_bytes
from mjcfbuild.meshes.product import PRODUCT_FORMAT, WHOLE_MESH, MeshProduct, ProductPart


def convert_mesh(
    source: Path,
    product_dir: Path,
    roles: list[str],
    max_faces: int | None = None,
    apply_up_axis: bool = False,
    collision_max_faces: int | None = None,
    max_hull_vertices: int | None = None,
    looks_from: Path | None = None,
) -> MeshProduct:
    """Write the product of ``source`` into ``product_dir`` and return its summary.

    ``max_faces`` budgets the visual parts, ``collision_max_faces`` the collision mesh, and
    ``max_hull_vertices`` the convex hull. ``looks_from`` is the mesh file a pre-generated
    OBJ stands for (``convert -a``), whose look it takes where it has none of its own."""
    warnings: list[str] = []
    original = load_parts(source, apply_up_axis=apply_up_axis, warnings=warnings)
    if looks_from is not None:
        from mjcfbuild.meshes.prebuilt_look import with_look_of

        original = with_look_of(original, source, looks_from, warnings)
    parts = _within_budget(original, max_faces, f"{source.name} (visual)", warnings)
    whole_parts = _within_budget(
        original, collision_max_faces, f"{source.name} (collision)", warnings
    )
    product_dir.mkdir(parents=True, exist_ok=True)
    files: dict[str, str] = {}
    if not original:  # a file that shows nothing (a DAE without a scene): an empty product
        _remove_stale(product_dir, files)
        return MeshProduct(PRODUCT_FORMAT, [], None, 0.0, None, 0, files, warnings)

    def store(name: str, data: bytes) -> str:
        write_if_changed(product_dir / name, data)
        files[name] = hashlib.md5(data, usedforsecurity=False).hexdigest()
        return name

    def store_mesh(name: str, vertices: np.ndarray, faces: np.ndarray, uv=None) -> str:
        vertices, uv = at_least_min_vertices(vertices, uv)
        # Numbers that read back as the float32 values the binary copy holds: both compile
        # to the same model.
        store(name, obj_bytes(text_values(vertices), faces, uv))
        if uv is None and len(vertices) and len(faces):
            store(copy_name(name), msh_bytes(vertices, faces))
        return name

    textures: dict[str, str] = {}
    summary_parts = []
    single = len(parts) == 1
    for index, part in enumerate(parts):
        texture_file = None
        if part.texture is not None:
            texture_file = textures.get(part.texture.key)
            if texture_file is None:
                texture_file = store(f"texture{len(textures)}.png", part.texture.png)
                textures[part.texture.key] = texture_file
        uv = part.uv if part.texture is not None else None
        name = store_mesh(
            WHOLE_MESH if single else f"part{index}.obj", part.vertices, part.faces, uv
        )
        summary_parts.append(
            ProductPart(
                file=name,
                rgba=[float(v) for v in part.rgba] if part.rgba is not None else None,
                texture=texture_file,
                emission=part.emission,
                vertices=len(part.vertices),
                faces=len(part.faces),
                volume=_volume(part.vertices, part.faces),
            )
        )
    vertices, faces = _whole(whole_parts)
    collision = None
    if "collision" in roles:
        same = single and whole_parts is parts  # no budget made them differ
        collision = WHOLE_MESH if same else store_mesh("collision.obj", vertices, faces)
    hull = None
    if "hull" in roles:
        hull = store_mesh("hull.obj", *_hull(_whole(original)[0], max_hull_vertices))
    _remove_stale(product_dir, files)
    return MeshProduct(
        format=PRODUCT_FORMAT,
        parts=summary_parts,
        collision=collision,
        collision_volume=_volume(vertices, faces),
        hull=hull,
        faces=int(sum(len(p.faces) for p in parts)),
        files=dict(sorted(files.items())),
        warnings=warnings,
    )


def convert_with_options(
    source: Path, product_dir: Path, options: dict, looks_from: Path | None = None
) -> MeshProduct:
    """:func:`convert_mesh` with a mesh task's options (as build steps and cluster workers get
    them)."""
    return convert_mesh(
        source,
        product_dir,
        options["roles"],
        max_faces=options["max_faces"],
        apply_up_axis=options["collada_up_axis"] == "apply",
        collision_max_faces=options.get("collision_max_faces"),
        max_hull_vertices=options.get("max_hull_vertices"),
        looks_from=looks_from,
    )


def _remove_stale(product_dir: Path, files: dict[str, str]) -> None:
    """Remove what an earlier product left in ``product_dir`` that is not one of ``files``."""
    for stale in product_dir.iterdir():
        if stale.name not in files:
            stale.unlink()


def _within_budget(
    parts: list[MeshPart], budget: int | None, what: str, warnings: list[str]
) -> list[MeshPart]:
    """``parts`` simplified together to about ``budget`` faces (the same list if within it)."""
    total = sum(len(p.faces) for p in parts)
    if budget is None or total <= budget:
        return parts
    simplified = [_simplify(part, max(4, int(len(part.faces) * budget / total))) for part in parts]
    warnings.append(
        f"{what}: {total} faces over the budget of {budget}; "
        f"simplified to {sum(len(p.faces) for p in simplified)}"
    )
    return simplified


def _whole(parts: list[MeshPart]) -> tuple[np.ndarray, np.ndarray]:
    offsets = np.cumsum([0] + [len(p.vertices) for p in parts[:-1]])
    vertices = np.concatenate([p.vertices for p in parts])
    faces = np.concatenate([p.faces + o for p, o in zip(parts, offsets, strict=True)])
    return vertices, faces


def _volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume enclosed by the triangles (positive for outward-facing closed meshes)."""
    a, b, c = (vertices[faces[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _hull(vertices: np.ndarray, max_vertices: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The convex hull of ``vertices`` (at most ``max_vertices``), in a reproducible order."""
    import trimesh

    # qhull starts from a simplex of 4 points: a mesh of one triangle gets a copy of a corner
    # (joggled, its hull is the triangle, which the assembly then says is flat).
    vertices, _ = at_least_min_vertices(vertices, None)
    with np.errstate(invalid="ignore", divide="ignore"):  # a flat hull's centre of mass
        hull = trimesh.Trimesh(vertices=vertices, process=False).convex_hull
    if max_vertices is not None and len(hull.vertices) > max_vertices:
        kept = farthest_points(np.asarray(hull.vertices), max_vertices)
        hull = trimesh.Trimesh(vertices=kept, process=False).convex_hull
    order = np.lexsort(np.round(hull.vertices, 12).T[::-1])  # a stable vertex order
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    faces = rank[hull.faces]
    faces = faces[np.lexsort(np.sort(faces, axis=1).T[::-1])]
    return np.asarray(hull.vertices)[order], faces


def farthest_points(points: np.ndarray, count: int) -> np.ndarray:
    """``count`` of ``points`` spread as far apart as possible (greedy farthest-point
    sampling from the lexicographically first point, so the choice is deterministic)."""
    order = np.lexsort(np.round(points, 12).T[::-1])
    points = points[order]
    chosen = [0]
    distance = np.linalg.norm(points - points[0], axis=1)
    for _ in range(count - 1):
        index = int(np.argmax(distance))
        chosen.append(index)
        distance = np.minimum(distance, np.linalg.norm(points - points[index], axis=1))
    return points[sorted(chosen)]


def _simplify(part: MeshPart, target_faces: int) -> MeshPart:
    """Quadric decimation of one part to about ``target_faces`` faces (textures dropped)."""
    import fast_simplification

    points, faces = fast_simplification.simplify(
        part.vertices.astype(np.float32),
        part.faces.astype(np.int32),
        target_count=target_faces,
    )
    return MeshPart(
        np.asarray(points, dtype=np.float64),
        np.asarray(faces, dtype=np.int64),
        part.rgba,
        emission=part.emission,
    )
