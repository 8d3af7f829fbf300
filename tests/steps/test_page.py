"""``output.page: true``: the example arm's report page, opened from file:// in a real headless
Chromium (Debian's ``chromium``), with MuJoCo's WebAssembly build from npm.

Without a browser the tests that need one are skipped, except in CI (``CI=true``), where they
fail: .ci/run installs it.
"""

from __future__ import annotations

import io
import json
import math
import shutil
from pathlib import Path

import pytest

from mjcfbuild.outputs import PAGE_FILES
from tests.conftest import EXAMPLES, copy_example, run_cli
from tests.page.chromium import Browser, require_chromium
from tests.page.hostile import (
    CODE,
    NAMES,
    TAG,
    build,
    hostile_robot,
    markup_outside_code,
    tables,
    unescaped,
)

RESULT = "document.getElementById('result').dataset"


def build_with_page(top: Path, name: str) -> Path:
    """A copy of ``examples/<name>`` with output.page on, built; its output folder."""
    folder = copy_example(name, top)  # with its siblings, which some examples refer to
    manifest = folder / "robot.yaml"
    text = manifest.read_text()
    assert "\noutput:\n  folder: mjcf\n" in text  # where the switch goes
    manifest.write_text(text.replace("\noutput:\n", "\noutput:\n  page: true\n"))
    result = run_cli("build", cwd=folder)
    assert result.code == 0, result.stderr
    return folder / "mjcf"


@pytest.fixture(scope="module")
def arm(tmp_path_factory) -> Path:
    """The arm's output folder, built with its page."""
    return build_with_page(tmp_path_factory.mktemp("page"), "arm")


@pytest.fixture(scope="module")
def browser():
    """One headless Chromium for the module's tests."""
    running = Browser(require_chromium())
    yield running
    running.close()


@pytest.fixture
def page(arm, browser):
    """The arm's page, freshly loaded and ready."""
    state = browser.open(arm / "report" / "index.html")
    assert state == "ready", browser.evaluate("window.mjcfbuildPage.error")
    return browser


def test_the_page_asks_for_its_own_files_only(page, arm):
    report = (arm / "report").resolve().as_uri()
    expected = {f"{report}/index.html"}
    expected |= {f"{report}/page/{name}" for name in ("page.css", "viewer.js", "tables.js")}
    expected |= {f"{report}/page/{name}" for name in ("mujoco.js", "mujoco-wasm.js", "model.js")}
    assert expected <= set(page.requests)
    assert all(url.startswith((f"{report}/", "data:", "blob:")) for url in page.requests), (
        page.requests
    )


def test_the_build_writes_the_page_beside_the_report(arm):
    report = arm / "report"
    for name in PAGE_FILES:
        assert (report / name).is_file(), name
    assert (report / "page" / "tables.js").is_file()
    index = (report / "index.html").read_text()
    assert "<title>example_arm: mjcfbuild report</title>" in index
    assert "http://" not in index and "https://" not in index  # nothing from a network
    total = sum(p.stat().st_size for p in report.rglob("*") if p.parent.name == "page")
    assert 3_000_000 < total < 5_000_000  # what docs/review.md says it weighs


