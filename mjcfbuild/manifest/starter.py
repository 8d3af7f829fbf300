"""``mjcfbuild init``: a commented starting manifest written from a look at the description."""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.console import shown_path
from mjcfbuild.errors import InputError, MjcfbuildError, OutputError, UsageError
from mjcfbuild.fsutil import unreadable_file
from mjcfbuild.manifest.models import NAME_PATTERN
from mjcfbuild.sources.infer import (
    InferredPackage,
    find_package_xml,
    infer_package,
    package_references,
)
from mjcfbuild.sources.kind import not_a_description, xacro_evidence
from mjcfbuild.sources.packages import PackageResolver, find_enclosing_package

if TYPE_CHECKING:
    from mjcfbuild.urdf.model import Robot

_PACKAGE_URI = re.compile(rb"package://([A-Za-z0-9_.-]+)/")
_FIND = re.compile(rb"\$\(find\s+([A-Za-z0-9_.-]+)\)")
_ROBOT_NAME = re.compile(rb"<robot[^>]*\sname=\"([^\"]+)\"")
_COMMENT = re.compile(rb"<!--.*?-->", re.S)
_CAD_NAME = re.compile(r"\.(SLDASM|SLDPRT|STEP|STP|IAM|IPT)$", re.IGNORECASE)


def write_starter_manifest(
    source: str, packages: dict[str, str], output: str, force: bool = False
) -> tuple[Path, list[str], list[str]]:
    """Write a manifest for ``source`` to ``output``; return its path, what the build will
    stop at unless the user acts (packages the description names that were not found, the
    error that kept the description from being read) and what the manifest chose for the
    user to know (files read from outside the description), one line each."""
    source_path = Path(source).resolve()
    if not source_path.is_file():
        raise InputError(f"source file {unreadable_file(source) or 'not found'}", file=source)
    what = not_a_description(source_path, source_path.read_bytes())
    if what is not None:
        raise InputError(
            f"{source} is {what}, not a URDF or xacro file",
            hint="pass the robot's .urdf or .xacro file; it names its meshes itself",
        )
    manifest_path = Path(output).resolve()
    if manifest_path.exists() and not force:
        raise UsageError(f"{output} already exists", hint="pass --force to overwrite it")
    warnings: list[str] = []
    notes: list[str] = []
    text = starter_manifest_text(
        source_path,
        packages,
        manifest_path.parent,
        Path(output).name,
        warnings,
        label=source,
        notes=notes,
    )
    try:
        manifest_path.parent.mkdir(parents=True, exist_ok=True)
        manifest_path.write_text(text)
    except OSError as exc:
        raise OutputError(f"cannot write the manifest: {exc.strerror}", file=output) from None
    return Path(output), warnings, notes


