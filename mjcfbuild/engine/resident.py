"""Resident workers: worker processes that stay after the build that started them.

Every build used to start its workers afresh, and each spent 0.3-0.4 s of CPU importing
MuJoCo and the steps, then had MuJoCo process every mesh of the model again (panda: 0.2 s,
go1: 0.5 s) before the first step that compiles it could finish. A worker that stays has all
of that in memory, and the next build of the same robot, typically seconds or minutes later in
an edit-and-rebuild loop, starts at its first step.

A resident worker waits on a Unix socket in a private folder (mode 0700) for the next build,
up to ``MJCFBUILD_RESIDENT_WORKERS`` seconds (default 900 where a person builds at a terminal;
``0`` turns resident workers off; without the variable they are off in CI, in git hooks and
without a terminal: see :func:`why_off`). A build claims one by connecting and sending its
environment, folder and process state; the worker closes its socket while it serves that
build, so no second build can claim it, and listens again when the build lets go. Workers are
found by a *key*: the installation (interpreter and mjcfbuild's folder), its code version
(mjcfbuild's code and the installed packages) and the environment variables read only when a
process starts (``MUJOCO_GL``, ``PYTHONHASHSEED``, library paths...). A build whose key differs
never uses them; one of the same installation with newer code asks those of older code to exit.

Nothing here waits without a limit or signals a process it has not identified: a worker that
does not answer a claim within ``MJCFBUILD_WORKER_ANSWER_SECONDS`` (stopped, or in a debugger)
is killed once its command line shows it is that worker (:func:`is_worker`), its socket is
removed and the build goes on with another; a socket nobody listens on is removed, whatever
process its name's number now belongs to. One user has at most ``MJCFBUILD_RESIDENT_MAX``
waiting workers, of every key together: a worker that has just served a build takes the place
of the worker of another key that has waited longest (:func:`make_room`). A worker whose socket
file is removed (its folder deleted) exits within a second.

What makes a worker that outlived a build safe to reuse (mjcfbuild.engine.worker_main):
each build's environment, folder, file mode mask, nice level and resource limits are set
anew (a worker that cannot take them on leaves, and the build starts one that inherits them);
a worker whose imported modules changed on disk since (an editable install, a patched
package) leaves instead of serving; MuJoCo's mesh cache, which tells files apart by name and
modification time in whole seconds, is emptied if the new build comes within the same second
the last one ended, or if a mesh product it processed was replaced by another file with the
same whole-second time (a product linked from the shared cache keeps the time another build
made it at); and a worker whose build goes away while it runs a step stops at once, as a
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
from mjcfbuild.filesig import signature

if TYPE_CHECKING:  # imported where used: every build reads the variables, few start workers
    import socket

VARIABLE = "MJCFBUILD_RESIDENT_WORKERS"
DIR_VARIABLE = "MJCFBUILD_RESIDENT_DIR"
DEFAULT_SECONDS = 900.0
# Variables a process reads only as it starts (the interpreter, the dynamic linker, the C
# library's allocator, MuJoCo's choice of OpenGL, Mesa, OpenMP, the locale, the temporary
# folder): a worker started with other values would not take new ones, so they are part of
# the key. Every other variable is set for each build.
_START_VARIABLES = (
    "PYTHON",
    "LD_",
    "MALLOC_",
    "GLIBC_TUNABLES",
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


# Seconds a waiting worker has to answer a build that claims it (a new one gets three times
# as long, and at least SPAWN_SECONDS: it starts an interpreter first). A worker that does not
# answer in time is killed.
ANSWER_VARIABLE = "MJCFBUILD_WORKER_ANSWER_SECONDS"
DEFAULT_ANSWER_SECONDS = 10.0
SPAWN_SECONDS = 30.0
# How many resident workers one user may have waiting, of every code version and key together.
MAX_VARIABLE = "MJCFBUILD_RESIDENT_MAX"
# Variables continuous integration services set: a CI job builds once, and nobody waits at a
# terminal for the next build (CI_PIPELINE_ID: GitLab, Woodpecker; BUILD_BUILDID: Azure).
CI_VARIABLES = (
    "CI",
    "CONTINUOUS_INTEGRATION",
    "JENKINS_URL",
    "JENKINS_HOME",
    "HUDSON_URL",
    "TF_BUILD",
    "BUILD_BUILDID",
    "GITLAB_CI",
    "GITHUB_ACTIONS",
    "BUILDKITE",
    "CIRCLECI",
    "TRAVIS",
    "APPVEYOR",
    "WOODPECKER",
    "CI_PIPELINE_ID",
    "CI_PIPELINE_NUMBER",
    "DRONE",
    "TEAMCITY_VERSION",
    "BITBUCKET_BUILD_NUMBER",
    "CODEBUILD_BUILD_ID",
    "SEMAPHORE",
    "BUILDKITE_BUILD_ID",
    "CIRRUS_CI",
    "HEROKU_TEST_RUN_ID",
)
# Variables a git hook or the pre-commit framework runs with: a hook builds once and returns.
HOOK_VARIABLES = ("PRE_COMMIT", "GIT_INDEX_FILE")
# The longest path a Unix socket may have, without its final NUL (sockaddr_un's sun_path:
# 108 bytes on Linux, 104 on macOS and the BSDs).
_SUN_PATH = 107 if sys.platform.startswith("linux") else 103
# A socket's name in the folder: <key: 20 characters>-<pid: up to 7 digits>.sock
_NAME_LENGTH = 20 + 1 + 7 + len(".sock")


def _set(value: str | None) -> bool:
    return value is not None and value.strip().lower() not in ("", "0", "false", "no", "off")


def why_off(
    environ: dict[str, str] | os._Environ[str], interactive: bool | None = None
) -> str | None:
    """Why resident workers are off by default here (CI, a hook, no terminal), or None when
    they are on; an explicit ``MJCFBUILD_RESIDENT_WORKERS`` is not asked about here."""
    for name in CI_VARIABLES:
        if _set(environ.get(name)):
            return f"${name} is set (continuous integration)"
    for name in HOOK_VARIABLES:
        if environ.get(name):
            return f"${name} is set (a git hook)"
    if interactive is None:
        interactive = _interactive()
    if not interactive:
        return "no terminal waits for the next build"
    return None


def _interactive() -> bool:
    """Whether a person is at a terminal: standard input or error is one."""
    for fd in (0, 2):
        try:
            if os.isatty(fd):
                return True
        except OSError:
            continue
    return False


def idle_seconds(
    environ: dict[str, str] | os._Environ[str], interactive: bool | None = None
) -> float:
    """How long a resident worker waits for the next build; 0 when they are off. Unless
    ``MJCFBUILD_RESIDENT_WORKERS`` says, they are on only where a person builds at a terminal
    (not in CI, not in a git hook: see :func:`why_off`)."""
    value = environ.get(VARIABLE, "").strip()
    if not value:
        return 0.0 if why_off(environ, interactive) else DEFAULT_SECONDS
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


def answer_seconds(environ: dict[str, str] | os._Environ[str]) -> float:
    """How long a waiting worker has to answer a build (``MJCFBUILD_WORKER_ANSWER_SECONDS``)."""
    return _positive(environ, ANSWER_VARIABLE, DEFAULT_ANSWER_SECONDS)


def most_workers(environ: dict[str, str] | os._Environ[str]) -> int:
    """How many resident workers this user may have waiting at once (``MJCFBUILD_RESIDENT_MAX``,
    default the number of cores, at least 2)."""
    return int(_positive(environ, MAX_VARIABLE, float(max(2, os.cpu_count() or 2))))


def _positive(environ: dict[str, str] | os._Environ[str], name: str, default: float) -> float:
    value = environ.get(name, "").strip()
    if not value:
        return default
    try:
        number = float(value)
    except ValueError:
        number = -1.0
    if not 0 < number < float("inf"):
        raise UsageError(f"{name}={value}: not a positive number", hint=f"unset {name}")
    return number


def off_reason(environ: dict[str, str] | os._Environ[str]) -> str | None:
    """Why a build here does without resident workers (one line), or None when it uses them."""
    if idle_seconds(environ) == 0:
        if environ.get(VARIABLE, "").strip():
            return f"${VARIABLE} is 0"
        return why_off(environ)
    return folder_problem(resident_dir_path(environ))


def folder_problem(folder: Path) -> str | None:
    """Why ``folder`` cannot hold this user's resident workers, or None when it can (made
    if needed)."""
    longest = len(os.fsencode(str(folder))) + 1 + _NAME_LENGTH
    if longest > _SUN_PATH:
        return (
            f"{folder} is too long for a socket path ({longest} of at most {_SUN_PATH} bytes); "
            f"set ${DIR_VARIABLE} to a shorter folder"
        )
    with contextlib.suppress(FileExistsError, OSError):
        folder.mkdir(mode=0o700, parents=True)
    try:
        info = folder.lstat()
    except OSError as exc:
        return f"{folder} cannot be made ({exc.strerror})"
    if not stat.S_ISDIR(info.st_mode):
        return f"{folder} is not a folder"
    if info.st_uid != os.getuid():
        return f"{folder} belongs to another user; set ${DIR_VARIABLE} to a folder of yours"
    if info.st_mode & 0o077:
        return f"{folder} may be opened by other users (mode {info.st_mode & 0o777:o}, not 700)"
    return None


def resident_dir(environ: dict[str, str] | os._Environ[str]) -> Path | None:
    """The private folder of this user's resident workers, made if needed; None if it cannot
    be made private (another user owns it, or others may write to it) or its path is too long
    for a socket (:func:`folder_problem` says why)."""
    folder = resident_dir_path(environ)
    return None if folder_problem(folder) else folder


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
    would get ``environ``: 20 hex digits, the first 6 naming this installation (interpreter
    and mjcfbuild's folder), the next 6 its code version (mjcfbuild's code and the installed
    packages), the last 8 the variables read at start. Edits of modules a worker imported
    since are found by the worker itself (mjcfbuild.engine.worker_main)."""
    package = Path(__file__).resolve().parents[1]
    # The interpreter itself and the environment it runs in: `mjcfbuild` runs a virtual
    # environment's python3, `python -m mjcfbuild` its python, links to the same program.
    install = [os.path.realpath(sys.executable), sys.prefix, str(package)]
    code = [sys.version, *_code_fingerprint(package)]
    here = os.getcwd()
    # The first entry is the running script's folder (a console script's bin/, the folder
    # `python -m` runs in), not one a worker imports from, unless Python was told not to add it.
    entries = sys.path if sys.flags.safe_path else sys.path[1:]
    for entry in entries:  # installing or removing a package changes its folder's mtime
        if entry in ("", ".", here):
            continue  # the folder `python -m` runs in: any file made there would change it
        with contextlib.suppress(OSError):
            code.append(f"{entry}@{os.stat(entry).st_mtime_ns}")
    start = sorted(f"{k}={v}" for k, v in environ.items() if k.startswith(_START_VARIABLES))
    return _digest(install, 6) + _digest(code, 6) + _digest(start, 8)


