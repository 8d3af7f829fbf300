"""Every bad input in the catalogue ends in one documented exit code and one line that names the
file (and line) and says what to do; no traceback, and no output written or damaged."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from mjcfbuild.errors import EXIT_CODES
from tests.cli.error_catalogue import CASES, MANIFEST, Case, urdf
from tests.conftest import run_cli

# An earlier build's outputs, as a description repo commits them; a failed build leaves them be.
EARLIER_OUTPUTS = {
    "mjcf/robot.xml": "<mujoco model='earlier build'/>\n",
    "mjcf/scene.xml": "<mujoco><include file='robot.xml'/></mujoco>\n",
    "mjcf/assets/arm.obj": "v 0 0 0\n",
}
STATE_FOLDER = "mjcf/.mjcfbuild"


def snapshot(folder: Path) -> dict[str, bytes | str]:
    """Every entry under ``folder``: file bytes, link targets, or 'folder'."""
    entries: dict[str, bytes | str] = {}
    for root, folders, files in os.walk(folder):
        for name in folders + files:
            path = Path(root) / name
            key = str(path.relative_to(folder))
            if path.is_symlink():
                entries[key] = "-> " + os.readlink(path)
            elif path.is_dir():
                entries[key] = "folder"
            else:
                entries[key] = path.read_bytes()
    return entries


def test_the_catalogue_is_large_and_names_are_unique():
    assert len(CASES) >= 40
    assert len({case.name for case in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_bad_input(case: Case, tmp_path: Path):
    if case.needs_unprivileged and os.geteuid() == 0:
        pytest.skip("root may write in read-only folders")
    case.write(tmp_path)
    for relative, text in EARLIER_OUTPUTS.items():
        (tmp_path / relative).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / relative).write_text(text)
    before = snapshot(tmp_path)

    result = run_cli(*case.args, cwd=tmp_path, env=case.env)

    assert result.code == case.code, result.stderr
    assert case.code in EXIT_CODES
    errors = [line for line in result.stderr.splitlines() if line.startswith("mjcfbuild: error:")]
    assert len(errors) == 1 or case.code == 2, result.stderr
    message = errors[0] if errors else result.stderr
    for expected in case.says:
        assert expected in message, f"{expected!r} not in {message!r}"
    assert "Traceback" not in result.stderr + result.stdout

    after = snapshot(tmp_path)
    for key, value in before.items():
        assert after.get(key) == value, f"{key} was changed by a failed build"
    written = [key for key in after if key not in before and not key.startswith(STATE_FOLDER)]
    assert written == [], f"a failed build wrote {written}"


def test_debug_shows_the_traceback_of_an_internal_error(tmp_path: Path):
    """--debug is the one way to see a traceback; the failure here is forced in a build step."""
    (tmp_path / "robot.yaml").write_text(MANIFEST)
    (tmp_path / "robot.urdf").write_text(urdf())
    env = {"MJCFBUILD_FAILPOINT": "assemble:raise"}
    plain = run_cli("build", cwd=tmp_path, env=env)
    debug = run_cli("--debug", "build", cwd=tmp_path, env=env)
    assert plain.code == debug.code == 70
    assert "Traceback" not in plain.stderr and "run again with --debug" in plain.stderr
    assert "Traceback" in debug.stderr


def test_failed_build_after_a_good_one_keeps_the_good_outputs(tmp_path: Path):
    (tmp_path / "robot.yaml").write_text(MANIFEST)
    (tmp_path / "robot.urdf").write_text(urdf())
    assert run_cli("build", "-q", cwd=tmp_path).code == 0
    good = {k: v for k, v in snapshot(tmp_path / "mjcf").items() if not k.startswith(".mjcf")}
    (tmp_path / "robot.urdf").write_text(urdf(('<child link="arm"/>', '<child link="arn"/>')))
    assert run_cli("build", "-q", cwd=tmp_path).code == 4
    after = {k: v for k, v in snapshot(tmp_path / "mjcf").items() if not k.startswith(".mjcf")}
    assert after == good
    stale = run_cli("check", "--up-to-date", cwd=tmp_path)
    assert stale.code == 6, stale.stdout + stale.stderr
