"""``mjcfbuild workers`` shows the workers that wait for the next build and stops them."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from mjcfbuild.engine import resident
from mjcfbuild.errors import EXIT_OK
from tests.conftest import copy_example, run_cli
from tests.engine.test_resident import _waiting, residents  # noqa: F401
from tests.engine.test_workers import _wait_for


def test_show_and_stop(residents, tmp_path):  # noqa: F811
    shown = run_cli("workers")
    assert shown.code == EXIT_OK and f"folder: {residents}" in shown.stdout
    assert "waiting: 0" in shown.stdout and "wait: 300 s" in shown.stdout
    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", "--no-check", "-j", "1", cwd=arm).code == EXIT_OK
    [pid] = _waiting(residents, 1)
    shown = run_cli("workers")
    assert "waiting: 1" in shown.stdout and f"pid {pid}: " in shown.stdout
    assert " MB" in shown.stdout
    stopped = run_cli("workers", "stop")
    assert stopped.code == EXIT_OK and "stopped 1 waiting worker" in stopped.stdout
    _wait_for(lambda: not resident.running(pid))
    assert "waiting: 0" in run_cli("workers").stdout


def test_off_says_so(tmp_path):
    env = {resident.DIR_VARIABLE: str(tmp_path / "w"), resident.VARIABLE: "0"}
    shown = run_cli("workers", env=env)
    assert shown.code == EXIT_OK and "resident workers are off" in shown.stdout


def test_a_folder_others_can_open_is_not_used_and_it_says_why():
    # A short folder: a socket's path is limited, and pytest's own folders can be too long
    # for one (under pytest-xdist), which the command reports first.
    shared = Path(tempfile.mkdtemp(prefix="mjw-", dir="/tmp"))
    try:
        shared.chmod(0o755)
        env = {resident.DIR_VARIABLE: str(shared), resident.VARIABLE: "60"}
        shown = run_cli("workers", env=env)
        assert shown.code == EXIT_OK
        assert f"resident workers are off: {shared} may be opened by other users" in shown.stdout
    finally:
        shutil.rmtree(shared, ignore_errors=True)
