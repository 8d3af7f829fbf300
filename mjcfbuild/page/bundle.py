"""Scripts a page opened from ``file://`` can load: Chromium refuses ``fetch()`` and ES module
imports of local files, but runs classic ``<script src>`` files. So MuJoCo's ES module becomes
a classic script, and the WebAssembly and the model's files become base64 strings in scripts
(the WebAssembly gzipped: the browser unpacks it with ``DecompressionStream``).

Every function returns the same bytes for the same inputs (gzip without a time stamp, files in
sorted order), so a rebuild leaves the page as it was.
"""

from __future__ import annotations

import base64
import gzip
import json

from mjcfbuild.errors import InputError

_EXPORT = b"export default loadMujoco;"
_META_URL = b"import.meta.url"


def mujoco_script(module: bytes) -> bytes:
    """``@mujoco/mujoco``'s ES module as a classic script defining ``window.loadMujoco``."""
    if module.count(_EXPORT) != 1 or _META_URL not in module:
        raise InputError(
            "@mujoco/mujoco's mujoco.js is not the ES module this mjcfbuild expects "
            "(no single `export default loadMujoco;`); use the pinned version"
        )
    # The module's own address only locates mujoco.wasm, which the page hands over as bytes.
    script = module.replace(_META_URL, b"document.baseURI").replace(
        _EXPORT, b"window.loadMujoco = loadMujoco;"
    )
    return script


def wasm_script(wasm: bytes) -> bytes:
    """The WebAssembly, gzipped and base64-encoded, as ``window.MJCFBUILD_WASM``."""
    return b'window.MJCFBUILD_WASM = "' + _packed(wasm).encode() + b'";\n'


def model_script(files: dict[str, bytes], scene: str, config: dict) -> bytes:
    """The model's files (paths relative to the output folder) and the page's settings as
    ``window.MJCFBUILD_MODEL``: ``{"scene", "files": {path: base64 of gzip}, "config"}``.
    Meshes are mostly OBJ text: gzip makes them a third to a fifth of their size."""
    payload = {
        "scene": scene,
        "config": config,
        "files": {path: _packed(files[path]) for path in sorted(files)},
    }
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"))
    return f"window.MJCFBUILD_MODEL = {text};\n".encode()


def _packed(data: bytes) -> str:
    """Gzipped (no time stamp in the header) and base64-encoded."""
    return base64.b64encode(gzip.compress(data, compresslevel=6, mtime=0)).decode()