def _digest(parts: list[str], length: int) -> str:
    data = "\0".join(parts).encode("utf-8", "surrogateescape")
    return hashlib.sha256(data).hexdigest()[:length]


def installation(key: str) -> str:
    """The part of a worker key that names the installation."""
    return key[:6]


def code_version(key: str) -> str:
    """The part of a worker key that names the installation and its code version."""
    return key[:12]


def _code_fingerprint(package: Path) -> list[str]:
    found = []
    for folder, subfolders, files in os.walk(package):
        subfolders[:] = sorted(d for d in subfolders if d != "__pycache__")
        for name in sorted(files):
            if name.endswith(".py"):
                identity = signature(os.stat(os.path.join(folder, name)))
                found.append(f"{folder}/{name}:{identity}")
    return found


@dataclass
class Resident:
    """A worker process this build holds: its connection, process id and what it holds."""

    connection: socket.socket
    pid: int
    holds: str | None  # the model whose meshes MuJoCo has processed there, if any


class NoAnswer(Exception):
    """A worker took the connection but did not answer within its time."""


def claim(folder: Path, key: str, hello: dict, seconds: float | None = None) -> Resident | None:
    """An idle resident worker of ``key`` in ``folder``, now serving this build (``hello``
    tells it the build's environment, folder, process state and what to preload); None if
    none is idle. A worker that does not answer within ``seconds`` (default
    :func:`answer_seconds`) is killed, once it is confirmed to be one, and its socket
    removed; a socket nobody listens on is removed."""
    seconds = answer_seconds(os.environ) if seconds is None else seconds
    end_older_versions(folder, key, seconds)
    for path in sorted(folder.glob(f"{key}-*.sock")):
        try:
            connection = _connect(path, seconds)
        except _Stale:
            continue
        except TimeoutError:  # its queue is full and it takes nobody off it: stopped
            _reap(path, folder)
            continue
        except OSError:
            continue
        try:
            reply = _handshake(connection, hello, seconds)
        except NoAnswer:
            connection.close()
            _reap(path, folder)
            continue
        if reply is not None and isinstance(reply.get("pid"), int):
            connection.settimeout(None)  # the build's calls have their own time limits
            return Resident(connection, reply["pid"], reply.get("holds"))
        connection.close()  # another build claimed it first, or it cannot serve this build
    return None


