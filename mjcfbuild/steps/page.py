"""Step ``page``: the interactive report page, ``report/index.html`` (``output.page: true``).

The page and the scripts beside it in ``report/page/`` hold everything it needs: MuJoCo's
WebAssembly build (mjcfbuild.page.vendor) and the model's files (scene, model, assets), so it
opens from a CI artifact or a local folder with no server or network. The report's tables come
with the report itself (``page/tables.js``, engine/report.py).
"""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.actuators import for_mujoco3
from mjcfbuild.markup import html_text
from mjcfbuild.page import WEB
from mjcfbuild.page.bundle import model_script, mujoco_script, wasm_script
from mjcfbuild.page.vendor import mujoco_js
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import PagePayload


def run(payload: dict) -> dict:
    """Write ``index.html`` and ``page/`` in the report folder."""
    request = PagePayload.from_dict(payload)
    folder = Path(request.folder)
    vendored = mujoco_js()
    assembly = _read(request.assembly_report)
    outputs: dict[str, str] = {}
    index = (WEB / "index.html").read_text(encoding="utf-8")
    write_output(
        folder / "index.html", index.replace("@TITLE@", html_text(request.name)).encode(), outputs
    )
    write_output(folder / "page" / "mujoco.js", mujoco_script(vendored.script), outputs)
    write_output(folder / "page" / "mujoco-wasm.js", wasm_script(vendored.wasm), outputs)
    config = {
        "name": request.name,
        "hold_tolerance": request.hold_tolerance,
        "passive": sorted((assembly.get("readiness") or {}).get("passive") or []),
    }
    files = _model_files(Path(request.scene), Path(request.model), Path(request.assets))
    scene = Path(request.scene).name
    write_output(folder / "page" / "model.js", model_script(files, scene, config), outputs)
    for name in ("viewer.js", "page.css"):
        write_output(folder / "page" / name, (WEB / name).read_bytes(), outputs)
    return {"outputs": outputs}


def _model_files(scene: Path, model: Path, assets: Path) -> dict[str, bytes]:
    """The scene, the model (as the page's MuJoCo reads it) and every asset, by their paths
    relative to the output folder."""
    base = scene.parent
    files = {
        scene.name: for_mujoco3(scene.read_bytes()),
        model.relative_to(base).as_posix(): for_mujoco3(model.read_bytes()),
    }
    if assets.is_dir():
        for path in sorted(p for p in assets.rglob("*") if p.is_file()):
            files[path.relative_to(base).as_posix()] = path.read_bytes()
    return files


def _read(path: str) -> dict:
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}
