"""Step ``plan``: parse the URDF, resolve every file it names, list the meshes to convert, and
read the MuJoCo inputs, ros2_control and Gazebo sensors it holds (and the inputs file, if any)."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.errors import InputError
from mjcfbuild.inputs.gazebo import read_gazebo_sensors, urdf_sensor_warnings
from mjcfbuild.inputs.ros2_control import read_ros2_control, transmission_joint_warnings
from mjcfbuild.inputs.xml_inputs import inputs_in_urdf, read_inputs_file
from mjcfbuild.mjcf.bodies import refuse_nested_floating
from mjcfbuild.mjcf.depth import refuse_deep_chains
from mjcfbuild.sources.packages import PackageResolver
from mjcfbuild.steps.depfile import Depfile
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import PlanPayload
from mjcfbuild.steps.plan_record import Plan, PlannedInputs, PlannedMesh
from mjcfbuild.urdf.parse import parse_urdf, parse_xml
from mjcfbuild.urdf.resolve import resolve_files


def run(payload: dict) -> dict:
    """Write the build plan (robot, meshes, inputs, ros2_control) to its ``output``."""
    request = PlanPayload.from_dict(payload)
    packages = PackageResolver(
        {name: Path(folder) for name, folder in request.packages.items()},
        request.environment,
    )
    data = Path(request.urdf).read_bytes()
    display = request.display
    try:
        robot = parse_urdf(data, display)
        refuse_deep_chains(robot)  # before any work: MuJoCo could not read the model back
        refuse_nested_floating(robot)  # nor compile it
        prebuilt = request.prebuilt_meshes
        resolved = resolve_files(
            robot,
            Path(request.base_dir),
            packages,
            Path(prebuilt) if prebuilt else None,
            roots=None if request.roots is None else [Path(root) for root in request.roots],
        )
        root = parse_xml(data, display, [])
        urdf_inputs = inputs_in_urdf(root, display)
        control = read_ros2_control(root, display)
        gazebo = read_gazebo_sensors(root, display)
        described = {sensor.name for sensor in control.sensors}
        sensor_warnings = urdf_sensor_warnings(root, display, gazebo, described)
        joints = [joint.name for joint in robot.joints]
        transmission_warnings = transmission_joint_warnings(control, joints)
    except InputError as exc:
        if request.expanded_from and exc.hint is None:
            exc.hint = f"the line is in the expansion of {request.expanded_from}"
        raise
    file_inputs = None
    if request.inputs_file:
        assert request.inputs_file_label is not None, "set with inputs_file"
        file_inputs = read_inputs_file(Path(request.inputs_file), request.inputs_file_label)
    meshes: dict[str, str] = {}
    for link in robot.links:
        for shape in link.shapes:
            mesh_id, path = shape.geometry.mesh_id, shape.geometry.path
            if shape.geometry.kind == "mesh" and mesh_id is not None and path is not None:
                meshes[mesh_id] = path
    plan = Plan(
        robot=robot.to_dict(),
        meshes=[
            PlannedMesh(mesh_id, path, resolved.originals.get(path))
            for mesh_id, path in sorted(meshes.items())
        ],
        inputs=PlannedInputs(
            urdf=urdf_inputs.to_dict(),
            file=file_inputs.to_dict() if file_inputs is not None else None,
        ),
        ros2_control=control.to_dict(),
        gazebo_sensors=[sensor.to_dict() for sensor in gazebo],
    )
    outputs: dict[str, str] = {}
    write_output(Path(request.output), plan.text(), outputs)
    if request.depfile:
        # A texture that appears (or goes) changes the plan: the next build notices.
        Depfile(resolved.textures, resolved.missing, {}).write(Path(request.depfile))
    warnings = [*robot.warnings, *sensor_warnings, *transmission_warnings]
    return {"outputs": outputs, "warnings": warnings}