def starter_manifest_text(
    source: Path,
    packages: dict[str, str],
    manifest_dir: Path,
    manifest_name: str = "robot.yaml",
    warnings: list[str] | None = None,
    label: str | None = None,
    notes: list[str] | None = None,
) -> str:
    """The manifest text: source, packages it needs, xacro args with their defaults.
    ``warnings`` receives what the first build would stop at: packages the description names
    that were not found, and the error that kept the description from being read, naming the
    source as ``label`` (as the user gave it; by default its path). ``notes`` receives what
    the manifest chose that the user should know: that it reads files from outside every
    package folder (``source.read_outside``), that a robot without mass stays fixed."""
    warnings = [] if warnings is None else warnings
    notes = [] if notes is None else notes
    label = label or str(source)
    data = source.read_bytes()
    # What a comment mentions is no reference (its line breaks kept, for the lines below).
    live = _COMMENT.sub(lambda comment: b"\n" * comment.group().count(b"\n"), data)
    # By what the file uses: a URDF that only declares the xacro namespace is read as it is
    # (through xacro, errors would cite lines of an expanded copy).
    is_xacro = xacro_evidence(data) is not None
    relative = _relative(source, manifest_dir)
    match = _ROBOT_NAME.search(data)
    stem = source.name.split(".")[0]
    raw_name = match.group(1).decode() if match else stem
    # A substitution, or a CAD assembly's name (SolidWorks' exporter writes
    # "SO_5DOF_ARM100_8j_URDF.SLDASM"): the file's own name reads better.
    name = _valid_name(stem if "$" in raw_name or _CAD_NAME.search(raw_name) else raw_name)

    needed = sorted({m.decode() for m in _PACKAGE_URI.findall(live) + _FIND.findall(live)})
    known = dict(packages)
    package_notes: dict[str, str] = {}
    references = package_references(data)
    for package in needed:
        if package in known:
            continue
        claimed = find_package_xml(package, source)
        named = references.get(package, [])
        if claimed and named and not any((claimed[0] / path).exists() for path in named):
            # A package.xml naming it beside none of the files the description names in it
            # (hpp-environments' wheel keeps its package.xml apart from its meshes): the build
            # would stop at the first file, so the files decide where they are found.
            found = infer_package(package, named, source)
            if found is not None:
                known[package] = str(found.folder)
                package_notes[package] = (
                    f"  # {package}: the package.xml naming it "
                    f"({_relative(claimed[0], manifest_dir)}) holds none of the files the "
                    "description names in it; they are in this folder"
                )
                continue
        if claimed:
            known[package] = str(claimed[0])
            if len(claimed) > 1:
                package_notes[package] = _twice_note(package, claimed, manifest_dir)
                warnings.append(
                    f"{shown_path(claimed[1] / 'package.xml')}: package '{package}' is named by "
                    f"{len(claimed)} package.xml files; the manifest takes the nearest, "
                    f"{_relative(claimed[0], manifest_dir)} (catkin and colcon refuse a "
                    "workspace with two): check its line under packages"
                )
            continue
        found = infer_package(package, references.get(package, []), source)
        if found is not None:
            known[package] = str(found.folder)
            package_notes[package] = _inferred_note(package, found, needed)
    enclosing = find_enclosing_package(source)
    # One name per folder: the description's own package only under a name it uses, or under
    # its package.xml's name when no other name already points there.
    if enclosing is not None and enclosing[0] not in known:
        folders = {Path(folder).resolve() for folder in known.values()}
        if enclosing[1].resolve() not in folders:
            known[enclosing[0]] = str(enclosing[1])

    lines = [
        f"# mjcfbuild manifest for {relative}. Build it with: mjcfbuild build {manifest_name}",
        "# Every path is relative to this file's folder.",
        "# Editor completion: run 'mjcfbuild schema > robot.schema.json' and make this line",
        "# the first one: # yaml-language-server: $schema=robot.schema.json",
        f"name: {name}",
        "",
        "source:",
        f"  {'xacro' if is_xacro else 'urdf'}: {relative}",
    ]
    early = _read_before_declared(live, data) if is_xacro else {}
    # The folders the build reads from without a warning (families/plan.py's roots).
    roots = [manifest_dir, source.parent, *(Path(folder) for folder in known.values())]
    outside: list[tuple[str, str]] = []
    free_joint, unread, expanded = _free_joint_lines(
        source, is_xacro, known, data, label, early, roots, outside, notes=notes
    )
    if is_xacro:
        arguments = _declared_args(data)
        if arguments:
            lines.append("  # xacro arguments as name: value. The file declares these defaults:")
            lines += [f"  #   {arg}: {_yaml_scalar(default)}" for arg, default in arguments]
        if early:
            # ur_description's <robot name="$(arg name)"> comes before <xacro:arg name="name">:
            # xacro reads in order, so such a default never applies and the argument is needed.
            lines.append("  # Read before the file declares them, so xacro needs these given:")
            lines.append("  args:")
            lines += [f"    {arg}: {_yaml_scalar(value)}" for arg, value in early.items()]
        else:
            lines.append("  args: {}")
    if outside:
        lines += _read_outside_lines(outside)
        where, uri = outside[0]
        more, them = (f" and {len(outside) - 1} more files", "them") if outside[1:] else ("", "it")
        notes.append(
            f"{where}: reads '{uri}'{more} from outside every package folder and "
            f"{manifest_name}'s folder; {manifest_name} sets source.read_outside: true, so the "
            f"build reads {them} without a warning (to publish a self-contained model, move "
            f"{them} into the description and drop that line)"
        )
    lines += [
        "",
        "# ROS packages named by package:// URIs and $(find ...), as name: folder.",
        "# Packages not listed are looked up in ROS_PACKAGE_PATH and AMENT_PREFIX_PATH.",
    ]
    unresolved = [package for package in needed if package not in known]
    # Read with its default arguments, the description did without these: found nowhere, so
    # xacro skipped what names them (a $(find) under a false <xacro:if>), and its URDF names
    # none. (One found in ROS_PACKAGE_PATH may have been used: it stays "needed".)
    nowhere = set(_not_in_the_environment(unresolved))
    optional = (
        [p for p in unresolved if p in nowhere and p.encode() not in _uris(expanded)]
        if expanded is not None
        else []
    )
    unresolved = [package for package in unresolved if package not in optional]
    lines += [
        f"#   {package}: path/to/{package}  # needed by the description" for package in unresolved
    ]
    lines += [
        f"#   {package}: path/to/{package}  # only with other xacro arguments than the defaults"
        for package in optional
    ]
    lines.append("packages:" if known else "packages: {}")
    for package in sorted(known):
        if package in package_notes:
            lines.append(package_notes[package])
        lines.append(f"  {package}: {_relative(Path(known[package]), manifest_dir)}")
    missing = _not_in_the_environment(unresolved)
    if missing:
        warnings.append(
            f"{label}:{_first_line_naming(live, missing[0])}: package"
            f"{'s' if len(missing) > 1 else ''} {', '.join(repr(p) for p in missing)} not "
            f"found; the manifest lists {'them' if len(missing) > 1 else 'it'} commented out "
            f"under packages: give {'each' if len(missing) > 1 else 'it'} its folder (or pass "
            "--package NAME=DIR)"
        )
    # A package not found is what kept the description from being read: said once, above.
    if unread is not None and not any(f"'{package}'" in unread for package in missing):
        warnings.append(f"{unread}; the build stops there until the description is fixed")
    lines += [
        "",
        "options:",
        *free_joint,
        "  fuse_static: true   # merge links on fixed joints into their parent body",
        "",
        "# Every moving joint gets a position servo (wheels on the floor a velocity servo) tuned",
        "# from its inertia at home to ring at 10 Hz, critically damped; <ros2_control> command",
        "# interfaces and <transmission>s pick the type where the description has them.",
        "actuators:",
        "  default: position   # or velocity, motor, none (a passive model)",
        "  # rules:            # first match wins",
        '  #   - {joints: ["*finger*"], frequency: 5, armature: 0.01}',
        '  #   - {joints: ["*wheel*"], type: velocity}',
        '  #   - {joints: ["*_knee"], motor: go1_knee}   # a real drive, by name',
        "",
        "# Real drives by their datasheet values: the joint gets the rotor's reflected inertia",
        "# (armature = rotor_inertia x ratio^2), the peak torque as its force limit and the",
        "# torque-speed line. Names: these, your files', or mjcfbuild's catalogue (go1_hip,",
        "# go1_knee, dynamixel_xm430_w350, maxon_ec45flat70_hd100); see docs/simulation.md.",
        "# motors:",
        "#   files: [motors.yaml]",
        "#   define:",
        "#     my_knee: {rotor_inertia: 1.1e-4, ratio: 9, peak_torque: 35.5, no_load_speed: 20}",
        "",
        "# The home pose, joint pattern: position. Joints not named take their ros2_control",
        "# initial_value, else 0 clipped into their range.",
        "home: {}",
        '#   "*elbow*": 1.57',
        "",
        "# Robot body pairs that are adjacent, touch at home or always touch are excluded from",
        "# contact. A MoveIt SRDF adds its <disable_collisions> pairs:",
        "# self_collision: {srdf: config/robot.srdf}",
        "",
        "output:",
        "  folder: mjcf        # writes mjcf/<name>.xml, mjcf/scene.xml and mjcf/assets/",
        "",
    ]
    return "\n".join(lines)


