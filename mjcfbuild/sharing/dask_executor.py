"""Mesh conversions and decompositions on an existing Dask cluster.

The build connects to the scheduler when the first product has to be computed, checks that
every worker has the same mjcfbuild, CoACD, trimesh (and other step tools) as this machine,
and then sends each product's input bytes to the cluster and gets the product back as one
verified object, which lands in the local store (and from there in the remote cache) exactly
as a local result would. A worker that dies while computing is replaced by Dask and the task
runs again elsewhere; when it keeps dying the task fails, naming it.
"""

from __future__ import annotations

import os
import threading
import uuid
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import MjcfbuildError, TaskCrashed
from mjcfbuild.failpoints import ONCE_DIR_VARIABLE, VARIABLE
from mjcfbuild.sharing.blob import BadObject, verify
from mjcfbuild.sharing.compute import compute_product, version_mismatch, worker_versions
from mjcfbuild.sharing_settings import ExecutorSpec

if TYPE_CHECKING:
    from distributed import Client

CONNECT_TIMEOUT_VARIABLE = "MJCFBUILD_DASK_CONNECT_TIMEOUT"
DEFAULT_CONNECT_TIMEOUT = 10.0


def connect_timeout() -> float:
    """Seconds to wait for the scheduler: ``$MJCFBUILD_DASK_CONNECT_TIMEOUT``, else 10."""
    try:
        return float(os.environ.get(CONNECT_TIMEOUT_VARIABLE) or DEFAULT_CONNECT_TIMEOUT)
    except ValueError:
        return DEFAULT_CONNECT_TIMEOUT


class ExecutorError(MjcfbuildError):
    """The cluster cannot be used for this build (its workers run other versions)."""


class DaskExecutor:
    """One build's connection to a Dask scheduler, opened on first use."""

    def __init__(self, spec: ExecutorSpec, warn: Callable[[str], None]) -> None:
        self.spec = spec
        self._warn = warn
        self._lock = threading.Lock()
        self._client: Client | None = None
        self._unusable = False
        self._refusal: ExecutorError | None = None
        self._versions = worker_versions()

    @property
    def display(self) -> str:
        """The executor as messages show it."""
        return f"dask://{self.spec.address}"

    def _connect(self) -> Client | None:
        """The client, or None when the scheduler cannot be reached (warned once)."""
        with self._lock:
            if self._refusal is not None:
                raise self._refusal
            if self._client is not None or self._unusable:
                return self._client
            from distributed import Client

            try:
                client = Client(
                    self.spec.scheduler, timeout=connect_timeout(), set_as_default=False
                )
            except (OSError, TimeoutError) as exc:
                self._unusable = True
                self._warn(
                    f"the Dask scheduler {self.display} cannot be reached "
                    f"({type(exc).__name__}); converting and decomposing on this machine"
                )
                return None
            answers = client.run(worker_versions)
            if not answers:
                client.close()
                self._unusable = True
                self._warn(f"the Dask cluster {self.display} has no workers; working locally")
                return None
            for worker, versions in sorted(answers.items()):
                mismatch = version_mismatch(self._versions, versions)
                if mismatch:
                    client.close()
                    self._refusal = ExecutorError(
                        f"Dask worker {worker} of {self.display} has {mismatch}; "
                        "its results could not share a cache with this machine's",
                        hint="install the same mjcfbuild, CoACD and trimesh versions on every "
                        "worker, or build with --executor local",
                    )
                    raise self._refusal
            self._client = client
            return client

    def compute(
        self,
        kind: str,
        key: str,
        options: dict,
        files: dict[Path, Path],
        main: Path,
        task: str,
        timeout: float | None,
    ) -> tuple[dict, dict[str, bytes]] | None:
        """Compute the product ``key`` on the cluster: its verified summary and files, or None
        when the cluster cannot be reached (the caller then computes locally).

        ``files`` maps each input's path here to its name in the worker's folder.
        """
        client = self._connect()
        if client is None:
            return None
        from distributed import KilledWorker

        payload = {name.as_posix(): path.read_bytes() for path, name in files.items()}
        failpoints = {
            "spec": os.environ.get(VARIABLE, ""),
            "once_dir": os.environ.get(ONCE_DIR_VARIABLE, ""),
        }
        # The inputs travel inside the task, not as scattered data: scattered data dies with
        # the worker holding it, and the task could then not run again elsewhere.
        future = client.submit(
            compute_product,
            kind,
            key,
            options,
            payload,
            files[main].as_posix(),
            self._versions,
            failpoints,
            key=f"mjcfbuild-{task}-{uuid.uuid4().hex[:8]}",
            pure=False,
        )
        try:
            reply = future.result(timeout=timeout)
        except KilledWorker as exc:
            raise TaskCrashed(
                f"{task}: the Dask worker running it was lost, and so was each worker Dask "
                "retried it on",
                hint=f"see the worker logs of {self.display}; {_first_line(exc)}",
            ) from None
        except TimeoutError:
            future.cancel()
            raise TaskCrashed(
                f"{task} did not finish on {self.display} within {timeout:g} s and was cancelled"
            ) from None
        except MjcfbuildError:
            raise
        except Exception as exc:  # the scheduler went away, the connection broke
            raise TaskCrashed(
                f"{task}: the Dask cluster {self.display} failed ({type(exc).__name__}: "
                f"{_first_line(exc)})",
                hint="build again, or with --executor local",
            ) from None
        finally:
            future.release()
        if "error" in reply:
            error = MjcfbuildError.from_dict(reply["error"])
            inputs = reply.get("inputs")
            if inputs and error.location is not None and error.location.file.startswith(inputs):
                error.location.file = str(main)  # name the file here, not the worker's copy
            if not error.message.startswith(task):
                error.message = f"{task}: {error.message}"
            raise error
        try:
            return verify(key, reply["object"])
        except BadObject as exc:
            raise TaskCrashed(f"{task}: the product sent by {self.display} is {exc}") from None

    def close(self) -> None:
        """Disconnect from the scheduler (the cluster keeps running)."""
        with self._lock:
            client, self._client = self._client, None
        if client is not None:
            client.close()


def _first_line(exc: BaseException) -> str:
    return (str(exc).strip().splitlines() or [type(exc).__name__])[0][:200]
