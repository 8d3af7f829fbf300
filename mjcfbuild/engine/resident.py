"""Resident workers: worker processes that stay after the build that started them.

Every build used to start its workers afresh, and each spent 0.3-0.4 s of CPU importing
MuJoCo and the steps, then had MuJoCo process every mesh of the model again (panda: 0.2 s,
go1: 0.5 s) before the first step that compiles it could finish. A worker that stays has all
of that in memory, and the next build of the same robot, typically seconds or minutes later in
an edit-and-rebuild loop, starts at its first step.

A resident worker waits on a Unix socket in a private folder (mode 0700) for the next build,
up to ``MJCFBUILD_RESIDENT_WORKERS`` seconds (default 900; ``0`` turns resident workers off,
and so does a set ``CI`` variable: a CI job builds once). A build claims it by connecting and
sending its environment and folder; the worker closes its socket while it serves that build,
so no second build can claim it, and listens again when the build lets go. Workers are found
by a *key*: the interpreter, the code of mjcfbuild and the installed packages, and the
environment variables read only when a process starts (``MUJOCO_GL``, ``PYTHONHASHSEED``,
library paths...). A build whose key differs never sees them, so code or packages that changed
start new workers; the old ones leave when their time runs out.

What makes a worker that outlived a build safe to reuse (mjcfbuild.engine.worker_main):
each build's environment and folder are set anew; MuJoCo's mesh cache, which tells files
apart by name and modification time in whole seconds, is emptied if the new build comes
within the same second the last one ended (a product rewritten in that second would look
unchanged); and a worker whose build goes away while it runs a step stops at once, as a
worker of its own would.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import stat
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import UsageError

if TYPE_CHECKING:  # imported where used: every build reads the variables, few start workers
    import socket

VARIABLE = "MJCFBUILD_RESIDENT_WORKERS"
DIR_VARIABLE = "MJCFBUILD_RESIDENT_DIR"
DEFAULT_SECONDS = 900.0
# A Unix socket's path is limited to 108 bytes; the folder keeps room for the file name.
_MAX_DIR_LENGTH = 80
# Variables a process reads only as it starts (the interpreter, the dynamic linker, MuJoCo's
# choice of OpenGL, Mesa, OpenMP, the locale, the temporary folder): a worker started with
# other values would not take new ones, so they are part of the key. Every other variable
# is set for each build.
_START_VARIABLES = (
    "PYTHON",
    "LD_",
    "MUJOCO_",
    "MESA",
    "GALLIUM",
    "LP_",
    "LIBGL",
    "EGL",
    "__EGL",
    "__GLX",
    "OMP_",
    "KMP_",
    "OPENBLAS",
    "MKL_",
    "LANG",
    "LC_",
    "TZ",
    "TMP",
    "TEMP",
)


def idle_seconds(environ: dict[str, str] | os._Environ[str]) -> float:
    """How long a resident worker waits for the next build; 0 when they are off."""
    value = environ.get(VARIABLE, "").strip()
    if not value:
        return 0.0 if environ.get("CI", "").lower() in ("1", "true", "yes") else DEFAULT_SECONDS
    try:
        seconds = float(value)
    except ValueError:
        seconds = -1.0
    if not 0 <= seconds < float("inf"):
        raise UsageError(
            f"{VARIABLE}={value}: not a number of seconds",
            hint="set it to how long workers wait for the next build, or 0 for no resident workers",
        )
    return seconds


def resident_dir(environ: dict[str, str] | os._Environ[str]) -> Path | None:
    """The private folder of this user's resident workers, made if needed; None if it cannot
    be made private (another user owns it, or others may write to it) or its path is too long
    for a socket."""
    folder = resident_dir_path(environ)
    if len(str(folder)) > _MAX_DIR_LENGTH:
        return None
    with contextlib.suppress(FileExistsError):
        folder.mkdir(mode=0o700, parents=True)
    try:
        info = folder.lstat()
    except OSError:
        return None
    private = info.st_uid == os.getuid() and not info.st_mode & 0o077
    return folder if stat.S_ISDIR(info.st_mode) and private else None


def resident_dir_path(environ: dict[str, str] | os._Environ[str]) -> Path:
    """Where resident workers wait (see :func:`resident_dir`), whether or not it can be used."""
    import tempfile

    explicit = environ.get(DIR_VARIABLE)
    if explicit:
        return Path(explicit)
    runtime = environ.get("XDG_RUNTIME_DIR")
    base = runtime if runtime and os.path.isdir(runtime) else tempfile.gettempdir()
    return Path(base) / f"mjcfbuild-{os.getuid()}"


def worker_key(environ: dict[str, str]) -> str:
    """What a resident worker must have been started with to serve a build whose workers
    would get ``environ``: a digest of the interpreter, mjcfbuild's code, the installed
    packages and the variables read at start."""
    digest = hashlib.sha256()
    package = Path(__file__).resolve().parents[1]
    parts = [sys.executable, sys.version, str(package)]
    parts += _code_fingerprint(package)
    here = os.getcwd()
    for entry in sys.path:  # installing or removing a package changes its folder's mtime
        if entry in ("", ".", here):
            continue  # the folder `python -m` runs in: any file made there would change it
        with contextlib.suppress(OSError):
            parts.append(f"{entry}@{os.stat(entry).st_mtime_ns}")
    parts += sorted(f"{k}={v}" for k, v in environ.items() if k.startswith(_START_VARIABLES))
    digest.update("\0".join(parts).encode("utf-8", "surrogateescape"))
    return digest.hexdigest()[:20]


def _code_fingerprint(package: Path) -> list[str]:
    found = []
    for folder, subfolders, files in os.walk(package):
        subfolders[:] = sorted(d for d in subfolders if d != "__pycache__")
        for name in sorted(files):
            if name.endswith(".py"):
                info = os.stat(os.path.join(folder, name))
                found.append(f"{folder}/{name}:{info.st_size}:{info.st_mtime_ns}")
    return found


@dataclass
class Resident:
    """A worker process this build holds: its connection, process id and what it holds."""

    connection: socket.socket
    pid: int
    holds: str | None  # the model whose meshes MuJoCo has processed there, if any


def claim(folder: Path, key: str, hello: dict) -> Resident | None:
    """An idle resident worker of ``key`` in ``folder``, now serving this build (``hello``
    tells it the build's environment, folder and what to preload); None if none is idle."""
    import socket

    for path in sorted(folder.glob(f"{key}-*.sock")):
        connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            connection.connect(str(path))
        except (ConnectionRefusedError, FileNotFoundError):
            connection.close()
            _remove_if_dead(path)
            continue
        except OSError:
            connection.close()
            continue
        reply = _handshake(connection, hello)
        if reply is not None:
            return Resident(connection, int(reply["pid"]), reply.get("holds"))
        connection.close()  # another build claimed it first
    return None


def spawn(folder: Path, key: str, hello: dict, env: dict[str, str]) -> Resident:
    """Start a resident worker of ``key`` serving this build first."""
    import socket

    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
    command = [sys.executable, "-m", "mjcfbuild.engine.worker_main", "--resident"]
    command += [str(theirs.fileno()), str(folder), key, repr(idle_seconds(env))]
    log = os.open(folder / "workers.log", os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o600)
    os.set_inheritable(theirs.fileno(), True)
    try:
        # Not subprocess: the worker outlives this build, and a Popen object would warn
        # when collected while it runs. Its own session: Ctrl-C in the terminal is for the
        # build. Its output is not the build's: a pipe reading the build must close with it.
        pid = os.posix_spawn(
            sys.executable,
            command,
            env,
            file_actions=[
                (os.POSIX_SPAWN_OPEN, 0, os.devnull, os.O_RDONLY, 0),
                (os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0),
                (os.POSIX_SPAWN_DUP2, log, 2),
            ],
            setsid=True,
        )
    finally:
        os.close(log)
        theirs.close()
    reply = _handshake(ours, hello)  # the hello sets its folder, as for a waiting worker
    if reply is None:
        ours.close()
        stop(pid)
        raise OSError("a new worker process did not answer")
    return Resident(ours, pid, None)


def _handshake(connection: socket.socket, hello: dict) -> dict | None:
    try:
        connection.sendall((json.dumps(hello) + "\n").encode())
    except OSError:
        return None
    return receive_line(connection)


def receive_line(connection: socket.socket) -> dict | None:
    """The next JSON line from ``connection`` (the first of a build's claim, or the reply to
    it); None if the other side closed or reset it first."""
    data = b""
    try:
        while not data.endswith(b"\n"):
            chunk = connection.recv(1 << 16)
            if not chunk:
                return None
            data += chunk
    except OSError:
        return None
    line: dict = json.loads(data)
    return line


def _remove_if_dead(path: Path) -> None:
    """A socket nobody listens on is left by a worker that was killed: remove it."""
    pid = _pid_of(path)
    if pid is not None and not _process_exists(pid):
        with contextlib.suppress(OSError):
            path.unlink()


def _pid_of(socket_file: Path) -> int | None:
    """The process id in a waiting worker's socket name (``<key>-<pid>.sock``)."""
    pid = socket_file.stem.rpartition("-")[2]
    return int(pid) if pid.isdigit() else None


def _process_exists(pid: int) -> bool:
    """Whether process ``pid`` runs: it exists and is not a zombie (an ended process whose
    parent has not reaped it, as a container's first process may never do)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()[0]
    except (OSError, IndexError):
        return True  # no /proc: as far as can be told, it runs
    return state != "Z"


# How the resident workers this process started and saw end ended (os.waitpid's status).
_ended: dict[int, int] = {}


def running(pid: int) -> bool:
    """Whether resident worker ``pid`` still runs. One this process started is its child
    until it ends, and then a zombie until reaped here."""
    if pid in _ended:
        return False
    try:
        done, status = os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:  # another build started it
        return _process_exists(pid)
    if done:
        _ended[pid] = status
        return False
    return True


def stop(pid: int) -> None:
    """Kill resident worker ``pid`` now (and reap it, if this process started it)."""
    import signal

    with contextlib.suppress(ProcessLookupError):
        os.kill(pid, signal.SIGKILL)
    if pid not in _ended:
        with contextlib.suppress(ChildProcessError):
            _ended[pid] = os.waitpid(pid, 0)[1]


def how_it_ended(pid: int) -> str:
    """How resident worker ``pid``, which no longer runs, ended, as far as this process saw."""
    import signal

    status = _ended.get(pid)
    if status is None:
        with contextlib.suppress(ChildProcessError):
            _, status = os.waitpid(pid, 0)
    if status is None:
        return "ended unexpectedly"
    if os.WIFSIGNALED(status):
        number = os.WTERMSIG(status)
        try:
            return f"crashed ({signal.Signals(number).name})"
        except ValueError:
            return f"was killed by signal {number}"
    return f"exited with code {os.waitstatus_to_exitcode(status)}"


def resident_pids(folder: Path, key: str | None = None) -> list[int]:
    """The process ids of the idle resident workers in ``folder`` (of ``key``, if given)."""
    pids = [_pid_of(path) for path in sorted(folder.glob(f"{key or '*'}-*.sock"))]
    return [pid for pid in pids if pid is not None and _process_exists(pid)]
