"""``mjcfbuild convert``: a drop-in for mujoco_ros2_control's make_mjcf_from_robot_description.py.

It takes the reference converter's flags, builds an implicit manifest from them and runs the
same build graph as ``mjcfbuild build``, with its state in the output folder, so converting
again into the same folder only redoes what changed.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from mjcfbuild.cli import jobs_argument, step_timeout, timeout_argument
from mjcfbuild.errors import EXIT_OK, UsageError

REFERENCE_ROBOT_FILE = "mujoco_description_formatted.xml"


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "convert",
        help="convert a URDF like mujoco_ros2_control's converter (same flags), incrementally",
        description=(
            "Convert a URDF or robot description to MJCF, accepting the flags of "
            "mujoco_ros2_control's make_mjcf_from_robot_description.py. Files are written to "
            "OUTPUT (mujoco_description_formatted.xml, scene.xml, assets/); repeating a "
            "conversion into the same folder only redoes what changed. Its flags are the "
            "reference converter's, so it takes no manifest and -m is --mujoco_inputs, not "
            "the --manifest of the other commands."
        ),
    )
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument(
        "-u", "--urdf", help="a URDF file (a xacro file is expanded, with NAME:=VALUE arguments)"
    )
    source.add_argument(
        "-r", "--robot_description", help="the robot description as a string ('-' reads stdin)"
    )
    parser.add_argument(
        "-m",
        "--mujoco_inputs",
        help="an XML file with <mujoco_inputs> (combined with any in the URDF; the file wins)",
    )
    parser.add_argument(
        "-o", "--output", default="mjcf_data", help="output folder (default: mjcf_data)"
    )
    parser.add_argument(
        "-p", "--publish_topic", help="not available: publishing needs ROS (write files with -o)"
    )
    parser.add_argument(
        "-c",
        "--convert_stl_to_obj",
        action="store_true",
        help="no effect: every mesh (STL included) is always written as OBJ, which is what -c "
        "asks of the reference converter",
    )
    parser.add_argument(
        "-s",
        "--save_only",
        action="store_true",
        help="no effect: files are always saved to OUTPUT, which is what -s asks of the "
        "reference converter (without it, it writes to a temporary folder)",
    )
    parser.add_argument(
        "-f", "--add_free_joint", action="store_true", help="give the root body a free joint"
    )
    parser.add_argument(
        "--fuse",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="merge links on fixed joints into their parents (default: on)",
    )
    parser.add_argument(
        "--use_collision_tags",
        action="store_true",
        help="no effect: the URDF's authored <collision> geometry is always the collision "
        "geometry, which is what --use_collision_tags asks of the reference converter; a link "
        "without any has none (the reference gives it its visual; robot.yaml's collision "
        "policies 'hull', 'primitive' and 'decompose' do too)",
    )
    parser.add_argument(
        "-a",
        "--asset_dir",
        help="a folder with pre-generated OBJ meshes (the reference converter's assets/ "
        "from an earlier run, or <stem>.obj files): a URDF mesh whose file stem has an OBJ "
        "there is read from that OBJ instead of being converted again, in the mesh file's "
        "colour where the OBJ has none of its own",
    )
    parser.add_argument("--scene", help="a scene file to use instead of the generated one")
    parser.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=DIR",
        help="where a ROS package is, for package:// and $(find) (repeatable)",
    )
    jobs_argument(parser)
    timeout_argument(parser)
    parser.add_argument(
        "xacro_args", nargs="*", metavar="NAME:=VALUE", help="xacro arguments, when -u is xacro"
    )
    parser.set_defaults(handler=run)
    parser.misuse = manifest_given  # read by Parser.error


# Options whose value is never the description: a .yaml there is no mistake.
_NOT_THE_SOURCE = ("-o", "--output", "--scene", "-a", "--asset_dir", "--package", "-p")


def manifest_given(words: list[str]) -> UsageError | None:
    """The error for a manifest (a .yaml or .yml file) given to convert as its source, as a
    positional word, or as -u, -r or -m (``mjcfbuild convert robot.yaml``), else None.
    convert takes the reference converter's flags: argparse only said that -u or -r is
    required, and ``-u ... -m robot.yaml`` read the manifest as XML ("malformed XML")."""
    for index, word in enumerate(words):
        if ":=" in word or (index and words[index - 1] in _NOT_THE_SOURCE):
            continue  # a xacro argument, or the value of an option that is not the source
        value = word.split("=", 1)[1] if word.startswith("--") and "=" in word else word
        if value.endswith((".yaml", ".yml")) and not value.startswith("-"):
            return UsageError(
                f"{value} is a manifest: convert takes the reference converter's flags "
                "(-u URDF or xacro, -r description, -m an XML file of <mujoco_inputs>), "
                "not a robot.yaml",
                hint=f"build the manifest with: mjcfbuild build {value}",
            )
    return None


def parse_packages(values: list[str]) -> dict[str, str]:
    """``NAME=DIR`` arguments as a dict; :class:`UsageError` for malformed ones."""
    from mjcfbuild.sources.packages import PACKAGE_PATTERN

    packages = {}
    for value in values:
        name, sep, folder = value.partition("=")
        if not sep or not name or not folder:
            raise UsageError(f"--package '{value}' is not NAME=DIR")
        if not PACKAGE_PATTERN.match(name):
            raise UsageError(
                f"--package '{value}': '{name}' is no ROS package name (letters, digits, '_', "
                "'-' and '.')"
            )
        packages[name] = str(Path(folder).resolve())
    return packages


def stamp_key(args: argparse.Namespace) -> str | None:
    """The no-op stamp's key of this conversion: the folder it runs in and every option that
    changes what it builds. None when the description comes from stdin (never the same)."""
    from mjcfbuild.engine.stamp import command_key

    if args.robot_description == "-":
        return None
    options = {
        name: getattr(args, name)
        for name in (
            "urdf",
            "robot_description",
            "mujoco_inputs",
            "output",
            "add_free_joint",
            "fuse",
            "asset_dir",
            "scene",
            "package",
            "xacro_args",
        )
    }
    return command_key("convert", os.getcwd(), options)


def run(args: argparse.Namespace) -> int:
    """Convert; nothing is imported or read beyond the stamp when nothing changed."""
    from mjcfbuild.cli.build import report_nothing_to_do
    from mjcfbuild.engine import stamp

    misuse = manifest_given(
        [
            word
            for name in ("urdf", "robot_description", "mujoco_inputs")
            if (word := getattr(args, name))
        ]
        + list(args.xacro_args)
    )
    if misuse is not None:
        raise misuse
    if args.publish_topic:
        raise UsageError(
            "-p/--publish_topic needs ROS, which mjcfbuild does not use",
            hint="write the model with -o DIR and load DIR/scene.xml",
        )
    key = stamp_key(args)
    if key is not None and report_nothing_to_do(
        lambda: stamp.nothing_to_do_for(key, run_check=True),
        args.quiet,
        check_command=check_command(args),
    ):
        return EXIT_OK
    return _convert(args, key)


def _convert(args: argparse.Namespace, key: str | None) -> int:
    """The full build of a conversion; its no-op stamp is filed under ``key``."""
    from mjcfbuild.cli.build import execute
    from mjcfbuild.engine.context import BuildContext, default_jobs
    from mjcfbuild.manifest.models import Manifest

    cwd = Path.cwd()
    output = Path(args.output)
    xacro_args = parse_xacro_args(args.xacro_args)
    if args.add_free_joint and _rooted_at_world(args):
        from mjcfbuild.console import report_warning

        # The reference's add_urdf_free_joint, word for word in effect: robot.yaml's
        # free_joint would float each body the world holds fixed (a sensor frame falls away).
        report_warning("-f: not adding a free joint, because world is the URDF's root")
        args.add_free_joint = False
    if args.urdf:
        kind = "xacro" if is_xacro(Path(args.urdf)) else "urdf"
        if xacro_args and kind != "xacro":
            raise UsageError(f"{args.urdf} is not a xacro file; NAME:=VALUE arguments need one")
        source = {kind: args.urdf, **({"args": xacro_args} if xacro_args else {})}
        name = Path(args.urdf).name.split(".")[0] or "robot"
    elif args.robot_description == "-":
        source = {"description": "-"}
        name = "robot"
    else:
        state = (cwd / output / ".mjcfbuild").resolve()
        state.mkdir(parents=True, exist_ok=True)
        description = state / "robot_description.urdf"
        from mjcfbuild.fsutil import write_if_changed

        write_if_changed(description, args.robot_description.encode("utf-8"))
        source = {"description": str(description)}
        name = "robot"
    manifest = Manifest.model_validate(
        {
            "name": _safe_name(name),
            "source": source,
            "packages": parse_packages(args.package),
            "options": {"free_joint": args.add_free_joint, "fuse_static": args.fuse},
            "scene": {"file": args.scene} if args.scene else {},
            "mujoco_inputs": {"file": args.mujoco_inputs} if args.mujoco_inputs else {},
            "output": {"folder": str(output), "robot": REFERENCE_ROBOT_FILE},
        }
    )
    jobs = args.jobs or default_jobs()
    prebuilt = None
    if args.asset_dir:
        if not Path(args.asset_dir).is_dir():
            raise UsageError(
                f"-a {args.asset_dir}: not a folder",
                hint="give the folder of pre-generated OBJ meshes (an earlier run's assets/)",
            )
        prebuilt = Path(args.asset_dir).resolve()
    ctx = BuildContext(
        manifest,
        cwd,
        manifest_label="the command line",
        jobs=jobs,
        step_timeout=step_timeout(args),
        prebuilt_mesh_dir=prebuilt,
        noop_stamp=key is not None,
        command_stamp_key=key,
    )
    return execute(
        ctx,
        quiet=args.quiet,
        debug=args.debug,
        hints=command_line_hint,
        check_command=check_command(args),
    )


def _rooted_at_world(args: argparse.Namespace) -> bool:
    """Whether the URDF given (a file that needs no xacro, or the -r text) has ``world`` for
    its root link; False where that is not known before the build (xacro, stdin) or the text
    does not read (the build says why)."""
    from mjcfbuild.errors import MjcfbuildError
    from mjcfbuild.urdf.parse import parse_urdf

    try:
        if args.urdf:
            path = Path(args.urdf)
            if is_xacro(path):
                return False
            data = path.read_bytes()
        elif args.robot_description and args.robot_description != "-":
            data = args.robot_description.encode("utf-8")
        else:
            return False
        return parse_urdf(data, "robot.urdf").root == "world"
    except (OSError, MjcfbuildError):
        return False


def check_command(args: argparse.Namespace) -> str:
    """The ``mjcfbuild check`` command that checks a conversion's model against its URDF:
    there is no robot.yaml for a plain ``mjcfbuild check`` to read."""
    import shlex

    from mjcfbuild.outputs import SOURCE_URDF
    from mjcfbuild.ownership import STATE_DIR

    model = shlex.quote(str(Path(args.output) / REFERENCE_ROBOT_FILE))
    if args.urdf and not args.xacro_args:
        urdf = shlex.quote(args.urdf)
        packages = "".join(f" --package {shlex.quote(entry)}" for entry in args.package or [])
        return f"mjcfbuild check --urdf {urdf} --mjcf {model}{packages}"
    # Expanded with NAME:=VALUE arguments, or given as a string: the URDF the build compared
    # the model with, which it keeps (check --urdf expands a xacro with its defaults).
    urdf = shlex.quote(str(Path(args.output) / STATE_DIR / SOURCE_URDF))
    return f"mjcfbuild check --urdf {urdf} --mjcf {model}"


# Errors advise changes to robot.yaml; convert has no robot.yaml, only these flags.
_IN = r"in (?:robot\.yaml|the command line)"
_FLAG_HINTS = (
    (rf"add '([^']+): <folder>' under 'packages' {_IN}", r"pass --package \1=<folder>"),
    (rf"fix its entry under 'packages' {_IN}", "fix its --package NAME=DIR"),
    (rf"the 'packages' {_IN}", "the --package NAME=DIR options"),
    (rf"under 'source\.args' {_IN}", "as NAME:=VALUE after the other arguments"),
    (rf"fix 'source(?:\.xacro|\.urdf)?' {_IN}", "fix -u"),
    (rf"fix 'mujoco_inputs\.file' {_IN}", "fix -m"),
    (rf"fix 'scene\.file' {_IN}", "fix --scene"),
    (r"set output\.folder to a folder of the build's own", "choose another -o, one of its own"),
    (r"set output\.folder to the folder it points at", "give -o the folder it points at"),
    (r"give this one an output\.folder of its own", "choose another -o for this conversion"),
    (r"set output\.folder", "choose another -o"),
    (
        r"carry the edit into robot\.yaml's mujoco_inputs or actuators, which every build "
        r"applies",
        "carry the edit into the -m file (raw MJCF, which every conversion applies)",
    ),
)


def without_ros_args(argv: list[str]) -> list[str]:
    """``argv`` without the ``--ros-args ... [--]`` sections ROS 2 launch files append to a
    node's arguments, which the reference converter drops (rclpy's remove_ros_args)."""
    kept: list[str] = []
    inside = False
    for word in argv:
        if word == "--ros-args":
            inside = True
        elif inside and word == "--":
            inside = False
        elif not inside:
            kept.append(word)
    return kept


def command_line_hint(hint: str) -> str:
    """``hint`` with robot.yaml keys replaced by the convert flags that set them."""
    import re

    for pattern, replacement in _FLAG_HINTS:
        hint = re.sub(pattern, replacement, hint)
    return hint


def parse_xacro_args(values: list[str]) -> dict[str, str]:
    """``NAME:=VALUE`` words as a dict, read as the ``xacro`` command reads them: name and
    value stripped of spaces, an empty value leaving the argument's default (what a launch
    file's empty argument gives), a ``_name`` (a ROS 1 private parameter) not an argument;
    :class:`UsageError` for anything else."""
    result = {}
    for value in values:
        parts = [part.strip() for part in value.split(":=")]
        if len(parts) != 2 or not parts[0]:
            raise UsageError(f"'{value}' is not NAME:=VALUE")
        name, text = parts
        if not text or (len(name) > 1 and name[0] == "_" and name[1] != "_"):
            continue
        result[name] = text
    return result


def is_xacro(path: Path) -> bool:
    """Whether a description file needs xacro: by name, or by what it uses (xacro elements or
    substitutions; declaring the namespace is not enough, as for ``init`` and the build)."""
    from mjcfbuild.sources.kind import xacro_evidence

    if path.name.endswith(".xacro"):
        return True
    try:
        return xacro_evidence(path.read_bytes()) is not None
    except OSError:
        return False


def _safe_name(stem: str) -> str:
    import re

    cleaned = re.sub(r"[^A-Za-z0-9_.-]+", "_", stem).strip("_.-")
    return cleaned or "robot"
