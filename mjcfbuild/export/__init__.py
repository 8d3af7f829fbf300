"""The other direction: any MJCF as a URDF, for RViz, MoveIt and ROS tools.

:func:`export_urdf` reads a model with MuJoCo and writes the URDF and its mesh files; the
mapping of MuJoCo's concepts onto URDF's is described in :mod:`mjcfbuild.export.urdf_writer`.
"""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.export.urdf_writer import ExportOptions, ExportResult


def export_urdf(
    model_path: Path, options: ExportOptions, speeds: dict[str, float] | None = None
) -> ExportResult:
    """The URDF of the MJCF at ``model_path`` and the mesh files it refers to (not written).

    ``speeds`` (joint name -> top speed, rad/s or m/s) are speed limits known from outside the
    model, used for the joints whose speed the model's actuators do not give."""
    from mjcfbuild.export.reader import read_mjcf
    from mjcfbuild.export.urdf_writer import write_urdf

    return write_urdf(read_mjcf(model_path, speeds), options)


__all__ = ["ExportOptions", "ExportResult", "export_urdf"]
