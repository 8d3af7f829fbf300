"""``mjcfbuild schema`` prints the committed schema."""

from __future__ import annotations

from tests.conftest import ROOT


def test_schema_command_prints_the_committed_schema(cli):
    result = cli("schema")
    assert result.code == 0
    assert result.stdout == (ROOT / "schemas" / "robot.schema.json").read_text()
