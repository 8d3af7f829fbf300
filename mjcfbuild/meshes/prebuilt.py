"""Meshes converted before, by another tool: ``convert -a ASSET_DIR``.

mujoco_ros2_control's converter takes ``-a/--asset_dir``, "an existing folder with
pre-generated OBJ meshes", and uses the OBJ found there for a URDF mesh of the same file stem
instead of converting the mesh again. Its own output keeps them in ``assets/full/<stem>/``
(``assets/visual/`` in later versions); a plain folder of ``<stem>.obj`` files works too.
Such an OBJ often carries no colour of its own (it stayed with the model it was written for):
it then takes the look of the mesh file it stands for (:mod:`mjcfbuild.meshes.prebuilt_look`).
"""

from __future__ import annotations

from pathlib import Path

_LAYOUTS = ("{stem}.obj", "visual/{stem}.obj", "full/{stem}/{stem}.obj")


def prebuilt_mesh(folder: Path, mesh_path: str) -> Path | None:
    """The pre-generated OBJ in ``folder`` (or its ``assets/``) for the mesh file
    ``mesh_path``, or None."""
    stem = Path(mesh_path).stem
    for root in (folder, folder / "assets"):
        for layout in _LAYOUTS:
            candidate = root / layout.format(stem=stem)
            if candidate.is_file():
                return candidate
    return None
