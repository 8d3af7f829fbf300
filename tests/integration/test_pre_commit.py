"""The pre-commit hooks, installed with the real pre-commit into a real git repository.

The hook repository is this project's own checkout at its current commit: pre-commit clones
it and installs mjcfbuild into an environment of its own, as it would from GitHub.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ROOT

pytestmark = pytest.mark.slow


def git(*args: str, cwd: Path, check: bool = True) -> subprocess.CompletedProcess:
    env = {
        **os.environ,
        "GIT_AUTHOR_NAME": "t",
        "GIT_AUTHOR_EMAIL": "t@example.com",
        "GIT_COMMITTER_NAME": "t",
        "GIT_COMMITTER_EMAIL": "t@example.com",
    }
    return subprocess.run(
        ["git", *args], cwd=cwd, env=env, check=check, capture_output=True, text=True
    )


def pre_commit_executable() -> str:
    candidate = Path(sys.executable).with_name("pre-commit")
    return str(candidate) if candidate.exists() else "pre-commit"


@pytest.fixture(scope="module")
def project_commit():
    head = git("rev-parse", "HEAD", cwd=ROOT, check=False)
    if head.returncode != 0:
        pytest.skip("this checkout has no commit for pre-commit to clone")
    return head.stdout.strip()


def test_hook_fails_regenerates_then_passes(tmp_path, project_commit, monkeypatch):
    monkeypatch.setenv("PRE_COMMIT_HOME", str(tmp_path / "pre-commit-home"))
    repo = tmp_path / "arm_description"
    shutil.copytree(EXAMPLES / "arm", repo, ignore=shutil.ignore_patterns("mjcf"))
    git("init", "-q", cwd=repo)
    (repo / ".pre-commit-config.yaml").write_text(
        "repos:\n"
        f"  - repo: {ROOT}\n"
        f"    rev: {project_commit}\n"
        "    hooks:\n"
        "      - id: mjcfbuild\n"
        "      - id: mjcfbuild-check\n"
    )
    # The description and its built model go in first, before the hooks are installed.
    build = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", "-q", "--no-check"],
        cwd=repo,
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr
    git("add", "-A", cwd=repo)
    git("commit", "-q", "-m", "arm with its model", cwd=repo)
    install = subprocess.run(
        [pre_commit_executable(), "install", "--install-hooks"],
        cwd=repo,
        capture_output=True,
        text=True,
    )
    assert install.returncode == 0, install.stdout + install.stderr

    # Edit a joint limit: the hook rebuilds the model, so the commit fails...
    limits = repo / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    first = git("commit", "-am", "narrower elbow", cwd=repo, check=False)
    assert first.returncode != 0
    assert "files were modified by this hook" in first.stdout + first.stderr
    model = (repo / "mjcf" / "example_arm.xml").read_text()
    assert 'range="-2.5 2.4"' in model

    # ...and passes once the regenerated model is staged with the change.
    git("add", "-A", cwd=repo)
    second = git("commit", "-m", "narrower elbow", cwd=repo, check=False)
    assert second.returncode == 0, second.stdout + second.stderr
    assert "mjcfbuild check --up-to-date" in second.stdout + second.stderr
    assert git("status", "--porcelain", cwd=repo).stdout.strip() == ""
