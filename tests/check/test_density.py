"""Bounds of the volume a model's geometry encloses, from MuJoCo's own compiled geometry, and
the densities the plausibility test judges with them."""

from __future__ import annotations

import math

import mujoco
import pytest
import trimesh

from mjcfbuild.check.density import (
    Volume,
    body_volumes,
    density_cause,
    density_fails,
    density_problem,
)


def compiled(tmp_path, geoms: str, meshes: dict[str, trimesh.Trimesh] | None = None):
    assets = ""
    for name, mesh in (meshes or {}).items():
        mesh.export(tmp_path / f"{name}.stl")
        assets += f'<mesh name="{name}" file="{tmp_path / name}.stl" inertia="shell"/>'
    xml = f"""<mujoco><asset>{assets}</asset><worldbody>
      <body name="b"><freejoint/><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>{geoms}
      </body></worldbody></mujoco>"""
    return mujoco.MjModel.from_xml_string(xml)


def test_primitives_enclose_their_exact_volume(tmp_path):
    model = compiled(
        tmp_path,
        '<geom type="box" size="0.1 0.2 0.3"/><geom type="sphere" size="0.1" pos="1 0 0"/>',
    )
    (volume,) = body_volumes(model).values()
    box, sphere = 0.2 * 0.4 * 0.6, 4 / 3 * math.pi * 0.001
    assert volume.low == pytest.approx(box) and volume.high == pytest.approx(box + sphere)


def test_a_closed_concave_mesh_encloses_less_than_its_hull(tmp_path):
    tube = trimesh.creation.annulus(r_min=0.08, r_max=0.1, height=0.2, sections=64)
    model = compiled(tmp_path, '<geom type="mesh" mesh="tube"/>', {"tube": tube})
    (volume,) = body_volumes(model).values()
    assert volume.low == pytest.approx(tube.volume, rel=1e-3)
    assert volume.high == pytest.approx(tube.convex_hull.volume, rel=1e-3)
    assert volume.high > 2.5 * volume.low


def test_an_open_mesh_encloses_nothing_for_sure(tmp_path):
    box = trimesh.creation.box([0.1, 0.1, 0.1])
    open_box = trimesh.Trimesh(box.vertices, box.faces[2:])  # one side missing
    model = compiled(tmp_path, '<geom type="mesh" mesh="shell"/>', {"shell": open_box})
    (volume,) = body_volumes(model).values()
    assert volume.low == 0 and volume.high == pytest.approx(1e-3)


def test_closed_means_every_edge_in_exactly_two_triangles():
    import numpy as np

    from mjcfbuild.check.density import _closed

    box = np.asarray(trimesh.creation.box().faces, dtype=np.int64)
    assert _closed(box)
    assert not _closed(box[1:])  # one triangle missing: three edges in one triangle only
    assert not _closed(np.concatenate([box, box[:1]]))  # one edge in three triangles
    assert not _closed(np.concatenate([box, box]))  # every edge in four
    fin = np.concatenate([box, [[0, 1, 8]]])  # a fin on an edge of the box
    assert not _closed(fin)


def test_visual_and_collision_geometry_are_bounded_apart(tmp_path):
    # The collision box and the visual box describe the same part: not twice its volume.
    model = compiled(
        tmp_path,
        '<geom type="box" size="0.1 0.1 0.1"/>'
        '<geom type="box" size="0.05 0.05 0.05" contype="0" conaffinity="0"/>',
    )
    (volume,) = body_volumes(model).values()
    assert volume.high == pytest.approx(8e-3) and volume.low == pytest.approx(8e-3)


def test_densities_far_outside_what_robots_are_made_of_are_named_with_their_cause():
    part = Volume(1e-3, 2e-3)
    assert density_problem(2.0, part) is None  # 1,000 to 2,000 kg/m^3
    heavy = density_problem(2000.0, part)
    assert heavy is not None and heavy[1] == pytest.approx(1e6) and density_fails(heavy[1])
    assert "grams written as kilograms" in density_cause(heavy[1])
    light = density_problem(0.002, part)
    assert light is not None and light[1] == pytest.approx(2.0) and density_fails(light[1])
    assert "tonnes" in density_cause(light[1])
    foam = density_problem(0.03, part)  # 30 kg/m^3: a placeholder, a warning
    assert foam is not None and not density_fails(foam[1])
    assert "mm" in density_cause(1e-7) and "cm" in density_cause(1e-4)


def test_a_density_just_past_a_bound_does_not_read_as_the_bound():
    from mjcfbuild.check.density import LOW_DENSITY, Volume, density_problem

    problem = density_problem(LOW_DENSITY * 0.02 * 0.99999, Volume(0.02, 0.02))
    assert problem is not None
    assert f"is {LOW_DENSITY:.6g} kg/m^3" not in problem[0]
    assert "49.9995 kg/m^3" in problem[0], problem[0]