def _read_outside_lines(outside: list[tuple[str, str]]) -> list[str]:
    """The manifest's ``read_outside`` line and the comment saying which files made it."""
    first = outside[0][1]
    more = f" and {len(outside) - 1} more" if outside[1:] else ""
    return [
        f"  # The description reads '{first}'{more} from outside every package folder and",
        "  # this folder; the build warns of each such file unless this is set. To publish a",
        "  # self-contained model, move them into the description and drop this line.",
        "  read_outside: true",
    ]


def _twice_note(package: str, folders: list[Path], manifest_dir: Path) -> str:
    """The comment above a package whose name more than one package.xml gives."""
    others = ", ".join(_relative(folder, manifest_dir) for folder in folders[1:])
    return f"  # {package}: the nearest package.xml naming it; named by another in: {others}"


def _inferred_note(package: str, found: InferredPackage, used: list[str]) -> str:
    """The comment above a package found from the files the description names in it
    (``used``: every package name the description uses)."""
    where = f"from the description's {found.evidence}, found in this folder"
    if found.package_xml is None:
        return f"  # {package}: inferred (no package.xml) {where}"
    if found.package_xml == package:
        return f"  # {package}: its package.xml is in this folder"
    if found.package_xml in used:
        return (
            f"  # {package}: inferred {where}; its package.xml names it '{found.package_xml}', "
            "which the description uses too: both names are this folder"
        )
    return (
        f"  # {package}: inferred {where}; its package.xml names it '{found.package_xml}', "
        "which the description does not use"
    )


