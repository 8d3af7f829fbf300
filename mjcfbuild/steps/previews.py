"""Step ``previews``: pictures of the model from the front and the side, visual and collision.

Only the pictures whose content changed are drawn again. The step's record lists each picture
it left in the folder with the digest of what it shows and the hash of its bytes; a picture
counts as drawn only while its file still has those bytes, so one edited by hand, or left
half-written by an interrupted build, is drawn again. A picture drawn before, in any folder, is
taken from the shared product cache by that digest (drawing costs about a second a model on a
CPU); the digest holds no path. Where no picture is drawn (the model does not load, no OpenGL
context, drawing fails) the earlier build's pictures and record go: a clean build has none,
and the report lists the pictures it finds.
"""

from __future__ import annotations

import contextlib
import json
from pathlib import Path

from mjcfbuild.check.loading import asset_sources
from mjcfbuild.check.previews import OffscreenUnavailable, render_previews
from mjcfbuild.errors import MjcfbuildError, ModelError, write_failure
from mjcfbuild.fsutil import md5_file
from mjcfbuild.products.store import ProductStore, open_store, product_key
from mjcfbuild.steps.outputs import record_output, write_output
from mjcfbuild.steps.payloads import PreviewsPayload
from mjcfbuild.steps.versions import PREVIEWS

PICTURE = "picture.png"


def run(payload: dict) -> dict:
    """Render the previews; a machine without offscreen OpenGL gets a warning, not a failure."""
    request = PreviewsPayload.from_dict(payload)
    folder, record = Path(request.folder), Path(request.record)
    try:
        sources = asset_sources(Path(request.assembly_report))
        store = open_store(request.cache)
        stored = StoredPictures(store) if store is not None else None
        shown = render_previews(
            Path(request.model),
            folder,
            sources=sources,
            drawn=pictures_in_place(folder, record),
            cache=stored,
        )
    except ModelError:  # a model that does not load: the check task says why
        no_pictures(folder, record)
        return {"outputs": {}}
    except MjcfbuildError:
        no_pictures(folder, record)
        raise
    except OffscreenUnavailable as exc:  # no EGL, no GPU driver...: the build itself is fine
        no_pictures(folder, record)
        return {
            "outputs": {},
            "warnings": [
                f"no preview pictures: no OpenGL context to draw them in ({exc}); "
                "on Linux install libegl1 and libegl-mesa0, or set check.previews: false"
            ],
        }
    except Exception as exc:
        no_pictures(folder, record)
        unwritable = write_failure(exc)  # a picture that cannot be written: a full disk...
        if unwritable is not None:
            raise unwritable from None
        # Anything else is no driver's: say what it is. The model itself is built.
        said = str(exc).strip().splitlines()
        return {
            "outputs": {},
            "warnings": [
                f"no preview pictures: drawing them failed with {type(exc).__name__}"
                f"{': ' + said[0] if said else ''} (a bug in mjcfbuild or MuJoCo; please report "
                "it with the model, or set check.previews: false)"
            ],
        }
    for stale in folder.glob("*.png"):  # pictures of views no longer drawn
        if stale.name not in shown:
            stale.unlink()
    outputs: dict[str, str] = {}
    entries = {}
    for name, digest in shown.items():
        record_output(folder / name, outputs)
        if digest is not None:
            entries[name] = {"shows": digest, "md5": outputs[str(folder / name)]}
    text = json.dumps(entries, indent=1, sort_keys=True) + "\n"
    write_output(record, text.encode(), outputs)
    if stored is None:
        return {"outputs": outputs}
    # "from cache" only when no picture was drawn; a drawn one grew the cache.
    return {
        "outputs": outputs,
        "cached": stored.taken > 0 and not stored.kept,
        "stored": stored.kept > 0,
    }


class StoredPictures:
    """Pictures in the shared product cache, each under the digest of what it shows and the
    drawing tools' versions."""

    def __init__(self, store: ProductStore) -> None:
        self.store = store
        self.versions = PREVIEWS.versions()
        self.taken = 0  # pictures found here
        self.kept = 0  # pictures drawn and kept here

    def _key(self, shows: str) -> str:
        return product_key("preview", {"shows": shows, "versions": self.versions}, [])

    def get(self, shows: str) -> bytes | None:
        """The PNG kept for ``shows``; None if there is none (or it cannot be used)."""
        png = self.store.fetch_file(self._key(shows), PICTURE, "preview")
        self.taken += png is not None
        return png

    def put(self, shows: str, png: bytes) -> None:
        """Keep ``png`` for ``shows`` (a full or read-only cache keeps nothing)."""
        self.kept += self.store.store_file(self._key(shows), PICTURE, png, "preview")


def no_pictures(folder: Path, record: Path) -> None:
    """Remove the pictures an earlier build left in ``folder``, and the step's ``record`` of
    them: where this build draws none, a clean build would have none, and the report lists the
    pictures it finds there. Only those the record names with the bytes it wrote: a picture
    put there or edited since is the user's. Best effort: one that cannot be removed stays."""
    ours = [folder / name for name in pictures_in_place(folder, record)]
    for path in [*ours, record]:
        with contextlib.suppress(OSError):
            path.unlink(missing_ok=True)
    with contextlib.suppress(OSError):
        folder.rmdir()  # only when empty, as a clean build leaves no folder


def pictures_in_place(folder: Path, record: Path) -> dict[str, str]:
    """The pictures in ``folder`` that are as the step's ``record`` says it left them, each
    with the digest of what it shows."""
    try:
        entries = json.loads(record.read_text())
        return {
            name: entry["shows"]
            for name, entry in entries.items()
            if _has_md5(folder / name, entry["md5"])
        }
    except (OSError, ValueError, AttributeError, KeyError, TypeError):
        return {}


def _has_md5(path: Path, md5: str) -> bool:
    try:
        return md5_file(path) == md5
    except OSError:
        return False
