"""Step ``previews``: pictures of the model from the front and the side, visual and collision."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.check.loading import asset_sources
from mjcfbuild.check.previews import render_previews
from mjcfbuild.errors import MjcfbuildError, ModelError
from mjcfbuild.steps.outputs import record_output
from mjcfbuild.steps.payloads import PreviewsPayload


def run(payload: dict) -> dict:
    """Render the previews; a machine without offscreen OpenGL gets a warning, not a failure."""
    request = PreviewsPayload.from_dict(payload)
    folder = Path(request.folder)
    try:
        sources = asset_sources(Path(request.assembly_report))
        names = render_previews(Path(request.model), folder, sources=sources)
    except ModelError:  # a model that does not load: the check task says why
        return {"outputs": {}}
    except MjcfbuildError:
        raise
    except Exception as exc:  # no EGL, no GPU driver...: the build itself is fine
        return {
            "outputs": {},
            "warnings": [
                f"no preview pictures: offscreen rendering failed ({str(exc).splitlines()[0]}); "
                "on Linux install libegl1 and libegl-mesa0, or set check.previews: false"
            ],
        }
    outputs: dict[str, str] = {}
    for name in names:
        record_output(folder / name, outputs)
    return {"outputs": outputs}