def _not_in_the_environment(packages: list[str]) -> list[str]:
    """Those of ``packages`` that ROS_PACKAGE_PATH and AMENT_PREFIX_PATH do not hold either
    (the build finds those that they hold)."""
    resolver = PackageResolver({}, os.environ)
    missing = []
    for package in packages:
        try:
            resolver.find(package)
        except InputError:
            missing.append(package)
    return missing


def _first_line_naming(data: bytes, package: str) -> int:
    """The line of the first ``package://`` URI or ``$(find)`` naming ``package`` in ``data``."""
    name = re.escape(package.encode())
    match = re.search(rb"package://" + name + rb"/|\$\(find\s+" + name + rb"\)", data)
    return data[: match.start()].count(b"\n") + 1 if match else 1


def _uris(urdf: bytes | None) -> set[bytes]:
    """The package names a URDF's ``package://`` URIs name."""
    return set(_PACKAGE_URI.findall(urdf or b""))


def _free_joint_lines(
    source: Path,
    is_xacro: bool,
    packages: dict[str, str],
    data: bytes,
    label: str,
    args: dict[str, str],
    roots: list[Path],
    outside: list[tuple[str, str]],
    notes: list[str] | None = None,
) -> tuple[list[str], str | None, bytes | None]:
    """The manifest's free_joint line, decided from the robot's kinematics and geometry
    (urdf.base); from its names only where the description cannot be read here, with the
    error (one line) that kept it from being read; and the URDF it read (None where none).
    ``outside`` receives the files it reads from outside ``roots`` (``_first_stop``).
    ``notes`` receives why a robot that would float does not (it has no mass)."""
    from mjcfbuild.sources.origins import map_lines
    from mjcfbuild.urdf.base import classify_base

    expansion = None
    try:
        from mjcfbuild.sources.expand import expand_source
        from mjcfbuild.urdf.parse import parse_urdf

        expansion = expand_source(source, is_xacro, args, packages, dict(os.environ))
        robot = parse_urdf(expansion.urdf, label)
        kind = classify_base(robot)
    except Exception as exc:  # an unreadable description: init still writes a starting manifest
        # The build reports anything else itself; a user error is worth telling now.
        # Its file named from the current folder, as the build names it; a line of the
        # expanded text where the xacro file wrote it.
        if isinstance(exc, MjcfbuildError) and expansion is not None:
            map_lines(exc, expansion.origins)
        here = Path.cwd()
        unread = exc.relocate(here, here).one_line() if isinstance(exc, MjcfbuildError) else None
        legs = _leg_words(data)
        if legs:
            return (
                [
                    f"  # Names like {', '.join(legs)} suggest a walking robot (the description",
                    "  # could not be read to tell): its base floats.",
                    "  free_joint: true",
                ],
                unread,
                None,
            )
        return (
            ["  free_joint: false   # true for a floating base (legged robots, humanoids)"],
            unread,
            None,
        )
    stop = _first_stop(robot, source, packages, expansion.origins, roots, outside)
    if kind.floating and not _has_mass(robot):
        # A free joint makes the root a moving body, and MuJoCo cannot simulate a moving body
        # of no mass: the build would refuse what the description leaves a static prop.
        if notes is not None:
            weighed = f", or {FROM_GEOMETRY}," if _has_geometry(robot) else ""
            notes.append(
                f"{label}: no link has a mass (<inertial>), so the manifest fixes the robot to "
                "the world (free_joint: false): MuJoCo cannot simulate a floating base without "
                f"one (add the links' <inertial> elements{weighed} then set free_joint: true "
                "to float it)"
            )
        return (
            [
                "  # No link has a mass (<inertial>), and MuJoCo cannot simulate a floating",
                "  # base without one: fixed to the world. true once the links have <inertial>",
                "  # (or masses from their geometry: inertia: {missing: geometry}).",
                "  free_joint: false",
            ],
            stop,
            expansion.urdf,
        )
    if kind.floating:
        return (
            [
                f"  # Its base floats: {kind.why}. The build stands it on the floor at home.",
                "  free_joint: true",
            ],
            stop,
            expansion.urdf,
        )
    return [f"  free_joint: false   # {kind.why}; true for a floating base"], stop, expansion.urdf


