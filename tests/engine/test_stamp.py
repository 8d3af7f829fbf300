"""The no-op fast path agrees with the full build: it skips exactly when the full build runs nothing."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mjcfbuild.engine import stamp
from tests.conftest import run_cli, write

FULL = {stamp.DISABLE_VARIABLE: "1"}


def fast_path_skips(folder: Path, check: bool = False) -> bool:
    """Whether ``mjcfbuild build`` would stop at the stamp (asked in a process of its own)."""
    probe = (
        "import sys; from mjcfbuild.engine.stamp import nothing_to_do; "
        f"print(nothing_to_do('robot.yaml', run_check={check}) is not None)"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe], cwd=folder, capture_output=True, text=True, check=True
    )
    return done.stdout.strip() == "True"


def full_build_runs(folder: Path, *flags: str) -> int:
    """How many tasks the full build runs (it also writes the next stamp)."""
    done = run_cli("build", "--no-check", *flags, cwd=folder, env=FULL)
    assert done.code == 0, done.stderr
    return int(re.search(r"(\d+) run", done.stdout).group(1))


def agree(folder: Path) -> bool:
    """The fast path's decision, after asserting that the full build agrees with it."""
    skips = fast_path_skips(folder)
    runs = full_build_runs(folder)
    assert skips == (runs == 0), f"fast path skips: {skips}, full build ran {runs}"
    return skips


@pytest.fixture
def built_arm(arm):
    assert full_build_runs(arm) > 0
    return arm


def test_the_fast_path_agrees_with_the_full_build_edit_by_edit(built_arm):
    arm = built_arm
    assert agree(arm)  # nothing changed

    later = time.time() + 100  # touched, same bytes: sources, included xacro, meshes, outputs
    for path in arm.rglob("*"):
        if path.is_file():
            os.utime(path, (later, later))
    assert agree(arm)

    finger = arm / "urdf" / "finger.xacro"  # found by xacro, not named in robot.yaml
    finger.write_text(finger.read_text() + "\n<!-- edited -->\n")
    assert not agree(arm)

    limits = arm / "config" / "joint_limits.yaml"  # a YAML file xacro loaded
    limits.write_text(limits.read_text() + "\n# edited\n")
    assert not agree(arm)

    mesh = arm / "meshes" / "forearm.obj"
    mesh.write_text(re.sub(r"(\nv\s+)(-?[0-9.]+)", r"\g<1>0.25", mesh.read_text(), count=1))
    assert not agree(arm)

    model = arm / "mjcf" / "example_arm.xml"  # an output edited by hand: the build keeps it
    model.write_text(model.read_text().replace("<mujoco", "<!-- mine -->\n<mujoco", 1))
    assert not fast_path_skips(arm)
    assert run_cli("build", "--no-check", cwd=arm, env=FULL).code == 7
    assert "<!-- mine -->" in model.read_text()
    model.unlink()  # then removed: the build writes it again
    assert not agree(arm)

    (arm / "mjcf" / "assets" / "base.obj").unlink()  # an output deleted
    assert not agree(arm)

    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text() + "options:\n  link_sites: fused\n")
    assert not agree(arm)
    assert agree(arm)


def test_a_same_size_edit_whose_mtime_was_restored_is_rebuilt(arm):
    """``cp -p``, ``rsync -a``, ``tar`` and ``os.utime`` leave an edited file its old size and
    time: the fast path and the full build both see the new bytes."""
    hour_ago = time.time() - 3600  # a checkout or an unpacked archive, not just written
    for path in arm.rglob("*"):
        if path.is_file():
            os.utime(path, (hour_ago, hour_ago))
    assert full_build_runs(arm) > 0
    assert agree(arm)

    finger = arm / "urdf" / "finger.xacro"  # edited in place: the same inode
    before = os.stat(finger)
    finger.write_text(finger.read_text().replace('<mass value="0.02"/>', '<mass value="0.03"/>'))
    os.utime(finger, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert os.stat(finger).st_size == before.st_size
    assert not agree(arm)
    assert 'mass="0.03"' in (arm / "mjcf" / "example_arm.xml").read_text()

    limits = arm / "config" / "joint_limits.yaml"  # replaced by a copy that kept its times
    before = os.stat(limits)
    edited = arm / "joint_limits.new"
    edited.write_text(limits.read_text().replace("upper: 2.5", "upper: 2.4"))
    os.utime(edited, ns=(before.st_atime_ns, before.st_mtime_ns))
    os.replace(edited, limits)
    assert os.stat(limits).st_size == before.st_size
    assert not agree(arm)
    assert agree(arm)


def test_environment_variables_fall_through(built_arm, monkeypatch):
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(built_arm))
    assert not agree(built_arm)  # expand and plan take the ROS environment as parameters
    assert agree(built_arm)
    monkeypatch.delenv("ROS_PACKAGE_PATH")
    assert not agree(built_arm)


