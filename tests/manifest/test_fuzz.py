"""Fuzzing the manifest: any YAML either validates or fails with one positioned ManifestError."""

from __future__ import annotations

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mjcfbuild.errors import ManifestError
from mjcfbuild.manifest.loading import parse_manifest
from tests.fuzzing import examples
from tests.strategies import manifest_data

FUZZ = settings(
    max_examples=examples(300), deadline=None, suppress_health_check=[HealthCheck.too_slow]
)


def validates_or_explains(text: str) -> None:
    try:
        parse_manifest(text)
    except ManifestError as error:
        assert error.location is not None and error.location.file == "robot.yaml"
        assert "\n" not in error.one_line() and error.message


@FUZZ
@given(manifest_data())
def test_any_manifest_data(data):
    validates_or_explains(yaml.safe_dump(data, sort_keys=False, allow_unicode=True))


@FUZZ
@given(manifest_data(), st.data())
def test_any_damage_to_the_text(data, draw):
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
    at = draw.draw(st.integers(0, len(text)))
    cut = draw.draw(st.integers(0, 5))
    inserted = draw.draw(st.text(alphabet=" \t\n:-[]{}&*!|>'\"%@`#,?\\x0", max_size=4))
    validates_or_explains(text[:at] + inserted + text[at + cut :])
