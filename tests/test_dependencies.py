"""The installed dependencies are the versions mjcfbuild was tested with (pyproject's bounds)."""

from __future__ import annotations

import tomllib
from importlib.metadata import PackageNotFoundError, requires, version
from pathlib import Path

from packaging.requirements import Requirement

PYPROJECT = Path(__file__).resolve().parents[1] / "pyproject.toml"


def _requirements() -> list[Requirement]:
    data = tomllib.loads(PYPROJECT.read_text())
    return [Requirement(text) for text in data["project"]["dependencies"]]


def test_every_dependency_has_bounds():
    unbounded = [
        str(r) for r in _requirements() if not any(s.operator in ("<", "==") for s in r.specifier)
    ]
    assert not unbounded, f"give these an upper bound (or a pin) and its reason: {unbounded}"


def test_installed_versions_are_the_tested_ones():
    outside = []
    for requirement in _requirements():
        try:
            installed = version(requirement.name)
        except PackageNotFoundError:
            outside.append(f"{requirement.name} is not installed (wanted {requirement.specifier})")
            continue
        if not requirement.specifier.contains(installed, prereleases=True):
            outside.append(
                f"{requirement.name} {installed} is installed; mjcfbuild is tested with "
                f"{requirement.specifier} (see the reason beside it in pyproject.toml)"
            )
    assert not outside, "; ".join(outside)


def _test_extras() -> dict[str, Requirement]:
    data = tomllib.loads(PYPROJECT.read_text())
    found = [Requirement(text) for text in data["project"]["optional-dependencies"]["test"]]
    return {requirement.name: requirement for requirement in found}


def test_the_test_extras_that_made_pip_backtrack_are_one_consistent_set():
    """s3fs pins aiobotocore, which pins botocore to a few patch releases; moto needs boto3,
    each release of which pins its own botocore. Unbounded, pip walked back through 22 boto3
    releases. The bounds must hold an installed, working set: the one installed here."""
    extras = _test_extras()
    for name in ("s3fs", "aiobotocore", "boto3", "moto"):
        assert name in extras, f"bound {name} in the test extras"
        specifier = extras[name].specifier
        assert any(s.operator in ("<", "==") for s in specifier), f"{name} needs an upper bound"
        assert specifier.contains(version(name)), f"{name} {version(name)} is outside {specifier}"
    # boto3's range lies inside what the bounded aiobotocore accepts of botocore.
    aiobotocore = [Requirement(r) for r in requires("aiobotocore") or []]
    [botocore] = [r for r in aiobotocore if r.name == "botocore"]
    for boto3 in ("1.43.115", "1.43.117"):
        if extras["boto3"].specifier.contains(boto3):
            assert botocore.specifier.contains(boto3), (boto3, botocore.specifier)


def test_readme_first_command_installs_no_test_extras_and_the_second_runs_the_tests():
    import subprocess
    import sys

    root = PYPROJECT.parent
    printed = subprocess.run(
        [sys.executable, str(root / ".ci" / "readme_commands.py"), str(root / "README.md")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.splitlines()
    assert printed == [
        "python3 -m venv .venv && .venv/bin/pip install -e . && "
        ".venv/bin/mjcfbuild build examples/arm/robot.yaml",
        '.venv/bin/pip install -e ".[test]" && .venv/bin/python -m pytest -n 2 --dist loadfile',
    ]
