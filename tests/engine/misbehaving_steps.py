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


def reuse_heap(payload: dict) -> dict:
    """Allocate, touch and free a block of ``payload["megabytes"]`` twice: the page faults
    each round cost (a block the C heap kept costs none the second time)."""
    import resource

    libc = ctypes.CDLL("libc.so.6")
    libc.malloc.restype = ctypes.c_void_p
    libc.free.argtypes = [ctypes.c_void_p]
    size = payload["megabytes"] << 20
    faults = []
    for _ in range(2):
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        block = libc.malloc(size)
        ctypes.memset(block, 1, size)
        faults.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
        libc.free(block)
    return {"faults": faults}
