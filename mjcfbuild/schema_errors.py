"""A pydantic validation error in words: what is wrong and what would be allowed.

robot.yaml's errors (:mod:`mjcfbuild.manifest.loading`) and those of the MuJoCo inputs' XML
elements (:mod:`mjcfbuild.inputs.processed`) are worded here, below both. A model whose keys
have other names elsewhere (the XML inputs' attributes) gives them from a ``key_aliases()``
class method, ``{other name: key}``; an unknown key that is one of them is pointed at its key.
"""

from __future__ import annotations

import difflib
import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pydantic import BaseModel
    from pydantic_core import ErrorDetails


def describe_error(
    error: ErrorDetails,
    root: type[BaseModel] | None,
    removed: dict[tuple, str] | None = None,
) -> str:
    """What is wrong, and what would be allowed, for one pydantic error of a model whose keys
    are those of ``root`` (None: no keys are listed); ``removed`` says what became of keys
    that are gone, by their place."""
    kind = error["type"]
    loc = tuple(error["loc"])
    value = error.get("input")
    if kind == "extra_forbidden":
        key = str(loc[-1]) if loc else "?"
        if removed and loc in removed:
            return removed[loc]
        model = _model_at(root, loc[:-1])
        allowed = sorted(model.model_fields) if model is not None else []
        aliases = getattr(model, "key_aliases", None)
        alias = aliases().get(key) if callable(aliases) else None
        suggestion = [alias] if alias else difflib.get_close_matches(key, allowed, n=1)
        text = f"unknown key '{key}'"
        if suggestion:
            text += f"; did you mean '{suggestion[0]}'?"
        if allowed:
            text += f"{'' if suggestion else ';'} allowed keys: {', '.join(allowed)}"
        return text
    if kind == "missing":
        if loc and isinstance(loc[-1], int):  # a fixed-length list, cut short
            return f"missing: the list needs {loc[-1] + 1} items"
        return "this key is required"
    if kind == "literal_error":
        expected = error.get("ctx", {}).get("expected", "")
        choices = re.findall(r"'([^']*)'", expected)
        close = difflib.get_close_matches(str(value), choices, n=1) if choices else []
        mean = f"; did you mean '{close[0]}'?" if close else ""
        return f"{_show(value)} is not allowed{mean or ';'} use one of {expected}"
    if kind in {"string_type", "string_too_short"}:
        return f"expected a non-empty string, got {_show(value)}"
    if kind == "string_pattern_mismatch":
        return (
            f"{_show(value)} is not a valid name; use letters, digits, '_', '-' and '.', "
            "starting with a letter or digit"
        )
    if kind in {"bool_type", "bool_parsing"}:
        return f"expected true or false, got {_show(value)}"
    if kind in {"int_type", "int_parsing", "float_type", "float_parsing", "int_from_float"}:
        return f"expected a number, got {_show(value)}"
    if kind == "finite_number":
        return f"expected a finite number, got {_show(value)}"
    if kind in {"dict_type", "model_type", "model_attributes_type"}:
        return f"expected a mapping of keys, got {_show(value)}"
    if kind in {"list_type", "tuple_type"}:
        return f"expected a list, got {_show(value)}"
    if kind in {"greater_than", "greater_than_equal", "less_than", "less_than_equal"}:
        return error["msg"].lower().replace("input", f"{_show(value)}")
    if kind == "value_error":
        return str(error.get("ctx", {}).get("error", error["msg"]))
    return error["msg"]


def _show(value: object) -> str:
    if isinstance(value, (dict, list)):
        return "a mapping" if isinstance(value, dict) else "a list"
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _model_at(root: type[BaseModel] | None, loc: tuple) -> type[BaseModel] | None:
    """The model at ``loc``, walking the models from ``root``."""
    import typing

    model = root
    keyed = False  # the part before was a mapping of names to models (motors.define)
    for part in loc:
        if keyed:
            keyed = False
            continue
        if isinstance(part, int):  # an item of a list of models: the model itself
            continue
        if model is None:
            return None
        field = model.model_fields.get(str(part))
        if field is None:
            return None
        keyed = typing.get_origin(field.annotation) is dict
        model = _model_of(field.annotation)
    return model


def _model_of(annotation: object) -> type[BaseModel] | None:
    from pydantic import BaseModel

    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in getattr(annotation, "__args__", ()) or ():
        found = _model_of(arg)
        if found is not None:
            return found
    return None
