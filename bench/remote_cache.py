"""A fresh CI runner with a warm remote cache: what it costs to build a robot there.

    python bench/remote_cache.py [--robots g1] [--decompose/--no-decompose]

For each robot (copied from example-robot-data), a real S3 API server (moto) runs on loopback
and three "machines" build it with the ``mjcfbuild`` command line, each with its own empty local
product cache and output folder:

1. the first runner: cold, nothing in the remote; it computes every product and uploads it;
2. a fresh runner: cold locally, the remote warm; it should compute nothing;
3. the fresh runner again, unchanged: the no-op build, with the remote still configured.

Times are wall clock; the counters come from each build's report (report/report.json).
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench import robot_data


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def build(manifest: Path, env: dict) -> tuple[float, dict]:
    """Seconds of one ``mjcfbuild build -j 2`` and its cache counters (build-stats.json)."""
    started = time.perf_counter()
    process = subprocess.run(
        [sys.executable, "-m", "mjcfbuild", "build", str(manifest), "-q", "-j", "2", "--no-check"],
        capture_output=True,
        text=True,
        env=env,
    )
    seconds = time.perf_counter() - started
    if process.returncode != 0 or "warning" in process.stderr:
        raise SystemExit(f"build of {manifest} failed or warned:\n{process.stderr}")
    stats = json.loads((manifest.parent / "mjcf" / ".mjcfbuild" / "build-stats.json").read_text())
    return seconds, stats.get("cache") or {}


def machine(robot: robot_data.Robot, folder: Path, decompose: bool) -> Path:
    """A private copy of the robot and its manifest under ``folder``."""
    urdf, packages = robot_data.copy_robot(robot, folder)
    extra = "collision:\n  default: decompose\n" if decompose else ""
    return robot_data.manifest(robot, folder, urdf, packages, extra=extra)


def remote_bytes(endpoint: str, bucket: str) -> tuple[int, int]:
    """Objects and bytes stored in the bucket."""
    import boto3

    client = boto3.client("s3", endpoint_url=endpoint)
    listing = client.list_objects_v2(Bucket=bucket).get("Contents", [])
    return len(listing), sum(item["Size"] for item in listing)


def measure(name: str, decompose: bool, scratch: Path) -> dict:
    from moto.server import ThreadedMotoServer

    robot = robot_data.ROBOTS[name]
    bucket = f"mjcfbuild-bench-{name.replace('_', '-')}"  # moto keeps buckets per process
    port = free_port()
    server = ThreadedMotoServer(ip_address="127.0.0.1", port=port, verbose=False)
    server.start()
    endpoint = f"http://127.0.0.1:{port}"
    env = dict(os.environ)
    env.update(
        {
            "AWS_ENDPOINT_URL": endpoint,
            "AWS_ACCESS_KEY_ID": "bench",
            "AWS_SECRET_ACCESS_KEY": "bench",
            "AWS_DEFAULT_REGION": "us-east-1",
            "MJCFBUILD_CACHE_REMOTE": f"s3://{bucket}/ci",
        }
    )
    os.environ.update({k: env[k] for k in ("AWS_ACCESS_KEY_ID", "AWS_SECRET_ACCESS_KEY")})
    import boto3

    boto3.client("s3", endpoint_url=endpoint, region_name="us-east-1").create_bucket(Bucket=bucket)
    row: dict = {"robot": name, "decompose": decompose}
    try:
        first = machine(robot, scratch / name / "first", decompose)
        fresh = machine(robot, scratch / name / "fresh", decompose)
        env["MJCFBUILD_CACHE_DIR"] = str(scratch / name / "first-cache")
        row["first"], made = build(first, env)
        row["products"] = made["computed_here"]
        row["objects"], row["bytes"] = remote_bytes(endpoint, bucket)
        env["MJCFBUILD_CACHE_DIR"] = str(scratch / name / "fresh-cache")
        row["fresh"], got = build(fresh, env)
        row["remote_hits"], row["computed"] = got["remote_hits"], got["computed_here"]
        time.sleep(2.1)  # let the hash cache trust the fresh files' timestamps
        build(fresh, env)
        row["noop"] = min(build(fresh, env)[0] for _ in range(3))
    finally:
        server.stop()
    return row


def print_table(rows: list[dict]) -> None:
    print("\nA fresh runner with a warm remote cache (S3 API on loopback), -j 2, seconds\n")
    print(
        "| robot | collision | products | first runner (computes, uploads) "
        "| fresh runner, warm remote | computed there | remote hits | no-op | remote size |"
    )
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        policy = "decompose all" if row["decompose"] else "default"
        print(
            f"| {row['robot']} | {policy} | {row['products']} | {row['first']:.2f} "
            f"| {row['fresh']:.2f} | {row['computed']} | {row['remote_hits']} "
            f"| {row['noop']:.3f} | {row['bytes'] / 1e6:.1f} MB in {row['objects']} objects |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default="g1", help="example-robot-data robots")
    parser.add_argument(
        "--decompose",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="decompose every collision mesh with CoACD (g1: about 15 minutes cold)",
    )
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for name in [n for n in args.robots.split(",") if n]:
            rows.append(measure(name, args.decompose, Path(scratch)))
            print(f"measured {name}", file=sys.stderr)
    print_table(rows)


if __name__ == "__main__":
    main()
