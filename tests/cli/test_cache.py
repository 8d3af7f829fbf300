"""``mjcfbuild cache`` shows, prunes and clears the shared cache."""

from __future__ import annotations


def test_cache_command_after_a_build(cli, arm, tmp_path):
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache")}
    assert cli("build", "-q", cwd=arm, env=env).code == 0
    shown = cli("cache", env=env)
    assert shown.code == 0
    assert f"cache: {tmp_path / 'cache' / 'products'}" in shown.stdout
    # Four mesh products, the collision matrix, the reference kinematics and seven pictures.
    assert "entries: 13" in shown.stdout
    pruned = cli("cache", "prune", "--max-size", "0", env=env)
    assert "removed 13 cache entries" in pruned.stdout
    assert "entries: 0" in pruned.stdout
    assert cli("cache", "clear", env=env).code == 0
    assert cli("cache", "prune", "--max-size", "lots", env=env).code == 2


def test_prune_to_a_size_does_not_show_it_as_the_cap(cli, arm, tmp_path):
    env = {"MJCFBUILD_CACHE_DIR": str(tmp_path / "cache"), "MJCFBUILD_CACHE_MAX": "2G"}
    assert cli("build", "-q", "--no-check", cwd=arm, env=env).code == 0
    pruned = cli("cache", "prune", "--max-size", "1M", env=env)
    assert pruned.code == 0
    assert "pruned to 1.0 MiB" in pruned.stdout
    assert "of 2.0 GiB" in pruned.stdout and "of 1.0 MiB" not in pruned.stdout


def test_the_revisions_diff_built_are_shown_and_cleared(cli, tmp_path):
    """`mjcfbuild diff` keeps the revisions it extracted and built under the cache folder:
    `cache` names them and `cache clear` removes them with the rest."""
    cache = tmp_path / "cache"
    kept = cache / "diff" / "repo" / "base" / "src"
    kept.mkdir(parents=True)
    (kept / "robot.yaml").write_text("name: r\n")
    env = {"MJCFBUILD_CACHE_DIR": str(cache)}
    shown = cli("cache", env=env)
    assert f"diff revisions: {cache / 'diff'} (8 B; `cache clear` removes them)" in shown.stdout
    cleared = cli("cache", "clear", env=env)
    assert cleared.code == 0 and not (cache / "diff").exists()
    assert "diff revisions" not in cleared.stdout.split("removed")[-1]
