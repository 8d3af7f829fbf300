"""``mjcfbuild check``: prove a built model against its URDF, or say whether outputs are stale."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.cli import (
    allow_outside_argument,
    chosen_manifests,
    load_context,
    manifest_argument,
    positive_int,
    timeout_argument,
)
from mjcfbuild.console import report_error, report_warnings, shown_path
from mjcfbuild.errors import EXIT_CHECK, EXIT_OK, CheckError, MjcfbuildError, UsageError

if TYPE_CHECKING:
    from collections.abc import Callable

    from mjcfbuild.check.results import CheckResults


def add_parser(commands) -> None:
    """Register the subcommand."""
    parser = commands.add_parser(
        "check",
        help="check a built model against its URDF, or whether outputs are up to date",
        description=(
            "Check the model a manifest builds (or any MJCF against any URDF) with code "
            "independent of MuJoCo's URDF import: it loads and simulates, every link is where "
            "the URDF puts it, joints, masses and inertias match. With --up-to-date, say "
            "whether the outputs still match their inputs, without building."
        ),
    )
    manifest_argument(parser, several=True)
    parser.add_argument("--urdf", help="check this URDF against --mjcf, without a manifest")
    parser.add_argument("--mjcf", help="the MuJoCo model to check against --urdf")
    parser.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=DIR",
        help="with --urdf: where a ROS package is, for $(find) in a xacro file and package:// "
        "(repeatable; others come from ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)",
    )
    parser.add_argument(
        "--xacro-arg",
        action="append",
        default=[],
        metavar="NAME:=VALUE",
        help="with --urdf: an argument for its xacro file (repeatable; NAME:=VALUE words "
        "after the other arguments work too, as in convert and the xacro command)",
    )
    parser.add_argument(
        "--up-to-date",
        action="store_true",
        help="exit with 6, naming what is stale, when the outputs no longer match their inputs",
    )
    parser.add_argument(
        "--warp",
        action="store_true",
        help="also load the model in MuJoCo Warp (on the CPU) and step several worlds, and "
        "prove the training variant where robot.yaml asks for one (output.training) "
        "(pip install 'mjcfbuild[warp]'; the first run compiles kernels for about a minute)",
    )
    parser.add_argument(
        "--configurations",
        type=_configurations,
        default=None,
        help="how many joint configurations the link-pose check compares (default: 20)",
    )
    parser.add_argument(
        "--tolerance",
        type=_tolerance,
        default=None,
        help="for every quantity: link poses in metres and radians, axes, ranges, masses and "
        "inertias relative to their size (default 1e-6; axes to inertias no finer than the "
        "model file's digits allow, 1e-5 for MuJoCo's 6)",
    )
    allow_outside_argument(parser)
    timeout_argument(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Dispatch to one of the three modes."""
    _split_xacro_args(args)
    if args.urdf or args.mjcf:
        _refuse_with_pair(args)
        if not (args.urdf and args.mjcf):
            raise UsageError("--urdf and --mjcf go together")
        return _pair(args)
    if args.package:
        raise UsageError("--package goes with --urdf", hint="a manifest lists its packages")
    if args.xacro_arg:
        raise UsageError(
            f"{args.xacro_arg[0]}: xacro arguments go with --urdf",
            hint="a manifest gives its own, under source.args",
        )
    code = EXIT_OK
    for manifest in chosen_manifests(args):
        try:
            ctx = load_context(manifest, args)
            result = _up_to_date(ctx) if args.up_to_date else _manifest(ctx, args)
        except MjcfbuildError as error:
            report_error(error, args.debug)
            result = error.exit_code
        code = code or result
    return code


def _split_xacro_args(args: argparse.Namespace) -> None:
    """Move ``NAME:=VALUE`` words from the manifests to ``args.xacro_arg``: the positional
    words of ``check --urdf X.xacro --mjcf M name:=ur`` are xacro arguments, as convert's
    and the xacro command's are (no manifest is named that way)."""
    words = args.manifest or []
    args.xacro_arg = [*(args.xacro_arg or []), *(w for w in words if ":=" in w)]
    if args.manifest is not None:
        args.manifest = [w for w in words if ":=" not in w]


