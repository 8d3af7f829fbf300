"""doit tasks of the mjcfbuild project: `doit list` shows them, `doit` builds the examples.

* ``examples`` - build every ``examples/*/robot.yaml``, as ``mjcfbuild build`` does and with
  its state (see :mod:`mjcfbuild.engine.dodo`): a model built by either is up to date for both;
* ``schema`` - regenerate ``schemas/robot.schema.json`` from the manifest models;
* ``example_meshes`` - regenerate the example arm's meshes;
* ``bench`` - run the build-time benchmark (downloads example-robot-data once).

doit's database is kept in the first example's state folder (``examples/*/mjcf/.mjcfbuild``).
"""

from pathlib import Path

from mjcfbuild.engine.dodo import RobotTasks

ROOT = Path(__file__).parent
EXAMPLES = sorted(str(p) for p in (ROOT / "examples").glob("*/robot.yaml"))
ROBOTS = RobotTasks(EXAMPLES)

DOIT_CONFIG = {"default_tasks": ["examples", "schema"], **ROBOTS.doit_config()}


def task_examples():
    """Build every example robot."""
    yield from ROBOTS.tasks()


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
