"""MuJoCo's load errors in one line of words, from MuJoCo's own exceptions."""

from __future__ import annotations

import mujoco
import pytest

from mjcfbuild.mjerrors import load_error


def _error_of(xml: str) -> str:
    with pytest.raises(ValueError) as info:
        mujoco.MjModel.from_xml_string(xml)
    return load_error(info.value)


def test_xml_the_parser_rejects_names_the_line_and_reason():
    assert _error_of("<mujoco>\n\n<worldbody/></mujoco>junk") == (
        "not well-formed XML at line 3 (parsing text)"
    )
    assert _error_of("<mujoco><worldbody><body></worldbody></mujoco>") == (
        "not well-formed XML at line 1 (mismatched element: XMLElement name=body)"
    )


def test_mujocos_own_xml_errors_name_the_element_and_line():
    assert _error_of('<mujoco>\n<option integrator="x"/></mujoco>') == (
        "invalid keyword: 'x' (<option> at line 2)"
    )


def test_an_error_without_text_is_named_by_its_kind():
    assert load_error(ValueError("")) == "ValueError"
