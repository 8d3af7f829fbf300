"""A :class:`ModelDiff` written for a terminal, a pull request comment (Markdown) or a program
(JSON); before/after pictures placed side by side."""

from __future__ import annotations

import json
import shutil
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mjcfbuild.diff.compare import GROUPS, Change, ModelDiff
from mjcfbuild.markup import markdown_code, markdown_target, markdown_text

NO_CHANGES = "no model changes"


@dataclass(frozen=True)
class Sides:
    """What is compared: each side's label (a git revision, a folder) and build folder."""

    base_label: str
    head_label: str
    base_folder: Path
    head_folder: Path
    model: str
    base_model: str = ""  # the base's model file, where the robot was renamed since

    @property
    def models(self) -> str:
        """The model's file, or both where the robot was renamed."""
        if self.base_model and self.base_model != self.model:
            return f"{self.base_model} -> {self.model} (renamed)"
        return self.model


def value_text(value: Any) -> str:
    """A value as a reviewer reads it: numbers to 6 significant digits, ``-`` for none."""
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list):
        return "[" + " ".join(value_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return ", ".join(f"{key} {value_text(item)}" for key, item in value.items())
    return str(value)


def change_line(change: Change, group: str) -> str:
    """One change as a line of text (``subject: what before -> after; note``)."""
    if group == "previews":
        return f"{change.subject}: {change.what}"
    if change.what in ("added", "removed"):
        shown = change.after if change.what == "added" else change.before
        text = f"{change.subject}: {change.what} ({value_text(shown)})"
    else:
        text = (
            f"{change.subject}: {change.what} {value_text(change.before)} -> "
            f"{value_text(change.after)}"
        )
    return text + (f"; {change.note}" if change.note else "")


def text(diff: ModelDiff, sides: Sides) -> str:
    """The diff for a terminal: a header, then each group's changes, one a line."""
    lines = [f"mjcfbuild diff: {sides.models}: {sides.base_label} -> {sides.head_label}"]
    if diff.empty:
        lines.append(NO_CHANGES)
    for key, title in GROUPS:
        changes = diff.groups.get(key)
        if not changes:
            continue
        lines.append(f"{title} ({len(changes)})")
        lines.extend(f"  {change_line(change, key)}" for change in changes)
    return "\n".join(lines) + "\n"


def _cell(value: Any) -> str:
    return markdown_text(value_text(value))


def markdown(diff: ModelDiff, sides: Sides, pictures: dict[str, str] | None = None) -> str:
    """The diff as a pull request comment: a table per group; ``pictures`` maps a changed
    preview's name to the side-by-side picture's path (relative to the Markdown file)."""
    lines = [
        f"### Model changes: {markdown_code(sides.models)}",
        "",
        f"{markdown_code(sides.base_label)} → {markdown_code(sides.head_label)}",
        "",
    ]
    if diff.empty:
        lines.append(f"**{NO_CHANGES}**")
    for key, title in GROUPS:
        changes = diff.groups.get(key)
        if not changes:
            continue
        lines += [f"#### {title} ({len(changes)})", ""]
        if key == "previews":
            for change in changes:
                path = (pictures or {}).get(change.subject)
                alt = markdown_text(f"{change.subject}: before, after")
                shown = f"![{alt}]({markdown_target(path)})" if path else ""
                subject = markdown_code(change.subject)
                lines.append(f"- {subject} {markdown_text(change.what)} (before, after): {shown}")
            lines.append("")
            continue
        lines += ["| | what | before | after | note |", "|---|---|---|---|---|"]
        for change in changes:
            lines.append(
                f"| {_cell(change.subject)} | {_cell(change.what)} | {_cell(change.before)} "
                f"| {_cell(change.after)} | {_cell(change.note or '')} |"
            )
        lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"


def as_json(diff: ModelDiff, sides: Sides) -> str:
    """The diff as JSON: both sides, whether anything changed, the groups' changes."""
    data = {
        "model": sides.model,
        "base_model": sides.base_model or sides.model,
        "base": sides.base_label,
        "head": sides.head_label,
        "changed": not diff.empty,
        "groups": diff.to_dict(),
    }
    return json.dumps(data, indent=1, sort_keys=True) + "\n"


def side_by_side(diff: ModelDiff, sides: Sides, folder: Path) -> dict[str, str]:
    """Write each changed preview's before and after pictures next to each other (a grey
    bar between) into ``folder/previews``; the picture paths relative to ``folder``."""
    from PIL import Image

    written = {}
    target = folder / "previews"
    for change in diff.groups.get("previews", []):
        name = change.subject
        before = sides.base_folder / "report" / "previews" / name
        after = sides.head_folder / "report" / "previews" / name
        target.mkdir(parents=True, exist_ok=True)
        if not (before.is_file() and after.is_file()):
            shutil.copyfile(after if after.is_file() else before, target / name)
        else:
            with Image.open(before) as left, Image.open(after) as right:
                gap = 8
                width = left.width + gap + right.width
                height = max(left.height, right.height)
                canvas = Image.new("RGB", (width, height), (128, 128, 128))
                canvas.paste(left.convert("RGB"), (0, 0))
                canvas.paste(right.convert("RGB"), (left.width + gap, 0))
                canvas.save(target / name, format="PNG", optimize=False)
        written[name] = f"previews/{name}"
    return written
