"""Finding the motors that actuator rules name: robot.yaml's ``motors.define``, then the files
of ``motors.files`` in order, then the catalogue shipped with mjcfbuild (``catalogue.yaml``
beside this module, each entry citing its datasheet)."""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

from mjcfbuild.errors import InputError, ManifestError
from mjcfbuild.sources.packages import did_you_mean

if TYPE_CHECKING:
    from mjcfbuild.manifest.motors import Motor, MotorSettings
    from mjcfbuild.manifest.simulation import ActuatorRule

SHIPPED = Path(__file__).with_name("catalogue.yaml")


def read_catalogue(path: Path, label: str) -> dict[str, Motor]:
    """The motors of one motor file; a :class:`ManifestError` with the file's line where it is
    unreadable or a motor does not validate."""
    from pydantic import ValidationError

    from mjcfbuild.manifest.loading import manifest_error_from_validation
    from mjcfbuild.manifest.motors import MotorCatalogue
    from mjcfbuild.manifest.yamlpos import YamlSyntaxError, load_with_positions

    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) else "not UTF-8 text"
        raise ManifestError(f"cannot read the motor file: {reason}", file=label) from None
    try:
        data, positions = load_with_positions(text)
    except YamlSyntaxError as exc:
        raise ManifestError(
            exc.message, file=label, line=exc.line, column=exc.column, hint=exc.hint
        ) from None
    try:
        return MotorCatalogue.model_validate(data or {}).root
    except ValidationError as exc:
        raise manifest_error_from_validation(exc, positions, label) from None


@cache
def shipped_motors() -> dict[str, Motor]:
    """The catalogue that comes with mjcfbuild."""
    return read_catalogue(SHIPPED, "mjcfbuild/control/catalogue.yaml")


def resolve_motors(
    settings: MotorSettings,
    rules: list[ActuatorRule],
    folder: Path,
    manifest_label: str,
) -> dict[str, dict]:
    """Every motor a rule names, as JSON-ready datasheet values (name -> values). An unknown
    name is a :class:`ManifestError` at the rule's ``motor`` key, listing the known names; every
    file of ``motors.files`` is read and checked, named by a rule or not."""
    wanted = [(index, rule.motor) for index, rule in enumerate(rules) if rule.motor]
    if not wanted and not settings.files:
        return {}
    sources: list[dict[str, Motor]] = [dict(settings.define)]
    for index, name in enumerate(settings.files):
        path = folder / name
        if not path.is_file():
            raise InputError(  # a missing input, as a missing source is: exit 4
                f"motor file '{name}' not found",
                file=f"{manifest_label} motors.files[{index}]",
                hint="give a YAML file of motors (name -> datasheet values), relative to "
                "robot.yaml",
            )
        sources.append(read_catalogue(path, name))
    sources.append(shipped_motors())
    resolved: dict[str, dict] = {}
    for index, name in wanted:
        assert name is not None
        found = next((source[name] for source in sources if name in source), None)
        if found is None:
            known = sorted({motor for source in sources for motor in source})
            raise ManifestError(
                f"unknown motor '{name}'{did_you_mean(name, known)}",
                file=f"{manifest_label} actuators.rules[{index}].motor",
                hint=f"use one of {', '.join(known)}, or define it under motors.define",
            )
        resolved[name] = found.model_dump(mode="json")
    return resolved
