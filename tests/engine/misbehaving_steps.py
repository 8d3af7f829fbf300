"""Build steps that crash, hang or fail, for testing the worker pool with real processes."""

from __future__ import annotations

import ctypes
import os
import time
from pathlib import Path

from mjcfbuild.errors import InputError


def segfault(payload: dict) -> dict:
    """Crash the process the way a bug in C++ code does."""
    print("about to crash", flush=True)
    ctypes.string_at(0)
    return {}


def hang(payload: dict) -> dict:
    """Never finish."""
    time.sleep(3600)
    return {}


def input_error(payload: dict) -> dict:
    """Fail the way a bad input does."""
    raise InputError("mesh is broken", file="m.stl", line=3, hint="fix it")


def bug(payload: dict) -> dict:
    """Fail the way a bug in Python code does."""
    raise ValueError("unexpected")


def echo(payload: dict) -> dict:
    """Succeed, saying which process ran the step."""
    os.write(1, b"C-level output that must not corrupt the protocol\n")
    return {"pid": os.getpid(), **payload}


def pause(payload: dict) -> dict:
    """Wait until the file ``payload["until"]`` exists, saying which process ran the step."""
    until = Path(payload["until"])
    while not until.exists():
        time.sleep(0.01)
    return {"pid": os.getpid()}


def allocator(payload: dict) -> dict:
    """The C allocator's settings this process started with (glibc reads them at start)."""
    environ = Path("/proc/self/environ").read_bytes().split(b"\0")
    return {
        name.decode(): value.decode()
        for name, _, value in (entry.partition(b"=") for entry in environ)
        if name.startswith(b"MALLOC_")
    }
