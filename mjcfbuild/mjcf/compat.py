"""A model as MuJoCo 3.x reads it: the report page's WebAssembly build (npm's newest is 3.14)
and MJX's JAX engine (mujoco-mjx 3.17, installed beside its MuJoCo) are older than the MuJoCo
that builds the model (4.0), which writes one thing they refuse.

MuJoCo 4.0 writes ``input="pos"`` on the actuators its ``<position>`` shortcut makes (an MJCF
part's servo, the training variant's servos); 3.14 allows ``input`` only on ``so3``, ``pid``
and ``dcmotor`` actuators and has no other meaning for it. Those actuators' gains and biases
are written out in full, so without the attribute 3.x simulates the same servo.
"""

from __future__ import annotations

import re

# The start tag of an actuator that 3.x refuses ``input`` on.
_TAG = re.compile(
    rb"<(?:general|position|velocity|intvelocity|motor|damper|cylinder|muscle|adhesion)\b[^>]*>"
)
_INPUT = re.compile(rb"\s+input=\"[^\"]*\"")


def for_mujoco3(xml: bytes) -> bytes:
    """``xml`` with what MuJoCo 3.x refuses taken out; the same bytes otherwise. A
    ``<general>`` with DC motor dynamics (how MjSpec writes a ``<dcmotor>``) keeps its input:
    there it means what it does on ``<dcmotor>``."""

    def without_input(tag: re.Match[bytes]) -> bytes:
        text = tag.group(0)
        return text if b'"dcmotor"' in text else _INPUT.sub(b"", text)

    return _TAG.sub(without_input, xml)
