"""Fuzzing whole builds: generated URDFs with generated options through the real command line
end in a documented exit code, at most one error line each, and no traceback."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import yaml
from hypothesis import HealthCheck, given, settings

from mjcfbuild.errors import EXIT_CODES, EXIT_INTERNAL
from tests.conftest import run_cli
from tests.fuzzing import examples
from tests.meshes.samples import ascii_stl
from tests.strategies import VALID_OPTIONS, urdf_text


@settings(max_examples=examples(12), deadline=None, suppress_health_check=list(HealthCheck))
@given(urdf_text(), VALID_OPTIONS)
def test_generated_builds_end_in_documented_exit_codes(text, options):
    folder = Path(tempfile.mkdtemp(prefix="mjcfbuild-fuzz-build-"))
    try:
        ascii_stl(folder / "part.stl")
        (folder / "robot.urdf").write_text(text)
        manifest = {"name": "fuzz", "source": {"urdf": "robot.urdf"}, **options}
        manifest["check"] = {"previews": False}
        (folder / "robot.yaml").write_text(yaml.safe_dump(manifest))
        result = run_cli("build", "-q", "-j", "1", cwd=folder)
        assert result.code in EXIT_CODES and result.code != EXIT_INTERNAL, result.stderr
        assert "Traceback" not in result.stderr
        for line in result.stderr.splitlines():
            assert line.startswith(("mjcfbuild: error: ", "mjcfbuild: warning: ")), line
        for line in result.stdout.splitlines():  # -q: only a failure's summary
            assert line.startswith("mjcfbuild: failed "), line
    finally:
        shutil.rmtree(folder, ignore_errors=True)