class _Stale(Exception):
    """A socket file nobody listens on: it was removed."""


def _connect(path: Path, seconds: float) -> socket.socket:
    """A connection to the worker listening on ``path``; raises :class:`_Stale` (after
    removing the file) when nobody listens there."""
    import socket

    try:
        before = path.lstat()
    except FileNotFoundError:
        raise _Stale() from None
    if not stat.S_ISSOCK(before.st_mode):
        raise _Stale()  # a file of another kind under a worker's name: never a worker
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    connection.settimeout(seconds)
    try:
        connection.connect(str(path))
    except (ConnectionRefusedError, FileNotFoundError):
        connection.close()
        _unlink_if_same(path, before)
        raise _Stale() from None
    except OSError:
        connection.close()
        raise
    return connection


def _unlink_if_same(path: Path, before: os.stat_result) -> None:
    """Remove ``path`` if it is still the file ``before`` described (not a new worker's)."""
    with contextlib.suppress(OSError):
        now = path.lstat()
        if (now.st_ino, now.st_dev) == (before.st_ino, before.st_dev):
            path.unlink()


def _reap(path: Path, folder: Path) -> None:
    """End the worker behind ``path``, which took a connection but did not answer (stopped,
    or attached to a debugger): it is killed only if its process is confirmed to be that
    worker; its socket is removed either way, so no build waits on it again."""
    import signal

    pid = _pid_of(path)
    key = path.name.rpartition("-")[0]
    if pid is not None and is_worker(pid, folder, key):
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)
    with contextlib.suppress(OSError):
        path.unlink()