def _first_stop(
    robot: Robot,
    source: Path,
    packages: dict[str, str],
    origins: dict[int, tuple[str, int]],
    roots: list[Path],
    outside: list[tuple[str, str]],
) -> str | None:
    """What the first build would stop at in a description that reads (a mesh that is not
    there, an absolute path from another machine, no mass anywhere), as one line: init says
    it now, not one build later. A xacro source's line is the one ``origins`` says wrote the
    expanded line, as the build names it. ``outside`` receives (where, URI) of each file the
    build would warn is read from outside ``roots`` and every package folder."""
    from mjcfbuild.sources.origins import map_lines, written_in
    from mjcfbuild.urdf.resolve import OutsideRead, resolve_files

    found: list[OutsideRead] = []
    try:
        folders = {name: Path(folder) for name, folder in packages.items()}
        resolver = PackageResolver(folders, dict(os.environ))
        resolve_files(robot, source.parent, resolver, roots=roots, outside=found)
    except MjcfbuildError as exc:
        map_lines(exc, origins)
        here = Path.cwd()
        return exc.relocate(here, here).one_line()
    for read in found:
        where = robot.source if read.line is None else f"{robot.source}:{read.line}"
        written = written_in(origins, read.line) if read.line is not None else None
        if written is not None:  # a xacro source: the line that wrote the element
            where = f"{shown_path(written[0])}:{written[1]}"
        outside.append((where, read.uri))
    moving = [joint for joint in robot.joints if joint.moves]
    if moving and not _has_mass(robot):
        weighed = f"; or {FROM_GEOMETRY}" if _has_geometry(robot) else ""
        return (
            f"{robot.source}: no link of the robot has a mass (<inertial>), so it cannot be "
            f"simulated (add each link's <inertial>: mass, centre of mass, inertia{weighed})"
        )
    return None