def _refuse_with_pair(args: argparse.Namespace) -> None:
    """Refuse a manifest, ``--up-to-date`` or ``--warp`` beside ``--urdf``/``--mjcf``, which
    check two files without a manifest (each was ignored)."""
    manifests = [*(args.manifest or []), *(args.manifest_flag or [])]
    others = [f"a manifest ({manifests[0]})"] if manifests else []
    others += ["--up-to-date"] if args.up_to_date else []
    others += ["--warp"] if args.warp else []
    if others:
        pair = "--urdf/--mjcf" if args.urdf and args.mjcf else "--urdf" if args.urdf else "--mjcf"
        raise UsageError(
            f"{', '.join(others)} and {pair} cannot go together",
            hint="--urdf with --mjcf checks those two files, without a manifest",
        )


def _options(args, settings=None):
    from mjcfbuild.check.model_check import CheckOptions

    configurations = args.configurations or (settings.configurations if settings else 20)
    tolerance_p = args.tolerance or (settings.position_tolerance if settings else 1e-6)
    tolerance_r = args.tolerance or (settings.rotation_tolerance if settings else 1e-6)
    steps = settings.steps if settings else 2000
    hold = settings.hold_tolerance if settings else 0.05
    # --tolerance governs every quantity; without it, axes, ranges, masses and inertias are
    # compared as precisely as the model file writes its numbers.
    return CheckOptions(
        configurations,
        0,
        tolerance_p,
        tolerance_r,
        steps,
        hold_tolerance=hold,
        relative_tolerance=args.tolerance,
    )


def _print(
    results: CheckResults,
    label: str,
    quiet: bool = False,
    stale: str = "",
    listed_in: str = "",
    place: Callable[[str], str] = str,
) -> int:
    """One line per check with its result, then the verdict (with what the checks did not
    prove, when they pass, and ``stale``: how the model is older than its inputs; the
    warning it quotes as ``place`` names it); the exit code. ``quiet``: the failures alone.
    Failures of one kind (a joint too fast, each joint) are one line, as warnings are, with
    where they are all listed (``listed_in``)."""
    from mjcfbuild.warning_groups import SHOWN_SUBJECTS, group_warnings

    # Their figures matter while they are few: only kinds with more than a line shows group.
    more = f"all in {listed_in}" if listed_in else ""
    failures = group_warnings(results.failures, more, fewest=SHOWN_SUBJECTS + 1)
    if quiet:
        for failure in failures:
            print(f"mjcfbuild: check failed: {failure}", file=sys.stderr)
        return EXIT_OK if results.passes else EXIT_CHECK
    print(f"mjcfbuild check: {label}")
    for name, result in results.console_lines():
        print(f"  {name:<28} {result}")
    contacts = results.resting_contacts
    if contacts and contacts.pairs:
        print(contacts.exclude)
    for failure in failures:
        print(f"mjcfbuild: check failed: {failure}", file=sys.stderr)
    verdict = results.console_verdict(place)
    if stale:
        verdict += f", {stale}"
    print(f"mjcfbuild: {verdict}")
    return EXIT_OK if results.passes else EXIT_CHECK


def _stale_since_built(ctx) -> str:
    """What the verdict must add about the model checked: edited by hand since the build
    wrote it, or how the built model is older than its inputs, in a few words ('' where it
    is neither, or where the folder has no build database to tell by: a fresh clone's
    committed outputs, which only --up-to-date's rebuild can judge)."""
    from mjcfbuild.engine import written
    from mjcfbuild.engine.freshness import stale_from_database

    name = ctx.robot_path.relative_to(ctx.out_dir).as_posix()
    if written.edited(ctx.out_dir, name, (written.recorded(ctx) or {}).get(name)):
        from mjcfbuild.engine.published import GitUnavailable, git_holds

        try:
            committed = bool(git_holds([str(ctx.robot_path)]))
        except GitUnavailable:
            committed = False
        if committed:  # a checkout or pull of another build's model, or a committed edit
            return (
                f"of {ctx.label(ctx.robot_path)} as git has it in HEAD, not as this folder's "
                f"last build wrote it; `mjcfbuild build {ctx.manifest_label}` makes it the build's"
            )
        return (
            f"of {ctx.label(ctx.robot_path)} as edited by hand, not as the build wrote it (a "
            "build stops at the edit until it is carried into robot.yaml or committed)"
        )
    stale = stale_from_database(ctx)
    if not stale:
        return ""
    more = f" (and {len(stale) - 1} more)" if len(stale) > 1 else ""
    return (
        f"of the model as it was built: it is out of date ({stale[0]}{more}); "
        f"`mjcfbuild build {ctx.manifest_label}` makes it current"
    )


