"""The page's scripts: MuJoCo's module made a classic script, the WebAssembly and the model's
files as base64, the same bytes for the same inputs."""

from __future__ import annotations

import base64
import gzip
import json

import pytest

from mjcfbuild.errors import InputError
from mjcfbuild.page.bundle import model_script, mujoco_script, wasm_script

MODULE = b"""var loadMujoco = (() => { var s = import.meta.url; return async () => s; })();
export default loadMujoco;
"""


def test_the_module_becomes_a_classic_script():
    script = mujoco_script(MODULE)
    assert b"export" not in script and b"import.meta" not in script
    assert script.endswith(b"window.loadMujoco = loadMujoco;\n")
    assert b"var s = document.baseURI;" in script


def test_a_module_of_another_shape_is_refused():
    with pytest.raises(InputError, match="not the ES module"):
        mujoco_script(b"module.exports = loadMujoco;")


def test_the_webassembly_comes_back_as_it_went_in():
    wasm = b"\0asm" + bytes(range(256)) * 100
    script = wasm_script(wasm)
    assert script == wasm_script(wasm)  # no time stamp in the gzip header
    prefix = b'window.MJCFBUILD_WASM = "'
    assert script.startswith(prefix) and script.endswith(b'";\n')
    assert gzip.decompress(base64.b64decode(script[len(prefix) : -3])) == wasm


def test_the_model_files_are_in_order_whatever_order_they_come_in():
    files = {"scene.xml": b"<mujoco/>", "assets/b.obj": b"v 0 0 0", "assets/a.obj": b"v 1 1 1"}
    reordered = dict(reversed(list(files.items())))
    script = model_script(files, "scene.xml", {"hold_tolerance": 0.05})
    assert script == model_script(reordered, "scene.xml", {"hold_tolerance": 0.05})
    data = json.loads(script.decode().removeprefix("window.MJCFBUILD_MODEL = ").rstrip(";\n"))
    assert list(data["files"]) == ["assets/a.obj", "assets/b.obj", "scene.xml"]
    assert gzip.decompress(base64.b64decode(data["files"]["assets/a.obj"])) == b"v 1 1 1"
    assert (data["scene"], data["config"]) == ("scene.xml", {"hold_tolerance": 0.05})