def end_older_versions(folder: Path, key: str, seconds: float) -> int:
    """Ask the waiting workers of this installation that run another code version (mjcfbuild
    or a package was upgraded or edited since they started) to exit: no build of this
    installation can use them again. How many were asked."""
    ended = 0
    mine = installation(key)
    for path in sorted(folder.glob(f"{mine}*-*.sock")):
        other = path.name.rpartition("-")[0]
        if len(other) != len(key) or code_version(other) == code_version(key):
            continue
        if shut_down(path, folder, seconds):
            ended += 1
    return ended


def shut_down(path: Path, folder: Path, seconds: float) -> bool:
    """Ask the worker listening on ``path`` to exit, over its own socket; one that takes the
    request and does not confirm within ``seconds`` is killed once confirmed to be that
    worker. Whether a worker was there. The socket file is gone afterwards."""
    try:
        connection = _connect(path, seconds)
    except _Stale:
        return False
    except OSError:
        return False
    try:
        reply = _handshake(connection, {"stop": True}, seconds)
    except NoAnswer:
        reply = None
        _reap(path, folder)
        return True
    finally:
        connection.close()
    with contextlib.suppress(OSError):
        path.unlink()
    return reply is not None and reply.get("stopping") is not None


def spawn(
    folder: Path, key: str, hello: dict, env: dict[str, str], seconds: float | None = None
) -> Resident:
    """Start a resident worker of ``key`` serving this build first; raises OSError if it
    does not answer within three times ``seconds``, and at least 30 s (it starts an
    interpreter, on a machine that may be busy; it is killed then)."""
    import socket

    seconds = answer_seconds(os.environ) if seconds is None else seconds
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
    command = [sys.executable, "-m", "mjcfbuild.engine.worker_main", "--resident"]
    command += [str(theirs.fileno()), str(folder), key, repr(idle_seconds(env))]
    command.append(str(most_workers(os.environ)))
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
    _spawned.add(pid)
    try:  # the hello sets its folder and process state, as for a waiting worker
        reply = _handshake(ours, hello, max(3 * seconds, SPAWN_SECONDS))
    except NoAnswer:
        reply = None
    if reply is None or reply.get("pid") != pid:
        ours.close()
        stop(pid)  # our own child: no doubt which process it is
        raise OSError("a new worker process did not answer")
    ours.settimeout(None)
    return Resident(ours, pid, None)


def _handshake(connection: socket.socket, hello: dict, seconds: float) -> dict | None:
    """Send ``hello`` and read the reply within ``seconds``; None if the worker closed the
    connection; raises :class:`NoAnswer` if it did not answer in time."""
    connection.settimeout(seconds)
    try:
        connection.sendall((json.dumps(hello) + "\n").encode())
    except TimeoutError:
        raise NoAnswer() from None
    except OSError:
        return None
    return receive_line(connection, seconds)


def receive_line(connection: socket.socket, seconds: float | None = None) -> dict | None:
    """The next JSON line from ``connection`` (the first of a build's claim, or the reply to
    it); None if the other side closed or reset it first. With ``seconds``, raises
    :class:`NoAnswer` when the whole line has not come within that time."""
    import time

    deadline = None if seconds is None else time.monotonic() + seconds
    data = b""
    try:
        while not data.endswith(b"\n"):
            if deadline is not None:
                left = deadline - time.monotonic()
                if left <= 0:
                    raise NoAnswer()
                connection.settimeout(left)
            chunk = connection.recv(1 << 16)
            if not chunk:
                return None
            data += chunk
    except TimeoutError:
        raise NoAnswer() from None
    except OSError:
        return None
    try:
        line = json.loads(data)
    except ValueError:
        return None
    return line if isinstance(line, dict) else None