def _pair(args) -> int:
    from mjcfbuild.check.model_check import check_model
    from mjcfbuild.check.reference import read_kinematics
    from mjcfbuild.errors import InputError
    from mjcfbuild.fsutil import unreadable_file
    from mjcfbuild.urdf.parse import parse_urdf

    urdf, mjcf = Path(args.urdf), Path(args.mjcf)
    for path in (urdf, mjcf):
        problem = unreadable_file(path)
        if problem:
            raise InputError(f"file {problem}", file=path)
    refuse_other_models(mjcf, "--mjcf takes the MuJoCo model the URDF (--urdf) was made into")
    from mjcfbuild.cli.convert import command_line_hint, parse_packages
    from mjcfbuild.errors import MjcfbuildError

    try:
        text, origins = _urdf_bytes(urdf, parse_packages(args.package), args.xacro_arg)
    except MjcfbuildError as error:  # no robot.yaml here: its hints name --package instead
        if error.hint:
            error.hint = command_line_hint(error.hint)
        raise
    try:
        robot = parse_urdf(text, str(urdf))
    except InputError as error:
        # A line of the expanded text: point at the xacro line that wrote its element.
        from mjcfbuild.sources.origins import map_lines

        expanded = map_lines(error, origins, shown_path)
        if expanded is not None:
            error.message += f" [line {expanded} of its expansion]"
        raise
    results = check_model(robot, mjcf, mjcf, set(), _options(args), reference=read_kinematics(text))
    packages = {name: Path(folder) for name, folder in parse_packages(args.package).items()}
    results = _runtime_section(results, text, robot, mjcf, str(urdf), origins, packages)
    return _print(results, f"{mjcf} against {urdf}", bool(getattr(args, "quiet", False)))


def _runtime_section(
    results,
    text: bytes,
    robot,
    mjcf: Path,
    label: str,
    origins: dict[int, tuple[str, int]],
    packages: dict[str, Path],
):
    """The mujoco_ros2_control section a build's check adds, from the URDF's <ros2_control>
    blocks: the runtime's rules hold for a model made by any tool. A xacro source's lines are
    named where its ``origins`` say each expanded line was written; ``packages`` are the
    --package folders."""
    from mjcfbuild.inputs.ros2_control import read_ros2_control
    from mjcfbuild.steps.check import add_runtime_check
    from mjcfbuild.urdf.parse import parse_xml

    control = read_ros2_control(parse_xml(text, label, []), label)
    for joint in control.joints:
        joint.origin = _written_at(joint.origin, origins)
    for sensor in control.sensors:
        sensor.origin = _written_at(sensor.origin, origins)
    for transmission in control.transmissions:
        transmission.origin = _written_at(transmission.origin, origins)
    for element in [*control.unknown_children, *control.jointless]:
        element.origin = _written_at(element.origin, origins)
    control.hardware_origins = {
        name: _written_at(origin, origins) for name, origin in control.hardware_origins.items()
    }
    joints = {joint.name: joint.mimic.joint if joint.mimic else None for joint in robot.joints}
    fixed = frozenset(joint.name for joint in robot.joints if joint.kind == "fixed")
    return add_runtime_check(
        results,
        mjcf,
        control,
        joints,
        {},
        fixed_joints=fixed,
        built=((mjcf, shown_path(mjcf)),),
        packages=packages,
    )


def _written_at(origin: str, origins: dict[int, tuple[str, int]]) -> str:
    """``file:line`` of an expanded URDF's line where the xacro file wrote it (as it is, for a
    URDF read as written)."""
    from mjcfbuild.sources.origins import written_in

    line = origin.rpartition(":")[2]
    written = written_in(origins, int(line)) if line.isdigit() else None
    return f"{shown_path(written[0])}:{written[1]}" if written else origin


