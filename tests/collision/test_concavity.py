"""How far convex geometry stands off a mesh, against figures worked out by hand."""

from __future__ import annotations

import numpy as np
import trimesh

from mjcfbuild.collision.concavity import hull_concavity, parts_concavity


def u_shape() -> trimesh.Trimesh:
    """A U: a 0.4 m base, 0.1 m thick, and two 0.1 m posts rising to 0.5 m, 0.2 m apart.

    Its hull closes the gap between the posts; the hull's points furthest from the mesh are
    midway between the posts' inner walls, 0.1 m from each (and 0.3 m or more above the
    base), so the hull stands off by 0.1 m. Half the largest extent is 0.25 m: 0.4 in
    CoACD's units.
    """
    base = trimesh.creation.box([0.4, 0.1, 0.1])
    base.apply_translation([0, 0, 0.05])
    left = trimesh.creation.box([0.1, 0.1, 0.5])
    left.apply_translation([-0.15, 0, 0.25])
    right = left.copy()
    right.apply_translation([0.3, 0, 0])
    return trimesh.util.concatenate([base, left, right])


def test_a_box_is_its_own_hull():
    box = trimesh.creation.box([0.3, 0.2, 0.1])
    assert hull_concavity(box.vertices, box.faces) < 1e-9


def test_the_hull_of_a_u_stands_off_by_the_half_gap():
    mesh = u_shape()
    measured = hull_concavity(mesh.vertices, mesh.faces)
    assert 0.37 < measured <= 0.4 + 1e-9
    assert measured == hull_concavity(mesh.vertices, mesh.faces)  # seeded: same figure


def test_parts_that_follow_the_mesh_stand_off_by_nothing():
    # The U's three boxes as parts: their union is the mesh, and their shared faces (inside
    # the mesh) do not count as standing off.
    mesh = u_shape()
    parts = [(b.vertices, b.faces) for b in mesh.split(only_watertight=False)]
    assert len(parts) == 3
    assert parts_concavity(mesh.vertices, mesh.faces, parts) < 1e-6


def test_an_open_mesh_is_measured_too():
    # Two faces of a box missing: not watertight, no volume, still a distance.
    box = trimesh.creation.box([0.2, 0.2, 0.2])
    normals = box.face_normals
    open_box = trimesh.Trimesh(box.vertices, box.faces[normals[:, 2] > -0.5], process=False)
    assert not open_box.is_watertight
    # The hull's bottom face is 0.1 m from the nearest remaining wall at its centre.
    assert np.isclose(hull_concavity(open_box.vertices, open_box.faces), 1.0, atol=0.05)
