"""The layers of docs/architecture.md, as import-linter checks them in CI (``lint-imports``
with the contracts in pyproject.toml): the package keeps them, and the contracts see an import
up a layer made inside a function and a module placed in no layer."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from tests.conftest import ROOT

LINT_IMPORTS = Path(sys.executable).parent / "lint-imports"


def lint_imports(folder: Path) -> subprocess.CompletedProcess[str]:
    """``lint-imports`` run in ``folder`` on the copy of mjcfbuild there, nothing cached."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run(
        [str(LINT_IMPORTS), "--no-logo", "--no-cache"],
        cwd=folder,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_the_package_keeps_its_layers():
    run = lint_imports(ROOT)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "Contracts: 2 kept, 0 broken." in run.stdout


def test_an_import_up_a_layer_inside_a_function_and_an_unplaced_module_break_the_layers(
    tmp_path,
):
    shutil.copytree(
        ROOT / "mjcfbuild", tmp_path / "mjcfbuild", ignore=shutil.ignore_patterns("__pycache__")
    )
    shutil.copy(ROOT / "pyproject.toml", tmp_path)
    for package in ("tests", "bench"):  # root packages of the contracts
        (tmp_path / package).mkdir()
        (tmp_path / package / "__init__.py").write_text("")
    numbers = tmp_path / "mjcfbuild" / "numbers.py"
    numbers.write_text(
        numbers.read_text() + "\n\ndef _report():\n    from mjcfbuild.cli import main\n\n"
        "    return main\n"
    )
    (tmp_path / "mjcfbuild" / "unplaced.py").write_text('"""In no layer."""\n')

    run = lint_imports(tmp_path)

    assert run.returncode == 1, run.stdout + run.stderr
    assert "mjcfbuild.numbers is not allowed to import mjcfbuild.cli" in run.stdout
    assert "not listed as layers:\n\n- mjcfbuild.unplaced" in run.stdout
    assert "Contracts: 1 kept, 1 broken." in run.stdout