def test_variables_and_files_xacro_looked_for_are_dependencies(tmp_path, monkeypatch):
    write(
        tmp_path / "r.xacro",
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<link name="$(optenv LINK_NAME base)"/></robot>',
    )
    write(tmp_path / "robot.yaml", "name: r\nsource:\n  xacro: r.xacro\n")
    monkeypatch.delenv("LINK_NAME", raising=False)
    full_build_runs(tmp_path)
    assert agree(tmp_path)
    monkeypatch.setenv("LINK_NAME", "torso")
    assert not agree(tmp_path)
    assert 'name="torso"' in (tmp_path / "mjcf" / "r.xml").read_text()
    assert agree(tmp_path)


def test_the_check_and_no_check_builds_have_their_own_stamps(built_arm):
    assert fast_path_skips(built_arm, check=False)
    assert not fast_path_skips(built_arm, check=True)  # the check has never run here


def test_a_failed_build_leaves_no_stamp(built_arm):
    finger = built_arm / "urdf" / "finger.xacro"
    finger.write_text("<robot")
    assert run_cli("build", "--no-check", cwd=built_arm).code != 0
    assert not fast_path_skips(built_arm)
    assert not stamp.stamp_path(built_arm.resolve() / "robot.yaml", False).exists()


@pytest.mark.parametrize("ros", [False, True])
def test_a_no_op_imports_no_engine_doit_pydantic_or_heavy_module(built_arm, ros, tmp_path):
    # With ROS_PACKAGE_PATH set, the no-op also takes what it offers package lookup
    # (sources.packages.environment_index) by folder listings alone: no package.xml is parsed.
    env = dict(os.environ)
    if ros:
        for name in ("a_pkg", "b_pkg"):
            (tmp_path / "ws" / name).mkdir(parents=True)
            (tmp_path / "ws" / name / "package.xml").write_text(
                f"<package><name>{name}</name></package>"
            )
        env["ROS_PACKAGE_PATH"] = str(tmp_path / "ws")
        subprocess.run(
            [sys.executable, "-m", "mjcfbuild", "build", "--no-check", "-q"],
            cwd=built_arm,
            env=env,
            check=True,
        )
    probe = (
        "import sys\n"
        "from mjcfbuild.cli import run\n"
        "code = run(['build', '--no-check'])\n"
        "print('imported:', ','.join(sorted(m for m in sys.modules if m.split('.')[0] in "
        "('doit', 'pydantic', 'yaml', 'numpy', 'mujoco', 'trimesh', 'lxml', 'fsspec', 'dask')"
        " or m.startswith(('mjcfbuild.engine.', 'mjcfbuild.manifest')) "
        "and m != 'mjcfbuild.engine.stamp')))\n"
        "sys.exit(code)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe], cwd=built_arm, capture_output=True, text=True, env=env
    )
    assert done.returncode == 0, done.stderr
    assert "0 run, 9 up to date" in done.stdout
    [imported] = [line for line in done.stdout.splitlines() if line.startswith("imported:")]
    assert imported.strip() == "imported:"


def test_a_build_that_warned_leaves_a_stamp_and_its_no_op_prints_the_warnings(tmp_path):
    from tests.cli.test_warning_groups import padded_robot, warning_lines

    folder = padded_robot(tmp_path)
    built = run_cli("build", "--no-check", cwd=folder)
    assert built.code == 0 and "8 warnings" in built.stdout
    assert fast_path_skips(folder)
    again = run_cli("build", "--no-check", cwd=folder)
    assert again.code == 0, again.stderr
    assert warning_lines(again.stderr) == warning_lines(built.stderr) != []
    assert re.search(r": 0 run, \d+ up to date, 8 warnings in ", again.stdout)
    # The warnings are the model's, whichever task gave them: a build that runs only the
    # check (the assembly that warned is up to date) prints them, and so does its no-op.
    checked = run_cli("build", cwd=folder)
    assert checked.code == 0 and ": 4 run, 5 up to date, 8 warnings in " in checked.stdout
    assert set(warning_lines(built.stderr)) <= set(warning_lines(checked.stderr))
    noop = run_cli("build", cwd=folder)
    assert ": 0 run, " in noop.stdout
    assert warning_lines(noop.stderr) == warning_lines(checked.stderr)
    urdf = folder / "robot.urdf"  # fixed: the next no-op is silent
    urdf.write_text(urdf.read_text().replace('size="0 0 0"', 'size="0.1 0.1 0.1"'))
    assert run_cli("build", "--no-check", "-q", cwd=folder).code == 0
    quiet = run_cli("build", "--no-check", cwd=folder)
    assert quiet.stderr == "" and "warning" not in quiet.stdout


