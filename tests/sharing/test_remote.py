"""The remote cache end to end: two machines share products through S3 (moto), a shared
folder and read-only HTTP; bad objects, a dead endpoint and wrong credentials are survived."""

from __future__ import annotations

import functools
import http.server
import threading

from mjcfbuild.sharing.blob import verify
from tests.conftest import run_cli
from tests.sharing.conftest import PRODUCTS, SECRET, free_port, s3_objects


def only_remote_warnings(result) -> list[str]:
    return [w for w in result.warnings if "remote cache" in w]


def test_second_machine_gets_every_product_from_s3(machines, s3_remote, monkeypatch):
    first, second = machines
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", s3_remote)
    first.build(monkeypatch)
    made = first.report()
    assert made["computed"] == {
        "decompose": {"here": 1, "on_cluster": 0},
        "mesh": {"here": 4, "on_cluster": 0},
    }
    assert made["remote_misses"] == PRODUCTS and made["uploaded"] == PRODUCTS
    objects = s3_objects(s3_remote)
    assert len(objects) == PRODUCTS
    for name, data in objects.items():
        verify(name.rsplit("/", 1)[1], data)  # complete, intact, under its own key

    result = second.build(monkeypatch)
    got = second.report()
    assert got["computed_here"] == 0 and got["computed"] == {}  # converted, decomposed nothing
    assert got["remote_hits"] == PRODUCTS and got["uploaded"] == 0
    assert not result.warnings
    assert second.outputs() == first.outputs()

    shown = run_cli("cache", "show", env={"MJCFBUILD_CACHE_DIR": str(second.cache)})
    assert f"remote {s3_remote}: last build {PRODUCTS} hits, 0 misses" in shown.stdout

    # Nothing secret reaches outputs, logs, reports or the caches.
    for root in (first.folder, second.folder, first.cache, second.cache):
        for path in root.rglob("*"):
            assert not path.is_file() or SECRET.encode() not in path.read_bytes(), path


