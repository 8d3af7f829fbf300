"""``mjcfbuild schema``: print the JSON Schema of robot.yaml."""

from __future__ import annotations

import argparse
import sys


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "schema",
        help="print the JSON Schema of robot.yaml",
        description="Print the JSON Schema of robot.yaml, for editors and validators.",
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the schema."""
    from mjcfbuild.manifest.schema import manifest_schema_text

    sys.stdout.write(manifest_schema_text())
    return 0
