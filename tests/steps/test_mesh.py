"""The mesh step warns of the files a mesh refers to that are missing, and converts the mesh
again when they appear."""

from __future__ import annotations

import json

from mjcfbuild.errors import EXIT_OK
from tests.conftest import run_cli

WARNING = (
    "meshes/forearm.obj: refers to 'forearm_colours.mtl' (material library), not found beside it; "
    "the model shows the mesh without it"
)


def _warnings(arm) -> list[str]:
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OK, result.stdout + result.stderr
    return json.loads((arm / "mjcf" / "report" / "report.json").read_text())["warnings"]


def test_a_missing_material_library_is_named_once_and_its_return_rebuilds(arm):
    library = arm / "meshes" / "forearm_colours.mtl"
    kept = library.read_bytes()
    library.unlink()
    warned = [w for w in _warnings(arm) if "forearm_colours.mtl" in w]
    assert len(warned) == 1 and warned[0].startswith(WARNING), warned
    library.write_bytes(kept)
    assert not [w for w in _warnings(arm) if "forearm_colours.mtl" in w]
    product = json.loads((arm / "mjcf" / ".mjcfbuild" / "products" / "forearm.json").read_text())
    assert len(product["parts"]) > 1  # the library's materials split the mesh again


def test_a_texture_named_in_another_folder_is_named_by_its_path_from_the_mesh(tmp_path):
    from mjcfbuild.steps.mesh import _missing_warning
    from tests.meshes.test_references import DAE

    dae = tmp_path / "meshes" / "part.dae"
    dae.parent.mkdir()
    dae.write_text(DAE.replace("textures/wood.png", "../materials/wood.png"))
    (dae.parent / "here.png").write_bytes(b"png")
    assert _missing_warning(dae, "meshes/part.dae") == [
        "meshes/part.dae: refers to '../materials/wood.png' (texture), not found where it says; "
        "the model shows the mesh without it (add the file, or remove the reference from the "
        "mesh)"
    ]


def test_a_collision_only_mesh_is_not_warned_about_its_materials_and_the_rest_group(tmp_path):
    """suite_panda: ten ungrouped lines, eight of them for collision OBJs, whose colours
    nothing shows."""
    from mjcfbuild.steps.mesh import _missing_warning
    from mjcfbuild.warning_groups import group_warnings

    warnings = []
    for name in ("link1", "link2"):
        obj = tmp_path / f"{name}.obj"
        obj.write_text(f"mtllib {name}.obj.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        assert _missing_warning(obj, f"{name}.obj", ["collision"]) == []
        warnings += _missing_warning(obj, f"{name}.obj", ["collision", "visual"])
    assert len(warnings) == 2
    grouped = group_warnings(warnings)
    assert grouped == [f"{warnings[0]} (and 1 more like it: link2.obj)"]


def test_a_file_outside_the_current_folder_is_named_without_climbs(tmp_path, monkeypatch):
    from mjcfbuild.console import shown_path

    (tmp_path / "here").mkdir()
    monkeypatch.chdir(tmp_path / "here")
    assert shown_path(tmp_path / "r" / "robot" / ".." / ".." / "src" / "m.obj") == str(
        tmp_path / "src" / "m.obj"
    )
