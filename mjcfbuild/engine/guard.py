"""The output folder's guard: builds and ``clean`` write and remove only inside it, and only
inside the manifest's folder tree unless the user allowed another place.

``output.folder`` is resolved with its symbolic links; a folder that leaves the tree of
robot.yaml's folder is refused unless ``output.allow_outside: true`` or ``--allow-outside``
says it is meant. The folders a build writes below the output folder (its state, ``assets/``,
``report/``, ...) are never written through a symbolic link, wherever it points.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import OutputError
from mjcfbuild.ownership import FOREIGN

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext

ALLOW_HINT = "set output.allow_outside: true in robot.yaml or pass --allow-outside if it is meant"


def check_output_folder(ctx: BuildContext) -> None:
    """Raise :class:`OutputError` unless the build of ``ctx`` may write its output folder."""
    if named_by_manifest(ctx):
        _check_inside(ctx)
        _check_not_a_file(ctx)
    for folder in build_folders(ctx):
        if folder.is_symlink():
            raise OutputError(
                f"is a symbolic link (to {os.readlink(folder)}); mjcfbuild does not write "
                "through links in its output folder",
                file=ctx.label(folder),
                hint="remove the link and let the build make the folder, or set output.folder "
                "to the folder it points at",
            )


def named_by_manifest(ctx: BuildContext) -> bool:
    """Whether the output folder comes from robot.yaml (``convert -o``, ``diff``'s scratch
    builds and the API's folders are named by their caller)."""
    return ctx.manifest_file is not None and ctx.output_override is None


def _check_not_a_file(ctx: BuildContext) -> None:
    """Refuse, at its line, an output.folder that names a file (``output.folder:
    robot.urdf``): the build would fail writing into it with the system's "Not a directory"."""
    if not ctx.out_dir.exists() or ctx.out_dir.is_dir():
        return
    from mjcfbuild.errors import ManifestError
    from mjcfbuild.manifest.pinpoint import pinpoint

    error = ManifestError(
        f"'{ctx.manifest.output.folder}' is a file, not a folder",
        file=f"{ctx.manifest_label} output.folder",
        hint="name the folder the model is written to, such as mjcf",
    )
    assert ctx.manifest_file is not None, "guarded only with a manifest file"
    raise pinpoint(error, ctx.manifest_label, ctx.manifest_file)


def _check_inside(ctx: BuildContext) -> None:
    if ctx.allow_outside or ctx.manifest.output.allow_outside:
        return
    tree = Path(os.path.realpath(ctx.base_dir))
    folder = Path(os.path.realpath(ctx.out_dir))
    if folder == tree or tree in folder.parents:
        return
    from mjcfbuild.manifest.pinpoint import pinpoint

    shown = ctx.manifest.output.folder
    if os.path.normpath(ctx.out_dir) != str(folder):
        where = f"'{shown}' leads through a link to {folder}"
    else:
        where = f"'{shown}'" if shown == str(folder) else f"'{shown}' ({folder})"
    error = OutputError(
        f"{where} is outside {tree}, the folder of {ctx.manifest_label}",
        file=f"{ctx.manifest_label} output.folder",
        hint=f"choose a folder inside it, or {ALLOW_HINT}",
    )
    assert ctx.manifest_file is not None, "guarded only with a manifest file"
    raise pinpoint(error, ctx.manifest_label, ctx.manifest_file)


def build_folders(ctx: BuildContext) -> list[Path]:
    """The folders below the output folder that builds write into, whether they exist or not."""
    from mjcfbuild.outputs import PACKAGE_FOLDER, report_dir

    out = ctx.out_dir
    report = report_dir(ctx)
    folders = [
        ctx.state_dir,
        ctx.assets_dir,
        report,
        report / "previews",
        report / "page",
        out / PACKAGE_FOLDER,
        out / PACKAGE_FOLDER / "assets",
    ]
    if ctx.urdf_mesh_dir is not None:
        folders.append(ctx.urdf_mesh_dir)
    from mjcfbuild.engine.written import recorded

    for name in recorded(ctx) or []:  # and those earlier builds wrote into (report/tuning, ...)
        parts = name.split("/")[:-1]
        folders += [out.joinpath(*parts[:depth]) for depth in range(1, len(parts) + 1)]
    return list(dict.fromkeys(folders))


def check_outputs_are_not_inputs(ctx: BuildContext, tasks: list[dict]) -> None:
    """Raise :class:`ManifestError` when the build would write a file it reads: a file some task
    depends on (the source, a file it includes, a mesh, an inputs file, the SRDF, a motor
    file, ...) that another task writes without coming before it, that the manifest names as
    an output, or that lies in a folder the build fills (``assets/``, ``report/``, the package,
    the exported URDF's meshes). The error names the manifest field that chose the output."""
    from mjcfbuild.engine.written import recorded

    resolved: dict[str, Path] = {}  # a task's dependencies are often another's: once each

    def real(path: str | os.PathLike) -> Path:
        key = os.fspath(path)
        found = resolved.get(key)
        if found is None:
            found = resolved[key] = real_path(key)
        return found

    outputs = _output_fields(ctx)
    named = {real(path): field for path, (field, folder) in outputs.items() if not folder}
    folders = [(real(path), field) for path, (field, folder) in outputs.items() if folder]
    writer = {real(target): task["name"] for task in tasks for target in task["targets"]}
    before = _upstream(tasks, writer, real)
    # What builds wrote in the folders they fill (previews, ...) is theirs, not an input.
    built = {real(ctx.out_dir / name) for name in recorded(ctx) or {}}
    state = real(ctx.state_dir)
    for task in tasks:
        for dependency in sorted(task["file_dep"]):
            path = real(dependency)
            if state in path.parents or path in built:
                continue
            if path in writer:
                maker = writer[path]
                if maker in before[task["name"]] and task["name"] not in before[maker]:
                    continue  # made by a task that runs first: a product, not an input
                field = named.get(path, "output.folder")
            elif path in named:
                field = named[path]
            else:
                filled = [(f, d) for d, f in folders if d in path.parents and path.exists()]
                if filled:
                    field, folder = filled[0]
                    _refuse(ctx, field, Path(dependency), task["name"], folder)
                continue
            _refuse(ctx, field, Path(dependency), task["name"])


def _upstream(
    tasks: list[dict], writer: dict[Path, str], real: Callable[[str], Path]
) -> dict[str, set[str]]:
    """Each task's name -> the tasks that come before it (whose targets it reads, or that it
    names in ``task_dep``), transitively; ``real`` resolves a path."""
    direct: dict[str, set[str]] = {}
    for task in tasks:
        found = direct.setdefault(task["name"], set())
        found.update(writer[p] for p in map(real, task["file_dep"]) if p in writer)
        found.update(task.get("task_dep", []))
        found.discard(task["name"])
    closed: dict[str, set[str]] = {}
    for name in direct:
        seen: set[str] = set()
        stack = list(direct[name])
        while stack:
            other = stack.pop()
            if other not in seen:
                seen.add(other)
                stack.extend(direct.get(other, ()))
        closed[name] = seen
    return closed


def real_path(path: str | os.PathLike) -> Path:
    """``path`` with every link resolved."""
    return Path(os.path.realpath(path))


def _output_fields(ctx: BuildContext) -> dict[Path, tuple[str, bool]]:
    """The paths the manifest makes the build write, each with the field that chose it and
    whether it is a folder the build fills."""
    from mjcfbuild.outputs import PACKAGE_FOLDER, report_dir

    output = ctx.manifest.output
    fields: dict[Path, tuple[str, bool]] = {
        ctx.state_dir: ("output.folder", True),
        ctx.assets_dir: ("output.folder", True),
        report_dir(ctx): ("output.folder", True),
        ctx.robot_path: ("output.robot" if output.robot else "name", False),
        ctx.scene_path: ("output.scene", False),
    }
    if output.package:
        fields[ctx.out_dir / PACKAGE_FOLDER] = ("output.package", True)
    if ctx.urdf_path is not None and ctx.urdf_mesh_dir is not None:
        fields[ctx.urdf_path] = ("output.urdf", False)
        fields[ctx.urdf_mesh_dir] = ("output.urdf", True)
    training = ctx.manifest.training_files
    if training is not None:
        fields[ctx.out_dir / training[0]] = ("output.training.file", False)
        fields[ctx.out_dir / training[1]] = ("output.training.scene", False)
    return fields


def _refuse(
    ctx: BuildContext, field: str, path: Path, task: str, folder: Path | None = None
) -> None:
    from mjcfbuild.errors import ManifestError
    from mjcfbuild.manifest.pinpoint import pinpoint

    step = task.split(":", 1)[0]
    what = _named_inputs(ctx).get(real_path(path)) or next(
        (words for kind, words in _INPUT_KINDS.items() if step.endswith(kind)),
        f"an input of its {step} step",
    )
    error = ManifestError(
        (
            f"would write {ctx.label(path)}, which the build reads ({what}); "
            "the build would overwrite its own input"
            if folder is None
            else f"would write into {ctx.label(folder)}/, which holds {ctx.label(path)}, a file "
            f"the build reads ({what}); the build would overwrite or remove its own inputs"
        ),
        file=f"{ctx.manifest_label} {field}",
        hint="choose another file name or output folder",
    )
    if ctx.manifest_file is not None:
        pinpoint(error, ctx.manifest_label, ctx.manifest_file)
    raise error


def _named_inputs(ctx: BuildContext) -> dict[Path, str]:
    """The inputs robot.yaml names by a field of their own, with what they are."""
    manifest = ctx.manifest
    named = {real_path(ctx.resolve(name)): f"motor file {name}" for name in manifest.motors.files}
    if manifest.mujoco_inputs.file:
        named[real_path(ctx.resolve(manifest.mujoco_inputs.file))] = "the mujoco_inputs file"
    if manifest.scene.file:
        named[real_path(ctx.resolve(manifest.scene.file))] = "the scene file"
    return named


# What a task's dependencies are, by its step (the end of its name before any ":").
_INPUT_KINDS = {
    "expand": "the source or a file it includes",
    "mesh": "a mesh or a file it references",
    "srdf": "the SRDF",
    "compose": "an attach: part",
    "part": "an attach: part or one of its files",
}


OWNER = "owner.json"
# What a state folder holds that says no build wrote here: the lock, which robot.yaml owns
# it, and what clean kept (its record and the .gitignore beside it).
_NO_STATE = ("lock", OWNER, FOREIGN, ".gitignore")


def claim_output_folder(ctx: BuildContext) -> None:
    """Record that the output folder is ``ctx``'s manifest's (``.mjcfbuild/owner.json``: the
    manifest's path relative to the folder, and the folder's relative to the manifest's),
    after :func:`check_owner`, and which files in it are the user's
    (:mod:`mjcfbuild.ownership`), which no step writes over. Called with the folder's lock
    held."""
    import json

    from mjcfbuild.fsutil import write_if_changed
    from mjcfbuild.ownership import record_foreign

    mine = check_owner(ctx)
    if mine is not None:
        assert ctx.manifest_file is not None, "a name to record only for robot.yaml's folder"
        # Where robot.yaml put the folder, too: a copy or a move of it (a snapshot) is not
        # an output folder robot.yaml left (mjcfbuild.engine.earlier_folders).
        placed = os.path.relpath(ctx.out_dir, ctx.manifest_file.parent)
        record = {"manifest": mine, "folder": Path(placed).as_posix()}
        write_if_changed(ctx.state(OWNER), (json.dumps(record) + "\n").encode())
    found, edited, git_problem = _users_files(ctx)
    record_foreign(ctx.out_dir, found, edited, git_problem)


def _users_files(ctx: BuildContext) -> tuple[list[str], list[str], str]:
    """The files in the output folder where builds write (the folder itself, ``assets/``,
    ``report/``, ...) that are the user's: those no build recorded writing, and the outputs
    edited since a build wrote them (the record's hash differs) whose edit git has no commit
    of (a checkout or a pull is safe to write over, and so is a merge conflict, which a
    rebuild resolves; a staged edit is not: the commit hook would leave it only in the
    index). None known
    where there is no record but a build's outputs are there: a folder an mjcfbuild from
    before the record built (its state is there), or a fresh clone of a repository that
    commits its models (no state; the model carries mjcfbuild's header), whose files the
    build keeps current; what ``clean`` kept as edited stays the user's there."""
    from mjcfbuild.engine.written import recorded, written_file
    from mjcfbuild.ownership import recorded_foreign

    names = recorded(ctx)
    before = recorded_foreign(ctx.out_dir)
    if names is None and (
        any(entry.name not in _NO_STATE for entry in ctx.state_dir.iterdir())
        or _built_model(ctx.robot_path)
    ):
        found = sorted(name for name in before.files if written_file(ctx.out_dir, name))
        # No record of what the build wrote (a fresh clone, the state folder removed): an
        # output whose bytes are not HEAD's is an edit all the same, and so is one whose bytes
        # are not those the last build here wrote, as its no-op stamp (outside the folder)
        # remembers them: a model git ignores, edited, then the state folder removed.
        edits = sorted({*_modified_in_git(ctx), *_edited_outputs(ctx, _stamped_outputs(ctx))})
    else:
        found = []
        for folder in [ctx.out_dir, *build_folders(ctx)]:
            if folder == ctx.state_dir or not folder.is_dir() or folder.is_symlink():
                continue
            for entry in folder.iterdir():
                name = entry.relative_to(ctx.out_dir).as_posix()
                if name not in (names or {}) and written_file(ctx.out_dir, name):
                    found.append(name)
        edits = _edited_outputs(ctx, names or {})
    # An edit recorded before (clean kept it; a build stopped at it) is still one.
    edits += [name for name in found if name in before.edited]
    kept, problem = _not_in_git(ctx, edits)
    from mjcfbuild.engine.published import has_conflict_markers

    for name in edits:
        if name not in kept:
            with contextlib.suppress(OSError):  # gone: writing it says what is wrong
                ctx.session.committed_edits[name] = ctx.session.hashes.md5(ctx.out_dir / name)
                if has_conflict_markers(str(ctx.out_dir / name)):
                    ctx.session.conflicts.add(name)
    return [name for name in found if name not in before.edited], kept, problem


def _modified_in_git(ctx: BuildContext) -> list[str]:
    """The files in the output folder, outside its state folder, that git tracks and whose
    bytes are not HEAD's (names relative to it, posix)."""
    from mjcfbuild.engine.published import git_modified
    from mjcfbuild.engine.written import written_file

    out = os.path.normpath(ctx.out_dir)
    names = (Path(os.path.relpath(path, out)).as_posix() for path in git_modified(out))
    state = ctx.state_dir.name + "/"
    return sorted(n for n in names if not n.startswith(state) and written_file(ctx.out_dir, n))


def _stamped_outputs(ctx: BuildContext) -> dict[str, str | None]:
    """The files the last successful build of robot.yaml wrote in the output folder (names
    relative to it, posix), each with the MD5 its no-op stamp recorded; empty without one.
    Every build discards both kinds of stamp when it starts, so the one left is the last
    build's. The report is left out: ``check`` rewrites it without a stamp of its own."""
    from mjcfbuild.engine import stamp
    from mjcfbuild.outputs import report_dir

    if ctx.manifest_file is None or ctx.output_override is not None:
        return {}
    recorded = stamp.recorded(ctx.manifest_file, ctx.run_check) or stamp.recorded(
        ctx.manifest_file, not ctx.run_check
    )
    if recorded is None:
        return {}
    out = os.path.normpath(ctx.out_dir)
    report = Path(os.path.relpath(report_dir(ctx), out)).as_posix() + "/"
    found: dict[str, str | None] = {}
    for path in recorded.written:
        name = Path(os.path.relpath(path, out)).as_posix()
        entry = recorded.files.get(path)
        if name.startswith(("../", ctx.state_dir.name + "/", report)):
            continue
        if isinstance(entry, list):
            found[name] = entry[1] if len(entry) > 1 and isinstance(entry[1], str) else None
    return found


def _edited_outputs(ctx: BuildContext, names: dict[str, str | None]) -> list[str]:
    """The recorded outputs whose bytes are no longer those the build recorded writing (the
    package's changelog aside: builds extend it around the user's notes; and the preview
    pictures, which are drawn again whatever they hold)."""
    from mjcfbuild.engine.written import settled_by_journal, written_file
    from mjcfbuild.outputs import PACKAGE_CHANGELOG, PACKAGE_FOLDER, report_dir

    changelog = f"{PACKAGE_FOLDER}/{PACKAGE_CHANGELOG}"
    # Bytes a step journaled writing are the build's (it failed, or was killed, before it
    # recorded them).
    skipped = {changelog, *settled_by_journal(ctx)}
    previews = Path(os.path.relpath(report_dir(ctx) / "previews", ctx.out_dir)).as_posix() + "/"
    edited = []
    for name, digest in names.items():
        if digest is None or name in skipped or name.startswith(previews):
            continue
        if not written_file(ctx.out_dir, name):
            continue
        try:
            if ctx.session.hashes.md5(ctx.out_dir / name) != digest:
                edited.append(name)
        except OSError:
            continue  # unreadable: writing it says what is wrong
    return edited


def _not_in_git(ctx: BuildContext, names: list[str]) -> tuple[list[str], str]:
    """Those of ``names`` (in the output folder) whose bytes git does not hold in a commit,
    and why git could not be asked ('' where it could): then none is taken as held."""
    if not names:
        return [], ""
    from mjcfbuild.engine.published import GitUnavailable, git_holds

    try:
        held = git_holds([str(ctx.out_dir / name) for name in names])
    except GitUnavailable as unavailable:
        return names, str(unavailable)
    return [name for name in names if os.path.normpath(ctx.out_dir / name) not in held], ""


def _built_model(path: Path) -> bool:
    """Whether ``path`` is a model a build wrote (it starts with the build's header)."""
    from mjcfbuild.outputs import MODEL_HEADER

    start = f"<!-- {MODEL_HEADER} ".encode()
    try:
        with open(path, "rb") as file:
            return file.read(len(start)) == start
    except OSError:
        return False


def check_owner(ctx: BuildContext) -> str | None:
    """Refuse (at robot.yaml's output.folder line) an output folder another robot.yaml that
    still names it built another robot's model in: two manifests in one folder deleted each
    other's assets and rewrote each other's scene, report and state, and each model then
    failed to load (``clean`` of one removed the other's). A manifest that was renamed,
    removed, no longer reads or points elsewhere gives the folder up. The name to record for
    ``ctx``'s manifest (None where the folder is named by a caller, not robot.yaml)."""
    import json

    if not named_by_manifest(ctx):
        return None
    assert ctx.manifest_file is not None, "guarded only with a manifest file"
    mine = os.path.relpath(ctx.manifest_file, ctx.out_dir)
    try:
        owner = json.loads(ctx.state(OWNER).read_text(encoding="utf-8")).get("manifest")
    except (OSError, ValueError, AttributeError):
        return mine
    if not isinstance(owner, str) or owner == mine or not _still_builds_here(ctx, owner):
        return mine
    from mjcfbuild.errors import ManifestError
    from mjcfbuild.manifest.pinpoint import pinpoint

    other = ctx.label(os.path.normpath(ctx.out_dir / owner))
    error = ManifestError(
        f"'{ctx.manifest.output.folder}' is the output folder of {other}, which built there; "
        "two robot.yaml files cannot share one (each would delete the other's assets and "
        "rewrite its scene and report)",
        file=f"{ctx.manifest_label} output.folder",
        hint=f"give this one an output.folder of its own, or remove {other} and its model "
        "from the folder",
    )
    raise pinpoint(error, ctx.manifest_label, ctx.manifest_file)


def _still_builds_here(ctx: BuildContext, owner: str) -> bool:
    """Whether the manifest at ``owner`` (relative to the output folder) exists, reads, names
    this output folder, and another robot's model in it."""
    from mjcfbuild.errors import MjcfbuildError
    from mjcfbuild.graph.context import GraphContext

    path = Path(os.path.normpath(ctx.out_dir / owner))
    if not path.is_file():
        return False
    try:
        other = GraphContext.from_manifest_file(path)
    except MjcfbuildError:
        return False  # a manifest that does not read claims nothing
    if os.path.realpath(other.out_dir) != os.path.realpath(ctx.out_dir):
        return False
    # One robot's model from two manifests (another source, other settings): each build
    # replaces the same files whole, as a rebuild with other settings does.
    return other.manifest.robot_file != ctx.manifest.robot_file
