"""An output robot.yaml stops asking for (output.urdf, output.package) leaves nothing of the
build's behind: its files went on looking current beside the model (real builds)."""

from __future__ import annotations

from tests.conftest import copy_example, run_cli


def _arm(tmp_path, output: str):
    """The example arm without the check, with ``output`` lines added; its folder and the
    manifest's text without them."""
    folder = copy_example("arm", tmp_path)
    manifest = folder / "robot.yaml"
    plain = manifest.read_text() + "check:\n  enabled: false\n"
    manifest.write_text(plain.replace("  folder: mjcf\n", "  folder: mjcf\n" + output))
    result = run_cli("build", "-q", cwd=folder)
    assert result.code == 0, result.stderr
    return folder, plain


def test_turning_the_urdf_export_off_removes_the_urdf_and_its_meshes(tmp_path):
    folder, plain = _arm(tmp_path, "  urdf: arm_export.urdf\n")
    out = folder / "mjcf"
    urdf, meshes = out / "arm_export.urdf", out / "arm_export_meshes"
    assert urdf.is_file() and any(meshes.iterdir())
    (folder / "robot.yaml").write_text(plain)
    stale = run_cli("check", "--up-to-date", cwd=folder)
    assert stale.code != 0 and "mjcf/arm_export.urdf" in stale.stderr, stale.stderr
    assert "no longer built (output.urdf is off)" in stale.stderr
    result = run_cli("build", cwd=folder)
    assert result.code == 0, result.stderr
    assert "removed mjcf/arm_export.urdf, mjcf/arm_export_meshes/ (" in result.stdout
    assert not urdf.exists() and not meshes.exists()
    assert not (out / ".mjcfbuild" / "urdf_export.json").exists()
    assert (out / "example_arm.xml").is_file() and any((out / "assets").iterdir())
    fresh = run_cli("check", "--up-to-date", cwd=folder)
    assert fresh.code == 0, fresh.stderr
    assert "removed" not in run_cli("build", cwd=folder).stdout  # said once


def test_a_new_name_for_the_exported_urdf_removes_the_old_one(tmp_path):
    folder, plain = _arm(tmp_path, "  urdf: arm_export.urdf\n")
    out = folder / "mjcf"
    old_meshes = sorted(path.name for path in (out / "arm_export_meshes").iterdir())
    edited = out / "arm_export_meshes" / old_meshes[0]
    edited.write_bytes(edited.read_bytes() + b"# mine\n")
    (folder / "robot.yaml").write_text(
        plain.replace("  folder: mjcf\n", "  folder: mjcf\n  urdf: renamed.urdf\n")
    )
    result = run_cli("build", cwd=folder)
    assert result.code == 0, result.stderr
    assert not (out / "arm_export.urdf").exists() and (out / "renamed.urdf").is_file()
    assert sorted(path.name for path in (out / "arm_export_meshes").iterdir()) == [edited.name]
    assert f"kept mjcf/arm_export_meshes/{edited.name} (edited since a build wrote it)" in (
        result.stdout
    )
    assert sorted(p.name for p in (out / "renamed_meshes").iterdir()) == old_meshes


def test_turning_the_package_off_removes_it_but_the_changelog_and_your_files(tmp_path):
    folder, plain = _arm(tmp_path, "  package: true\n")
    package = folder / "mjcf" / "package"
    assert (package / "example_arm.xml").is_file() and (package / "LICENSE").is_file()
    (package / "NOTES.md").write_text("mine\n")  # the user's: no build wrote it
    (folder / "robot.yaml").write_text(plain)
    result = run_cli("build", cwd=folder)
    assert result.code == 0, result.stderr
    assert sorted(path.name for path in package.iterdir()) == ["CHANGELOG.md", "NOTES.md"]
    line = next(line for line in result.stdout.splitlines() if "output.package is off" in line)
    assert line.startswith("mjcfbuild: removed ") and "files in mjcf/package/" in line
    assert "kept mjcf/package/CHANGELOG.md (the history of earlier builds" in line
    assert "mjcf/package/NOTES.md (not written by a build)" in line
    assert run_cli("check", "--up-to-date", cwd=folder).code == 0
    # On again: the package is back, its history continued.
    (folder / "robot.yaml").write_text(
        plain.replace("  folder: mjcf\n", "  folder: mjcf\n  package: true\n")
    )
    assert run_cli("build", "-q", cwd=folder).code == 0
    assert (package / "example_arm.xml").is_file() and (package / "NOTES.md").is_file()


def test_an_exported_urdf_robot_yaml_now_builds_from_is_not_removed(tmp_path):
    # Build from the URDF an earlier build exported, with output.urdf off: the export is the
    # source now, and removing it as a leftover stopped the build ("source file not found").
    from tests.conftest import two_link_urdf, write

    write(tmp_path / "robot.urdf", two_link_urdf())
    manifest = tmp_path / "robot.yaml"
    write(manifest, "name: r\nsource:\n  urdf: robot.urdf\noutput:\n  urdf: exported.urdf\n")
    assert run_cli("build", "--no-check", "-j", "1", cwd=tmp_path).code == 0
    exported = tmp_path / "mjcf" / "exported.urdf"
    assert exported.is_file()
    write(manifest, "name: r\nsource:\n  urdf: mjcf/exported.urdf\n")
    again = run_cli("build", "--no-check", "-j", "1", cwd=tmp_path)
    assert again.code == 0, again.stderr
    assert exported.is_file()
