"""The no-op build that pre-commit runs stays fast with a remote cache and a cluster configured."""

from __future__ import annotations

import subprocess
import sys

from tests.sharing.conftest import free_port

SHARING_MODULES = ("fsspec", "s3fs", "botocore", "aiohttp", "dask", "distributed")
PROBE = (
    "import sys\n"
    "from mjcfbuild.cli import run\n"
    "code = run(['build', '--no-check'])\n"
    "print('imported:', ','.join(m for m in {modules!r} if m in sys.modules))\n"
    "sys.exit(code)\n"
)


def test_a_no_op_build_imports_no_fsspec_s3fs_or_dask(machines, tmp_path):
    first, _ = machines
    env = {
        "MJCFBUILD_CACHE_DIR": str(first.cache),
        "MJCFBUILD_CACHE_REMOTE": str(tmp_path / "shared"),
    }
    done = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", "--no-check", "-q"],
        cwd=first.folder,
        env={**_environ(), **env},
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    # Now nothing changed: with an S3 remote and a Dask executor set, nothing is contacted
    # (the endpoint and scheduler do not exist) and nothing of theirs is imported.
    env.update(
        {
            "MJCFBUILD_CACHE_REMOTE": "s3://team-products/robots",
            "AWS_ENDPOINT_URL": f"http://127.0.0.1:{free_port()}",
            "MJCFBUILD_EXECUTOR": f"dask://127.0.0.1:{free_port()}",
        }
    )
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(modules=SHARING_MODULES)],
        cwd=first.folder,
        env={**_environ(), **env},
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert "0 run" in done.stdout and "warning" not in done.stderr
    [imported] = [line for line in done.stdout.splitlines() if line.startswith("imported:")]
    assert imported.strip() == "imported:"
    # That build left a stamp: the next no-op stops at it, before doit and pydantic too.
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(modules=(*SHARING_MODULES, "doit", "pydantic"))],
        cwd=first.folder,
        env={**_environ(), **env},
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert "0 run" in done.stdout
    [imported] = [line for line in done.stdout.splitlines() if line.startswith("imported:")]
    assert imported.strip() == "imported:"


def _environ() -> dict[str, str]:
    import os

    return dict(os.environ)