def refuse_other_models(path: Path, hint: str) -> None:
    """Refuse ``path`` where it is not an MJCF model, naming what it is: MuJoCo would read a
    URDF in its place without a word."""
    from mjcfbuild.errors import InputError
    from mjcfbuild.sources.kind import not_an_mjcf

    kind = not_an_mjcf(path, path.read_bytes())
    if kind is not None:
        raise InputError(f"this is {kind}, not an MJCF model", file=path, hint=hint)


def _urdf_bytes(
    path: Path, packages: dict[str, str], xacro_args: list[str]
) -> tuple[bytes, dict[int, tuple[str, int]]]:
    """The URDF text of ``path`` and, for xacro, where each line's element was written; a
    xacro file is expanded first (``xacro_args`` as ``NAME:=VALUE``, else its defaults;
    packages from ``packages``, else ROS_PACKAGE_PATH / AMENT_PREFIX_PATH), as ``convert -u``
    does."""
    from mjcfbuild.cli.convert import is_xacro, parse_xacro_args
    from mjcfbuild.sources.expand import COMMAND_LINE, expand_xacro
    from mjcfbuild.sources.packages import PackageResolver

    mappings = parse_xacro_args(xacro_args)
    if not is_xacro(path):
        if mappings:
            raise UsageError(f"{path} is not a xacro file; NAME:=VALUE arguments need one")
        return path.read_bytes(), {}
    folders = {name: Path(folder) for name, folder in packages.items()}
    resolver = PackageResolver(folders, os.environ)
    expansion = expand_xacro(path.resolve(), mappings, resolver, COMMAND_LINE)
    return expansion.urdf, expansion.origins


def _manifest(ctx, args) -> int:
    import dataclasses
    import json
    import tempfile
    from functools import partial
    from pathlib import Path

    from mjcfbuild.check.reference import read_kinematics
    from mjcfbuild.engine import written
    from mjcfbuild.engine.guard import check_output_folder
    from mjcfbuild.engine.placing import placed_warning
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.report import write_report
    from mjcfbuild.engine.runner import build_lock
    from mjcfbuild.families.check import check_payload
    from mjcfbuild.families.mjcfpart import mjcf_parts
    from mjcfbuild.outputs import CHECK_RESULTS, PLAN, REFERENCE, planned_urdf
    from mjcfbuild.steps.check import check_built, write_results
    from mjcfbuild.steps.plan_record import read_plan

    if not ctx.robot_path.exists() or not ctx.state(PLAN).exists():
        raise CheckError(
            "nothing to check: the model has not been built in this output folder",
            file=ctx.label(ctx.robot_path),
            hint=f"run mjcfbuild build {ctx.manifest_label}",
        )
    check_output_folder(ctx)  # it writes the report and its results where a build would
    robot = read_plan(ctx.state(PLAN)).robot_model()
    options = dataclasses.asdict(_options(args, ctx.manifest.check))
    request = check_payload(ctx, mjcf_parts(ctx, robot), options)
    with tempfile.TemporaryDirectory() as scratch:
        if not ctx.state(REFERENCE).exists():  # a build that did not check reads none
            record = read_kinematics(_read_if_present(planned_urdf(ctx)))
            reference = Path(scratch) / "reference.json"
            reference.write_text(json.dumps(record))
            request = dataclasses.replace(request, reference=str(reference))
        # The same checks, and the same check.json, as the build's check task.
        results = check_built(request)
    # What it writes in the folder, a build writes too: under the folder's lock, as a build.
    with build_lock(ctx, Progress(quiet=bool(getattr(args, "quiet", False)))):
        write_results(results, ctx.state(CHECK_RESULTS), {})
        folder = write_report(ctx)
        written.record(ctx, ctx.session.written)
    place = partial(placed_warning, ctx)  # where the build names them: the xacro's lines
    if not getattr(args, "quiet", False):  # as the build prints them: one line per kind
        warnings = [place(warning) for warning in results.warnings()]
        report_warnings(warnings, shown_path(folder / "report.md"), base_dir=ctx.base_dir)
    quiet = bool(getattr(args, "quiet", False))
    report = shown_path(folder / "report.md")
    stale = _stale_since_built(ctx)
    code = _print(results, shown_path(ctx.robot_path), quiet, stale, report, place)
    if not quiet:
        print(f"  report: {shown_path(folder / 'report.md')}")
        if (folder / "index.html").is_file():  # output.page: its tables are the report's
            print(f"  page: {shown_path(folder / 'index.html')}")
    if args.warp:
        from mjcfbuild.check.warp import check_in_warp

        scene = ctx.scene_path if ctx.scene_path.exists() else ctx.robot_path
        warp = check_in_warp(str(scene))
        print(f"  MuJoCo Warp: {warp.worlds} worlds, {warp.steps} steps, finite")
        if ctx.manifest.training is not None:
            code = _prove_training_variant(ctx) or code
    return code


