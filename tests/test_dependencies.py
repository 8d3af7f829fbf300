"""The installed dependencies are the versions mjcfbuild was tested with (pyproject's bounds)."""

from __future__ import annotations

import tomllib
from importlib.metadata import PackageNotFoundError, version
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
