"""The build report is the same bytes for the same inputs, however the build ran: everything,
nothing (up to date), after files were touched, from the product cache, waiting for another
build, or through ``mjcfbuild check``; what changes from run to run goes to build-stats.json."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import run_cli
from tests.page.hostile import build, hostile_robot

pytestmark = pytest.mark.slow

REPORT_FILES = ("report.md", "report.json", "page/tables.js", "index.html")


def report_bytes(output: Path) -> dict[str, bytes]:
    return {name: (output / "report" / name).read_bytes() for name in REPORT_FILES}


def test_the_report_is_the_same_bytes_however_the_build_ran(tmp_path):
    hostile_robot(tmp_path)
    output = build(tmp_path)
    first = report_bytes(output)
    markdown = first["report.md"].decode()
    assert "## Warnings" in markdown  # the description's commas: the build warns of them
    assert "## Products (meshes, decompositions)" in markdown
    assert "1 mesh file converted" in markdown
    report = json.loads(first["report.json"])
    assert "times" not in report and "cache" not in report
    assert "Build times" not in markdown and "cache hits" not in markdown

    # Up to date: the build warned, so it leaves no no-op stamp and doit runs, running nothing.
    again = run_cli("build", "-v", cwd=tmp_path)
    assert again.code == 0 and " 0 run" in again.stdout + again.stderr, again.stderr
    assert report_bytes(output) == first

    # Every input touched: new times, same bytes.
    for path in [p for p in tmp_path.rglob("*") if p.is_file() and "mjcf" not in p.parts]:
        stat = path.stat()
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**10))
    build(tmp_path)
    assert report_bytes(output) == first

    # The check on its own writes the report too.
    checked = run_cli("check", cwd=tmp_path)
    assert checked.code == 0, checked.stderr
    assert report_bytes(output) == first

    # A whole build again, its product from the cache this time.
    shutil.rmtree(output)
    build(tmp_path)
    assert report_bytes(output) == first
    stats = json.loads((output / ".mjcfbuild" / "build-stats.json").read_text())
    assert stats["cache"]["local_hits"] == 1 and stats["times"]["assemble"] > 0

    # Two builds at once: one builds, the other waits for it and finds everything done.
    shutil.rmtree(output)
    command = [sys.executable, "-m", "mjcfbuild", "build", "-q"]
    builds = [
        subprocess.Popen(command, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        for _ in range(2)
    ]
    for process in builds:
        _, err = process.communicate(timeout=600)
        assert process.returncode == 0, err
    assert report_bytes(output) == first


def test_the_stats_keep_each_tasks_last_time_and_stay_out_of_git(tmp_path):
    hostile_robot(tmp_path, page=False)
    output = build(tmp_path)
    path = output / ".mjcfbuild" / "build-stats.json"
    stats = json.loads(path.read_text())
    assert {"expand", "plan", "assemble", "check"} <= set(stats["times"])
    assert stats["warnings"] == []  # the description's warning is the report's, not a run's
    cache = stats["cache"]  # the one mesh: computed, or from the tests' shared cache
    assert cache["computed"].get("mesh", {}).get("here", 0) + cache["local_hits"] == 1
    written = path.read_bytes()
    build(tmp_path)  # the fast no-op (the build warned, and replays its warnings) writes nothing
    assert path.read_bytes() == written
    # The whole graph, up to date: nothing ran, the times stay those of the last run.
    again = run_cli("build", cwd=tmp_path, env={"MJCFBUILD_FULL_BUILD": "1"})
    assert again.code == 0, again.stderr
    later = json.loads(path.read_text())
    assert later["times"] == stats["times"] and later["cache"] is None
    ignored = (output / ".mjcfbuild" / ".gitignore").read_text().splitlines()
    assert "*" in ignored


def test_turning_the_page_off_removes_only_what_builds_wrote(tmp_path):
    """Without output.page, the page an earlier build wrote goes; a file the user keeps in the
    report folder stays (issue 40)."""
    from tests.conftest import copy_example, run_cli

    arm = copy_example("arm", tmp_path)
    manifest = arm / "robot.yaml"
    text = manifest.read_text()
    manifest.write_text(text + "  page: true\ncheck:\n  enabled: false\n")
    assert run_cli("build", str(manifest)).code == 0
    report = arm / "mjcf" / "report"
    assert (report / "index.html").is_file() and (report / "page" / "tables.js").is_file()
    (report / "page" / "notes.md").write_text("mine\n")
    manifest.write_text(text + "check:\n  enabled: false\n")
    assert run_cli("build", str(manifest)).code == 0
    assert not (report / "index.html").exists() and not (report / "page" / "tables.js").exists()
    assert (report / "page" / "notes.md").read_text() == "mine\n"


def test_the_report_keeps_warnings_of_tasks_that_did_not_run_again(tmp_path):
    """After a build whose assembly warned, a rebuild that only runs the check keeps them."""
    import json

    from tests.cli.test_warning_groups import padded_robot
    from tests.conftest import run_cli

    folder = padded_robot(tmp_path)
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    # Now the check and previews run; the assembly that warned is up to date.
    again = run_cli("build", cwd=folder)
    assert again.code == 0, again.stderr
    report = json.loads((folder / "mjcf" / "report" / "report.json").read_text())
    assert report["warnings"] == [
        f"robot.urdf:15: link 'pad{i}' visual 0 has box size 0 0 0; dropped it" for i in range(8)
    ]
    text = (folder / "mjcf" / "report" / "report.md").read_text()
    listed = [line for line in text.splitlines() if line.startswith("- ") and "box size" in line]
    assert len(listed) == 8


def test_a_warning_fixed_in_the_source_leaves_the_report(tmp_path):
    import json

    from tests.cli.test_warning_groups import padded_robot
    from tests.conftest import run_cli

    folder = padded_robot(tmp_path)
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    urdf = folder / "robot.urdf"
    urdf.write_text(urdf.read_text().replace('size="0 0 0"', 'size="0.1 0.1 0.1"'))
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    report = json.loads((folder / "mjcf" / "report" / "report.json").read_text())
    assert report["warnings"] == []


def test_a_build_without_the_check_reports_no_check_of_another_model(tmp_path):
    """--no-check after an edit: the report is of the new model, and the last check was of
    the old one; it must not say "checks pass" over a model the check would fail."""
    from tests.conftest import copy_example

    arm = copy_example("arm", tmp_path)
    assert run_cli("build", "-q", cwd=arm).code == 0
    report = arm / "mjcf" / "report" / "report.md"
    assert "Result: all checks pass." in report.read_text()
    limits = arm / "config" / "joint_limits.yaml"
    limits.write_text(limits.read_text().replace("effort: 60.0", "effort: 1.0"))
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    text = report.read_text()
    assert "Result:" not in text
    assert "Not run on this model: it was built with --no-check" in text
    # Checked, then built again without the check and no change: that check speaks for it.
    assert run_cli("build", "-q", cwd=arm).code == 6  # the check fails the weak servos
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    assert "Result: **checks failed**" in report.read_text()
