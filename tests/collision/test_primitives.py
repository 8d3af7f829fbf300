"""Primitive fits: the right kind, enclosing every point, in the right place."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from mjcfbuild.collision.primitives import fit_primitive

SHAPES = {
    "box": lambda: trimesh.creation.box([0.1, 0.2, 0.4]),
    "cylinder": lambda: trimesh.creation.cylinder(0.05, 0.3, sections=64),
    "capsule": lambda: trimesh.creation.capsule(0.3, 0.05),
    "sphere": lambda: trimesh.creation.icosphere(3, 0.1),
}


@pytest.mark.parametrize("kind", sorted(SHAPES))
def test_fits_the_shape_it_is_given_wherever_it_is(kind):
    mesh = SHAPES[kind]()
    pose = trimesh.transformations.random_rotation_matrix(np.random.default_rng(3).random(3))
    pose[:3, 3] = [0.2, -0.1, 0.5]
    mesh.apply_transform(pose)
    points = mesh.convex_hull.vertices
    fit = fit_primitive(points)
    assert fit.kind == kind
    assert fit.volume == pytest.approx(mesh.volume, rel=0.05)
    local = (np.c_[points, np.ones(len(points))] @ np.linalg.inv(fit.transform).T)[:, :3]
    if kind == "box":
        assert np.all(np.abs(local) <= np.array(fit.size) + 1e-9)
    elif kind == "sphere":
        assert np.all(np.linalg.norm(local, axis=1) <= fit.size[0] + 1e-9)
    else:
        radial = np.hypot(local[:, 0], local[:, 1])
        assert np.all(radial <= fit.size[0] + 1e-9)


def test_kinds_limit_the_candidates_and_the_fit_still_encloses():
    box = trimesh.creation.box(extents=(0.3, 0.1, 0.05))
    points = box.vertices
    assert fit_primitive(points).kind == "box"
    fit = fit_primitive(points, ("sphere", "capsule"))
    assert fit.kind == "capsule"
    local = (np.c_[points, np.ones(len(points))] @ np.linalg.inv(fit.transform).T)[:, :3]
    radial = np.hypot(local[:, 0], local[:, 1])
    capped = np.maximum(np.abs(local[:, 2]) - fit.size[1], 0)
    assert np.all(np.hypot(radial, capped) <= fit.size[0] + 1e-9)


@pytest.mark.parametrize(
    ("points", "kind"),
    [
        ([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], "box"),  # a square plate
        ([[0, 0, 0], [0, 0, 0.3]], "box"),  # a rod
        ([[0.1, 0.2, 0.3]], "box"),  # one point
    ],
)
def test_points_without_volume_get_a_thin_primitive_around_them(points, kind):
    # qhull refuses flat input (QH6022), which stopped the build with an internal error
    points = np.array(points, dtype=float)
    fit = fit_primitive(points)
    assert fit.kind == kind
    local = (np.c_[points, np.ones(len(points))] @ np.linalg.inv(fit.transform).T)[:, :3]
    assert np.all(np.abs(local) <= np.array(fit.size) + 1e-9)
    # The thickness is 1 % of the span (twice the farthest point from the mean), whichever
    # way the plate's in-plane axes fall: exactly, not between its side and its diagonal.
    span = 2 * np.linalg.norm(points - points.mean(axis=0), axis=1).max()
    assert min(fit.size) * 2 == pytest.approx(max(span * 0.01, 2e-6), rel=1e-6)
    for kinds in (("sphere",), ("capsule",), ("cylinder",)):
        assert fit_primitive(points, kinds).kind == kinds[0]


def test_a_flat_disc_gets_a_thin_cylinder():
    angles = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    points = np.c_[0.1 * np.cos(angles), 0.1 * np.sin(angles), np.zeros(64)]
    fit = fit_primitive(points)
    assert fit.kind == "cylinder"
    assert fit.size[0] == pytest.approx(0.1, rel=1e-3) and fit.size[1] < 0.002