def test_shared_folder_and_read_only_http(machines, tmp_path, monkeypatch):
    first, second = machines
    shared = tmp_path / "shared"
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", str(shared))
    first.build(monkeypatch)
    assert first.report()["uploaded"] == PRODUCTS
    assert not list(shared.rglob("*.tmp"))

    # The same folder served over HTTP: readable, never written.
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(shared))
    handler.log_message = lambda *args: None
    server = http.server.ThreadingHTTPServer(("127.0.0.1", free_port()), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        url = f"http://127.0.0.1:{server.server_address[1]}/"
        monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", url)
        result = second.build(monkeypatch)
    finally:
        server.shutdown()
    got = second.report()
    assert got["remote_hits"] == PRODUCTS and got["computed_here"] == 0
    assert not result.warnings
    assert second.outputs() == first.outputs()


def test_bad_objects_are_rebuilt_warned_once_and_replaced(machines, tmp_path, monkeypatch):
    first, second = machines
    shared = tmp_path / "shared"
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", str(shared))
    first.build(monkeypatch)
    objects = sorted(p for p in shared.rglob("*") if p.is_file())
    assert len(objects) == PRODUCTS
    corrupted, truncated, foreign = objects[:3]
    data = bytearray(corrupted.read_bytes())
    data[-10] ^= 0xFF
    corrupted.write_bytes(bytes(data))
    truncated.write_bytes(truncated.read_bytes()[:-100])
    foreign.write_bytes(objects[3].read_bytes())  # another product under this one's key

    result = second.build(monkeypatch)
    got = second.report()
    assert got["remote_rejected"] == 3 and got["remote_hits"] == PRODUCTS - 3
    assert got["computed_here"] == 3 and got["uploaded"] == 3
    warnings = only_remote_warnings(result)
    assert len(warnings) == 1 and "ignored object" in warnings[0]
    assert second.outputs() == first.outputs()  # never used: rebuilt, same bytes
    for path in objects:  # the remote is healed
        verify(path.name, path.read_bytes())


def test_unreachable_endpoint_is_a_warning(machines, s3_remote, monkeypatch):
    first, _ = machines
    monkeypatch.setenv("AWS_ENDPOINT_URL", f"http://127.0.0.1:{free_port()}")
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", s3_remote)
    result = first.build(monkeypatch)
    warnings = only_remote_warnings(result)
    assert len(warnings) == 1 and "cannot be used" in warnings[0], result.warnings
    got = first.report()
    assert got["computed_here"] == PRODUCTS and got["remote_errors"] == 1
    assert first.outputs()


def test_wrong_credentials_are_a_warning(machines, tmp_path, monkeypatch):
    import os
    import subprocess
    import sys
    import time
    import urllib.request

    first, _ = machines
    port = free_port()
    # A server that checks credentials: after one unauthenticated action (the bucket), every
    # request must carry a key known to its IAM, and ours is not.
    server = subprocess.Popen(
        [sys.executable, "-m", "moto.server", "-H", "127.0.0.1", "-p", str(port)],
        env={**os.environ, "INITIAL_NO_AUTH_ACTION_COUNT": "1"},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        endpoint = f"http://127.0.0.1:{port}"
        deadline = time.monotonic() + 30
        while True:
            try:
                urllib.request.urlopen(f"{endpoint}/moto-api/", timeout=1)
                break
            except OSError:
                assert time.monotonic() < deadline, "moto server did not start"
                time.sleep(0.1)
        import boto3

        boto3.client(
            "s3",
            endpoint_url=endpoint,
            region_name="us-east-1",
            aws_access_key_id="setup",
            aws_secret_access_key="setup",
        ).create_bucket(Bucket="guarded-products")
        monkeypatch.setenv("AWS_ENDPOINT_URL", endpoint)
        monkeypatch.setenv("AWS_ACCESS_KEY_ID", "not-a-known-key")
        monkeypatch.setenv("AWS_SECRET_ACCESS_KEY", SECRET)
        monkeypatch.setenv("AWS_CONFIG_FILE", str(tmp_path / "none"))
        monkeypatch.setenv("AWS_SHARED_CREDENTIALS_FILE", str(tmp_path / "none"))
        monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", "s3://guarded-products/team")
        result = first.build(monkeypatch)
    finally:
        server.kill()
        server.wait()
    warnings = only_remote_warnings(result)
    assert len(warnings) == 1 and "refused access" in warnings[0], result.warnings
    assert SECRET not in warnings[0]
    assert first.report()["computed_here"] == PRODUCTS


def test_no_remote_flag_turns_it_off_for_one_build(machines, tmp_path, cli):
    first, _ = machines
    env = {
        "MJCFBUILD_CACHE_REMOTE": str(tmp_path / "shared"),
        "MJCFBUILD_CACHE_DIR": str(first.cache),
    }
    done = cli("build", "--no-check", "--no-remote", "-q", cwd=first.folder, env=env)
    assert done.code == 0, done.stderr
    assert first.report()["remote"] is None
    assert not (tmp_path / "shared").exists()


# --- Issue 32: deadlines and signatures -----------------------------------------------------


def test_a_server_that_stops_answering_at_lookup_costs_one_deadline(
    machines, s3_process, monkeypatch
):
    import os
    import signal

    first, _ = machines
    os.kill(s3_process.process.pid, signal.SIGSTOP)
    env = {
        "MJCFBUILD_CACHE_REMOTE": s3_process.remote,
        "MJCFBUILD_REMOTE_TIMEOUT": "1",
        "MJCFBUILD_CACHE_DIR": str(first.cache),
        "MJCFBUILD_RESIDENT_WORKERS": "0",
    }
    # Before: 910 s of silence (run_cli gives up after 600 s).
    result = run_cli("build", "--no-check", "-j", "2", cwd=first.folder, env=env)
    assert result.code == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if "remote cache" in line]
    assert len(warnings) == 1 and "did not answer in time" in warnings[0], result.stderr
    made = first.report()
    assert made["computed_here"] == PRODUCTS and made["remote_hits"] == 0


def test_a_server_that_stops_answering_at_upload_is_given_up_after_the_deadline(
    s3_process, tmp_path
):
    import os
    import signal

    from mjcfbuild.products.store import ProductStore
    from mjcfbuild.sharing.remote import RemoteCache
    from mjcfbuild.sharing.stats import ShareStats
    from mjcfbuild.sharing_settings import parse_remote
    from tests.sharing.test_blob import KEY, product

    store = ProductStore(tmp_path / "store")
    made = store.temporary_folder(KEY)
    store.store(KEY, made, product(made))
    warnings: list[str] = []
    environ = {**os.environ, "MJCFBUILD_REMOTE_TIMEOUT": "1"}
    stats = ShareStats()
    remote = RemoteCache(parse_remote(s3_process.remote), stats, warnings.append, environ)
    os.kill(s3_process.process.pid, signal.SIGSTOP)
    remote.upload_later(KEY, store)
    remote.wait()  # before: waited as long as the server stayed stopped
    assert len(warnings) == 1, warnings
    assert "did not answer in time" in warnings[0] or "did not take 1 upload" in warnings[0]
    assert not remote.enabled and stats.as_dict()["uploaded"] == 0


def _forge(data: bytes, key: str, folder, secret: bytes | None) -> bytes:
    """The product ``data`` with one of its files changed and every checksum recomputed, as
    anyone who may write to the bucket can do; signed with ``secret`` if given."""
    import hashlib
    import hmac

    from mjcfbuild.sharing.blob import pack

    summary, files = verify(key, data)
    folder.mkdir(parents=True)
    name = sorted(n for n in files if n.endswith(".obj"))[0]
    files[name] += b"v 9 9 9\n"
    for file, content in files.items():
        (folder / file).write_bytes(content)
    summary["files"][name] = hashlib.md5(files[name], usedforsecurity=False).hexdigest()
    forged = pack(key, folder, summary)
    if secret is None:
        return forged
    first, _, rest = forged.partition(b"\n")
    signed = hmac.new(secret, key.encode() + b"\n" + rest, hashlib.sha256).hexdigest()
    return first + f" hmac-sha256={signed}\n".encode() + rest


def test_with_a_signing_key_forged_products_are_ignored_and_rebuilt(
    machines, s3_remote, monkeypatch, tmp_path
):
    import os

    import boto3

    signing = "team-key-" + "k" * 32
    first, second = machines
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", s3_remote)
    monkeypatch.setenv("MJCFBUILD_CACHE_KEY", signing)
    first.build(monkeypatch)
    objects = s3_objects(s3_remote)
    assert len(objects) == PRODUCTS
    # Someone who may write to the bucket replaces two mesh products: one unsigned, one
    # signed with a key of their own; both pass every checksum.
    bucket = s3_remote.removeprefix("s3://").partition("/")[0]
    client = boto3.client("s3", endpoint_url=os.environ["AWS_ENDPOINT_URL"])
    meshes = [n for n, d in sorted(objects.items()) if b'.obj"' in d.partition(b"\n")[2][:2000]]
    secrets = [None, b"attacker-" + b"a" * 20]
    for index, (name, secret) in enumerate(zip(meshes[:2], secrets, strict=True)):
        key = name.rsplit("/", 1)[1]
        forged = _forge(objects[name], key, tmp_path / f"forged{index}", secret)
        client.put_object(Bucket=bucket, Key=name, Body=forged)

    result = second.build(monkeypatch)
    assert second.outputs() == first.outputs()  # before: the forged meshes were used
    got = second.report()
    assert got["remote_rejected"] == 2 and got["remote_hits"] == PRODUCTS - 2
    assert any("ignored object" in w for w in only_remote_warnings(result)), result.warnings
    # Rebuilt and uploaded again, signed.
    for name, data in s3_objects(s3_remote).items():
        verify(name.rsplit("/", 1)[1], data, signing.encode())


def test_a_short_or_unreadable_signing_key_is_a_one_line_usage_error(arm, tmp_path):
    env = {"MJCFBUILD_CACHE_REMOTE": str(tmp_path / "shared"), "MJCFBUILD_CACHE_KEY": "short"}
    result = run_cli("build", "--no-check", cwd=arm, env=env)
    assert result.code == 2 and result.stderr.count("\n") <= 2, result.stderr
    assert "shorter than 16 characters" in result.stderr and "Traceback" not in result.stderr
    env = {
        "MJCFBUILD_CACHE_REMOTE": str(tmp_path / "shared"),
        "MJCFBUILD_CACHE_KEY_FILE": str(tmp_path / "missing-key"),
    }
    result = run_cli("build", "--no-check", cwd=arm, env=env)
    assert result.code == 2 and "signing key file cannot be read" in result.stderr


def _unusable(data: bytes, key: str, folder) -> bytes:
    """The product ``data`` with a summary that names a file it does not contain, every
    checksum right: what a buggy or hostile writer can upload."""
    from mjcfbuild.sharing.blob import pack

    summary, files = verify(key, data)
    folder.mkdir(parents=True)
    for name, content in files.items():
        (folder / name).write_bytes(content)
    if "parts" in summary and "collision" not in summary:  # a decomposition
        summary["parts"].append("part999.obj")
    else:
        summary["collision"] = "ghost.obj"
    return pack(key, folder, summary)


def test_products_whose_summary_names_a_missing_file_never_break_a_build(
    machines, s3_remote, monkeypatch, tmp_path
):
    import os

    import boto3

    first, second = machines
    monkeypatch.setenv("MJCFBUILD_CACHE_REMOTE", s3_remote)
    first.build(monkeypatch)
    objects = s3_objects(s3_remote)
    assert len(objects) == PRODUCTS
    bucket = s3_remote.removeprefix("s3://").partition("/")[0]
    client = boto3.client("s3", endpoint_url=os.environ["AWS_ENDPOINT_URL"])
    for index, (name, data) in enumerate(sorted(objects.items())):
        bad = _unusable(data, name.rsplit("/", 1)[1], tmp_path / f"bad{index}")
        verify(name.rsplit("/", 1)[1], bad)  # passes every checksum
        client.put_object(Bucket=bucket, Key=name, Body=bad)

    result = second.build(monkeypatch)  # before: exit 70, KeyError 'ghost.obj'
    got = second.report()
    assert got["remote_rejected"] == PRODUCTS and got["remote_hits"] == 0
    assert got["computed_here"] == PRODUCTS and got["uploaded"] == PRODUCTS
    warnings = only_remote_warnings(result)
    assert len(warnings) == 1 and "does not contain" in warnings[0], result.warnings
    assert second.outputs() == first.outputs()
    healed = s3_objects(s3_remote)
    assert sorted(healed) == sorted(objects)
    for name, data in healed.items():  # uploaded again over the unusable ones
        verify(name.rsplit("/", 1)[1], data)
        assert b"ghost.obj" not in data and b"part999.obj" not in data
    # Nothing unusable was stored: a build without the remote uses the local cache alone.
    (second.folder / "mjcf").rename(second.folder / "old")
    monkeypatch.delenv("MJCFBUILD_CACHE_REMOTE")
    second.build(monkeypatch)  # raises BuildFailed if a step failed
    assert second.report()["local_hits"] == PRODUCTS


def test_an_unusable_local_entry_is_dropped_counted_and_rebuilt(machines, monkeypatch):
    import json
    import shutil

    first, _ = machines
    first.build(monkeypatch)
    summaries = sorted(first.cache.rglob("summary.json"))
    assert summaries
    for path in summaries:  # each names a file its entry does not hold
        summary = json.loads(path.read_text())
        if "parts" in summary and "collision" not in summary:
            summary["parts"].append("part999.obj")
        elif "collision" in summary:
            summary["collision"] = "ghost.obj"
        else:
            (path.parent / "matrix.json").unlink()
        path.write_text(json.dumps(summary))
    before = first.outputs()
    shutil.rmtree(first.folder / "mjcf")

    first.build(monkeypatch)  # before: exit 70
    got = first.report()
    assert got["local_dropped"] == PRODUCTS and got["computed_here"] == PRODUCTS
    assert first.outputs() == before
    shutil.rmtree(first.folder / "mjcf")
    first.build(monkeypatch)  # the rebuilt products were stored: used from now on
    assert first.report()["local_hits"] == PRODUCTS and first.report()["local_dropped"] == 0
