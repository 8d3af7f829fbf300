"""How many tasks a build runs at once where it is not told: ``$MJCFBUILD_JOBS``, else one per
CPU; a value that is not a number of jobs is one line and exit code 2, never ignored."""

from __future__ import annotations

import os

import pytest

from mjcfbuild.errors import EXIT_CODES, UsageError
from mjcfbuild.jobs import JOBS_VARIABLE, default_jobs
from tests.conftest import copy_example, run_cli


def test_the_variable_decides_and_without_it_one_job_per_cpu(monkeypatch):
    monkeypatch.setenv(JOBS_VARIABLE, "3")
    assert default_jobs() == 3
    monkeypatch.delenv(JOBS_VARIABLE)
    assert default_jobs() == len(os.sched_getaffinity(0))


@pytest.mark.parametrize("value", ["abc", "0", "-1", "1.5", "²"])
def test_a_value_that_is_not_a_number_of_jobs_is_refused(monkeypatch, value):
    monkeypatch.setenv(JOBS_VARIABLE, value)
    with pytest.raises(UsageError, match=f"{JOBS_VARIABLE}={value}: not a number of jobs"):
        default_jobs()


def test_the_command_line_says_so_in_one_line_and_an_explicit_j_wins(tmp_path):
    arm = copy_example("arm", tmp_path)
    refused = run_cli("build", "--no-check", cwd=arm, env={JOBS_VARIABLE: "two"})
    assert refused.code == 2 and 2 in EXIT_CODES
    assert refused.stderr.splitlines() == [
        f"mjcfbuild: error: {JOBS_VARIABLE}=two: not a number of jobs (set it to how many "
        "tasks a build runs at once (1 or more), or unset it for one per CPU)"
    ]
    assert not (arm / "mjcf").exists()
    built = run_cli("build", "--no-check", "-q", "-j", "1", cwd=arm, env={JOBS_VARIABLE: "two"})
    assert built.code == 0, built.stderr
    # Refused before the no-op fast path too, by every command that builds: the value is
    # wrong whether or not this build needed it.
    for command in (
        ["build", "--no-check"],
        ["watch", "--no-check"],
        ["convert", "-u", "urdf/arm.urdf.xacro"],
    ):
        again = run_cli(*command, cwd=arm, env={JOBS_VARIABLE: "two"})
        assert (again.code, again.stderr.splitlines()) == (2, refused.stderr.splitlines())
