"""What a step's output depends on besides its inputs (steps/versions.py): the formats of the
steps whose products the machine-wide cache keeps are declared once, below the steps, and their
families read them from there."""

from __future__ import annotations

from dataclasses import replace
from importlib import metadata

import pytest

from mjcfbuild.families import decompose, mesh, selfcollision
from mjcfbuild.steps import mesh as mesh_step
from mjcfbuild.steps.versions import DECOMPOSE, MESH, SELFCOLLISION, StepFormat, tool_version
from mjcfbuild.version import __version__


@pytest.mark.parametrize(
    ("family", "step"),
    [(mesh.FAMILY, MESH), (decompose.FAMILY, DECOMPOSE), (selfcollision.FAMILY, SELFCOLLISION)],
    ids=["mesh", "decompose", "selfcollision"],
)
def test_a_cached_steps_family_declares_the_format_and_tools_the_step_keys_by(family, step):
    assert (family.name, family.format, family.tools) == (step.name, step.format, step.tools)
    assert family.versions() == step.versions()


def test_the_versions_are_the_installed_tools_the_format_and_mjcfbuild():
    versions = StepFormat("toy", 4, ("numpy", "no-such-distribution-here")).versions()

    assert versions == {
        "numpy": metadata.version("numpy"),
        "no-such-distribution-here": "missing",
        "mjcfbuild-step": "toy-4",
        "mjcfbuild": __version__,
    }
    assert tool_version("numpy") == metadata.version("numpy")


def test_every_tool_a_family_declares_has_the_version_importlib_reads():
    from mjcfbuild.families.registry import FAMILIES

    tools = {tool for family in FAMILIES for tool in family.tools}
    assert tools >= {"mujoco", "numpy", "trimesh"}
    for tool in sorted(tools):
        try:
            expected = metadata.version(tool)
        except metadata.PackageNotFoundError:
            expected = "missing"
        assert tool_version(tool) == expected, tool


def test_a_version_is_read_from_a_dist_info_folder_first_on_the_path(tmp_path, monkeypatch):
    from mjcfbuild.steps import versions

    for folder, version in (("first", "1.2.3"), ("second", "9.9.9")):
        (tmp_path / folder / f"toy_tool-{version}.dist-info").mkdir(parents=True)
    monkeypatch.setattr("sys.path", [str(tmp_path / "first"), str(tmp_path / "second")])
    versions._installed_versions.cache_clear()
    versions.tool_version.cache_clear()
    try:
        assert tool_version("Toy.Tool") == "1.2.3"  # names compare as PEP 503 says
    finally:
        versions._installed_versions.cache_clear()
        versions.tool_version.cache_clear()


def test_a_mesh_format_bump_changes_the_key_its_products_are_kept_under(tmp_path, monkeypatch):
    source = tmp_path / "part.stl"
    source.write_text("solid part\nendsolid part\n")
    params = {"scale": [1.0, 1.0, 1.0]}
    before = mesh_step._key(params, source, [])
    assert mesh_step._key(params, source, []) == before  # the same inputs, the same key

    monkeypatch.setattr(mesh_step, "MESH", replace(MESH, format=MESH.format + 1))

    assert mesh_step._key(params, source, []) != before