def _prove_training_variant(ctx) -> int:
    """The training variant against the full model in MuJoCo Warp; EXIT_CHECK if it fails."""
    import json

    from mjcfbuild.check.warp_variant import gpu_device, prove_on_gpu, prove_variant
    from mjcfbuild.engine.progress import Progress
    from mjcfbuild.engine.report import write_report
    from mjcfbuild.engine.runner import build_lock
    from mjcfbuild.fsutil import md5_file
    from mjcfbuild.outputs import TRAINING_WARP, training_paths

    variant, scene = training_paths(ctx)
    if not scene.exists():
        raise CheckError(
            "the training variant has not been built",
            file=ctx.label(scene),
            hint=f"run mjcfbuild build {ctx.manifest_label}",
        )
    hold = ctx.manifest.check.hold_tolerance
    proof = prove_variant(str(ctx.scene_path), str(scene), hold)
    print("\n".join(proof.lines()))
    record: dict = {
        "full": proof.full.to_dict(),
        "variant": proof.variant.to_dict(),
        "behaviour": proof.behaviour,
        "failures": proof.failures,
        "variant_md5": md5_file(variant),
    }
    failures = list(proof.failures)
    gpu = gpu_device()
    if gpu:  # measured there too, at a training batch size
        record["gpu"], on_gpu = prove_on_gpu(str(ctx.scene_path), str(scene), hold, *gpu)
        failures += on_gpu
    with build_lock(ctx, Progress(quiet=True)):
        ctx.state(TRAINING_WARP).write_text(json.dumps(record, indent=1, sort_keys=True) + "\n")
        write_report(ctx)
    for failure in failures:
        print(f"mjcfbuild: check failed: {ctx.label(scene)}: {failure}", file=sys.stderr)
    return EXIT_CHECK if failures else EXIT_OK


def _read_if_present(path: Path) -> bytes | None:
    try:
        return path.read_bytes()
    except OSError:
        return None


def _up_to_date(ctx) -> int:
    from mjcfbuild.engine.freshness import report_behind, stale_outputs

    stale = stale_outputs(ctx)
    if not stale:
        behind = report_behind(ctx)
        after = (
            f" (its report is not: {', '.join(behind)} did not complete since their inputs "
            "changed; mjcfbuild build runs them)"
            if behind
            else ""
        )
        print(f"mjcfbuild: {ctx.manifest_label}: {ctx.label(ctx.out_dir)} is up to date{after}")
        return EXIT_OK
    for line in stale:
        print(f"mjcfbuild: stale: {line}", file=sys.stderr)
    print(
        f"mjcfbuild: {ctx.manifest_label}: {ctx.label(ctx.out_dir)} is out of date; "
        f"run mjcfbuild build {ctx.manifest_label}",
        file=sys.stderr,
    )
    return EXIT_CHECK


def _tolerance(text: str) -> float:
    """A tolerance: a positive number (nan compared false with every error and passed all)."""
    import math

    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError("must be a positive number, such as 1e-6")
    return value


def _configurations(text: str) -> int:
    """A count of configurations: 1 to MOST_CONFIGURATIONS."""
    from mjcfbuild.manifest.models import MOST_CONFIGURATIONS

    value = positive_int(text)
    if value > MOST_CONFIGURATIONS:
        raise argparse.ArgumentTypeError(f"must be from 1 to {MOST_CONFIGURATIONS}")
    return value
