"""The generic parts every task family uses (engine/family.py), on real files."""

from __future__ import annotations

from mjcfbuild.engine.context import BuildContext
from mjcfbuild.graph.family import discovered_inputs, largest_first, read_record
from mjcfbuild.steps.depfile import Depfile
from tests.conftest import simple_manifest, two_link_urdf, write


def _context(folder) -> BuildContext:
    write(folder / "robot.urdf", two_link_urdf())
    return BuildContext.from_manifest_file(simple_manifest(folder))


def test_what_a_task_read_last_time_becomes_its_dependencies(tmp_path):
    ctx = _context(tmp_path)
    included = write(tmp_path / "included.xacro", "<robot/>")
    depfile = tmp_path / "deps.json"
    assert discovered_inputs(ctx, depfile) == ([], [])  # never ran: nothing recorded
    Depfile(files=[str(included)], missing=[str(tmp_path / "later.xacro")]).write(depfile)
    files, stale = discovered_inputs(ctx, depfile)
    assert files == [included] and stale == []


def test_a_file_it_looked_for_that_appeared_or_one_it_read_that_went_reruns_it(tmp_path):
    ctx = _context(tmp_path)
    included = write(tmp_path / "included.xacro", "<robot/>")
    later = tmp_path / "later.xacro"
    depfile = tmp_path / "deps.json"
    Depfile(files=[str(included)], missing=[str(later)]).write(depfile)
    write(later, "<robot/>")
    _, stale = discovered_inputs(ctx, depfile)
    assert len(stale) == 1 and stale[0](None, {}) is False
    assert "now exists" in stale[0].reason
    later.unlink()
    included.unlink()
    files, stale = discovered_inputs(ctx, depfile)
    assert files == [] and "was removed" in stale[0].reason


def test_the_largest_source_comes_first_and_a_missing_one_last(tmp_path):
    sizes = {"small": 10, "large": 1000, "middle": 100}
    for name, size in sizes.items():
        (tmp_path / name).write_bytes(b"x" * size)
    order = largest_first([*sizes, "gone", "also_gone"], lambda name: str(tmp_path / name))
    assert order == ["large", "middle", "small", "also_gone", "gone"]


def test_a_record_is_empty_until_its_task_wrote_it_whole(tmp_path):
    record = tmp_path / "check.json"
    assert read_record(record) == {}
    record.write_text('{"ok": tr')  # a record cut short
    assert read_record(record) == {}
    record.write_text('{"ok": true}')
    assert read_record(record) == {"ok": True}