# robot.yaml's option for a description without masses whose links have geometry.
FROM_GEOMETRY = (
    "set inertia: {missing: geometry} in robot.yaml to give each link the mass of its "
    "geometry, as MuJoCo's own URDF import does"
)


def _has_mass(robot: Robot) -> bool:
    """Whether some link of ``robot`` has a mass (an ``<inertial>`` with a positive one)."""
    return any(link.inertial and link.inertial.mass > 0 for link in robot.links)


def _has_geometry(robot: Robot) -> bool:
    """Whether some link of ``robot`` has geometry that could give it a mass."""
    return any(link.shapes for link in robot.links)


_LEG_WORDS = ("hip", "thigh", "knee", "calf", "shank", "ankle", "foot", "HFE", "KFE", "HAA")


def _leg_words(data: bytes) -> list[str]:
    """The leg words the description's joint and link names use, if it has two legs or more."""
    names = re.findall(rb"<(?:joint|link)\s[^>]*name=\"([^\"]+)\"", data)
    found = []
    for word in _LEG_WORDS:
        count = sum(1 for name in names if word.lower().encode() in name.lower())
        if count >= 2:
            found.append(word)
    return found[:3]


def _relative(path: Path, start: Path) -> str:
    """``path`` as robot.yaml (in ``start``) names it: relative, unless it is three folders
    or more up and over (another tree, which may stay where it is when the repo moves). A folder
    holding robot.yaml, however far up (the description's own package: xacro's sdist keeps
    its robot in test/robots/pr2), moves with it, so it stays relative."""
    relative = os.path.relpath(path, start)
    if not relative.startswith("../../..") or all(part == ".." for part in Path(relative).parts):
        return relative
    return str(path)


def _valid_name(text: str) -> str:
    cleaned = re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_.-")
    return cleaned if re.match(NAME_PATTERN, cleaned or "") else "robot"


def _yaml_scalar(text: str) -> str:
    if text in ("true", "false") or re.fullmatch(r"-?[0-9.]+", text or "x"):
        return text
    return '"' + text.replace('"', '\\"') + '"'


def _read_before_declared(live: bytes, data: bytes) -> dict[str, str]:
    """The arguments a xacro file reads (``$(arg name)``, outside comments) on a line before
    its ``<xacro:arg>`` declares them, with their declared defaults: xacro reads the file in
    order, so it fails there unless they are given."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:
        return {}
    # A macro's body is read where the macro is called, not where it is written.
    macros = [
        (macro.sourceline or 0, max(e.sourceline or 0 for e in macro.iter()))
        for macro in root.iter("{*}macro")
        if "xacro" in (etree.QName(macro).namespace or "")
    ]
    early: dict[str, str] = {}
    for element in root.iter("{*}arg"):
        name = element.get("name")
        if not name or "xacro" not in (etree.QName(element).namespace or ""):
            continue
        declared = element.sourceline or 0
        for use in re.finditer(rb"\$\(arg\s+" + re.escape(name.encode()) + rb"\s*\)", live):
            line = live.count(b"\n", 0, use.start()) + 1
            if line >= declared:
                break
            if not any(start <= line <= end for start, end in macros):
                early.setdefault(name, element.get("default", ""))
                break
    return early


def _declared_args(data: bytes) -> list[tuple[str, str]]:
    """The ``<xacro:arg>`` elements of a xacro file, as (name, default), in file order: read as
    XML, as xacro reads them (either quote, spaces around ``=``, attributes in any order);
    none where the file is no well-formed XML (the build then says why)."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:
        return []
    return [
        (element.get("name", ""), element.get("default", ""))
        for element in root.iter("{*}arg")
        if "xacro" in (etree.QName(element).namespace or "") and element.get("name")
    ]
