"""``mjcfbuild graph``: the task graph as text and as Graphviz DOT."""

from __future__ import annotations

from tests.conftest import run_cli


def test_text_graph_lists_tasks_inputs_and_order(arm):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    result = run_cli("graph", cwd=arm)
    assert result.code == 0
    text = result.stdout
    assert (
        "mesh:forearm  (mesh forearm)\n  reads: meshes/forearm.obj, meshes/forearm_colours.mtl"
        in (text)
    )
    assemble = text[text.index("assemble  (") :].splitlines()[1]
    assert assemble.startswith("  after: ") and "mesh:base" in assemble and "plan" in assemble
    assert "scene  (scene scene.xml)\n  after: assemble" in text


def test_dot_graph_has_an_edge_per_dependency(arm):
    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    dot = run_cli("graph", "--dot", cwd=arm).stdout
    assert dot.startswith("digraph mjcfbuild {") and dot.rstrip().endswith("}")
    assert '"mesh:base" -> "assemble";' in dot
    assert '"meshes/base.stl" -> "mesh:base";' in dot
    assert '"assemble" -> "scene";' in dot


def test_before_the_first_build_only_the_planning_tasks_are_known(arm):
    result = run_cli("graph", cwd=arm)
    assert result.code == 0
    assert "expand  (expand urdf/arm.urdf.xacro)" in result.stdout
    assert "mesh:" not in result.stdout and "once the plan has been made" in result.stdout


def test_dot_into_a_closed_pipe_ends_quietly(arm):
    """`mjcfbuild graph --dot | head -1`: the reader leaves early; no internal error. Here the
    reader is gone before the first write, so every run sees the broken pipe."""
    import os
    import subprocess
    import sys

    assert run_cli("build", "-q", "--no-check", cwd=arm).code == 0
    read_end, write_end = os.pipe()
    os.close(read_end)
    try:
        process = subprocess.run(
            [sys.executable, "-m", "mjcfbuild", "graph", "--dot"],
            cwd=arm,
            stdout=write_end,
            stderr=subprocess.PIPE,
            text=True,
        )
    finally:
        os.close(write_end)
    assert process.returncode == 0, process.stderr
    assert process.stderr == ""


def test_the_manifest_is_a_positional_argument_and_m_still_works(arm, tmp_path):
    manifest = str(arm / "robot.yaml")
    positional = run_cli("graph", manifest, cwd=tmp_path)
    flag = run_cli("graph", "-m", manifest, cwd=tmp_path)
    assert positional.code == flag.code == 0, positional.stderr
    assert positional.stdout == flag.stdout and "expand" in positional.stdout
