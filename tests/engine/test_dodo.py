"""Real doit on this repository's dodo.py and on a user's own dodo.py built from the README."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from tests.conftest import ROOT, copy_example

DOIT = [sys.executable, "-m", "doit"]


def _doit(folder: Path, *args: str, cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "MJCFBUILD_CACHE_DIR": str(cache)}
    return subprocess.run(
        [*DOIT, *args], cwd=folder, capture_output=True, text=True, env=env, timeout=600
    )


def _ran(output: str) -> list[str]:
    """The tasks doit ran (``.  title``), not those it found up to date (``-- title``)."""
    return [line[3:] for line in output.splitlines() if line.startswith(".  ")]


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


def test_doit_and_doit_examples_in_this_repository(tmp_path):
    root = _repository_copy(tmp_path)
    first = _doit(root, cache=tmp_path / "cache")
    assert first.returncode == 0, first.stdout + first.stderr
    assert "assemble example_arm.xml" in _ran(first.stdout)
    for example in ("arm", "reference_demo", "reference_demo_native"):
        assert (root / "examples" / example / "mjcf" / "scene.xml").is_file()
    again = _doit(root, "examples", cache=tmp_path / "cache")
    assert again.returncode == 0, again.stdout + again.stderr
    assert _ran(again.stdout) == []


def _readme_dodo() -> str:
    """The dodo.py the README shows (its 'In your own dodo.py' block)."""
    readme = (ROOT / "README.md").read_text()
    section = readme.split("### In your own dodo.py", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_a_users_dodo_checks_content_tidies_and_locks(tmp_path):
    robots = tmp_path / "robots"
    shutil.copytree(copy_example("arm", tmp_path / "src"), robots / "arm")
    (tmp_path / "dodo.py").write_text(_readme_dodo())
    cache = tmp_path / "cache"
    first = _doit(tmp_path, cache=cache)
    assert first.returncode == 0, first.stdout + first.stderr
    model = robots / "arm" / "mjcf" / "example_arm.xml"
    built = model.read_bytes()
    # A hand-edited model is rebuilt, as by `mjcfbuild build`.
    model.write_bytes(built.replace(b"<worldbody>", b"<worldbody><!-- edited -->"))
    again = _doit(tmp_path, cache=cache)
    assert again.returncode == 0, again.stdout + again.stderr
    assert "assemble example_arm.xml" in _ran(again.stdout)
    assert model.read_bytes() == built
    # Products the plan no longer uses are removed.
    stale = robots / "arm" / "mjcf" / ".mjcfbuild" / "products" / "gone.json"
    stale.write_text("{}")
    tidy = _doit(tmp_path, cache=cache)
    assert tidy.returncode == 0 and not stale.exists(), tidy.stdout + tidy.stderr
    # While another build holds the output folder, doit waits for it.
    import fcntl

    with open(robots / "arm" / "mjcf" / ".mjcfbuild" / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        waiting = subprocess.Popen(
            DOIT,
            cwd=tmp_path,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env={**os.environ, "MJCFBUILD_CACHE_DIR": str(cache)},
        )
        first_line = waiting.stdout.readline()
        assert "waiting for another build of" in first_line, first_line
        fcntl.flock(lock, fcntl.LOCK_UN)
    rest = waiting.communicate(timeout=600)[0]
    assert waiting.returncode == 0, rest
