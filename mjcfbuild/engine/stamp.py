"""The no-op fast path: decide "nothing changed" from a stamp, before importing the engine.

A successful build writes a *stamp*: every file the build read (the manifest,
each task's file dependencies, what xacro and mesh steps discovered), every file it wrote
(targets, products, assets, report, its own state), the files it looked for and did not find,
the environment variables that can change a build, the folders Python imports packages from
(their mtime moves when a package is installed or upgraded) and mjcfbuild's own source files.
Each file is recorded with its signature (:mod:`mjcfbuild.filesig`: size, mtime and ctime
to the nanosecond, inode, device) and MD5. The stamp also keeps the warnings of the tasks that
made the outputs (the state folder's ``warnings.json``), which the fast path prints as the
build did, and whether the output folder is outside the manifest's tree by ``--allow-outside``
alone: a later run without the flag is refused by the full build's guard, never "up to date".

The next ``mjcfbuild build`` of the same manifest checks the stamp first, importing nothing
but the standard library. A file whose signature is unchanged is unchanged; one whose size
changed has changed; any other difference - a ``touch``, a fresh checkout, a ``cp -p`` or
``tar`` that restored the mtime - has the file hashed, and if its bytes are the same the
stamp is updated so it is not hashed again. Anything else - a changed byte, a file gone or
appeared, a variable or package changed, no stamp - falls through to the full build, which
decides what to run. A full build removes the stamp before it starts, so an interrupted or
failed build never leaves one behind.

A file changed within the file system's timestamp tick before the stamp (``racy``,
:func:`mjcfbuild.filesig.racy`: 0.1 s, or 2 s where times are coarse) is always hashed: a
later edit in the same timestamp tick would otherwise keep its signature.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
import time
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, NamedTuple

from mjcfbuild import filesig

if TYPE_CHECKING:
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.graph.hashes import HashCache

# 4: warnings to replay, and whether the folder needed --allow-outside; 5: which files the
# build wrote (mjcfbuild watch); 6: the file-name patterns xacro includes listed
FORMAT = 6
# Set to any value to skip the fast path (benchmarks of the full path, debugging).
DISABLE_VARIABLE = "MJCFBUILD_FULL_BUILD"
# Variables read by the build besides those a depfile records; every MJCFBUILD_* counts too.
_VARIABLES = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH", "XDG_CACHE_HOME", "HOME")
# In the state folder: bookkeeping no step reads (the lock, workers' logs, the database of a
# user's doit, which doit writes after the build it ran).
STATE_NOT_CHECKED = ("lock", "logs", "dodo")


def stamp_path(manifest: Path | str, run_check: bool) -> Path:
    """Where the stamp of a build of ``manifest`` (with or without its check) is kept.

    ``manifest`` is the manifest file, or for a build without one (``convert``) the key that
    :func:`command_key` makes of its command line."""
    from mjcfbuild.cachedir import user_cache_dir

    key = hashlib.sha256(f"{manifest}\0{run_check}".encode()).hexdigest()[:32]
    return user_cache_dir() / "noop" / f"{key}.json"


def _environment() -> dict[str, str | None]:
    names = set(_VARIABLES) | {n for n in os.environ if n.startswith("MJCFBUILD_")}
    names.discard(DISABLE_VARIABLE)
    return {name: os.environ.get(name) for name in sorted(names)}


def _same_environment(recorded: dict[str, str | None]) -> bool:
    if any(name not in recorded for name in _environment()):
        return False  # an MJCFBUILD_* variable was set since
    return all(os.environ.get(name) == value for name, value in recorded.items())


def _package_index() -> str:
    """What ROS_PACKAGE_PATH and AMENT_PREFIX_PATH provide now (``environment_index``; empty,
    and no folder read, where neither is set)."""
    from mjcfbuild.sources.packages import environment_index

    return environment_index(os.environ)


def _python_folders() -> dict[str, int | None]:
    """The mtimes of the folders packages are installed in: the standard library's, every
    site-packages and the PYTHONPATH entries. Not the folder of the script that runs (the
    ``mjcfbuild`` command's, doit's dodo.py's) nor the current one, so that ``mjcfbuild``,
    ``python -m mjcfbuild`` and doit agree on one stamp."""
    folders: dict[str, int | None] = {}
    explicit = set(filter(None, os.environ.get("PYTHONPATH", "").split(os.pathsep)))
    prefixes = tuple(os.path.join(p, "lib") for p in {sys.prefix, sys.base_prefix})
    for entry in sys.path:
        installed = os.path.basename(entry) in ("site-packages", "dist-packages")
        chosen = entry in explicit or installed or entry.startswith(prefixes)
        if chosen and os.path.isdir(entry):
            folders[entry] = os.stat(entry).st_mtime_ns
    return folders


def _interpreter() -> str:
    """Which Python runs: its environment and its real executable (``python`` and
    ``python3`` in one environment, the ``mjcfbuild`` script's and ``python -m``'s, agree)."""
    return f"{sys.prefix}|{os.path.realpath(sys.executable)}"


def _md5(path: str) -> str:
    digest = hashlib.md5(usedforsecurity=False)
    with open(path, "rb") as handle:
        while chunk := handle.read(1 << 20):
            digest.update(chunk)
    return digest.hexdigest()


def _record(stat: os.stat_result, digest: str, now_ns: int) -> list:
    """``[signature, digest, racy]`` of a file whose ``stat`` is taken at ``now_ns``."""
    return [filesig.signature(stat), digest, filesig.racy(stat, now_ns)]


def command_key(command: str, cwd: str, options: dict) -> str:
    """The stamp key of a build described by a command line rather than a manifest file:
    the command, the folder it ran in and its options (only those that change the build)."""
    return f"{command}\0{cwd}\0{json.dumps(options, sort_keys=True)}"


def nothing_to_do(
    manifest: str | os.PathLike, run_check: bool, allow_outside: bool = False
) -> dict | None:
    """The stamp's summary if nothing changed since the last successful build, else None.

    ``{"robot": <model file name>, "tasks": <tasks of that build>, "warnings": <to print>,
    "report": <report.md, which lists them all>, "check_results": <check.json, or None where
    the build did not check>, ...}``. ``allow_outside``: whether this run
    passes ``--allow-outside``; without it, the stamp of a build whose output folder needed
    it is not used (the full build's guard refuses the folder). Never raises: any problem
    reading the stamp means the full build decides.
    """
    key = Path(os.path.normpath(os.path.abspath(manifest)))
    return nothing_to_do_for(key, run_check, allow_outside)


def nothing_to_do_for(key: Path | str, run_check: bool, allow_outside: bool = False) -> dict | None:
    """:func:`nothing_to_do` for the build whose stamp key is ``key`` (a normalised manifest
    path, or a :func:`command_key`)."""
    if os.environ.get(DISABLE_VARIABLE):
        return None
    path = stamp_path(key, run_check)
    stamp = _read(path)
    if stamp is None:
        return None
    try:
        if stamp["outside"] and not allow_outside:
            return None
        started = time.time_ns()
        if not _same_environment(stamp["environment"]):
            return None
        if stamp["python_folders"] != _python_folders():
            return None
        if stamp.get("package_index", "") != _package_index():
            return None  # a ROS package came to shadow another (or went)
        if any(os.path.lexists(name) for name in stamp["absent"]):
            return None
        if stamp["globs"]:
            from mjcfbuild.steps.depfile import globs_changed

            if globs_changed(stamp["globs"]):
                return None
        refreshed = _verify_files(stamp["files"], started)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
    if refreshed is None:
        return None
    if refreshed:
        stamp["files"].update(refreshed)
        _write(path, stamp)
    return stamp["summary"]


def previous_build(manifest: str | os.PathLike, run_check: bool) -> dict | None:
    """What the last successful build of ``manifest`` recorded for the next one's workers
    (its workers' ``logs`` folder, its ``assembly_report``, whether it ``checks``), whether
    or not anything changed since, with ``meshes_moved``: whether a mesh file it read has
    another size or time now (touched or edited). None without a readable stamp. A
    prediction only: never raises."""
    stamp = _read(stamp_path(Path(os.path.normpath(os.path.abspath(manifest))), run_check))
    if stamp is None or not isinstance(stamp.get("next_build"), dict):
        return None
    return {**stamp["next_build"], "meshes_moved": _meshes_moved(stamp.get("files"))}


class Recorded(NamedTuple):
    """What a stamp says the last successful build depends on."""

    files: dict[str, list]  # name -> [signature, MD5, racy]: every file it read or wrote
    written: list[str]  # those of them it wrote
    absent: list[str]  # files it looked for and did not find
    python_folders: dict[str, int | None]  # where packages are imported from -> mtime
    globs: dict[str, list[str]]  # file-name patterns it listed -> the files each matched


def recorded(manifest: str | os.PathLike, run_check: bool) -> Recorded | None:
    """The files and folders the last successful build of ``manifest`` depends on, as its
    stamp records them; None without a readable stamp."""
    stamp = _read(stamp_path(Path(os.path.normpath(os.path.abspath(manifest))), run_check))
    if stamp is None:
        return None
    try:
        return Recorded(
            dict(stamp["files"]),
            list(stamp["written"]),
            list(stamp["absent"]),
            dict(stamp["python_folders"]),
            dict(stamp.get("globs", {})),
        )
    except (KeyError, TypeError, ValueError):
        return None


def _meshes_moved(files: object) -> bool:
    from mjcfbuild.meshes.formats import mesh_format

    if not isinstance(files, dict):
        return True
    for name, record in files.items():
        if not mesh_format(name):
            continue
        try:
            if filesig.signature(os.stat(name)) != record[0]:
                return True
        except (OSError, TypeError):
            return True
    return False


def _read(path: Path) -> dict | None:
    """The stamp at ``path`` if it is one this mjcfbuild and this Python wrote, else None."""
    try:
        stamp = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(stamp, dict):
        return None
    if stamp.get("format") != FORMAT or stamp.get("python") != _interpreter():
        return None
    return stamp


def _verify_files(files: dict[str, list], now_ns: int) -> dict[str, list] | None:
    """None if a file changed; else the records of files whose signature moved or were racy."""
    refreshed = {}
    for name, (recorded, digest, racy) in files.items():
        stat = os.stat(name)  # FileNotFoundError: a file is gone, the caller falls through
        now = filesig.signature(stat)
        if now[0] != recorded[0]:
            return None  # another size: changed, no need to read it
        if now == recorded and not racy:
            continue
        if _md5(name) != digest:
            return None
        refreshed[name] = _record(stat, digest, now_ns)
    return refreshed


def _write(path: Path, stamp: dict) -> None:
    temp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        temp.write_text(json.dumps(stamp, separators=(",", ":")))
        os.replace(temp, path)
    except OSError:
        # Without a stamp the next build takes the full path: slower, never wrong. A full
        # cache keeps no half-written one.
        with contextlib.suppress(OSError):
            temp.unlink(missing_ok=True)


def discard(manifest: Path | str, run_check: bool) -> None:
    """Remove the stamp: called when a build starts, so only a finished one leaves a stamp."""
    with contextlib.suppress(OSError):
        stamp_path(manifest, run_check).unlink()


def write(
    manifest: Path | str,
    run_check: bool,
    summary: dict,
    inputs: Iterable[Path | str],
    outputs: Iterable[Path | str],
    absent: Iterable[str],
    variables: Iterable[str],
    hashes: HashCache,
    next_build: dict | None = None,
    outside: bool = False,
    started_ns: int | None = None,
    globs: dict[str, list[str]] | None = None,
) -> None:
    """Record the state a successful build left, for :func:`nothing_to_do`.

    ``hashes`` is the build's :class:`~mjcfbuild.graph.hashes.HashCache`, so files hashed by
    the build are not read again; ``next_build`` is kept for :func:`previous_build`;
    ``outside``: the output folder may be written only with ``--allow-outside``; ``globs``:
    the file-name patterns xacro listed, with their files (another match means a change). No
    stamp is written when an input the build did not write itself changed after ``started_ns``, when
    the build began reading: a step may have read it before the change, and the stamp would
    then call the older model current (the next build takes the full path, which knows).
    """
    now = time.time_ns()
    inputs, outputs = list(inputs), list(outputs)
    if started_ns is not None and _changed_during(inputs, outputs, started_ns):
        return
    files: dict[str, list] = {}
    for name in sorted({os.fspath(p) for p in [*inputs, *outputs]}):
        try:
            stat = os.stat(name)
            if not os.path.isfile(name):
                continue
            files[name] = _record(stat, hashes.md5(name, stat), now)
        except OSError:
            continue  # a file the build names but never made: the full path decides again
    environment = _environment()
    for name in variables:
        environment.setdefault(name, os.environ.get(name))
    stamp = {
        "format": FORMAT,
        "python": _interpreter(),
        "summary": summary,
        "environment": environment,
        "python_folders": _python_folders(),
        "package_index": _package_index(),
        "absent": sorted(set(absent)),
        "globs": dict(sorted((globs or {}).items())),
        "files": files,
        "written": sorted({os.fspath(p) for p in outputs} & set(files)),
        "next_build": next_build,
        "outside": outside,
    }
    _write(stamp_path(manifest, run_check), stamp)


def _changed_during(
    inputs: Iterable[Path | str], outputs: Iterable[Path | str], started_ns: int
) -> bool:
    """Whether one of ``inputs`` that is not one of ``outputs`` changed after ``started_ns``,
    or is gone (the build read it: it went while the build ran, and a stamp without it would
    never look at it again)."""
    written = {os.fspath(p) for p in outputs}
    for name in {os.fspath(p) for p in inputs} - written:
        try:
            if filesig.changed_since(os.stat(name), started_ns):
                return True
        except OSError:
            return True
    return False


def files_under(folder: Path, skip: Iterable[str] = ()) -> list[Path]:
    """Every file below ``folder`` except the top-level entries named in ``skip``."""
    if not folder.is_dir():
        return []
    found = []
    for entry in sorted(folder.iterdir()):
        if entry.name in skip:
            continue
        if entry.is_dir():
            found += [p for p in sorted(entry.rglob("*")) if p.is_file()]
        elif entry.is_file():
            found.append(entry)
    return found


def mjcfbuild_sources() -> list[Path]:
    """mjcfbuild's own Python files and data (the motor catalogue): a changed step, model or
    catalogue falls through to the full path."""
    package = Path(__file__).resolve().parents[1]
    return sorted([*package.rglob("*.py"), *package.rglob("*.yaml")])


def record_build(
    ctx: BuildContext, tasks: list[dict], task_count: int, warnings: list[str]
) -> None:
    """Write the stamp of the successful build of ``ctx`` that ran ``tasks``; ``warnings``
    are those of the tasks that made its outputs, for the fast path to print."""
    from mjcfbuild.outputs import ASSEMBLY_REPORT
    from mjcfbuild.steps.depfile import Depfile

    manifest = ctx.stamp_key
    assert manifest is not None, "a stamp is kept only for a build with a stamp key"
    inputs: list[Path | str] = [*mjcfbuild_sources()]
    if ctx.manifest_file is not None:
        inputs.append(ctx.manifest_file)
    outputs: list[Path | str] = [ctx.robot_path, ctx.scene_path]
    absent: list[str] = []
    variables: list[str] = []
    globs: dict[str, list[str]] = {}
    for task in tasks:
        inputs += task["file_dep"]
        outputs += task["targets"]
        absent += (task.get("meta") or {}).get("absent", [])  # looked for when planned
    # Every depfile a task of this plan keeps: the source's, the SRDF's, the check's, the
    # attach: parts' and the meshes'. A task's file_dep above is what it declared before it
    # ran, without what it discovered then. One a task no longer in the plan left (robot.yaml
    # no longer names the SRDF) is not read: its files are no longer inputs.
    for depfile in filter(None, (Depfile.read(path) for path in task_depfiles(tasks))):
        inputs += depfile.files
        absent += depfile.missing
        variables += list(depfile.environment)
        globs.update(depfile.globs)
    from mjcfbuild.families.srdf import srdf_searches

    # Where the plan looked for an SRDF beside the description: one added later is an edit.
    globs.update(srdf_searches(ctx))
    outputs += files_under(ctx.state_dir, skip=STATE_NOT_CHECKED)
    for folder in (ctx.assets_dir, ctx.out_dir / "report", ctx.urdf_mesh_dir):
        if folder is not None:
            outputs += files_under(folder)
    if ctx.urdf_path is not None:
        outputs.append(ctx.urdf_path)
    from mjcfbuild.engine.published import published_files
    from mjcfbuild.outputs import CHECK_RESULTS, report_dir

    summary = {
        "robot": ctx.robot_path.name,
        "tasks": task_count,
        "outputs": [str(path) for path in published_files(ctx)],  # for --fail-on-change
        "warnings": warnings,
        "report": str(report_dir(ctx) / "report.md"),
        # The check's results, whose verdict the fast path prints (None: not checked).
        "check_results": str(ctx.state(CHECK_RESULTS)) if ctx.run_check else None,
    }
    write(
        manifest,
        ctx.run_check,
        summary,
        inputs,
        outputs,
        absent,
        variables,
        ctx.session.hashes,
        {
            "logs": str(ctx.logs_dir),
            "assembly_report": str(ctx.state(ASSEMBLY_REPORT)),
            "checks": ctx.session.checks,
        },
        _needs_allow_outside(ctx),
        ctx.started_ns,
        globs=globs,
    )


def task_depfiles(tasks: list[dict]) -> list[Path]:
    """The depfiles the steps of ``tasks`` write (the ``depfile`` of each one's payload)."""
    from mjcfbuild.graph.family import task_payload

    payloads = filter(None, (task_payload(task) for task in tasks))
    return sorted({Path(payload["depfile"]) for payload in payloads if payload.get("depfile")})


def _needs_allow_outside(ctx: BuildContext) -> bool:
    """Whether the output folder of ``ctx`` is one the guard allows only because the command
    line said ``--allow-outside``."""
    from dataclasses import replace

    from mjcfbuild.engine.guard import check_output_folder
    from mjcfbuild.errors import OutputError

    if not ctx.allow_outside:
        return False
    try:
        check_output_folder(replace(ctx, allow_outside=False))
    except OutputError:
        return True
    return False
