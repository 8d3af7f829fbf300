"""The tuning report's section of report.md: one row per actuator group (its worst joint for
each figure) and its plot. How to read it: docs/simulation.md, "The tuning report"."""

from __future__ import annotations

from mjcfbuild.markup import markdown_target, markdown_text


def tuning_lines(tuning: dict) -> list[str]:
    """The section, or nothing where the report was not made."""
    groups = tuning.get("groups")
    if not groups:
        return []
    lines = [
        "## Tuning",
        "",
        "Each group stepped and swept from home, base held and contacts off (docs/simulation.md"
        ", the tuning report); worst joint of the group per figure.",
        "",
        "| group | joints | rise time (s) | overshoot | settling time (s) "
        "| steady-state error | sine tracking error | saturation |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for group in groups:
        settling = group.get("settling_time")
        lines.append(
            f"| {markdown_text(group['label'])} | {len(group['joints'])} "
            f"| {_seconds(group.get('rise_time'))} "
            f"| {group['overshoot']:.1%} "
            f"| {'not settled' if settling is None else _seconds(settling)} "
            f"| {group['steady_state_error']:.3g} | {group['tracking_error']:.3g} "
            f"| {group['saturation']:.1%} |"
        )
    lines.append("")
    for name, path in sorted((tuning.get("plots") or {}).items()):
        lines.append(f"![tuning {markdown_text(name)}]({markdown_target(path)})")
    return [*lines, ""]


def _seconds(value: float | None) -> str:
    return "-" if value is None else f"{value:.4f}"
