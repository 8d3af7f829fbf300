"""Step ``reference``: what the check's independent reader (yourdfpy) reads from the URDF for
forward kinematics, kept as a record for the check (see mjcfbuild.check.reference).

Reading costs about a second (importing yourdfpy, trimesh and scipy), so the record is kept in
the shared product cache under the URDF's text without its comments (xacro writes the source's
absolute path into one): another folder or a clone of the same description, whose expanded URDF
names meshes by ``package://``, not by folder, takes it from there. A record that says the
reader failed is kept too: it is what the reader makes of that text.
"""

from __future__ import annotations

import json
from pathlib import Path

from mjcfbuild.check.reference import read_kinematics, reader_input_digest
from mjcfbuild.products.store import open_store, product_key
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import ReferencePayload
from mjcfbuild.steps.versions import REFERENCE

RECORD = "reference.json"


def run(payload: dict) -> dict:
    """Read the URDF's kinematics (or take what was read of the same text from the cache) and
    write the record (one that says why, if unreadable)."""
    request = ReferencePayload.from_dict(payload)
    urdf_text = Path(request.urdf).read_bytes()
    store = open_store(request.cache)
    params = {"urdf": reader_input_digest(urdf_text), "versions": REFERENCE.versions()}
    key = product_key("reference", params, [])
    record_text = _kept(store.fetch_file(key, RECORD, "reference")) if store is not None else None
    cached = record_text is not None
    if record_text is None:
        record = read_kinematics(urdf_text)
        record_text = (json.dumps(record, indent=1, sort_keys=True) + "\n").encode()
        if store is not None:
            store.store_file(key, RECORD, record_text, "reference")
    outputs: dict[str, str] = {}
    write_output(Path(request.output), record_text, outputs)
    return {"outputs": outputs, "cached": cached, "stored": not cached and store is not None}


def _kept(record_text: bytes | None) -> bytes | None:
    """A record from the cache, if it is one (JSON); None otherwise, and it is read again."""
    if record_text is None:
        return None
    try:
        json.loads(record_text)
    except ValueError:
        return None
    return record_text
