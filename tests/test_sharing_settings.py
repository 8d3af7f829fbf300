"""Remote and executor addresses: checked without importing fsspec or dask; bad ones are
one-line errors with exit 2 (command line, environment) or 3 (robot.yaml)."""

from __future__ import annotations

import importlib.util

import pytest

from mjcfbuild.sharing_settings import (
    AddressError,
    choose,
    parse_executor,
    parse_remote,
    redact,
)


@pytest.mark.parametrize(
    ("text", "protocol", "path"),
    [
        ("s3://bucket/team/robots", "s3", "bucket/team/robots"),
        ("s3://bucket", "s3", "bucket"),
        ("gs://bucket/prefix/", "gs", "bucket/prefix"),
        ("https://cache.example.org/mjcf", "https", "cache.example.org/mjcf"),
        ("file:///srv/share", "file", "/srv/share"),
        ("/mnt/team-cache", "file", "/mnt/team-cache"),
    ],
)
def test_remote_addresses(text, protocol, path):
    spec = parse_remote(text)
    assert (spec.protocol, spec.path) == (protocol, path)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("s3:/bucket", "not a URL"),
        ("relative/folder", "not a URL"),
        ("s3://", "no valid bucket"),
        ("s3://bad bucket/x", "no valid bucket"),
        ("ftp2://host/x", "not a protocol"),
        ("https://", "no valid host"),
        ("https://host:port/x", "port that is not a number"),
        ("file://host/share", "not a file URL"),
        ("  ", "empty"),
    ],
)
def test_malformed_remote_addresses(text, message):
    with pytest.raises(AddressError, match=message):
        parse_remote(text)


def test_credentials_in_an_address_are_never_shown():
    assert redact("https://user:hunter2@cache.example.org/x?token=abc") == (
        "https://cache.example.org/x"
    )
    with pytest.raises(AddressError) as info:
        parse_remote("https://user:hunter2@/x")
    assert "hunter2" not in str(info.value)


def test_executor_addresses():
    assert parse_executor("local").kind == "local"
    assert parse_executor("dask://scheduler.lan:8786").scheduler == "tcp://scheduler.lan:8786"
    assert parse_executor("dask://10.0.0.5").address == "10.0.0.5:8786"
    for bad in ("dask://", "tcp://host:8786", "dask://host:x", "dask://host/path", "ray://h"):
        with pytest.raises(AddressError):
            parse_executor(bad)


def pick(**overrides):
    arguments = {
        "manifest_remote": None,
        "manifest_executor": None,
        "environ": {},
        "cli_executor": None,
        "use_remote": True,
        "manifest_label": "robot.yaml",
    }
    return choose(**{**arguments, **overrides})


def test_the_environment_wins_over_robot_yaml_and_the_command_line_over_both():
    chosen = pick(
        manifest_remote="/from/yaml",
        manifest_executor="dask://yaml:1",
        environ={"MJCFBUILD_CACHE_REMOTE": "/from/env", "MJCFBUILD_EXECUTOR": "dask://env:2"},
    )
    assert chosen.remote.path == "/from/env" and chosen.executor.address == "env:2"
    assert pick(manifest_remote="/from/yaml").remote.path == "/from/yaml"
    assert pick(manifest_remote="/from/yaml", use_remote=False).remote is None
    assert (
        pick(environ={"MJCFBUILD_EXECUTOR": "dask://env:2"}, cli_executor="local").executor.kind
        == "local"
    )


@pytest.mark.skipif(importlib.util.find_spec("gcsfs") is not None, reason="gcsfs is installed")
def test_a_protocol_whose_package_is_missing_names_the_extra():
    from mjcfbuild.errors import UsageError

    with pytest.raises(UsageError) as info:
        pick(environ={"MJCFBUILD_CACHE_REMOTE": "gs://bucket/x"})
    assert "pip install 'mjcfbuild[gcs]'" in info.value.one_line()
    assert info.value.exit_code == 2


def write_arm(tmp_path, extra: str):
    """The example arm with ``extra`` appended to its manifest; (folder, first added line)."""
    from tests.conftest import copy_example

    folder = copy_example("arm", tmp_path)
    manifest = folder / "robot.yaml"
    text = manifest.read_text()
    manifest.write_text(text + extra)
    return folder, len(text.splitlines()) + 1


@pytest.mark.parametrize(
    ("extra", "env", "args", "code", "expected"),
    [
        ("cache:\n  remote: 'sftp2://h/x'\n", {}, [], 3, "robot.yaml:{second}:3: cache.remote"),
        ("executor: 'dask:/nowhere'\n", {}, [], 3, "robot.yaml:{first}:1: executor: 'dask:/no"),
        ("", {"MJCFBUILD_CACHE_REMOTE": "s3://"}, [], 2, "$MJCFBUILD_CACHE_REMOTE: 's3://'"),
        ("", {"MJCFBUILD_EXECUTOR": "tcp://h:1"}, [], 2, "$MJCFBUILD_EXECUTOR:"),
        ("", {}, ["--executor", "dask://h:port"], 2, "--executor: 'dask://h:port' has a port"),
    ],
)
def test_bad_addresses_are_one_line_errors(tmp_path, cli, extra, env, args, code, expected):
    folder, added = write_arm(tmp_path, extra)
    done = cli("build", "-q", *args, cwd=folder, env=env)
    assert done.code == code, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mjcfbuild: error: "), done.stderr
    assert expected.format(first=added, second=added + 1) in lines[0]
    assert not (folder / "mjcf").exists()  # refused before anything was built


@pytest.mark.skipif(importlib.util.find_spec("gcsfs") is not None, reason="gcsfs is installed")
def test_a_missing_package_in_robot_yaml_points_at_its_line(tmp_path, cli):
    folder, added = write_arm(tmp_path, "cache:\n  remote: gs://team-bucket/robots\n")
    done = cli("build", "-q", cwd=folder)
    assert done.code == 3
    assert done.stderr.strip() == (
        f"mjcfbuild: error: robot.yaml:{added + 1}:3: cache.remote: a gs:// remote cache needs a "
        "package that is not installed (pip install 'mjcfbuild[gcs]', or build with --no-remote)"
    )
