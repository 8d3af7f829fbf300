"""Real doit on this repository's dodo.py and on a user's own dodo.py built from the README:
one state with the command line, doit's database in the state folder, lines naming robots."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from tests.conftest import ROOT, copy_example

DOIT = [sys.executable, "-m", "doit"]

# `mjcfbuild build` in a process that says what it imported: nothing of the engine when the
# no-op stamp answered.
_PROBE = (
    "import sys\n"
    "from mjcfbuild.cli import run\n"
    "code = run(sys.argv[1:])\n"
    "print('doit imported:', 'doit' in sys.modules)\n"
    "sys.exit(code)\n"
)


def _env(cache: Path) -> dict[str, str]:
    return {**os.environ, "MJCFBUILD_CACHE_DIR": str(cache)}


def _doit(folder: Path, *args: str, cache: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [*DOIT, *args], cwd=folder, capture_output=True, text=True, env=_env(cache), timeout=600
    )


def _build(folder: Path, manifest: str, cache: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", _PROBE, "build", manifest],
        cwd=folder,
        capture_output=True,
        text=True,
        env=_env(cache),
        timeout=600,
    )


def _ran(output: str) -> list[str]:
    """The tasks doit ran (``.  title``), not those it found up to date (``-- title``)."""
    return [line[3:] for line in output.splitlines() if line.startswith(".  ")]


def _up_to_date(output: str) -> list[str]:
    return [line[3:] for line in output.splitlines() if line.startswith("-- ")]


def _repository_copy(tmp_path: Path) -> Path:
    """What the project's dodo.py reads: itself, the examples, the package, the schema."""
    root = tmp_path / "repo"
    copy_example("arm", root)
    shutil.copy(ROOT / "dodo.py", root / "dodo.py")
    shutil.copytree(
        ROOT / "mjcfbuild", root / "mjcfbuild", ignore=shutil.ignore_patterns("__pycache__")
    )
    shutil.copytree(ROOT / "schemas", root / "schemas")
    return root


def test_doit_in_this_repository_shares_state_with_the_command_line(tmp_path):
    root = _repository_copy(tmp_path)
    cache = tmp_path / "cache"
    arm = "examples/arm/robot.yaml"
    # Built by the command line first: doit finds the arm up to date and builds the others.
    assert _build(root, arm, cache).returncode == 0
    first = _doit(root, cache=cache)
    assert first.returncode == 0, first.stdout + first.stderr
    assert f"examples:example_arm ({arm})" in _up_to_date(first.stdout)
    ran = _ran(first.stdout)
    assert "examples:arm_with_gripper (examples/arm_gripper/robot.yaml)" in ran
    assert (
        "examples:two_dof_robot@examples/reference_demo (examples/reference_demo/robot.yaml)" in ran
    )
    # Each line a build prints names its robot.
    assert "arm_with_gripper: [4/4] plan (" in first.stdout, first.stdout
    for example in ("arm", "reference_demo", "reference_demo_native"):
        assert (root / "examples" / example / "mjcf" / "scene.xml").is_file()
    # doit's database is in the first example's state folder, not beside dodo.py.
    assert not list(root.glob(".doit.db*"))
    assert list((root / "examples").glob("*/mjcf/.mjcfbuild/dodo/doit.sqlite3"))
    again = _doit(root, "examples", cache=cache)
    assert again.returncode == 0, again.stdout + again.stderr
    assert _ran(again.stdout) == []
    # What doit built is up to date for the command line; where it built without warnings,
    # the no-op stamp answers (a build that warned leaves none, as on the command line).
    summaries = re.findall(r"^mjcfbuild: built (\S+)\.xml: .*$", first.stdout, re.M)
    quiet = [
        name
        for name, line in zip(
            summaries, re.findall(r"^mjcfbuild: built .*$", first.stdout, re.M), strict=True
        )
        if "warning" not in line
    ]
    assert "arm_with_mjcf_hand" in quiet, first.stdout
    for example in ("arm_gripper", "arm_mjcf_gripper", "reference_demo", "reference_demo_native"):
        manifest = f"examples/{example}/robot.yaml"
        built = _build(root, manifest, cache)
        assert built.returncode == 0, built.stderr
        assert " 0 run," in built.stdout
        if any(f"{name}.xml" in built.stdout for name in quiet):
            assert "doit imported: False" in built.stdout, (manifest, built.stdout)


def _readme_dodo() -> str:
    """The dodo.py the README shows (its 'In your own dodo.py' block)."""
    readme = (ROOT / "README.md").read_text()
    section = readme.split("### In your own dodo.py", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_a_users_dodo_checks_content_shares_state_and_locks(tmp_path):
    robots = tmp_path / "robots"
    shutil.copytree(copy_example("arm", tmp_path / "src"), robots / "arm")
    (tmp_path / "dodo.py").write_text(_readme_dodo())
    cache = tmp_path / "cache"
    first = _doit(tmp_path, cache=cache)
    assert first.returncode == 0, first.stdout + first.stderr
    assert "robots:example_arm (robots/arm/robot.yaml)" in _ran(first.stdout)
    assert "mjcfbuild: built example_arm.xml: 13 run" in first.stdout
    assert not list(tmp_path.glob(".doit.db*"))
    built_by_doit = _build(tmp_path, "robots/arm/robot.yaml", cache)
    assert "doit imported: False" in built_by_doit.stdout, built_by_doit.stdout
    model = robots / "arm" / "mjcf" / "example_arm.xml"
    built = model.read_bytes()
    # A removed model is rebuilt, as by `mjcfbuild build`.
    model.unlink()
    again = _doit(tmp_path, cache=cache)
    assert again.returncode == 0, again.stdout + again.stderr
    # (its place in the order is not the point: tasks that wait for the model come after it)
    assert re.search(r"example_arm: \[\d+/13\] assemble example_arm.xml", again.stdout), (
        again.stdout
    )
    assert model.read_bytes() == built
    # An edit the command line built is up to date for doit.
    limits = robots / "arm" / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    assert _build(tmp_path, "robots/arm/robot.yaml", cache).returncode == 0
    after_cli = _doit(tmp_path, cache=cache)
    assert _ran(after_cli.stdout) == [], after_cli.stdout
    # While another build holds the output folder, doit waits for it.
    import fcntl

    model.unlink()
    with open(robots / "arm" / "mjcf" / ".mjcfbuild" / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        waiting = subprocess.Popen(
            DOIT,
            cwd=tmp_path,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=_env(cache),
        )
        lines = [waiting.stdout.readline(), waiting.stdout.readline()]
        assert "waiting for another build of" in lines[1], lines
        fcntl.flock(lock, fcntl.LOCK_UN)
    rest = waiting.communicate(timeout=600)[0]
    assert waiting.returncode == 0, rest