def _pid_of(socket_file: Path) -> int | None:
    """The process id in a waiting worker's socket name (``<key>-<pid>.sock``)."""
    pid = socket_file.stem.rpartition("-")[2]
    return int(pid) if pid.isdigit() else None


def is_worker(pid: int, folder: Path | None, key: str | None = None) -> bool:
    """Whether process ``pid`` is this user's resident worker of ``folder`` (of any folder
    if None; and of ``key``, if given), as its command line says; False where that cannot be
    told (no /proc). A process id alone proves nothing: after a worker ends, its number goes
    to another process."""
    try:
        owner = os.stat(f"/proc/{pid}").st_uid
        argv = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
    except OSError:
        return False
    if owner != os.getuid():
        return False
    words = [os.fsdecode(word) for word in argv]
    try:
        at = words.index("--resident")
    except ValueError:
        return False
    if at < 2 or words[at - 1] != "mjcfbuild.engine.worker_main" or len(words) < at + 4:
        return False
    same_folder = folder is None or words[at + 2] == str(folder)
    return same_folder and (key is None or words[at + 3] == key)


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
# The resident workers this process started (its children until they end).
_spawned: set[int] = set()


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
    """Kill resident worker ``pid`` now (and reap it, if this process started it). One this
    process did not start is signalled only while its command line says it is a resident
    worker: its number may belong to another process once it has ended."""
    import signal

    if pid in _ended:
        return
    ours = pid in _spawned
    if ours:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            _ended[pid] = status
            return
    if ours or is_worker(pid, None):
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)
    if ours:
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
    """The process ids of the idle resident workers in ``folder`` (of ``key``, if given):
    only processes confirmed to be such workers (:func:`is_worker`); socket files nobody
    listens on are removed on the way, and files of other kinds are not counted."""
    return [waiting.pid for waiting in _waiting(folder, key)]


@dataclass(frozen=True)
class _Waiting:
    """An idle resident worker: its socket, process id, key and since when it waits."""

    path: Path
    pid: int
    key: str
    since_ns: int  # the socket file's modification time: made when the worker began to wait


def _waiting(folder: Path, key: str | None = None) -> list[_Waiting]:
    """The idle resident workers in ``folder`` (see :func:`resident_pids`)."""
    found = []
    for path in sorted(folder.glob(f"{key or '*'}-*.sock")):
        pid = _pid_of(path)
        try:
            info = path.lstat()
        except OSError:
            continue
        if pid is None or not stat.S_ISSOCK(info.st_mode):
            continue
        its_key = path.name.rpartition("-")[0]
        if is_worker(pid, folder, its_key) and _process_exists(pid):
            found.append(_Waiting(path, pid, its_key, info.st_mtime_ns))
        elif not _listening(path):
            _unlink_if_same(path, info)
    return found


def make_room(folder: Path, key: str, most: int, seconds: float) -> bool:
    """Whether a worker of ``key`` that has just served a build may wait in ``folder``, with
    at most ``most`` waiting there of every key together. Where they are as many already,
    those of other keys that have waited longest are asked to exit (:func:`shut_down`): the
    worker of the latest build is the likeliest to serve the next one, and workers of an
    environment nobody builds in any more (another ``MUJOCO_GL``, another virtual
    environment) would otherwise hold every place for their whole wait. Workers of ``key``
    are never asked: the next build of that key may use them as well as this one."""
    asked: set[Path] = set()
    for _ in range(most + 1):  # each turn ends a worker, or finds one gone meanwhile
        waiting = _waiting(folder)
        if len(waiting) < most:
            return True
        others = [w for w in waiting if w.key != key and w.path not in asked]
        if not others:
            return False
        oldest = min(others, key=lambda worker: (worker.since_ns, worker.path.name))
        asked.add(oldest.path)  # asked once: one that would not go is not asked again
        shut_down(oldest.path, folder, seconds)
    return False


def _listening(path: Path) -> bool:
    """Whether a process listens on the socket ``path`` (connecting costs it nothing: it
    sees a connection that closes before any hello and waits on)."""
    import socket

    probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    probe.settimeout(1.0)
    try:
        probe.connect(str(path))
    except OSError:
        return False
    finally:
        probe.close()
    return True
