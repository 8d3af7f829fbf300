"""The progress reporter announces the model as soon as the tasks that write it are done,
before any task that reads it (check, previews, tuning report) starts."""

from __future__ import annotations

import io

from mjcfbuild.engine.progress import FAILED, RAN, UP_TO_DATE, Progress

LINE = "mjcfbuild: model ready: mjcf/arm.xml, mjcf/scene.xml"


class Recorded(Progress):
    """A progress that also writes when each task starts, in the order events come."""

    def started(self, name: str, title: str) -> None:
        self.stream.write(f"started {name}\n")
        super().started(name, title)


def _announced(progress: Progress) -> list[str]:
    stream = progress.stream
    assert isinstance(stream, io.StringIO)
    return [line for line in stream.getvalue().splitlines() if line.startswith(LINE)]


def test_the_line_waits_for_every_task_that_writes_the_model():
    progress = Progress(stream=io.StringIO(), live=False)
    progress.announce_model(["assemble", "scene"], LINE, since=0.0)
    progress.started("assemble", "assemble arm.xml")
    progress.finished("assemble", RAN)
    assert _announced(progress) == [] and progress.model_ready is None
    progress.finished("scene", UP_TO_DATE)  # the floor did not move: the scene stands
    assert len(_announced(progress)) == 1 and progress.model_ready is not None
    progress.finished("check", RAN)
    assert len(_announced(progress)) == 1  # once


def test_no_line_when_the_model_did_not_change_or_was_not_written():
    unchanged = Progress(stream=io.StringIO(), live=False)
    unchanged.announce_model(["assemble", "scene"], LINE, since=0.0)
    unchanged.finished("assemble", UP_TO_DATE)
    unchanged.finished("scene", UP_TO_DATE)
    assert _announced(unchanged) == []
    failed = Progress(stream=io.StringIO(), live=False)
    failed.announce_model(["assemble", "scene"], LINE, since=0.0)
    failed.finished("assemble", FAILED)
    failed.finished("scene", RAN)
    assert _announced(failed) == []
    quiet = Progress(stream=io.StringIO(), quiet=True)
    quiet.announce_model(["assemble"], LINE, since=0.0)
    quiet.finished("assemble", RAN)
    assert quiet.stream.getvalue() == "" and quiet.model_ready is not None


def test_on_a_terminal_the_line_goes_above_the_status_line():
    progress = Progress(stream=io.StringIO(), live=True)
    progress.announce_model(["assemble"], LINE, since=0.0)
    progress.started("assemble", "assemble arm.xml")
    progress.finished("assemble", RAN)
    text = progress.stream.getvalue()
    # cleared, the line, then the status line drawn again below it
    assert f"\r\x1b[2K{LINE} (" in text
    assert text.rindex("\r\x1b[2K[") > text.index(LINE)


def test_a_real_build_announces_the_model_before_anything_it_does_not_need_starts(arm):
    from mjcfbuild.engine.context import BuildContext
    from mjcfbuild.engine.runner import run_build

    ctx = BuildContext.from_manifest_file(arm / "robot.yaml", jobs=2)
    progress = Recorded(stream=io.StringIO(), live=False)
    result = run_build(ctx, progress)
    assert result.ok, result.errors
    lines = progress.stream.getvalue().splitlines()
    ready = [i for i, line in enumerate(lines) if line.startswith("mjcfbuild: model ready: ")]
    assert len(ready) == 1
    assert str(ctx.robot_path) in lines[ready[0]] and str(ctx.scene_path) in lines[ready[0]]
    started = {line.split()[1]: i for i, line in enumerate(lines) if line.startswith("started ")}
    assert started["assemble"] < ready[0]
    # what reads the model, and what only the check needs (its reference kinematics)
    readers = [name for name in started if name in ("check", "previews", "tuning", "reference")]
    assert {"check", "previews", "reference"} <= set(readers), started
    assert all(started[name] > ready[0] for name in readers), "\n".join(lines)