def test_a_stamp_written_with_allow_outside_does_not_skip_the_guard(arm):
    from mjcfbuild.errors import EXIT_OUTPUT

    manifest = arm / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("  folder: mjcf\n", "  folder: ../out\n"))
    assert run_cli("build", "-q", "--no-check", "--allow-outside", cwd=arm).code == 0
    allowed = run_cli("build", "--no-check", "--allow-outside", cwd=arm)
    assert allowed.code == 0 and ": 0 run, " in allowed.stdout  # the fast path, with the flag
    refused = run_cli("build", "--no-check", cwd=arm)
    assert refused.code == EXIT_OUTPUT, refused.stdout
    assert "'../out'" in refused.stderr and "is outside" in refused.stderr
    assert "up to date" not in refused.stdout


def test_every_way_of_finding_the_folder_up_to_date_prints_the_same(tmp_path):
    """The fast path, the full graph finding every task up to date (MJCFBUILD_FULL_BUILD, or
    no stamp) and a rebuild of a task that did not warn print the same warning lines and the
    same summary; with -q none of them prints anything."""
    from tests.cli.test_warning_groups import padded_robot, warning_lines

    folder = padded_robot(tmp_path)
    built = run_cli("build", "--no-check", cwd=folder)
    assert built.code == 0 and "8 warnings" in built.stdout, built.stdout
    key = Path(os.path.normpath(folder / "robot.yaml"))

    def printed(env: dict | None = None, *flags: str) -> tuple[list[str], str]:
        done = run_cli("build", "--no-check", *flags, cwd=folder, env=env)
        assert done.code == 0, done.stderr
        other = [
            line for line in done.stderr.splitlines() if line not in warning_lines(done.stderr)
        ]
        assert other == [], done.stderr
        return warning_lines(done.stderr), re.sub(r"in \d+\.\d+ s", "in _ s", done.stdout)

    fast = printed()
    assert fast[0] == warning_lines(built.stderr) != []
    assert re.fullmatch(
        r"mjcfbuild: built robot\.xml: 0 run, 5 up to date, 8 warnings in _ s\n"
        r"  check: not run \(--no-check\); `mjcfbuild check` runs it\n",
        fast[1],
    )
    assert printed(FULL) == fast
    assert stamp.stamp_path(key, False).is_file()
    stamp.discard(key, False)
    assert not fast_path_skips(folder)
    assert printed() == fast  # the full graph (it leaves the stamp again)
    assert fast_path_skips(folder)
    for env in ({}, FULL):
        quiet = run_cli("build", "--no-check", "-q", cwd=folder, env=env)
        assert (quiet.code, quiet.stdout, quiet.stderr) == (0, "", "")

    # The scene reruns (another camera angle) while the assembly that warned is up to date.
    manifest = folder / "robot.yaml"
    manifest.write_text(
        manifest.read_text() + "scene: {mjcf: '<visual><global azimuth=\"120\"/></visual>'}\n"
    )
    rebuilt = run_cli("build", "--no-check", cwd=folder)
    assert rebuilt.code == 0, rebuilt.stderr
    assert warning_lines(rebuilt.stderr) == fast[0]
    assert re.search(r": [1-5] run, \d+ up to date, 8 warnings in ", rebuilt.stdout), rebuilt.stdout


@pytest.mark.parametrize("how", ["edited", "moved away"])
def test_an_input_changed_while_the_build_runs_leaves_no_stamp(arm, tmp_path, how):
    """The build stops where it would write its stamp and the mesh is edited there (or moved
    away, and back edited after the build): a step may have read the mesh before, so no stamp
    may call the model current. The next build takes the full path and converts the mesh
    again."""
    process = subprocess.Popen(
        [sys.executable, "-m", "mjcfbuild", "build", "--no-check", "-q"],
        cwd=arm,
        env={**os.environ, "MJCFBUILD_FAILPOINT": "stamp:stop"},
    )
    _, status = os.waitpid(process.pid, os.WUNTRACED)
    assert os.WIFSTOPPED(status)
    mesh = arm / "meshes" / "forearm.obj"
    edited = mesh.read_text().replace(" 0.240000", " 0.250000")
    if how == "edited":
        mesh.write_text(edited)
    else:
        mesh.rename(tmp_path / "forearm.obj")
    os.kill(process.pid, signal.SIGCONT)
    assert process.wait(timeout=600) == 0
    mesh.write_text(edited)
    assert not stamp.stamp_path(arm / "robot.yaml", False).exists()
    assert not fast_path_skips(arm)
    rebuilt = run_cli("build", "--no-check", cwd=arm)
    assert rebuilt.code == 0, rebuilt.stderr
    assert "mesh forearm" in rebuilt.stdout
    assert fast_path_skips(arm)  # that build changed nothing on the way: it left a stamp
