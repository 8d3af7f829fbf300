"""Two "machines" (each its own product cache and output folder) and the remotes they share."""

from __future__ import annotations

import json
import socket
import uuid
from dataclasses import dataclass
from pathlib import Path

import pytest

import mjcfbuild
from tests.conftest import copy_example

DECOMPOSE_UPPER_ARM = """collision:
  rules:
    - links: [upper_arm_link]
      policy: decompose
      decompose: {threshold: 0.05, preprocess_mode: "off"}
"""
# The example arm with one decomposition: 4 mesh conversions and 1 decomposition.
PRODUCTS = 5


@dataclass
class Machine:
    """A checkout of the example arm with its own product cache, as on another computer."""

    folder: Path
    cache: Path

    @property
    def manifest(self) -> Path:
        return self.folder / "robot.yaml"

    def build(self, monkeypatch, **kwargs):
        """Build with this machine's cache folder (no check: it is not what is shared)."""
        monkeypatch.setenv("MJCFBUILD_CACHE_DIR", str(self.cache))
        return mjcfbuild.build(self.manifest, jobs=2, check=False, **kwargs)

    def report(self) -> dict:
        """The last build's cache counters (build-stats.json: they are not in the report)."""
        stats = self.folder / "mjcf" / ".mjcfbuild" / "build-stats.json"
        return json.loads(stats.read_text())["cache"]

    def outputs(self) -> dict[str, bytes]:
        """The model and its assets, by relative path."""
        out = self.folder / "mjcf"
        return {
            str(p.relative_to(out)): p.read_bytes()
            for p in sorted(out.rglob("*"))
            if p.is_file() and p.relative_to(out).parts[0] not in ("report", ".mjcfbuild")
        }


def make_machine(root: Path, name: str) -> Machine:
    """A fresh machine under ``root/name``."""
    folder = copy_example("arm", root / name)
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text() + DECOMPOSE_UPPER_ARM)
    return Machine(folder, root / name / "cache")


@pytest.fixture
def machines(tmp_path) -> tuple[Machine, Machine]:
    """Two machines that share nothing but what a test gives them."""
    return make_machine(tmp_path, "one"), make_machine(tmp_path, "two")


def free_port() -> int:
    """A TCP port nobody listens on (for now)."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture(scope="session")
def s3_endpoint():
    """A real S3 API server (moto) on loopback for the whole session."""
    from moto.server import ThreadedMotoServer

    port = free_port()
    server = ThreadedMotoServer(ip_address="127.0.0.1", port=port, verbose=False)
    server.start()
    yield f"http://127.0.0.1:{port}"
    server.stop()


SECRET = "s3cr3t-" + uuid.uuid4().hex


@pytest.fixture
def s3_remote(s3_endpoint, monkeypatch, tmp_path) -> str:
    """A fresh bucket on the S3 server; the environment points the AWS tools at it."""
    monkeypatch.setenv("AWS_ENDPOINT_URL", s3_endpoint)
    monkeypatch.setenv("AWS_ACCESS_KEY_ID", "mjcfbuild-test")
    monkeypatch.setenv("AWS_SECRET_ACCESS_KEY", SECRET)
    monkeypatch.setenv("AWS_DEFAULT_REGION", "us-east-1")
    monkeypatch.setenv("AWS_CONFIG_FILE", str(tmp_path / "no-aws-config"))
    monkeypatch.setenv("AWS_SHARED_CREDENTIALS_FILE", str(tmp_path / "no-aws-credentials"))
    import boto3

    bucket = f"products-{uuid.uuid4().hex[:12]}"
    boto3.client("s3", endpoint_url=s3_endpoint).create_bucket(Bucket=bucket)
    return f"s3://{bucket}/team"


def s3_objects(remote: str) -> dict[str, bytes]:
    """Every object under ``remote`` (an s3:// URL), by key."""
    import os

    import boto3

    bucket, _, prefix = remote.removeprefix("s3://").partition("/")
    client = boto3.client("s3", endpoint_url=os.environ["AWS_ENDPOINT_URL"])
    listing = client.list_objects_v2(Bucket=bucket, Prefix=prefix).get("Contents", [])
    return {
        item["Key"]: client.get_object(Bucket=bucket, Key=item["Key"])["Body"].read()
        for item in listing
    }


@dataclass
class Server:
    """An S3 API server (moto) in a process of its own, which a test may stop with a signal."""

    process: object  # subprocess.Popen
    endpoint: str
    remote: str  # s3://<a fresh bucket>/team


@pytest.fixture
def s3_process(monkeypatch, tmp_path):
    """A real S3 API server in its own process, a fresh bucket on it, and the environment
    pointing the AWS tools at it."""
    import os
    import signal
    import subprocess
    import sys
    import time

    import boto3

    port = free_port()
    process = subprocess.Popen(
        [sys.executable, "-m", "moto.server", "-H", "127.0.0.1", "-p", str(port)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    endpoint = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 60
    while True:
        with socket.socket() as probe:
            if probe.connect_ex(("127.0.0.1", port)) == 0:
                break
        assert time.monotonic() < deadline and process.poll() is None, "moto did not start"
        time.sleep(0.05)
    monkeypatch.setenv("AWS_ENDPOINT_URL", endpoint)
    monkeypatch.setenv("AWS_ACCESS_KEY_ID", "mjcfbuild-test")
    monkeypatch.setenv("AWS_SECRET_ACCESS_KEY", SECRET)
    monkeypatch.setenv("AWS_DEFAULT_REGION", "us-east-1")
    monkeypatch.setenv("AWS_CONFIG_FILE", str(tmp_path / "no-aws-config"))
    monkeypatch.setenv("AWS_SHARED_CREDENTIALS_FILE", str(tmp_path / "no-aws-credentials"))
    bucket = f"products-{uuid.uuid4().hex[:12]}"
    boto3.client("s3", endpoint_url=endpoint).create_bucket(Bucket=bucket)
    yield Server(process, endpoint, f"s3://{bucket}/team")
    os.kill(process.pid, signal.SIGCONT)
    process.kill()
    process.wait()
