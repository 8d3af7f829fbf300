"""doit tasks of the mjcfbuild project: `doit list` shows them, `doit` builds the examples.

* ``plan_examples`` / ``examples`` - build every ``examples/*/robot.yaml`` through the same
  task generators as ``mjcfbuild build`` (see :mod:`mjcfbuild.engine.dodo`);
* ``schema`` - regenerate ``schemas/robot.schema.json`` from the manifest models;
* ``example_meshes`` - regenerate the example arm's meshes;
* ``bench`` - run the build-time benchmark (downloads example-robot-data once).
"""

from pathlib import Path

from doit import create_after

from mjcfbuild.engine.dodo import RobotTasks

DOIT_CONFIG = {
    "default_tasks": ["plan_examples", "examples", "schema"],
    "backend": "sqlite3",
    "dep_file": ".doit.db",
}

ROOT = Path(__file__).parent
EXAMPLES = sorted(str(p) for p in (ROOT / "examples").glob("*/robot.yaml"))
_robots = None


def _examples() -> RobotTasks:
    global _robots
    if _robots is None:
        _robots = RobotTasks(EXAMPLES)
    return _robots


def task_plan_examples():
    """Expand and plan every example robot."""
    yield from _examples().planning("plan_examples")


@create_after(executed="plan_examples")
def task_examples():
    """Build every example robot."""
    yield from _examples().building("examples")


def _write_schema(targets):
    from mjcfbuild.manifest.schema import manifest_schema_text

    Path(targets[0]).write_text(manifest_schema_text())


def task_schema():
    """Regenerate the JSON Schema of robot.yaml from the pydantic models."""
    return {
        "actions": [_write_schema],
        "file_dep": [str(ROOT / "mjcfbuild" / "manifest" / "models.py")],
        "targets": [str(ROOT / "schemas" / "robot.schema.json")],
    }


def task_example_meshes():
    """Regenerate the example arm's meshes."""
    script = ROOT / "examples" / "arm" / "make_meshes.py"
    return {
        "actions": [f"python {script}"],
        "file_dep": [str(script)],
        "verbosity": 2,
    }


def task_bench():
    """Run the build-time benchmark and print its table."""
    return {
        "actions": [f"python {ROOT / 'bench' / 'build_times.py'}"],
        "uptodate": [False],
        "verbosity": 2,
    }
