"""The report page's "Training variant" section, rendered from the records a build and
``check --warp`` keep."""

from __future__ import annotations

from mjcfbuild.check.report_page import _training


def figures(worlds: int, full: float, variant: float) -> tuple[dict, dict]:
    row = {"worlds": worlds, "steps": 100, "collision_geoms": 5, "contact_pairs": 4}
    return {**row, "steps_per_second": full}, {**row, "steps_per_second": variant}


RECORD = {
    "file": "go1_mjx.xml",
    "geoms": {"trunk": ["box"], "FL_calf": ["sphere"]},
    "floor": ["FL_calf"],
    "pairs": [],
    "notes": ["12 <dcmotor> servos are <position> servos"],
    "solver": {"device": "gpu", "solver": "newton", "iterations": 1, "ls_iterations": 5},
}


def test_the_section_names_the_solver_settings_the_variant_has():
    text = "\n".join(_training(RECORD))
    assert "Solver for a GPU: newton, 1 iteration, 5 line-search iterations" in text
    assert "- 12 \\<dcmotor> servos are \\<position> servos" in text  # not HTML tags
    assert "Not yet measured in MuJoCo Warp" in text


def test_gpu_figures_appear_beside_the_cpu_ones_only_when_measured():
    full, variant = figures(64, 11000.0, 24000.0)
    warp = {"full": full, "variant": variant, "behaviour": "stands", "failures": []}
    text = "\n".join(_training({**RECORD, "warp": warp}))
    assert "| variant | 5 | 4 | 24000 |" in text and "On NVIDIA" not in text
    gpu_full, gpu_variant = figures(4096, 800000.0, 900000.0)
    gpu = {
        "device": "NVIDIA H100",
        "full": gpu_full,
        "variant": gpu_variant,
        "behaviour": "stands at home for 5 s",
        "failures": ["the training variant does not stand"],
    }
    text = "\n".join(_training({**RECORD, "warp": {**warp, "gpu": gpu}}))
    assert (
        "On NVIDIA H100 (4096 worlds): stands at home for 5 s; full 800000 steps/s, "
        "variant 900000 steps/s." in text
    )
    assert "- check failed on the GPU: the training variant does not stand" in text


def test_a_gpu_that_failed_is_one_failure_line_beside_the_cpu_figures():
    full, variant = figures(64, 11000.0, 24000.0)
    error = "MuJoCo Warp failed on NVIDIA H100: out of memory"
    warp = {
        "full": full,
        "variant": variant,
        "behaviour": "stands",
        "failures": [],
        "gpu": {"device": "NVIDIA H100", "error": error, "failures": [error]},
    }
    text = "\n".join(_training({**RECORD, "warp": warp}))
    assert "| variant | 5 | 4 | 24000 |" in text
    assert f"- check failed on the GPU: {error}" in text and "On NVIDIA" not in text
