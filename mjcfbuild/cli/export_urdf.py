"""``mjcfbuild export-urdf``: any MJCF as a URDF with its meshes, for RViz, MoveIt and ROS."""

from __future__ import annotations

import argparse
from pathlib import Path

from mjcfbuild.errors import EXIT_OK
from mjcfbuild.export.stamp import STAMP, refuse_overwriting


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "export-urdf",
        help="write a URDF (and OBJ meshes) of any MJCF model",
        description=(
            "Write a URDF of an MJCF model, hand-written ones included: links from bodies with "
            "their inertia, joints (several per body through intermediate links), primitives, "
            "meshes as OBJ with one material file per colour, sites as frame links, joint "
            "couplings as <mimic>. See docs/export_urdf.md for how each MuJoCo concept maps."
        ),
    )
    parser.add_argument(
        "model", metavar="MODEL", help="the MJCF file (its includes and meshes are read too)"
    )
    parser.add_argument("-o", "--output", required=True, help="the URDF file to write")
    parser.add_argument(
        "--mesh-folder",
        help="where the OBJ and MTL files go (default: <output stem>_meshes next to the URDF)",
    )
    parser.add_argument(
        "--asset-prefix",
        help="how the URDF names mesh files, e.g. package://my_pkg/meshes/ "
        "(default: the mesh folder relative to the URDF)",
    )
    parser.add_argument(
        "--no-sites", action="store_true", help="do not export sites as fixed frame links"
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help="overwrite an output file that export-urdf did not write (by default only an "
        "earlier export is replaced)",
    )
    parser.add_argument(
        "--limits-from",
        metavar="SOURCE",
        help="the URDF the model was made from: its velocity limits are kept for the joints "
        "whose speed the model's actuators do not set (<dcmotor> and velocity servos do). A "
        "xacro file is expanded (arguments with --xacro-arg); a robot.yaml gives its source "
        "expanded as the build expands it, with its args and packages",
    )
    parser.add_argument(
        "--xacro-arg",
        action="append",
        default=[],
        metavar="NAME:=VALUE",
        help="an argument for the xacro file --limits-from names (repeat for several)",
    )
    parser.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=DIR",
        help="where a ROS package is, for $(find) in the xacro file --limits-from names "
        "(repeatable; others come from ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)",
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Export, write, and print a summary line."""
    from mjcfbuild.cli.check import refuse_other_models
    from mjcfbuild.console import report_warnings
    from mjcfbuild.errors import InputError
    from mjcfbuild.export import ExportOptions, export_urdf
    from mjcfbuild.export.publish import default_asset_prefix, publish
    from mjcfbuild.fsutil import unreadable_file

    model = Path(args.model)
    problem = unreadable_file(model)
    if problem:
        raise InputError(f"file {problem}", file=model, hint="give the MJCF model to export")
    refuse_other_models(model, "export-urdf writes a URDF from an MJCF model (a robot.xml)")
    urdf_path = Path(args.output)
    if not args.force:
        refuse_overwriting([urdf_path])  # before the export's work, which takes a while
    mesh_dir = Path(args.mesh_folder or urdf_path.with_name(f"{urdf_path.stem}_meshes"))
    prefix = args.asset_prefix
    if prefix is None:
        prefix = default_asset_prefix(urdf_path, mesh_dir)
    options = ExportOptions(
        asset_prefix=prefix,
        sites=not args.no_sites,
        header=f"{STAMP} from {Path(args.model).name}",
    )
    speeds = _limits(args) if args.limits_from is not None else None
    if args.xacro_arg and speeds is None:
        from mjcfbuild.errors import UsageError

        raise UsageError("--xacro-arg needs a xacro file as --limits-from")
    result = export_urdf(Path(args.model), options, speeds)
    publish(result, urdf_path, mesh_dir, force=args.force)
    if args.quiet:
        return EXIT_OK
    report_warnings(result.warnings)
    meshes = len([name for name in result.meshes if name.endswith(".obj")])
    print(f"mjcfbuild: wrote {urdf_path} and {meshes} mesh file(s) in {mesh_dir}")
    return EXIT_OK


def _limits(args: argparse.Namespace) -> dict[str, float]:
    """The velocity limits of ``--limits-from``: a URDF as it is, a xacro file expanded with
    ``--xacro-arg``, or a robot.yaml's source expanded as its build expands it."""
    import os

    from mjcfbuild.cli import MANIFEST_SUFFIXES
    from mjcfbuild.cli.convert import (
        command_line_hint,
        is_xacro,
        parse_packages,
        parse_xacro_args,
    )
    from mjcfbuild.errors import MjcfbuildError, UsageError
    from mjcfbuild.export.speeds import read_urdf_speeds, urdf_speeds
    from mjcfbuild.sources.expand import COMMAND_LINE, expand_xacro
    from mjcfbuild.sources.packages import PackageResolver
    from mjcfbuild.urdf.parse import parse_urdf

    source = Path(args.limits_from)
    if args.package and not (source.is_file() and is_xacro(source)):
        raise UsageError(f"--package is for a xacro file as --limits-from, and {source} is not one")
    if source.suffix.lower() in MANIFEST_SUFFIXES:
        if args.xacro_arg:
            raise UsageError(
                "--xacro-arg is for a xacro file; a robot.yaml gives its own source.args"
            )
        return _manifest_limits(source, args)
    if not (source.is_file() and is_xacro(source)):
        if args.xacro_arg:
            raise UsageError(f"--xacro-arg needs a xacro file, and {source} is not one")
        return read_urdf_speeds(source)
    # Packages as the build finds them without a manifest: --package, the ROS environment
    # and the package.xml files above the file.
    given = {name: Path(folder) for name, folder in parse_packages(args.package).items()}
    resolver = PackageResolver(given, os.environ)
    try:
        expansion = expand_xacro(source, parse_xacro_args(args.xacro_arg), resolver, COMMAND_LINE)
    except MjcfbuildError as error:
        error.hint = command_line_hint(error.hint) if error.hint else error.hint
        raise
    return urdf_speeds(parse_urdf(expansion.urdf, str(source)))


def _manifest_limits(manifest: Path, args: argparse.Namespace) -> dict[str, float]:
    """The velocity limits of the source of the robot.yaml at ``manifest``, expanded with its
    ``source.args`` and ``packages`` (``attach:`` parts are not read)."""
    from mjcfbuild.cli import load_context
    from mjcfbuild.cli.convert import is_xacro
    from mjcfbuild.errors import MjcfbuildError
    from mjcfbuild.export.speeds import urdf_speeds
    from mjcfbuild.manifest.pinpoint import pinpoint
    from mjcfbuild.sources.expand import expand_source
    from mjcfbuild.urdf.parse import parse_urdf

    ctx = load_context(manifest, args)
    path = ctx.source_path
    xacro = ctx.source_kind == "xacro" or (ctx.source_kind == "description" and is_xacro(path))
    packages = {name: str(folder) for name, folder in ctx.resolver.explicit.items()}
    try:
        expansion = expand_source(
            path,
            xacro,
            ctx.manifest.source.xacro_args,
            packages,
            ctx.environ,
            args_key=f"{ctx.manifest_label} source.args",
        )
    except MjcfbuildError as error:
        assert ctx.manifest_file is not None, "loaded from a file"
        raise pinpoint(error, ctx.manifest_label, ctx.manifest_file) from None
    return urdf_speeds(parse_urdf(expansion.urdf, ctx.label(path)))
