"""Running doit for a build: only doit's own plugins, whatever else is installed."""

from __future__ import annotations

import sys

from doit.plugin import PluginDict

from mjcfbuild.engine.loader import only_doits_own_plugins


def test_a_doit_plugin_installed_beside_mjcfbuild_is_not_used(tmp_path, monkeypatch):
    # An installed package declaring a doit command that would replace doit's own ``run``.
    info = tmp_path / "other_doit_plugin-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: other-doit-plugin\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text("[doit.COMMAND]\nrun = other_doit_plugin:Run\n")
    monkeypatch.setattr(sys, "path", [str(tmp_path), *sys.path])
    commands = PluginDict()
    commands.add_plugins({}, "COMMAND")
    assert "run" in commands  # doit alone would use it
    with only_doits_own_plugins():
        commands = PluginDict()
        commands.add_plugins({}, "COMMAND")
        assert "run" not in commands
    commands.add_plugins({}, "COMMAND")
    assert "run" in commands  # restored afterwards
