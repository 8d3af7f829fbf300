"""The pre-commit hooks, installed with the real pre-commit into a real git repository.

The hook repository is this project's own checkout at its current commit: pre-commit clones
it and installs mjcfbuild into an environment of its own, as it would from GitHub.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ROOT

pytestmark = pytest.mark.slow


def git(
    *args: str, cwd: Path, check: bool = True, env: dict | None = None
) -> subprocess.CompletedProcess:
    env = {
        **(env or os.environ),
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


@pytest.fixture(scope="module")
def hook_repository_home(tmp_path_factory) -> Path:
    """One PRE_COMMIT_HOME for the tests whose hook repository is this checkout: the first
    test's `pre-commit install --install-hooks` clones it and installs mjcfbuild into an
    environment (about 20 s); the next test's install of the same repository and rev finds
    them there, as a user's second description repo does."""
    return tmp_path_factory.mktemp("pre-commit-home")


def readme_configs() -> list[str]:
    """The two .pre-commit-config.yaml blocks the README shows, as written there."""
    readme = (ROOT / "README.md").read_text()
    section = readme.split("### In a description repo: pre-commit", 1)[1].split("\n### ", 1)[0]
    return re.findall(r"```yaml\n(.*?)```", section, re.S)


def description_repo(tmp_path: Path) -> Path:
    """A git repository holding the example arm under robots/arm, with its built model."""
    repo = tmp_path / "description"
    arm = repo / "robots" / "arm"
    shutil.copytree(EXAMPLES / "arm", arm, ignore=shutil.ignore_patterns("mjcf"))
    git("init", "-q", cwd=repo)
    build = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", "-q", "--no-check"],
        cwd=arm,
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr
    git("add", "-A", cwd=repo)
    git("commit", "-q", "-m", "arm with its model", cwd=repo)
    return repo


def install_and_commit_an_edit(repo: Path, config: str, env: dict | None = None) -> str:
    """Install ``config``'s hooks, commit an edited joint limit: fails, then passes once the
    rebuilt model is staged. What the passing commit printed."""
    (repo / ".pre-commit-config.yaml").write_text(config)
    git("add", ".pre-commit-config.yaml", cwd=repo)
    install = subprocess.run(
        [pre_commit_executable(), "install", "--install-hooks"],
        cwd=repo,
        capture_output=True,
        text=True,
        env=env,
    )
    assert install.returncode == 0, install.stdout + install.stderr

    # Edit a joint limit: the hook rebuilds the model, so the commit fails...
    arm = repo / "robots" / "arm"
    limits = arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    first = git("commit", "-am", "narrower elbow", cwd=repo, check=False, env=env)
    assert first.returncode != 0, first.stdout + first.stderr
    assert "files were modified by this hook" in first.stdout + first.stderr
    model = (arm / "mjcf" / "example_arm.xml").read_text()
    assert 'range="-2.5 2.4"' in model

    # ...and passes once the regenerated model is staged with the change.
    git("add", "-A", cwd=repo)
    second = git("commit", "-m", "narrower elbow", cwd=repo, check=False, env=env)
    assert second.returncode == 0, second.stdout + second.stderr
    assert git("status", "--porcelain", cwd=repo).stdout.strip() == ""
    return second.stdout + second.stderr


def test_readme_config_with_a_local_clone_and_rev(
    tmp_path, project_commit, hook_repository_home, monkeypatch
):
    monkeypatch.setenv("PRE_COMMIT_HOME", str(hook_repository_home))
    config = readme_configs()[0]
    assert "https://github.com/<owner>/mjcfbuild" in config and "<tag or commit>" in config
    config = config.replace("https://github.com/<owner>/mjcfbuild", str(ROOT))
    config = config.replace("<tag or commit>", project_commit)
    output = install_and_commit_an_edit(description_repo(tmp_path), config)
    assert "mjcfbuild build" in output


def test_readme_config_with_repo_local(tmp_path, monkeypatch):
    """The README's `repo: local` hook runs the mjcfbuild on PATH (this environment's)."""
    monkeypatch.setenv("PRE_COMMIT_HOME", str(tmp_path / "pre-commit-home"))
    config = readme_configs()[1]
    assert "repo: local" in config
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    output = install_and_commit_an_edit(description_repo(tmp_path), config, env)
    assert "mjcfbuild build" in output


def repo_without_model(tmp_path: Path) -> Path:
    """A git repository holding the example arm under robots/arm, never built."""
    repo = tmp_path / "description"
    shutil.copytree(
        EXAMPLES / "arm", repo / "robots" / "arm", ignore=shutil.ignore_patterns("mjcf")
    )
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-q", "-m", "the arm's description", cwd=repo)
    return repo


def first_commit_fails_until_the_model_is_added(repo: Path, config: str, env: dict | None) -> None:
    """Install ``config``'s hooks in a repo with no model; the first commit builds it and fails
    (so does a second one without `git add`); after `git add` the commit passes."""
    (repo / ".pre-commit-config.yaml").write_text(config)
    git("add", ".pre-commit-config.yaml", cwd=repo)
    install = subprocess.run(
        [pre_commit_executable(), "install", "--install-hooks"],
        cwd=repo,
        capture_output=True,
        text=True,
        env=env,
    )
    assert install.returncode == 0, install.stdout + install.stderr
    # The first commit's build creates the model; the second's finds it there, not added.
    for words in ("files were created", "files git does not track"):
        first = git("commit", "-m", "hooks", cwd=repo, check=False, env=env)
        output = first.stdout + first.stderr
        assert first.returncode != 0, output
        assert f"{words}: robots/arm/mjcf/example_arm.xml" in output, output
        assert "git add them" in output and "Failed" in output
    assert (repo / "robots" / "arm" / "mjcf" / "example_arm.xml").is_file()
    git("add", "-A", cwd=repo)
    tracked = git("ls-files", cwd=repo).stdout.splitlines()
    assert "robots/arm/mjcf/scene.xml" in tracked
    assert not [name for name in tracked if "/.mjcfbuild/" in name or "/report/" in name]
    passed = git("commit", "-m", "hooks and the model", cwd=repo, check=False, env=env)
    assert passed.returncode == 0, passed.stdout + passed.stderr
    assert git("status", "--porcelain", cwd=repo).stdout.strip() == ""


def test_the_first_run_fails_when_it_creates_the_model_repo_local(tmp_path, monkeypatch):
    monkeypatch.setenv("PRE_COMMIT_HOME", str(tmp_path / "pre-commit-home"))
    config = readme_configs()[1]
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    first_commit_fails_until_the_model_is_added(repo_without_model(tmp_path), config, env)


def test_the_first_run_fails_when_it_creates_the_model_hook_repository(
    tmp_path, project_commit, hook_repository_home, monkeypatch
):
    monkeypatch.setenv("PRE_COMMIT_HOME", str(hook_repository_home))
    config = readme_configs()[0].replace("https://github.com/<owner>/mjcfbuild", str(ROOT))
    config = config.replace("<tag or commit>", project_commit)
    first_commit_fails_until_the_model_is_added(repo_without_model(tmp_path), config, None)
