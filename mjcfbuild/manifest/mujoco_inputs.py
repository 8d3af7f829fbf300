"""The ``mujoco_inputs`` of robot.yaml as :class:`Inputs`, with origins in robot.yaml.

The processed items are the manifest's own models (inputs.processed); only the raw MJCF text is
read here, as the reader of ``<raw_inputs>`` reads it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from lxml import etree

from mjcfbuild.errors import InputError
from mjcfbuild.inputs.model import Inputs
from mjcfbuild.inputs.processed import PROCESSED_INPUTS
from mjcfbuild.inputs.xml_inputs import read_raw_sections

if TYPE_CHECKING:
    from mjcfbuild.manifest.models import MujocoInputs


def native_inputs(settings: MujocoInputs, manifest_label: str) -> Inputs:
    """Inputs from the manifest's ``mujoco_inputs``, each item given at its key path."""
    where = f"{manifest_label} mujoco_inputs"
    inputs = Inputs()
    if settings.raw:
        inputs.raw = read_raw_sections(_wrap(settings.raw, f"{where}.raw"), f"{where}.raw")
    for kind in PROCESSED_INPUTS:
        for index, item in enumerate(getattr(settings, kind.manifest_key)):
            inputs.processed.append(item.given_at(f"{where}.{kind.manifest_key}[{index}]"))
    return inputs


def _wrap(text: str, label: str) -> etree._Element:
    try:
        return etree.fromstring(
            f"<raw_inputs>{text}</raw_inputs>",
            etree.XMLParser(
                resolve_entities=False, no_network=True, load_dtd=False, remove_comments=True
            ),
        )
    except etree.XMLSyntaxError as exc:
        raise InputError(f"malformed XML: {exc.msg}", file=label, line=exc.lineno) from None
