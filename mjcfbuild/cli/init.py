"""``mjcfbuild init``: write a commented starting manifest for a robot description."""

from __future__ import annotations

import argparse
import sys


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "init",
        help="write a commented starting robot.yaml for a URDF or xacro file",
        description="Write a commented starting manifest for a URDF or xacro file.",
    )
    parser.add_argument("source", help="the URDF or xacro file")
    parser.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=DIR",
        help="where a package the description names lives (repeatable; by default found from "
        "package.xml files and ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)",
    )
    parser.add_argument("-o", "--output", default="robot.yaml", help="manifest to write")
    parser.add_argument("--force", action="store_true", help="overwrite an existing manifest")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Write the manifest."""
    from mjcfbuild.cli.convert import parse_packages
    from mjcfbuild.manifest.starter import write_starter_manifest

    path, warnings, notes = write_starter_manifest(
        args.source, parse_packages(args.package), args.output, force=args.force
    )
    if getattr(args, "quiet", False):  # errors only
        return 0
    for warning in warnings:
        print(f"mjcfbuild: warning: {warning}", file=sys.stderr)
    for note in notes:
        print(f"mjcfbuild: {note}")
    print(f"mjcfbuild: wrote {path}; build it with: mjcfbuild build {path}")
    return 0
