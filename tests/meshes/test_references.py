"""What a mesh file refers to: the files there (dependencies) and those missing (a warning)."""

from __future__ import annotations

from mjcfbuild.meshes.references import missing_paths, missing_references, referenced_files
from tests.meshes import samples

DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_images>
    <image id="wood-image" name="Material.001-image"><init_from>textures/wood.png</init_from></image>
    <image id="here-image"><init_from>here.png</init_from></image>
  </library_images>
  <library_effects>
    <effect id="e"><profile_COMMON>
      <newparam sid="wood-surface"><surface type="2D"><init_from>wood-image</init_from></surface></newparam>
    </profile_COMMON></effect>
  </library_effects>
</COLLADA>
"""


def test_an_obj_whose_material_library_is_missing(tmp_path):
    obj = samples.obj_with_named_mtl_and_texture(tmp_path)
    (tmp_path / "looks.mtl").unlink()
    assert referenced_files(obj) == []
    assert missing_references(obj) == ["'looks.mtl' (material library)"]
    assert missing_paths(obj) == [tmp_path / "looks.mtl"]


def test_an_obj_whose_material_names_a_missing_texture(tmp_path):
    obj = samples.obj_with_named_mtl_and_texture(tmp_path)
    (tmp_path / "skin.png").unlink()
    assert referenced_files(obj) == [tmp_path / "looks.mtl"]
    assert missing_references(obj) == ["'skin.png' (texture)"]


def test_a_dae_image_that_is_missing_and_image_ids_that_are_no_files(tmp_path):
    dae = tmp_path / "part.dae"
    dae.write_text(DAE)
    (tmp_path / "here.png").write_bytes(b"png")
    assert referenced_files(dae) == [tmp_path / "here.png"]
    # the path from the mesh's folder, where it was looked for (roboschool's atlas meshes
    # name ../materials/textures/*.png; "extremities_diffuse.png, not found beside it" sent
    # the user to the wrong folder)
    assert missing_references(dae) == ["'textures/wood.png' (texture)"]
    assert missing_paths(dae) == [tmp_path / "textures" / "wood.png"]


def test_nothing_missing(tmp_path):
    obj = samples.obj_with_named_mtl_and_texture(tmp_path)
    assert missing_references(obj) == [] and missing_paths(obj) == []


def test_a_missing_file_far_outside_the_mesh_is_named_without_the_way_there(tmp_path):
    # file:///opt/textures/wood.png from m1/a/b/part.dae: a path of ../ up to the root would
    # depend on where the description sits, and differ between folders.
    folder = tmp_path / "m1" / "a" / "b"
    folder.mkdir(parents=True)
    dae = folder / "part.dae"
    far = tmp_path.parent / "elsewhere" / "textures" / "wood.png"
    dae.write_text(DAE.replace("textures/wood.png", far.as_uri()).replace("here.png", "x.png"))
    assert missing_references(dae) == ["'wood.png' (texture)", "'x.png' (texture)"]
