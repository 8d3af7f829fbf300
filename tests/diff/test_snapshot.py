"""What a model snapshot holds of a mesh: its size in the mesh file's own axes."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.diff.snapshot import model_snapshot


def _box(folder: Path, moved: str) -> dict:
    """A 6 x 6 x 24 cm box mesh, one corner at ``moved``, as the only geom of a body."""
    corners = [f"{x} {y} {z}" for x in (0, 0.06) for y in (0, 0.06) for z in (0, 0.24)]
    corners[1] = moved
    path = folder / "box.xml"
    path.write_text(
        f'<mujoco><asset><mesh name="box" vertex="{" ".join(corners)}"/></asset><worldbody>'
        '<body name="b"><geom type="mesh" mesh="box"/></body></worldbody></mujoco>\n'
    )
    return model_snapshot(path)


def _meshes(snapshot: dict) -> list[dict]:
    return [
        entry
        for body in snapshot["geometry"].values()
        for entry in body["collision"] + body["visual"]
        if "extent" in entry
    ]


def test_a_meshs_extent_is_in_its_files_axes_not_its_principal_axes(tmp_path):
    # The moved corner turns the principal axes of inertia by about 30 degrees: MuJoCo's own
    # vertices span 8 x 8 cm, the file's still 6 x 6.
    [mesh] = _meshes(_box(tmp_path, "0.002 0 0.24"))
    assert [round(value, 6) for value in mesh["extent"]] == [0.06, 0.06, 0.24]
