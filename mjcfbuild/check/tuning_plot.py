"""The tuning report's plot of one actuator group, drawn with Pillow: the step response (a share
of the step made, against time) beside the sine response (from the settled pose, a share of the
commanded amplitude, with the command dashed). Same traces, same bytes."""

from __future__ import annotations

import io

from mjcfbuild.check.tuning import SINE_HZ

WIDTH, HEIGHT = 900, 340
PANEL = 420  # each panel's width
MARGIN = 44
COLOURS = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
]
SHOWN = len(COLOURS)  # joints drawn per plot; the table has them all


def plot_group(group) -> bytes:
    """A PNG of a :class:`~mjcfbuild.check.tuning.GroupResponse`."""
    from PIL import Image, ImageDraw, ImageFont

    image = Image.new("RGB", (WIDTH, HEIGHT), (255, 255, 255))
    draw = ImageDraw.Draw(image)
    font = ImageFont.load_default()
    draw.text((MARGIN, 6), f"{group.label} ({group.kind})", fill=(0, 0, 0), font=font)
    joints = list(group.step_traces)[:SHOWN]
    # The step panel spans three settling times (the whole window where a joint never settles),
    # so a fast servo's response is not a vertical line at the left edge.
    settling = [j.settling_time for j in group.joints]
    span = group.times[-1] if None in settling or not settling else 3 * max(settling)
    shown = [k for k, t in enumerate(group.times) if t <= max(span, 0.05)]
    times = [0.0] + [group.times[k] for k in shown]  # from the moment of the step
    steps = [[0.0] + [group.step_traces[j][k] for k in shown] for j in joints]
    step_values = [v for trace in steps for v in trace] + [0.0, 1.2]
    _panel(
        draw,
        font,
        0,
        "step (share of the step made)",
        times,
        steps,
        (min(step_values), max(step_values)),
        reference=[1.0] * len(times),
    )
    sine_values = [v for j in joints for v in group.sine_traces[j]] + group.sine_reference
    extent = max((abs(v) for v in sine_values), default=1.0) or 1.0
    _panel(
        draw,
        font,
        1,
        f"sine at {SINE_HZ:g} Hz (share of the amplitude; dashed: command)",
        [0.0, *group.times],
        [[0.0, *group.sine_traces[j]] for j in joints],
        (-1.1 * extent, 1.1 * extent),
        reference=[0.0, *group.sine_reference],
    )
    for k, joint in enumerate(joints):
        x = MARGIN + k * (WIDTH - 2 * MARGIN) // max(1, len(joints))
        draw.rectangle((x, HEIGHT - 16, x + 10, HEIGHT - 8), fill=COLOURS[k])
        draw.text((x + 14, HEIGHT - 19), joint[:18], fill=(0, 0, 0), font=font)
    buffer = io.BytesIO()
    image.save(buffer, format="PNG", optimize=False)
    return buffer.getvalue()


def _panel(draw, font, column, title, times, traces, bounds, reference) -> None:
    left = MARGIN + column * (PANEL + MARGIN)
    top, bottom = 34, HEIGHT - 48
    right = left + PANEL - MARGIN // 2
    low, high = bounds
    if high <= low:
        high = low + 1.0
    end = times[-1] if times else 1.0

    def point(t: float, y: float) -> tuple[float, float]:
        x = left + (right - left) * t / end
        return x, bottom - (bottom - top) * (y - low) / (high - low)

    draw.rectangle((left, top, right, bottom), outline=(0, 0, 0))
    draw.text((left, top - 14), title, fill=(0, 0, 0), font=font)
    draw.text((left - 40, top - 4), f"{high:.3g}", fill=(0, 0, 0), font=font)
    draw.text((left - 40, bottom - 8), f"{low:.3g}", fill=(0, 0, 0), font=font)
    draw.text((right - 40, bottom + 4), f"{end:.3g} s", fill=(0, 0, 0), font=font)
    if low < 0 < high:
        draw.line([point(0, 0), point(end, 0)], fill=(200, 200, 200))
    dashes = [point(t, y) for t, y in zip(times, reference, strict=False)]
    for k in range(0, len(dashes) - 1, 6):
        draw.line(dashes[k : k + 4], fill=(90, 90, 90))
    for k, trace in enumerate(traces):
        draw.line(
            [point(t, y) for t, y in zip(times, trace, strict=False)], fill=COLOURS[k], width=2
        )
