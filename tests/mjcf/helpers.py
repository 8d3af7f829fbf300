"""Assembling a URDF in-process, the way the build steps do, for focused tests."""

from __future__ import annotations

from pathlib import Path

import mujoco

from mjcfbuild.meshes.convert import convert_mesh
from mjcfbuild.mjcf.assemble import Assembly, AssemblyOptions, assemble
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.urdf.parse import parse_urdf
from mjcfbuild.urdf.resolve import resolve_files


def build(urdf: str, folder: Path, **options) -> tuple[Assembly, mujoco.MjModel]:
    """Assemble ``urdf`` (meshes relative to ``folder``); the assembly and the loaded model."""
    robot = parse_urdf(urdf.encode(), "robot.urdf")
    resolve_files(robot, folder, PackageResolver({}, {}))
    products, dirs = {}, {}
    for link in robot.links:
        for shape in link.shapes:
            geometry = shape.geometry
            if geometry.kind == "mesh" and geometry.mesh_id not in products:
                dirs[geometry.mesh_id] = folder / "products" / geometry.mesh_id
                products[geometry.mesh_id] = convert_mesh(
                    Path(geometry.path), dirs[geometry.mesh_id], ["collision", "visual"]
                )
    assembly = assemble(robot, products, dirs, AssemblyOptions(**options))
    out = folder / "out"
    (out / "assets").mkdir(parents=True, exist_ok=True)
    for name, source in assembly.assets.items():
        (out / "assets" / name).write_bytes(Path(source).read_bytes())
    (out / "robot.xml").write_bytes(assembly.xml)
    return assembly, mujoco.MjModel.from_xml_path(str(out / "robot.xml"))