def test_the_page_draws_the_robot(page):
    import numpy as np
    from PIL import Image

    def view() -> np.ndarray:
        picture = Image.open(io.BytesIO(page.screenshot())).convert("RGB").crop(box)
        return np.asarray(picture, dtype=int)

    box = page.evaluate(
        "(() => { const r = document.getElementById('view').getBoundingClientRect();"
        " return [r.left, r.top, r.right, r.bottom].map(Math.round); })()"
    )
    shown = view()
    page.evaluate("document.getElementById('show-visual').click(); mjcfbuildPage.draw()")
    floor_only = view()
    assert len(np.unique(shown.reshape(-1, 3), axis=0)) > 100  # shaded, not blank
    robot = np.abs(shown - floor_only).sum(axis=2) > 30
    assert robot.mean() > 0.03  # the robot covers a fair part of the view
    height, width = robot.shape
    assert robot[height // 4 : 3 * height // 4, width // 4 : 3 * width // 4].mean() > 0.05
    page.evaluate("document.getElementById('show-collision').click(); mjcfbuildPage.draw()")
    collision = np.abs(view() - floor_only).sum(axis=2) > 30
    assert collision.mean() > 0.03  # the collision geometry, drawn alone


def test_a_joint_slider_moves_its_joint(page):
    before = page.evaluate("mjcfbuildPage.bodyPosition('wrist_link')")
    assert page.evaluate("mjcfbuildPage.qpos('elbow')") == pytest.approx(1.2)
    page.evaluate(
        "(() => { const s = document.querySelector('input[data-joint=\"elbow\"]');"
        " s.value = '0.2'; s.dispatchEvent(new Event('input')); })()"
    )
    assert page.evaluate("mjcfbuildPage.qpos('elbow')") == pytest.approx(0.2)
    after = page.evaluate("mjcfbuildPage.bodyPosition('wrist_link')")
    assert math.dist(before, after) > 0.2  # the 0.27 m link after it turned by 1 rad
    joints = page.evaluate("mjcfbuildPage.joints")
    assert joints == [
        "shoulder_pan",
        "shoulder_lift",
        "elbow",
        "wrist_roll",
        "left_finger_joint",
        "right_finger_joint",
    ]


def test_playing_the_hold_test_keeps_the_arm_at_home(page, arm):
    page.evaluate("document.getElementById('hold').click()")
    status = page.wait_for(f"['pass', 'fail'].includes({RESULT}.status) && {RESULT}.status")
    result = page.evaluate(f"Object.assign({{}}, {RESULT})")
    assert status == "pass", result
    assert result["test"] == "hold"
    report = json.loads((arm / "report" / "report.json").read_text())
    measured = report["check"]["hold"]["max_deviation"]
    assert f"the build measured {measured:.3g}" in result["summary"]
    assert float(result["tolerance"]) == 0.05  # check.hold_tolerance's default
    assert float(result["deviation"]) <= 0.05
    # The browser's MuJoCo (3.14, WebAssembly) agrees with the build's check (Python).
    assert float(result["deviation"]) == pytest.approx(
        report["check"]["hold"]["max_deviation"], rel=0.02
    )
    assert page.evaluate("mjcfbuildPage.qpos('elbow')") == pytest.approx(1.2, abs=0.05)


def test_the_menagerie_test_plays_without_warnings(page):
    page.evaluate("document.getElementById('menagerie').click()")
    status = page.wait_for(f"['pass', 'fail'].includes({RESULT}.status) && {RESULT}.status")
    result = page.evaluate(f"Object.assign({{}}, {RESULT})")
    assert (status, result["test"], result["warnings"], result["finite"]) == (
        "pass",
        "menagerie",
        "0",
        "true",
    )


def test_the_tables_are_the_reports(page, arm):
    headings = page.evaluate("[...document.querySelectorAll('#report h3')].map(h => h.textContent)")
    assert {"Checks", "Actuators", "Home pose"} <= set(headings)
    assert "Build times" not in " ".join(headings)  # they change from run to run
    cells = page.evaluate("[...document.querySelectorAll('#report td')].map(c => c.textContent)")
    assert "hold home's ctrl for 1 s" in cells


def test_the_quadruped_stands_in_the_browser(tmp_path, browser):
    folder = build_with_page(tmp_path, "quadruped")
    assert browser.open(folder / "report" / "index.html") == "ready"
    assert browser.evaluate("document.getElementById('hold').hidden")  # a floating robot
    browser.evaluate("document.getElementById('stand').click()")
    status = browser.wait_for(f"['pass', 'fail'].includes({RESULT}.status) && {RESULT}.status")
    result = browser.evaluate(f"Object.assign({{}}, {RESULT})")
    assert (status, result["test"]) == ("pass", "stand"), result
    assert float(result["tilt"]) < 0.2


def page_bytes(output: Path) -> dict[str, bytes]:
    report = output / "report"
    names = [*PAGE_FILES, "page/tables.js"]
    return {name: (report / name).read_bytes() for name in names}


def test_the_page_is_the_same_bytes_in_another_folder_and_a_rebuild_does_nothing(arm, tmp_path):
    other = build_with_page(tmp_path, "arm")
    assert page_bytes(other) == page_bytes(arm)
    again = run_cli("build", "-v", cwd=other.parent)
    assert again.code == 0, again.stderr
    assert " 0 run" in again.stdout + again.stderr


def test_a_new_home_pose_rebuilds_the_page_and_turning_it_off_removes_it(tmp_path):
    output = build_with_page(tmp_path, "arm")
    before = page_bytes(output)
    manifest = output.parent / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("elbow: 1.2", "elbow: 1.0"))
    result = run_cli("build", cwd=output.parent)
    assert result.code == 0, result.stderr
    assert "report page" in result.stdout + result.stderr
    after = page_bytes(output)
    changed = {name for name in before if before[name] != after[name]}
    assert changed == {"page/model.js", "page/tables.js"}  # the model and its home table
    manifest.write_text(manifest.read_text().replace("  page: true\n", ""))
    result = run_cli("build", cwd=output.parent)
    assert result.code == 0, result.stderr
    assert not (output / "report" / "index.html").exists()
    assert not (output / "report" / "page").exists()
    assert (output / "report" / "report.md").is_file()


