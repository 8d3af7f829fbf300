"""Step ``package``: the model's Menagerie-grade folder (``output.package: true``).

The folder holds the model formatted the Menagerie way, the scene, the assets, ``<name>.png``,
the description's LICENSE, a README and a CHANGELOG. The CHANGELOG is kept across builds: each
time the packaged model changes, an entry on top says what changed (the groups of
``mjcfbuild diff``), compared with the snapshot of the model packaged last time.
"""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.check.results import CheckResults
from mjcfbuild.diff.compare import compare
from mjcfbuild.diff.render import change_line
from mjcfbuild.diff.snapshot import model_snapshot
from mjcfbuild.fsutil import write_if_changed
from mjcfbuild.markup import markdown_code, markdown_text
from mjcfbuild.outputs import PACKAGE_CHANGELOG, PACKAGE_COPIES
from mjcfbuild.ownership import remove_output
from mjcfbuild.package.documents import Provenance, changelog, readme
from mjcfbuild.package.format import format_model
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import PackagePayload
from mjcfbuild.version import __version__

CHANGELOG = PACKAGE_CHANGELOG


def run(payload: dict) -> dict:
    """Write the folder; warn when the description has no license file."""
    request = PackagePayload.from_dict(payload)
    folder = Path(request.folder)
    outputs: dict[str, str] = {}
    warnings: list[str] = []
    model = folder / f"{request.name}.xml"
    write_output(model, format_model(Path(request.model).read_bytes()), outputs)
    write_output(folder / "scene.xml", Path(request.scene).read_bytes(), outputs)
    copies = Path(request.record).with_name(PACKAGE_COPIES)
    copied = _read(copies).get("files", [])  # what this step copied last time
    _copy_assets(Path(request.assets), folder / "assets", outputs, copied)
    picture = folder / f"{request.name}.png"
    drawn = request.picture is not None and Path(request.picture).is_file()
    if request.picture is not None and drawn:
        write_output(picture, Path(request.picture).read_bytes(), outputs)
    elif picture.name in copied:  # our picture of the model as an earlier build drew it
        remove_output(picture)
    if request.license:
        write_output(folder / "LICENSE", Path(request.license).read_bytes(), outputs)
    else:
        if "LICENSE" in copied:  # our copy of a license the description no longer has
            remove_output(folder / "LICENSE")
        warnings.append(
            "package: no LICENSE found in the description package (or its repository): the "
            "packaged folder has none; add the description's license before sharing it"
        )
    info = Provenance(
        name=request.name,
        mjcfbuild_version=__version__,
        **{key: request.provenance[key] for key in _PROVENANCE},
        revision=request.git["revision"],
        remote=request.git["remote"],
    )
    check = CheckResults.read(Path(request.check)) if request.check else None
    assembly = _read(Path(request.assembly_report))
    write_output(folder / "README.md", readme(info, check, assembly, drawn).encode(), outputs)
    _changelog(folder, model, info, Path(request.record))
    names = sorted(
        str(Path(path).relative_to(folder)) for path in outputs if Path(path).is_relative_to(folder)
    )
    write_if_changed(copies, (json.dumps({"files": names}, indent=1) + "\n").encode())
    # The changelog is kept, not checked (a user may edit it); recorded as written, and kept
    # by clean, which leaves the history of earlier builds alone (cli.clean).
    written = [str(folder / CHANGELOG)] if (folder / CHANGELOG).is_file() else []
    return {"outputs": outputs, "warnings": warnings, "written": written}


_PROVENANCE = ("source", "manifest_text", "mujoco_version", "license_from")


def _copy_assets(source: Path, target: Path, outputs: dict[str, str], copied: list[str]) -> None:
    """The output folder's assets; the copies an earlier package made of assets the model no
    longer has go (``copied``: what it copied, relative to the package folder), a file the user
    put there stays."""
    files = source.iterdir() if source.is_dir() else iter(())
    wanted = {path.name for path in files if path.is_file()}
    for name in sorted(wanted):
        write_output(target / name, (source / name).read_bytes(), outputs)
    for name in copied:
        stale = target.parent / name
        if stale.parent == target and stale.name not in wanted and not stale.is_symlink():
            remove_output(stale)


def _changelog(folder: Path, model: Path, info: Provenance, record: Path) -> None:
    """Add an entry on top of CHANGELOG.md when the packaged model changed (or on the first
    package); the snapshot compared next time goes to ``record``."""
    snapshot = model_snapshot(model)
    previous = _read(record).get("snapshot")
    path = folder / CHANGELOG
    text = path.read_text() if path.is_file() else ""
    title = info.revision[:12] + info.revision[40:] if info.revision else "unversioned sources"
    if previous is None or not text:
        lines = [
            f"packaged by mjcfbuild {info.mjcfbuild_version} from {markdown_code(info.source)}"
        ]
    else:
        diff = compare(previous, snapshot)
        lines = [
            markdown_text(change_line(change, group))
            for group, changes in diff.groups.items()
            for change in changes
        ]
    if lines:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_if_changed(path, changelog(text, title, lines).encode())
    write_output(record, (json.dumps({"snapshot": snapshot}, sort_keys=True) + "\n").encode(), {})


def _read(path: Path) -> dict:
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}
