"""The check's reference kinematics, read from the URDF by an independent reader (yourdfpy).

The build parses the URDF with mjcfbuild's own parser. If the check computed its reference
poses from that same parse, a parser bug (an origin read wrongly, a joint axis dropped) would
pass both. The reference poses therefore come from yourdfpy, which reads the URDF text on its
own, mimic joints included; mjcfbuild's parse only supplies names and lines for messages.
"""

from __future__ import annotations

import io

from mjcfbuild.urdf.transforms import Transform

Matrix = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]


class ReferenceKinematics:
    """Link poses of a URDF text, relative to its root link, at given joint values."""

    name = "yourdfpy"

    def __init__(self, urdf: bytes) -> None:
        import yourdfpy  # numpy, trimesh: only when a check runs

        self._urdf = yourdfpy.URDF.load(
            io.BytesIO(urdf),
            load_meshes=False,
            build_collision_scene_graph=False,
            load_collision_meshes=False,
        )
        self._actuated = set(self._urdf.actuated_joint_names)
        self.links = list(self._urdf.link_map)

    def poses(self, joint_values: dict[str, float]) -> dict[str, Transform]:
        """Every link's pose at ``joint_values`` (by joint name; mimic joints follow their
        leaders as the URDF says, whatever value they are given here)."""
        self._urdf.update_cfg(
            {name: value for name, value in joint_values.items() if name in self._actuated}
        )
        base = self._urdf.base_link
        result = {}
        for link in self.links:
            matrix = self._urdf.get_transform(frame_to=link, frame_from=base)
            rotation: Matrix = tuple(  # type: ignore[assignment]
                tuple(float(v) for v in matrix[row, :3]) for row in range(3)
            )
            x, y, z = (float(v) for v in matrix[:3, 3])
            result[link] = Transform(rotation, (x, y, z))
        return result


def reference_kinematics(urdf: bytes | None) -> tuple[ReferenceKinematics | None, str | None]:
    """The independent reference for ``urdf``, or (None, why not) when yourdfpy cannot read
    it (the check then falls back to mjcfbuild's own forward kinematics and says so)."""
    if urdf is None:
        return None, "no URDF text given"
    try:
        return ReferenceKinematics(urdf), None
    except Exception as exc:  # any reader failure: fall back, never fail the check for it
        return None, f"yourdfpy could not read the URDF ({type(exc).__name__}: {exc})"
