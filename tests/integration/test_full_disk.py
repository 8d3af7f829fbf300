"""A full disk on a real, size-limited file system (tmpfs): a full output folder is exit 7 with
one line naming the file that could not be written, and the next build, with room again,
builds; a full cache never fails a build, its preview pictures included (Mesa's shader cache
once killed the preview worker with SIGBUS there)."""

from __future__ import annotations

import errno
import os
import re
import subprocess
from pathlib import Path

import pytest

from tests.conftest import run_cli

EXIT_OUTPUT = 7
WRITE_ERROR = re.compile(
    r"^mjcfbuild: error: (mjcf/\S+): cannot write: (no space left on the device|read-only file "
    r"system) \(.+\)$"
)


@pytest.fixture
def small_disk():
    """Mount a tmpfs of a given size on a folder: ``mount(folder, "100k")``; skipped, with the
    reason, where this process may not mount one."""
    mounted: list[Path] = []

    def mount(folder: Path, size: str, *options: str) -> Path:
        folder.mkdir(parents=True, exist_ok=True)
        command = ["mount", "-t", "tmpfs", "-o", ",".join([f"size={size}", *options])]
        try:
            done = subprocess.run([*command, "tmpfs", str(folder)], capture_output=True, text=True)
        except FileNotFoundError:
            pytest.skip("no mount command: a real full file system cannot be made here")
        if done.returncode != 0:
            pytest.skip(
                f"cannot mount a size-limited tmpfs ({done.stderr.strip()}): a real full file "
                "system needs root or CAP_SYS_ADMIN"
            )
        mounted.append(folder)
        return folder

    yield mount
    for folder in reversed(mounted):
        subprocess.run(["umount", "-l", str(folder)], check=False)


def remount(folder: Path, options: str) -> None:
    subprocess.run(["mount", "-o", f"remount,{options}", str(folder)], check=True)


def fill(folder: Path) -> None:
    """Write into ``folder`` until its file system has no byte left."""
    with open(folder / "filler", "wb", buffering=0) as handle:
        try:
            while True:
                handle.write(b"\0" * 4096)
        except OSError as exc:
            assert exc.errno == errno.ENOSPC
    assert os.statvfs(folder).f_bavail == 0


def assert_write_errors(stderr: str) -> list[str]:
    """Every line of ``stderr`` is a one-line write error naming a file in the output folder;
    the files named."""
    lines = stderr.strip().splitlines()
    assert lines, "no error"
    for line in lines:
        assert WRITE_ERROR.match(line), line
    return [WRITE_ERROR.match(line).group(1) for line in lines]


@pytest.mark.parametrize(
    "size",
    [
        "8k",  # the build's database: doit said "remove the database file(s)", exit 1
        "100k",  # the mesh products: an internal error, exit 70
        "350k",  # the report's pictures: the previews blamed EGL
    ],
)
def test_a_full_output_folder_is_exit_7_naming_the_file(arm, small_disk, size):
    out = small_disk(arm / "mjcf", size)
    result = run_cli("build", "-q", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    named = assert_write_errors(result.stderr)
    assert all("no space left" in line for line in result.stderr.splitlines())
    for name in named:
        # A file of the output folder; its folder may be gone (a previews step that drew
        # nothing removes its pictures' folder).
        assert (arm / name).resolve().is_relative_to((arm / "mjcf").resolve()), name

    remount(out, "size=8m")  # room again: the next build builds, whatever the last one left
    again = run_cli("build", "-q", cwd=arm)
    assert again.code == 0, again.stderr
    assert (arm / "mjcf" / "example_arm.xml").is_file()


def test_a_read_only_output_folder_says_so(arm, small_disk):
    out = small_disk(arm / "mjcf", "1m")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    remount(out, "ro")
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0  # nothing to write: fine
    source = arm / "urdf" / "arm.urdf.xacro"
    source.write_text(source.read_text() + "\n<!-- edited -->\n")
    result = run_cli("build", "-q", "--no-check", cwd=arm)
    assert result.code == EXIT_OUTPUT, result.stderr
    assert_write_errors(result.stderr)
    assert "read-only file system" in result.stderr


def test_a_full_cache_never_fails_a_build(arm, small_disk, tmp_path):
    cache = small_disk(tmp_path / "cache", "1m")
    fill(cache)
    env = {"MJCFBUILD_CACHE_DIR": str(cache), "MJCFBUILD_RESIDENT_WORKERS": "0"}
    result = run_cli("build", cwd=arm, env=env)  # with the check and its preview pictures
    assert result.code == 0, result.stderr  # before: the previews worker died of SIGBUS
    assert "warning" not in result.stderr, result.stderr
    pictures = sorted((arm / "mjcf" / "report" / "previews").glob("*.png"))
    assert pictures, "no preview pictures"
    assert not list((cache / "products").rglob("summary.json"))  # nothing could be stored
    # The next build of another folder computes again, and is fine too.
    (arm / "mjcf").rename(arm / "first")
    again = run_cli("build", "--no-check", "-q", cwd=arm, env=env)
    assert again.code == 0, again.stderr
