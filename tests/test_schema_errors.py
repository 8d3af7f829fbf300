"""A pydantic validation error in words (mjcfbuild/schema_errors.py), for robot.yaml and for
the MuJoCo inputs' XML elements alike."""

from __future__ import annotations

import pytest
from pydantic import BaseModel, ConfigDict, ValidationError

from mjcfbuild.manifest.loading import describe
from mjcfbuild.schema_errors import describe_error


class Wheel(BaseModel):
    model_config = ConfigDict(extra="forbid")

    radius: float
    width: float = 0.01


class Cart(BaseModel):
    model_config = ConfigDict(extra="forbid")

    name: str
    wheels: list[Wheel] = []


def first_error(model: type[BaseModel], data: dict, kind: str | None = None):
    """The first error of validating ``data`` (of type ``kind`` where given)."""
    with pytest.raises(ValidationError) as raised:
        model.model_validate(data)
    return next(e for e in raised.value.errors() if kind in (None, e["type"]))


def test_an_unknown_key_is_named_with_its_closest_key_and_the_keys_of_its_model():
    error = first_error(Cart, {"name": "c", "wheels": [{"radius": 0.1, "widht": 0.02}]})

    assert describe_error(error, Cart) == (
        "unknown key 'widht'; did you mean 'width'? allowed keys: radius, width"
    )


def test_an_unknown_key_without_a_close_one_lists_the_keys_after_a_semicolon():
    error = first_error(Cart, {"name": "c", "colour": "red"})

    assert describe_error(error, Cart) == "unknown key 'colour'; allowed keys: name, wheels"


class Axle(BaseModel):
    """A model whose key ``width`` is named ``track`` elsewhere."""

    model_config = ConfigDict(extra="forbid")

    width: float

    @classmethod
    def key_aliases(cls) -> dict[str, str]:
        return {"track": "width"}


def test_a_key_by_its_other_name_points_at_the_key():
    error = first_error(Axle, {"width": 1, "track": 1}, "extra_forbidden")

    assert (
        describe_error(error, Axle)
        == "unknown key 'track'; did you mean 'width'? allowed keys: width"
    )


def test_without_a_root_model_the_key_is_named_alone():
    error = first_error(Cart, {"name": "c", "colour": "red"})

    assert describe_error(error, None) == "unknown key 'colour'"


def test_a_removed_key_says_what_became_of_it():
    error = first_error(Cart, {"name": "c", "colour": "red"})

    assert describe_error(error, Cart, {("colour",): "colour is gone"}) == "colour is gone"


def test_values_of_the_wrong_kind_say_what_was_expected():
    assert describe_error(first_error(Wheel, {"radius": "big"}), Wheel) == (
        "expected a number, got 'big'"
    )
    assert describe_error(first_error(Cart, {}), Cart) == "this key is required"


def test_a_fixed_length_list_cut_short_says_how_many_items_it_needs():
    class Range(BaseModel):
        limits: tuple[float, float]

    error = first_error(Range, {"limits": [5]})
    assert describe_error(error, Range) == "missing: the list needs 2 items"


def test_robot_yaml_errors_list_the_manifests_keys_and_its_removed_section():
    from mjcfbuild.manifest.models import Manifest

    unknown = first_error(Manifest, {"colision": {}}, "extra_forbidden")
    removed = first_error(Manifest, {"ros2_control": {}}, "extra_forbidden")

    assert describe(unknown).startswith("unknown key 'colision'; did you mean 'collision'?")
    assert "allowed keys: " in describe(unknown) and "source" in describe(unknown)
    assert describe(removed).startswith("the ros2_control section is gone")