def test_a_registry_out_of_reach_fails_the_build_in_one_line(tmp_path):
    folder = tmp_path / "arm"
    shutil.copytree(EXAMPLES / "arm", folder, ignore=shutil.ignore_patterns("mjcf"))
    manifest = folder / "robot.yaml"
    manifest.write_text(manifest.read_text().replace("\noutput:\n", "\noutput:\n  page: true\n"))
    environment = {
        "MJCFBUILD_CACHE_DIR": str(tmp_path / "empty-cache"),
        "MJCFBUILD_NPM_REGISTRY": "http://127.0.0.1:9",
    }
    result = run_cli("build", cwd=folder, env=environment)
    assert result.code == 1, result.stderr
    errors = [line for line in result.stderr.splitlines() if "error" in line]
    assert len(errors) == 1, result.stderr
    assert "cannot download @mujoco/mujoco 3.14.0 from http://127.0.0.1:9" in errors[0]
    assert "MJCFBUILD_MUJOCO_JS" in errors[0]
    assert "Traceback" not in result.stderr


def test_a_servo_from_an_mjcf_part_loads_in_the_browsers_older_mujoco(tmp_path, browser):
    # MuJoCo 4.0 writes input="pos" on the part's <position> servo, which 3.14 refuses
    # (mjcfbuild.actuators.for_mujoco3); the hold test agrees with the build's check.
    folder = build_with_page(tmp_path, "arm_mjcf_gripper")
    assert b'input="pos"' in (folder / "arm_with_mjcf_hand.xml").read_bytes()
    state = browser.open(folder / "report" / "index.html")
    assert state == "ready", browser.evaluate("window.mjcfbuildPage.error")
    browser.evaluate("document.getElementById('hold').click()")
    status = browser.wait_for(f"['pass', 'fail'].includes({RESULT}.status) && {RESULT}.status")
    result = browser.evaluate(f"Object.assign({{}}, {RESULT})")
    report = json.loads((folder / "report" / "report.json").read_text())
    assert status == "pass", result
    assert float(result["deviation"]) == pytest.approx(
        report["check"]["hold"]["max_deviation"], rel=0.02
    )


def test_the_check_command_names_the_page_and_keeps_its_tables(arm):
    tables = arm / "report" / "page" / "tables.js"
    before = tables.read_bytes()
    result = run_cli("check", cwd=arm.parent)
    assert result.code == 0, result.stderr
    assert "  page: mjcf/report/index.html" in result.stdout
    assert tables.read_bytes() == before  # the same checks, the same tables


@pytest.fixture(scope="module")
def hostile(tmp_path_factory) -> Path:
    """The output folder of a robot whose links and joints are named like Markdown and HTML
    (tests/page/hostile.py), built with its page."""
    folder = tmp_path_factory.mktemp("hostile")
    hostile_robot(folder)
    return build(folder)


def test_names_like_markup_are_text_on_the_page_and_fetch_nothing(hostile, browser):
    assert browser.open(hostile / "report" / "index.html") == "ready"
    report = (hostile / "report").resolve().as_uri()
    assert all(url.startswith((f"{report}/", "data:", "blob:")) for url in browser.requests), (
        browser.requests
    )
    assert not any("8765" in url for url in browser.requests)
    found = browser.evaluate(
        """(() => {
          const report = document.getElementById('report');
          return {
            pictures: [...document.images].map((image) => image.getAttribute('src')),
            handlers: [...document.querySelectorAll('*')].filter(
              (e) => [...e.attributes].some((a) => a.name.startsWith('on'))).length,
            tables: [...report.querySelectorAll('table')].map(
              (table) => [...table.rows].map((row) => row.cells.length)),
            cells: [...report.querySelectorAll('td')].map((cell) => cell.textContent),
            items: [...report.querySelectorAll('li')].map((item) => item.textContent),
            sliders: [...document.querySelectorAll('#joints span')].map((s) => s.textContent),
          };
        })()"""
    )
    assert found["pictures"] and all(
        src.startswith(("previews/", "tuning/")) for src in found["pictures"]
    )
    assert found["handlers"] == 0
    assert found["tables"] and all(len(set(rows)) == 1 for rows in found["tables"])
    assert set(NAMES) <= set(found["cells"])  # each name one cell, as written
    assert set(found["sliders"]) == {TAG, CODE}
    assert any('<origin xyz="0,0,0.05">' in item for item in found["items"])  # the warning


def test_names_like_markup_are_text_in_report_md(hostile):
    markdown = (hostile / "report" / "report.md").read_text()
    assert markup_outside_code(markdown) == []
    found = tables(markdown)
    assert found and all(len({len(row) for row in rows}) == 1 for rows in found)
    every_cell = {cell for rows in found for row in rows for cell in row}
    assert set(NAMES) <= every_cell
    assert '<origin xyz="0,0,0.05">' in unescaped(markdown)  # the warning, as text
