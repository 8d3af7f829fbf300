"""Survey: the mesh plausibility test and the COLLADA up-axis decisions on real robots.

Builds each URDF of the unpacked example-robot-data wheel from a bare robot.yaml (no check:
the survey loads the model itself), then prints each body the plausibility test names and each
DAE file whose up axis the build decided. Usage::

    python bench/plausibility_survey.py [NAME_SUBSTRING ...]
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench import robot_data


def main(filters: list[str]) -> int:
    import mjcfbuild
    from mjcfbuild.check.loading import asset_sources, compile_model
    from mjcfbuild.check.plausibility import check_plausibility

    # The wheel's descriptions, unpacked where the other benchmarks unpack them.
    robots = robot_data.unpack_all()
    urdfs = sorted(robots.glob("*/*/*.urdf"))
    urdfs = [u for u in urdfs if not filters or any(f in str(u) for f in filters)]
    if not urdfs:
        print(f"no URDF under {robots} matches {' '.join(filters)}", file=sys.stderr)
        return 1
    cache = Path(tempfile.gettempdir()) / "plausibility-survey"
    for urdf in urdfs:
        name = urdf.relative_to(robots).as_posix()
        folder = cache / name.replace("/", "_")
        folder.mkdir(parents=True, exist_ok=True)
        manifest = folder / "robot.yaml"
        manifest.write_text(
            f"name: {urdf.stem.replace('-', '_')}\nsource:\n  urdf: {urdf}\n"
            f"packages:\n  example-robot-data: {robots.parent}\n"
        )
        try:
            result = mjcfbuild.build(manifest, jobs=1, check=False)
        except Exception as exc:  # a survey: report and go on
            print(f"{name}: build raised {type(exc).__name__}: {exc}")
            continue
        if not result.ok:
            print(f"{name}: build failed: {str(result)[:200]}")
            continue
        sources = asset_sources(folder / "mjcf" / ".mjcfbuild" / "assembly.json")
        found = check_plausibility(compile_model(result.robot, sources), sources)
        decisions = []
        for summary in sorted((folder / "mjcf" / ".mjcfbuild" / "products").glob("*.json")):
            data = json.loads(summary.read_text())
            if isinstance(data, dict) and data.get("up_axis"):
                decisions.append((summary.stem, data["up_axis"]))
        turned = [d for d in decisions if d[1]["turned"]]
        print(
            f"{name}: {found.bodies} bodies, {len(found.findings)} named; "
            f"{len(turned)}/{len(decisions)} DAE files turned",
            flush=True,
        )
        for finding in found.findings:
            print(f"   {'FAIL' if finding.fails else 'warn'} {finding.text()}")
        for mesh, decision in decisions:
            print(f"   up axis {mesh}: {decision['reason'][:300]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
