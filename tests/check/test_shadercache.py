"""Mesa's shader cache is used only where it cannot kill the previews: a folder with room and
an index with its space allocated; otherwise it is turned off."""

from __future__ import annotations

import os

from mjcfbuild.check.shadercache import DISABLE_VARIABLE, FOLDER_VARIABLE, choose_shader_cache


def test_a_folder_with_room_is_used(tmp_path):
    environ: dict[str, str] = {}
    assert choose_shader_cache(environ, tmp_path / "mesa")
    assert environ == {FOLDER_VARIABLE: str(tmp_path / "mesa")}
    assert (tmp_path / "mesa").is_dir()


def test_the_users_choices_are_kept(tmp_path):
    environ = {FOLDER_VARIABLE: str(tmp_path / "mine")}
    assert choose_shader_cache(environ, tmp_path / "default")
    assert environ[FOLDER_VARIABLE] == str(tmp_path / "mine")
    assert not (tmp_path / "default").exists()
    off = {DISABLE_VARIABLE: "true"}
    assert not choose_shader_cache(off, tmp_path / "default")
    assert off == {DISABLE_VARIABLE: "true"}


def test_a_folder_that_cannot_be_made_turns_it_off(tmp_path):
    (tmp_path / "file").write_text("not a folder")
    environ: dict[str, str] = {}
    assert not choose_shader_cache(environ, tmp_path / "file" / "mesa")
    assert environ == {DISABLE_VARIABLE: "true"}


def test_a_sparse_index_gets_its_space_before_mesa_maps_it(tmp_path):
    index = tmp_path / "mesa" / "mesa_shader_cache" / "index"
    index.parent.mkdir(parents=True)
    with open(index, "wb") as handle:
        handle.truncate(1 << 20)  # as Mesa makes it: a length, no blocks
    assert index.stat().st_blocks * 512 < index.stat().st_size
    assert choose_shader_cache({}, tmp_path / "mesa")
    info = index.stat()
    assert info.st_blocks * 512 >= info.st_size == 1 << 20
    assert index.read_bytes() == bytes(1 << 20)  # its contents untouched
    assert os.access(index, os.W_OK)
